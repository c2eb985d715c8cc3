//! The renderers a scheduler owns: the view's, the A/B side's and the homework check's, on one
//! device. Each stage (a file each) adds what it does with them.

use super::homework::HomeworkRunner;
use super::keys::{MapKey, ReferenceKey};
use crate::render::{GpuWait, RenderError, Renderer};

/// The worker's renderers: `a` for the view, `b` for the A/B split's right side (made on first use).
pub(super) struct Renderers {
    pub(super) device: wgpu::Device,
    pub(super) queue: wgpu::Queue,
    pub(super) a: Renderer,
    pub(super) b: Option<Renderer>,
    /// What the last map picture sent was drawn from.
    pub(super) last_map: Option<MapKey>,
    /// Ground truths at probes finished lately, newest last: what each depends on, the value at
    /// the probed pixel and the samples averaged.
    pub(super) probe_truths: Vec<(ReferenceKey, f32, u32)>,
    /// The view's last finished ground truth.
    pub(super) view_truth: Option<(ReferenceKey, Vec<f32>, u32)>,
    pub(super) homework: HomeworkRunner,
}

/// Renderers on a device of their own (the desktop: the device opens at once).
#[cfg(not(target_arch = "wasm32"))]
pub(super) fn open(adapter: &wgpu::Adapter) -> Result<Renderers, RenderError> {
    let descriptor = crate::render::device_descriptor(adapter, "shadowlab render worker");
    let (device, queue) = pollster::block_on(adapter.request_device(&descriptor))
        .map_err(|e| RenderError::Device(e.to_string()))?;
    open_on(device, queue)
}

/// Renderers on a device already open (a page's: a browser's adapter gives one device).
pub(super) fn open_on(device: wgpu::Device, queue: wgpu::Queue) -> Result<Renderers, RenderError> {
    let a = Renderer::new(&device, &queue)?;
    Ok(Renderers {
        device,
        queue,
        a,
        b: None,
        last_map: None,
        probe_truths: Vec::new(),
        view_truth: None,
        homework: Default::default(),
    })
}

impl Renderers {
    /// Block until the GPU has done everything submitted so far.
    pub(super) fn wait_for_gpu(&self) -> Result<(), RenderError> {
        GpuWait::Block.poll(&self.device)
    }
}

//! The scheduler for a page without threads: the renderers live on the caller's thread and each
//! `poll` (once per UI frame) runs one step of the newest job without waiting for the GPU. A step
//! collects what has arrived of the work under way (or returns at once where it has not), sends
//! what that finishes and submits the next piece: the image, then the maps one picture at a time,
//! the overlays' analysis and the probe a light at a time, then the ground truths a batch at a
//! time. What is submitted in a poll is collected on a later one (a browser maps a buffer only
//! after the frame returns). A newer job replaces the one in progress between polls.

use super::renderers::Renderers;
use super::{JobBook, RenderEvent, RenderJob, RenderScheduler, Stage};
use crate::render::{GpuWait, RenderError};
use std::time::Duration;
use web_time::Instant;

pub struct FrameDriven {
    /// None until the device opens (on the first poll), and where it failed.
    renderers: Option<Renderers>,
    adapter: Option<wgpu::Adapter>,
    /// A device to render on, already open (else one of the adapter's is opened).
    device: Option<(wgpu::Device, wgpu::Queue)>,
    current: Option<CurrentJob>,
    /// Events to hand out on the next poll (the device's readiness).
    pending: Vec<RenderEvent>,
    book: JobBook,
}

/// The job in progress.
struct CurrentJob {
    id: u64,
    job: RenderJob,
    /// The step to run next, with the work it has under way.
    stage: Stage,
    started: Instant,
}

impl FrameDriven {
    /// A scheduler that opens a device of `adapter` on its first poll.
    #[cfg(not(target_arch = "wasm32"))]
    pub fn new(adapter: wgpu::Adapter) -> Self {
        Self {
            renderers: None,
            adapter: Some(adapter),
            device: None,
            current: None,
            pending: Vec::new(),
            book: JobBook::default(),
        }
    }

    /// A scheduler that renders on `device`, of `adapter`, from its first poll (a page's: its
    /// adapter gives one device, which the window paints with too).
    pub fn on_device(adapter: wgpu::Adapter, device: wgpu::Device, queue: wgpu::Queue) -> Self {
        Self {
            renderers: None,
            adapter: Some(adapter),
            device: Some((device, queue)),
            current: None,
            pending: Vec::new(),
            book: JobBook::default(),
        }
    }

    /// Block until the GPU has done all the work submitted so far, so that the next poll finds
    /// its read-backs there: for a caller with nothing else to do between polls (a test, a
    /// command-line run), never for a page's frames.
    pub fn wait_for_gpu(&self) -> Result<(), RenderError> {
        self.renderers.as_ref().map_or(Ok(()), Renderers::wait_for_gpu)
    }
}

impl RenderScheduler for FrameDriven {
    fn submit(&mut self, job: RenderJob) -> u64 {
        let id = self.book.latest + 1;
        self.book.submitted(id);
        // Newest request wins, whatever step the last one was at (its work under way is dropped).
        self.current = Some(CurrentJob { id, job, stage: Stage::Image, started: Instant::now() });
        id
    }

    fn poll(&mut self) -> Vec<RenderEvent> {
        let mut events = std::mem::take(&mut self.pending);
        if let Some(adapter) = self.adapter.take() {
            let opened = match self.device.take() {
                Some((device, queue)) => super::renderers::open_on(device, queue),
                #[cfg(not(target_arch = "wasm32"))]
                None => super::renderers::open(&adapter),
                #[cfg(target_arch = "wasm32")]
                None => Err(RenderError::Device("no device to render on".into())),
            };
            match opened {
                Ok(r) => {
                    self.renderers = Some(r);
                    events.push(RenderEvent::Ready(Ok(crate::render::describe_adapter(&adapter.get_info()))));
                }
                Err(e) => events.push(RenderEvent::Ready(Err(e.to_string()))),
            }
        }
        let (Some(renderers), Some(current)) = (self.renderers.as_mut(), self.current.as_mut()) else {
            self.book.heard(&events);
            return events;
        };
        let stage = std::mem::replace(&mut current.stage, Stage::Done);
        // Nothing newer can arrive during a step here: only between polls.
        current.stage = renderers.run_stage(
            current.id,
            &current.job,
            stage,
            current.started,
            &mut |e| events.push(e),
            &|| false,
            GpuWait::Poll,
        );
        if current.stage.is_done() {
            self.current = None;
        }
        self.book.heard(&events);
        events
    }

    fn busy(&self) -> bool {
        self.book.busy()
    }

    fn waiting_for(&self) -> Option<Duration> {
        self.book.waiting_for()
    }

    fn needs_polling(&self) -> bool {
        self.current.is_some() || self.adapter.is_some() || !self.pending.is_empty()
    }
}

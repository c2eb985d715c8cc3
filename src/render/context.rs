//! Adapter and device for headless use (CLI, tests). The app gets its device from eframe.
//! What an error scope caught, asked in a way a page can too.

#[cfg(not(target_arch = "wasm32"))]
use super::RenderError;

#[cfg(not(target_arch = "wasm32"))]
pub struct GpuContext {
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub adapter_info: wgpu::AdapterInfo,
}

/// Features used when the adapter has them (timestamps make the benchmark show per-pass times).
pub fn optional_features() -> wgpu::Features {
    wgpu::Features::TIMESTAMP_QUERY
}

#[cfg(not(target_arch = "wasm32"))]
impl GpuContext {
    /// A device on the adapter `headless_adapter` picks.
    pub fn new_headless() -> Result<Self, RenderError> {
        Self::from_adapter(&headless_adapter()?)
    }

    fn from_adapter(adapter: &wgpu::Adapter) -> Result<Self, RenderError> {
        let adapter_info = adapter.get_info();
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("shadowlab"),
            required_features: adapter.features() & optional_features(),
            required_limits: adapter.limits(),
            experimental_features: wgpu::ExperimentalFeatures::disabled(),
            memory_hints: wgpu::MemoryHints::Performance,
            trace: wgpu::Trace::Off,
        }))
        .map_err(|e| RenderError::Device(e.to_string()))?;
        Ok(Self { device, queue, adapter_info })
    }

    /// "llvmpipe (LLVM 15.0.6, 256 bits) via Vulkan (Cpu)".
    pub fn describe(&self) -> String {
        describe_adapter(&self.adapter_info)
    }
}

pub fn describe_adapter(info: &wgpu::AdapterInfo) -> String {
    format!("{} via {:?} ({:?})", info.name, info.backend, info.device_type)
}

/// What an error scope caught (`popped`: its `pop()`). The desktop waits for the answer. A page
/// cannot wait: where the browser answers later (WebGPU) the error goes to the browser's console
/// when it comes, and this returns None.
pub(crate) fn scope_error(
    popped: impl Future<Output = Option<wgpu::Error>> + 'static,
) -> Option<wgpu::Error> {
    #[cfg(not(target_arch = "wasm32"))]
    {
        pollster::block_on(popped)
    }
    #[cfg(target_arch = "wasm32")]
    {
        let mut popped = Box::pin(popped);
        let mut cx = std::task::Context::from_waker(std::task::Waker::noop());
        match popped.as_mut().poll(&mut cx) {
            std::task::Poll::Ready(error) => error,
            std::task::Poll::Pending => {
                wasm_bindgen_futures::spawn_local(async move {
                    if let Some(e) = popped.await {
                        log::error!("GPU error: {e}");
                    }
                });
                None
            }
        }
    }
}

/// An adapter on the backends named by `WGPU_BACKEND` (`vulkan`, `gl`, ...); by default Vulkan,
/// and OpenGL only where Vulkan has none (GL probing prints noise on headless machines).
#[cfg(not(target_arch = "wasm32"))]
pub fn headless_adapter() -> Result<wgpu::Adapter, RenderError> {
    let attempts = match wgpu::Backends::from_env() {
        Some(backends) => vec![backends],
        None => vec![wgpu::Backends::VULKAN, wgpu::Backends::GL],
    };
    let mut failure = String::new();
    for backends in attempts {
        let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
        desc.backends = backends;
        let instance = wgpu::Instance::new(desc);
        match pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: None,
            apply_limit_buckets: false,
        })) {
            Ok(adapter) => return Ok(adapter),
            Err(e) => failure = format!("{backends:?}: {e}"),
        }
    }
    Err(RenderError::NoAdapter(failure))
}

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

/// What every device shadowlab opens asks for: the adapter's limits, the optional features it
/// has, and memory in small blocks. On a software adapter device memory is the process's own,
/// and a page of a block, once touched, stays resident while the block lives. wgpu's default
/// blocks (128-256 MB) outlive the targets and read-backs that come and go in them, so the
/// process would keep the most it ever used; blocks of 8-64 MB, freed when empty, follow what
/// is alive.
pub fn device_descriptor(adapter: &wgpu::Adapter, label: &'static str) -> wgpu::DeviceDescriptor<'static> {
    wgpu::DeviceDescriptor {
        label: Some(label),
        required_features: adapter.features() & optional_features(),
        required_limits: adapter.limits(),
        experimental_features: wgpu::ExperimentalFeatures::disabled(),
        memory_hints: wgpu::MemoryHints::MemoryUsage,
        trace: wgpu::Trace::Off,
    }
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
        let (device, queue) =
            pollster::block_on(adapter.request_device(&device_descriptor(adapter, "shadowlab")))
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

/// A wgpu error on one line, its sources joined.
pub fn error_line(e: &wgpu::Error) -> String {
    let mut message = e.to_string();
    let mut source = std::error::Error::source(e);
    while let Some(cause) = source {
        message += &format!(": {cause}");
        source = cause.source();
    }
    message.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// An error scope's answer asked for without waiting (`popped`: its `pop()`): the desktop has
/// it at once; a page's browser answers on a later frame, and `poll` says so until it has.
pub struct ScopeAnswer(ScopeState);

enum ScopeState {
    Known(Option<String>),
    #[cfg(target_arch = "wasm32")]
    Coming(std::pin::Pin<Box<dyn Future<Output = Option<wgpu::Error>>>>),
}

impl ScopeAnswer {
    pub fn new(popped: impl Future<Output = Option<wgpu::Error>> + 'static) -> Self {
        #[cfg(not(target_arch = "wasm32"))]
        return Self(ScopeState::Known(pollster::block_on(popped).map(|e| error_line(&e))));
        #[cfg(target_arch = "wasm32")]
        {
            let mut answer = Self(ScopeState::Coming(Box::pin(popped)));
            let _ = answer.poll();
            answer
        }
    }

    /// The error the scope caught (None: none), once the answer is in.
    pub fn poll(&mut self) -> std::task::Poll<Option<String>> {
        #[cfg(target_arch = "wasm32")]
        if let ScopeState::Coming(popped) = &mut self.0 {
            // A browser's promise keeps its result until asked again: no waker is needed.
            let mut cx = std::task::Context::from_waker(std::task::Waker::noop());
            match popped.as_mut().poll(&mut cx) {
                std::task::Poll::Ready(error) => self.0 = ScopeState::Known(error.map(|e| error_line(&e))),
                std::task::Poll::Pending => return std::task::Poll::Pending,
            }
        }
        match &self.0 {
            ScopeState::Known(error) => std::task::Poll::Ready(error.clone()),
            #[cfg(target_arch = "wasm32")]
            ScopeState::Coming(_) => std::task::Poll::Pending,
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

//! The renderer: offscreen, into textures it owns. It knows nothing of windows, egui or files;
//! the app shows its textures, the CLI and the tests read them back.

mod analysis;
mod camera_pass;
mod context;
mod frame;
pub mod gpu_types;
mod layouts;
mod moments;
mod pipelines;
mod prepare;
pub mod readback;
mod reference_pass;
mod scene_gpu;
pub mod shaders;
mod shadow_pass;
mod targets;
mod timing;

use crate::shadow::gpu::MAX_SHADOW_VIEWS;
use crate::shadow::{DepthImage, LightGpu, ShadowParamsGpu, ShadowViewGpu, frame_lights, views_needed};
pub use analysis::{Analysis, AnalysisPixel, MomentsLevel};
pub(crate) use context::scope_error;
#[cfg(not(target_arch = "wasm32"))]
pub use context::{GpuContext, headless_adapter};
pub use context::{ScopeAnswer, error_line};
pub use context::{describe_adapter, device_descriptor, optional_features};
pub use frame::{Frame, FrameRequest};
pub use pipelines::pipelines_built;
pub use readback::{GpuWait, Readback};
pub use reference_pass::{Batches, GroundTruth, GroundTruthProgress};
pub use targets::COLOR_FORMAT;
pub use timing::PassTimes;

use crate::scene::{MAX_LIGHTS, Scene, ShadowSettings, Technique};
use crate::shadow::kernels::{MAX_TAPS, filter_taps, kernel_table};
use gpu_types::{DYNAMIC_STRIDE, FrameGpu};
use layouts::Layouts;
use moments::Moments;
use pipelines::{CameraOutputs, CameraPipelineKey, Pipelines};
use scene_gpu::SceneGpu;
use targets::{ShadowMaps, ShadowMapsKey, ShadowPipelineKey, ViewTargets};

#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    #[error(
        "no GPU adapter found ({0}); install a Vulkan or OpenGL driver, e.g. `apt-get install mesa-vulkan-drivers` for a software one"
    )]
    NoAdapter(String),
    #[error("could not open the GPU device: {0}")]
    Device(String),
    #[error("{0}")]
    Limits(String),
    #[error("reading back from the GPU failed: {0}")]
    Readback(String),
    #[error("{0}")]
    Usage(String),
}

pub struct Renderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    layouts: Layouts,
    pipelines: Pipelines,
    frame_buffer: wgpu::Buffer,
    lights_buffer: wgpu::Buffer,
    /// Every light's shadow views, as the camera pass indexes them.
    views_buffer: wgpu::Buffer,
    params_buffer: wgpu::Buffer,
    shadow_view_buffer: wgpu::Buffer,
    /// Unit-disk patterns, unrotated: tap i of the filter in xy, of the blocker search in zw.
    kernel_table_buffer: wgpu::Buffer,
    frame_bind_group: wgpu::BindGroup,
    shadow_view_bind_group: wgpu::BindGroup,
    /// Group 3 while a view's albedo cache is being filled (a pass cannot read what it writes).
    albedo_placeholder: targets::AlbedoCache,
    compare_sampler: wgpu::Sampler,
    shadow_maps: Option<ShadowMaps>,
    /// The maps' VSM moments, made with them and rebuilt for frames that use VSM.
    moments: Option<Moments>,
    /// Told (samples done, samples in all) as a ground truth accumulates (the CLI's progress bar).
    reference_ticker: Option<Box<dyn FnMut(u32, u32) + Send>>,
    lights_bind_group: Option<wgpu::BindGroup>,
    scene_gpu: Option<SceneGpu>,
    targets: Option<ViewTargets>,
    /// The targets of the size used before (the app alternates its view's size with a lesson
    /// probe's frame): kept so that switching back allocates nothing.
    spare_targets: Option<ViewTargets>,
    timer: Option<timing::Timer>,
    /// The last frame rendered: its targets are the ones the read-backs and the ground truth use.
    last_frame: Option<Frame>,
}

fn uniform_buffer(device: &wgpu::Device, label: &str, size: u64) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

fn compare_sampler(device: &wgpu::Device) -> wgpu::Sampler {
    device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some("shadow compare"),
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        compare: Some(wgpu::CompareFunction::LessEqual),
        ..Default::default()
    })
}

impl Renderer {
    /// Build the pipelines. Fails (rather than panicking) where the adapter cannot compile them.
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue) -> Result<Self, RenderError> {
        let internal = device.push_error_scope(wgpu::ErrorFilter::Internal);
        let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let layouts = Layouts::new(device);
        let pipelines = Pipelines::new(device, &layouts);
        let error = scope_error(validation.pop()).or(scope_error(internal.pop()));
        if let Some(e) = error {
            return Err(RenderError::Device(format!(
                "this adapter cannot build shadowlab's pipelines: {}",
                first_cause(&e)
            )));
        }
        let frame_buffer = uniform_buffer(device, "frame", std::mem::size_of::<FrameGpu>() as u64);
        let lights_buffer =
            uniform_buffer(device, "lights", (std::mem::size_of::<LightGpu>() * MAX_LIGHTS) as u64);
        let params_buffer =
            uniform_buffer(device, "shadow params", std::mem::size_of::<ShadowParamsGpu>() as u64);
        let views_buffer = uniform_buffer(
            device,
            "shadow views",
            (std::mem::size_of::<ShadowViewGpu>() * MAX_SHADOW_VIEWS) as u64,
        );
        let shadow_view_buffer =
            uniform_buffer(device, "shadow pass views", DYNAMIC_STRIDE * MAX_SHADOW_VIEWS as u64);
        let kernel_table_buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("kernel table"),
            size: u64::from(MAX_TAPS) * 16,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let frame_bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("frame"),
            layout: &layouts.frame,
            entries: &[wgpu::BindGroupEntry { binding: 0, resource: frame_buffer.as_entire_binding() }],
        });
        let shadow_view_bind_group = shadow_view_group(device, &layouts, &shadow_view_buffer);
        let timer = device
            .features()
            .contains(wgpu::Features::TIMESTAMP_QUERY)
            .then(|| timing::Timer::new(device, queue));
        let albedo_placeholder = targets::AlbedoCache::placeholder(device, &layouts.albedo_cache);
        Ok(Self {
            albedo_placeholder,
            device: device.clone(),
            queue: queue.clone(),
            compare_sampler: compare_sampler(device),
            layouts,
            pipelines,
            frame_buffer,
            lights_buffer,
            views_buffer,
            params_buffer,
            shadow_view_buffer,
            kernel_table_buffer,
            frame_bind_group,
            shadow_view_bind_group,
            shadow_maps: None,
            moments: None,
            reference_ticker: None,
            lights_bind_group: None,
            scene_gpu: None,
            targets: None,
            spare_targets: None,
            timer,
            last_frame: None,
        })
    }

    pub fn device(&self) -> &wgpu::Device {
        &self.device
    }

    pub fn queue(&self) -> &wgpu::Queue {
        &self.queue
    }

    pub fn has_timestamps(&self) -> bool {
        self.timer.is_some()
    }

    /// Check a scene against this device's limits before rendering it.
    pub fn check_scene(&self, scene: &Scene) -> Result<(), RenderError> {
        let limits = self.device.limits();
        for (i, light) in scene.lights.iter().enumerate() {
            if light.shadow_map_size > limits.max_texture_dimension_2d {
                return Err(RenderError::Limits(format!(
                    "light {i}: shadow_map_size {} exceeds this device's limit of {} texels",
                    light.shadow_map_size, limits.max_texture_dimension_2d
                )));
            }
        }
        Ok(())
    }

    /// Run `work`, turning wgpu validation and out-of-memory errors into a `RenderError`
    /// (wgpu's default handler would panic).
    pub(crate) fn guarded<T>(
        &mut self,
        work: impl FnOnce(&mut Self) -> Result<T, RenderError>,
    ) -> Result<T, RenderError> {
        let memory = self.device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let internal = self.device.push_error_scope(wgpu::ErrorFilter::Internal);
        let validation = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let result = work(self);
        let validation_error = scope_error(validation.pop());
        let internal_error = scope_error(internal.pop());
        let memory_error = scope_error(memory.pop());
        match (validation_error.or(internal_error).or(memory_error), result) {
            (Some(e), _) => Err(RenderError::Device(
                e.to_string().lines().next().unwrap_or("GPU error").to_string() + " " + &first_cause(&e),
            )),
            (None, result) => result,
        }
    }

    /// Render one frame into the renderer's own targets (read them back with `read_*` until the
    /// next render).
    pub fn render(&mut self, scene: &Scene, request: &FrameRequest) -> Result<Frame, RenderError> {
        self.guarded(|r| r.render_unguarded(scene, request))
    }

    /// The last frame rendered.
    pub fn last_frame(&self) -> Option<&Frame> {
        self.last_frame.as_ref()
    }

    fn render_unguarded(&mut self, scene: &Scene, request: &FrameRequest) -> Result<Frame, RenderError> {
        self.check_scene(scene)?;
        let (width, height) = request.size;
        let max_dim = self.device.limits().max_texture_dimension_2d;
        if width == 0 || height == 0 || width > max_dim || height > max_dim {
            return Err(RenderError::Usage(format!(
                "image size {width}x{height} must be 1..={max_dim} on each side"
            )));
        }
        if !scene.lights.is_empty() && request.selected_light >= scene.lights.len() {
            return Err(RenderError::Usage(format!(
                "light {} does not exist (the scene has {})",
                request.selected_light,
                scene.lights.len()
            )));
        }
        let (lights, views, params) = self.prepare(scene, request);
        let (albedo_from_cache, fill_albedo_cache) = self.plan_albedo_cache(scene, request);
        let unprepared = || RenderError::Usage("the renderer's resources were not made".into());
        let scene_gpu = self.scene_gpu.as_ref().ok_or_else(unprepared)?;
        let (Some(maps), Some(targets), Some(lights_group)) =
            (&self.shadow_maps, &self.targets, &self.lights_bind_group)
        else {
            return Err(unprepared());
        };
        let key = ShadowPipelineKey {
            depth_bias_constant: scene.shadow.depth_bias_constant,
            depth_bias_slope_bits: scene.shadow.depth_bias_slope.to_bits(),
            cull_front_faces: scene.shadow.cull_front_faces,
            stores_distance: false,
        };
        let shadow_pipeline = self.pipelines.shadow(&self.device, key).clone();
        let distance_pipeline = (views.iter().any(|v| v.cube == 1)).then(|| {
            self.pipelines.shadow(&self.device, ShadowPipelineKey { stores_distance: true, ..key }).clone()
        });
        let maps_key = ShadowMapsKey {
            views: (views.iter())
                .map(|view| {
                    let matrix: [f32; 16] = bytemuck::cast(view.clip_from_world);
                    (matrix.map(f32::to_bits), view.map_size_texels as u32)
                })
                .collect(),
            object_transforms: SceneGpu::object_transforms(scene, request.time_s),
            scene_upload: scene_gpu.generation,
            pipeline: key,
        };
        let shadow_maps_kept = maps.drawn_for.as_ref() == Some(&maps_key);
        // Colour and analysis together come from one pass (one filtering of the selected light).
        let shaded_outputs = match (request.final_color, request.analysis) {
            (true, true) => Some(CameraOutputs::FinalAndAnalysis),
            (true, false) => Some(CameraOutputs::Final),
            (false, _) => None,
        };
        // The pre-pass shades each pixel once; where shading is cheap (no lookup, or one tap) and
        // one pass follows, that pass's own depth test costs less than a second trip over the
        // geometry.
        let cheap = matches!(scene.shadow.technique, Technique::None | Technique::Hard);
        let depth_prepass = !(cheap && request.final_color && request.only_pixel.is_none());
        let mut pipeline = |outputs, from_cache| {
            let key = CameraPipelineKey::new(&params, &lights, &views, outputs, from_cache);
            let key = CameraPipelineKey { after_prepass: depth_prepass, ..key };
            self.pipelines.camera(&self.device, key).clone()
        };
        let shaded_pipeline = shaded_outputs.map(|o| pipeline(o, false));
        let from_cache_pipeline = shaded_outputs.filter(|_| albedo_from_cache).map(|o| pipeline(o, true));
        let analysis_pipeline =
            (request.analysis && !request.final_color).then(|| pipeline(CameraOutputs::Analysis, false));
        let timer = self.timer.as_ref().filter(|_| request.timestamps);
        let mut encoder =
            self.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("frame") });
        let vsm = scene.shadow.technique.uses_moments();
        if !shadow_maps_kept {
            shadow_pass::encode(
                &mut encoder,
                &views,
                scene_gpu,
                maps,
                shadow_pass::Pipelines { projected: &shadow_pipeline, distance: distance_pipeline.as_ref() },
                &self.shadow_view_bind_group,
                timer,
                !vsm,
            );
        }
        let mut moments_built = false;
        if let Some(moments) = &mut self.moments {
            if !shadow_maps_kept {
                moments.current = false;
            }
            if vsm && !moments.current {
                moments.encode(&mut encoder, &self.pipelines.moments, maps.layers, timer, shadow_maps_kept);
                moments_built = true;
            }
        }
        let camera = camera_pass::CameraPasses {
            depth_only: &self.pipelines.camera_depth,
            shaded: shaded_pipeline.as_ref(),
            shaded_writes_analysis: shaded_outputs == Some(CameraOutputs::FinalAndAnalysis),
            depth_prepass,
            shaded_from_cache: from_cache_pipeline.as_ref(),
            analysis: analysis_pipeline.as_ref(),
            fill_albedo_cache: fill_albedo_cache.then_some(&self.pipelines.camera_albedo),
            frame_group: &self.frame_bind_group,
            lights_group,
            albedo_placeholder: &self.albedo_placeholder.bind_group,
        };
        camera.encode(&mut encoder, request, targets, scene, scene_gpu, timer);
        if let Some(t) = timer {
            t.resolve(&mut encoder);
        }
        self.queue.submit([encoder.finish()]);
        if let Some(maps) = &mut self.shadow_maps {
            maps.drawn_for = Some(maps_key);
        }
        let frame = Frame {
            request: *request,
            lights,
            views,
            params,
            albedo_from_cache,
            shadow_maps_kept,
            moments_built,
        };
        self.last_frame = Some(frame.clone());
        Ok(frame)
    }

    /// GPU time of the shadow passes and the camera passes of the last frame rendered with
    /// `timestamps: true` (None where the adapter has no timestamp queries).
    pub fn last_pass_times(&self) -> Result<Option<PassTimes>, RenderError> {
        self.pass_times_readback().wait(&self.device)
    }

    /// `last_pass_times`, on its way back.
    pub fn pass_times_readback(&self) -> Readback<Option<PassTimes>> {
        let kept = self.last_frame.as_ref().is_some_and(|f| f.shadow_maps_kept && !f.moments_built);
        match &self.timer {
            // Kept maps cost nothing this frame (and wrote no timestamps).
            Some(t) => t.readback(&self.device, &self.queue).map(move |times| {
                Ok(Some(PassTimes { shadow_ms: if kept { 0.0 } else { times.shadow_ms }, ..times }))
            }),
            None => Readback::ready(None),
        }
    }

    /// Wait until the GPU has finished everything submitted.
    pub fn wait_idle(&self) -> Result<(), RenderError> {
        GpuWait::Block.poll(&self.device)
    }

    /// The camera view's colour texture (Rgba8Unorm holding sRGB-encoded bytes).
    pub fn color_texture(&self) -> Option<&wgpu::Texture> {
        self.targets.as_ref().map(|t| &t.color)
    }

    fn targets(&self) -> Result<&ViewTargets, RenderError> {
        self.targets.as_ref().ok_or_else(|| RenderError::Usage("nothing rendered yet".into()))
    }

    /// The camera view as sRGB RGBA8.
    pub fn read_color(&self) -> Result<image::RgbaImage, RenderError> {
        self.color_readback()?.wait(&self.device)
    }

    /// `read_color`, on its way back.
    pub fn color_readback(&self) -> Result<Readback<image::RgbaImage>, RenderError> {
        let targets = self.targets()?;
        let (w, h) = targets.size;
        let region = readback::Region::whole(0, targets.size, 4, wgpu::TextureAspect::All);
        Ok(Readback::texture(&self.device, &self.queue, &targets.color, region, move |mapped| {
            image::RgbaImage::from_raw(w, h, mapped.to_vec())
                .ok_or_else(|| RenderError::Readback("colour buffer has the wrong size".into()))
        }))
    }

    /// The map of shadow view `index` (of the last frame's `views`) as rendered in that frame.
    pub fn read_shadow_map(&self, index: usize) -> Result<DepthImage, RenderError> {
        self.shadow_map_readback(index)?.wait(&self.device)
    }

    /// Every map of light `light` of the last frame, in the order of its views (a point light's
    /// six faces: what its twin reads, `Twin::for_views`).
    pub fn read_light_maps(&self, light: usize) -> Result<Vec<DepthImage>, RenderError> {
        let frame =
            self.last_frame.as_ref().ok_or_else(|| RenderError::Usage("nothing rendered yet".into()))?;
        let (first, views) = frame
            .views_of(light)
            .ok_or_else(|| RenderError::Usage(format!("light {light} does not exist in the last frame")))?;
        let readbacks: Vec<_> =
            (first..first + views.len()).map(|i| self.shadow_map_readback(i)).collect::<Result<_, _>>()?;
        readbacks.into_iter().map(|r| r.wait(&self.device)).collect()
    }

    /// `read_shadow_map`, on its way back.
    pub fn shadow_map_readback(&self, index: usize) -> Result<Readback<DepthImage>, RenderError> {
        let maps =
            self.shadow_maps.as_ref().ok_or_else(|| RenderError::Usage("nothing rendered yet".into()))?;
        let views = self.last_frame.as_ref().map_or(&[][..], |f| &f.views[..]);
        let view = views.get(index).ok_or_else(|| {
            RenderError::Usage(format!("shadow view {index} does not exist (the frame has {})", views.len()))
        })?;
        // A view with a smaller map uses the top-left corner of its layer. Depth textures are
        // copied whole (wgpu allows no partial depth copy), the corner is kept.
        let size = view.map_size_texels as u32;
        let atlas = maps.atlas_size;
        let region = readback::Region::whole(view.layer, (atlas, atlas), 4, wgpu::TextureAspect::DepthOnly);
        Ok(Readback::texture(&self.device, &self.queue, &maps.texture, region, move |mapped| {
            let mut depth_ndc = Vec::with_capacity((size * size) as usize);
            for row in mapped.rows().take(size as usize) {
                depth_ndc.extend(readback::f32s(&row[..4 * size as usize]));
            }
            Ok(DepthImage { size, depth_ndc })
        }))
    }
}

/// The innermost cause of a wgpu error, on one line (shader compiler logs cut short).
fn first_cause(e: &wgpu::Error) -> String {
    let mut source: Option<&dyn std::error::Error> = std::error::Error::source(e);
    let mut last = String::new();
    while let Some(s) = source {
        last = s.to_string();
        source = s.source();
    }
    let line = last.replace('\n', " ");
    match line.char_indices().nth(240) {
        Some((cut, _)) => format!("{}...", &line[..cut]),
        None => line,
    }
}

/// Background of the camera view, linear: the sRGB view stores it as the bytes of sRGB
/// (0.16, 0.17, 0.20).
pub(crate) const BACKGROUND: wgpu::Color = wgpu::Color { r: 0.021_981, g: 0.024_515, b: 0.033_105, a: 1.0 };

fn shadow_view_group(device: &wgpu::Device, layouts: &Layouts, buffer: &wgpu::Buffer) -> wgpu::BindGroup {
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("shadow view"),
        layout: &layouts.shadow_view,
        entries: &[wgpu::BindGroupEntry {
            binding: 0,
            resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                buffer,
                offset: 0,
                size: std::num::NonZeroU64::new(std::mem::size_of::<ShadowViewGpu>() as u64),
            }),
        }],
    })
}

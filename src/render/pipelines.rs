//! Pipelines, for the bind group layouts of `layouts.rs` and the formats of `targets.rs`.

use super::layouts::Layouts;
use super::moments::MomentsPipelines;
use super::shaders;
use super::targets::{
    ALBEDO_CACHE_FORMAT, ANALYSIS_FORMAT, COLOR_TARGET_FORMAT, DEPTH_FORMAT, ShadowPipelineKey,
};
use crate::scene::Vertex;
use crate::shadow::{LightGpu, ShadowParamsGpu, ShadowViewGpu};
use std::collections::HashMap;
use std::sync::atomic::{AtomicU64, Ordering};

/// The targets a camera pass writes.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub enum CameraOutputs {
    /// `fs_final`: the shaded colour.
    Final,
    /// `fs_analysis`: the selected light's shadow terms, position and normal (float targets).
    Analysis,
    /// `fs_final_and_analysis`: both from one filtering of the selected light.
    FinalAndAnalysis,
}

/// What a camera pipeline is specialised for: the switch values of shaders/specialisation.wgsl
/// (as `ShadowParamsGpu` numbers them) and which fragment entry point it runs.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub struct CameraPipelineKey {
    pub technique: u32,
    pub kernel: u32,
    pub bias_mode: u32,
    pub clamp_outside: u32,
    pub depth_storage: u32,
    /// What all lights share (SPEC_* in the shader; 0 = mixed).
    pub projection: u32,
    pub size_model: u32,
    pub light_count: u32,
    /// What the fragment shader writes: colour, the analysis floats, or both.
    pub outputs: CameraOutputs,
    /// Still textured objects read their albedo from the view's cache (ALBEDO_FROM_CACHE).
    pub albedo_from_cache: bool,
    /// The depth pre-pass ran: test against its depth (LessEqual, no writes). Without it the
    /// pass keeps the nearest fragment itself (LessEqual, writes: of fragments at equal depth
    /// the last drawn wins, as after the pre-pass).
    pub after_prepass: bool,
}

impl CameraPipelineKey {
    pub fn new(
        params: &ShadowParamsGpu,
        lights: &[LightGpu],
        views: &[ShadowViewGpu],
        outputs: CameraOutputs,
        albedo_from_cache: bool,
    ) -> Self {
        // 1 or 2 where every light (or view) agrees (SPEC_ALL_*), 0 where they differ or there
        // are none.
        fn shared<T>(items: &[T], value: fn(&T) -> u32) -> u32 {
            match items.split_first() {
                Some((first, rest)) if rest.iter().all(|l| value(l) == value(first)) => value(first) + 1,
                _ => 0,
            }
        }
        Self {
            technique: params.technique,
            kernel: params.kernel,
            bias_mode: params.bias_mode,
            clamp_outside: params.clamp_outside,
            depth_storage: params.depth_storage,
            // SPEC_ALL_ORTHOGRAPHIC = 1, SPEC_ALL_PERSPECTIVE = 2, SPEC_ALL_CUBE = 3.
            // A directional light's views are orthographic, a spot light's perspective, a point
            // light's cube faces.
            projection: shared(views, |v| if v.cube == 1 { 2 } else { 1 - v.orthographic.min(1) }),
            // SPEC_ALL_WIDTH = 1, SPEC_ALL_ANGULAR = 2.
            size_model: shared(lights, |l| l.size_model.min(1)),
            light_count: lights.len() as u32,
            outputs,
            albedo_from_cache: albedo_from_cache && outputs != CameraOutputs::Analysis,
            after_prepass: true,
        }
    }
}

/// Specialised pipelines built so far by every renderer of this process. Each stays cached
/// for its renderer's life, so a long session's memory grows with every new combination of
/// settings until all it uses are built (`bench --app --window --soak` reports it beside memory).
static PIPELINES_BUILT: AtomicU64 = AtomicU64::new(0);

pub fn pipelines_built() -> u64 {
    PIPELINES_BUILT.load(Ordering::Relaxed)
}

pub struct Pipelines {
    shadow_module: wgpu::ShaderModule,
    shadow_layout: wgpu::PipelineLayout,
    shadow: HashMap<ShadowPipelineKey, wgpu::RenderPipeline>,
    camera_module: wgpu::ShaderModule,
    camera_layout: wgpu::PipelineLayout,
    camera: HashMap<CameraPipelineKey, wgpu::RenderPipeline>,
    /// The camera's depth pre-pass: depth only, no fragment shader.
    pub camera_depth: wgpu::RenderPipeline,
    /// Fills the view's albedo cache (`fs_albedo`).
    pub camera_albedo: wgpu::RenderPipeline,
    pub reference: wgpu::ComputePipeline,
    pub moments: MomentsPipelines,
}

fn vertex_layout() -> wgpu::VertexBufferLayout<'static> {
    const ATTRIBUTES: [wgpu::VertexAttribute; 3] =
        wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x2];
    wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<Vertex>() as u64,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &ATTRIBUTES,
    }
}

fn module(device: &wgpu::Device, source: shaders::ShaderSource) -> wgpu::ShaderModule {
    device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(source.name),
        source: wgpu::ShaderSource::Wgsl(source.source.into()),
    })
}

/// The camera passes after the depth pre-pass: only the nearest surface (already in the depth
/// buffer) passes, so each pixel is shaded once however much geometry overlaps it.
fn depth_state_after_prepass() -> wgpu::DepthStencilState {
    wgpu::DepthStencilState {
        format: DEPTH_FORMAT,
        depth_write_enabled: Some(false),
        depth_compare: Some(wgpu::CompareFunction::LessEqual),
        stencil: wgpu::StencilState::default(),
        bias: wgpu::DepthBiasState::default(),
    }
}

fn depth_state(bias: wgpu::DepthBiasState) -> wgpu::DepthStencilState {
    wgpu::DepthStencilState {
        format: DEPTH_FORMAT,
        depth_write_enabled: Some(true),
        depth_compare: Some(wgpu::CompareFunction::Less),
        stencil: wgpu::StencilState::default(),
        bias,
    }
}

impl Pipelines {
    pub fn new(device: &wgpu::Device, layouts: &Layouts) -> Self {
        let shadow_module = module(device, shaders::shadow_pass());
        let camera_module = module(device, shaders::camera());
        let reference_module = module(device, shaders::reference());
        let moments = MomentsPipelines::new(device, &module(device, shaders::moments()));
        let shadow_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("shadow pass"),
            bind_group_layouts: &[Some(&layouts.shadow_view), Some(&layouts.object)],
            immediate_size: 0,
        });
        let camera_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("camera pass"),
            bind_group_layouts: &[
                Some(&layouts.frame),
                Some(&layouts.lights),
                Some(&layouts.object),
                Some(&layouts.albedo_cache),
            ],
            immediate_size: 0,
        });
        let reference_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("reference"),
            bind_group_layouts: &[Some(&layouts.reference_io), Some(&layouts.reference_light)],
            immediate_size: 0,
        });
        let reference = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("reference"),
            layout: Some(&reference_layout),
            module: &reference_module,
            entry_point: Some("cs_accumulate"),
            compilation_options: Default::default(),
            cache: None,
        });
        // Both write the camera view's depth from the camera's own vertex shader.
        let writes_depth = |label, fragment| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(label),
                layout: Some(&camera_layout),
                vertex: wgpu::VertexState {
                    module: &camera_module,
                    entry_point: Some("vs_camera"),
                    compilation_options: Default::default(),
                    buffers: &[Some(vertex_layout())],
                },
                primitive: wgpu::PrimitiveState { cull_mode: None, ..Default::default() },
                depth_stencil: Some(depth_state(wgpu::DepthBiasState::default())),
                multisample: wgpu::MultisampleState::default(),
                fragment,
                multiview_mask: None,
                cache: None,
            })
        };
        let camera_depth = writes_depth("camera depth pre-pass", None);
        let camera_albedo = writes_depth(
            "camera albedo cache",
            Some(wgpu::FragmentState {
                module: &camera_module,
                entry_point: Some("fs_albedo"),
                compilation_options: Default::default(),
                targets: &[Some(ALBEDO_CACHE_FORMAT.into())],
            }),
        );
        let mut pipelines = Self {
            shadow_module,
            shadow_layout,
            shadow: HashMap::new(),
            camera_module,
            camera_layout,
            camera: HashMap::new(),
            camera_depth,
            camera_albedo,
            reference,
            moments,
        };
        // Build the default variants now, so that a device that cannot compile them fails here.
        let defaults = ShadowParamsGpu::new(&Default::default());
        for outputs in [CameraOutputs::Final, CameraOutputs::Analysis, CameraOutputs::FinalAndAnalysis] {
            pipelines.camera(device, CameraPipelineKey::new(&defaults, &[], &[], outputs, false));
        }
        pipelines.camera(device, CameraPipelineKey::new(&defaults, &[], &[], CameraOutputs::Final, true));
        pipelines
    }

    /// The camera pipeline specialised for `key`, built on first use.
    pub fn camera(&mut self, device: &wgpu::Device, key: CameraPipelineKey) -> &wgpu::RenderPipeline {
        let (module, layout) = (&self.camera_module, &self.camera_layout);
        self.camera.entry(key).or_insert_with(|| {
            PIPELINES_BUILT.fetch_add(1, Ordering::Relaxed);
            let constants = [
                ("SPECIALISED", 1.0),
                ("SPEC_TECHNIQUE", f64::from(key.technique)),
                ("SPEC_KERNEL", f64::from(key.kernel)),
                ("SPEC_BIAS_MODE", f64::from(key.bias_mode)),
                ("SPEC_CLAMP_OUTSIDE", f64::from(key.clamp_outside)),
                ("SPEC_DEPTH_STORAGE", f64::from(key.depth_storage)),
                ("SPEC_PROJECTION", f64::from(key.projection)),
                ("SPEC_SIZE_MODEL", f64::from(key.size_model)),
                ("SPEC_LIGHT_COUNT", f64::from(key.light_count)),
                ("ALBEDO_FROM_CACHE", if key.albedo_from_cache { 1.0 } else { 0.0 }),
            ];
            let options = wgpu::PipelineCompilationOptions { constants: &constants, ..Default::default() };
            let analysis_target = Some(wgpu::ColorTargetState::from(ANALYSIS_FORMAT));
            let final_targets = [Some(COLOR_TARGET_FORMAT.into())];
            let analysis_targets =
                [analysis_target.clone(), analysis_target.clone(), analysis_target.clone()];
            let both_targets =
                [final_targets[0].clone(), analysis_target.clone(), analysis_target.clone(), analysis_target];
            let (label, entry, targets): (_, _, &[Option<wgpu::ColorTargetState>]) = match key.outputs {
                CameraOutputs::Final => ("camera final", "fs_final", &final_targets),
                CameraOutputs::Analysis => ("camera analysis", "fs_analysis", &analysis_targets),
                CameraOutputs::FinalAndAnalysis => {
                    ("camera final and analysis", "fs_final_and_analysis", &both_targets)
                }
            };
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(label),
                layout: Some(layout),
                vertex: wgpu::VertexState {
                    module,
                    entry_point: Some("vs_camera"),
                    compilation_options: options.clone(),
                    buffers: &[Some(vertex_layout())],
                },
                primitive: wgpu::PrimitiveState { cull_mode: None, ..Default::default() },
                depth_stencil: Some(match key.after_prepass {
                    true => depth_state_after_prepass(),
                    false => wgpu::DepthStencilState {
                        depth_write_enabled: Some(true),
                        ..depth_state_after_prepass()
                    },
                }),
                multisample: wgpu::MultisampleState::default(),
                fragment: Some(wgpu::FragmentState {
                    module,
                    entry_point: Some(entry),
                    compilation_options: options,
                    targets,
                }),
                multiview_mask: None,
                cache: None,
            })
        })
    }

    /// The shadow-pass pipeline for these settings, built on first use.
    pub fn shadow(&mut self, device: &wgpu::Device, key: ShadowPipelineKey) -> &wgpu::RenderPipeline {
        let (module, layout) = (&self.shadow_module, &self.shadow_layout);
        self.shadow.entry(key).or_insert_with(|| {
            PIPELINES_BUILT.fetch_add(1, Ordering::Relaxed);
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some("shadow pass"),
                layout: Some(layout),
                vertex: wgpu::VertexState {
                    module,
                    entry_point: Some(if key.stores_distance { "vs_shadow_distance" } else { "vs_shadow" }),
                    compilation_options: Default::default(),
                    buffers: &[Some(vertex_layout())],
                },
                primitive: wgpu::PrimitiveState {
                    cull_mode: key.cull_front_faces.then_some(wgpu::Face::Front),
                    ..Default::default()
                },
                depth_stencil: Some(depth_state(wgpu::DepthBiasState {
                    constant: key.depth_bias_constant,
                    slope_scale: f32::from_bits(key.depth_bias_slope_bits),
                    clamp: 0.0,
                })),
                multisample: wgpu::MultisampleState::default(),
                fragment: key.stores_distance.then_some(wgpu::FragmentState {
                    module,
                    entry_point: Some("fs_shadow_distance"),
                    compilation_options: Default::default(),
                    targets: &[],
                }),
                multiview_mask: None,
                cache: None,
            })
        })
    }
}

//! Bind group layouts and pipelines. Bind groups by update rate: 0 per frame, 1 lights and
//! shadow maps, 2 per object (the shadow pass uses 0 = light view, 1 = object).

use super::shaders;
use crate::scene::Vertex;
use std::collections::HashMap;

pub const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
pub const ANALYSIS_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// Number of float targets of the analysis pass: shadow terms, position, normal.
pub const ANALYSIS_TARGETS: usize = 3;

pub struct Layouts {
    pub frame: wgpu::BindGroupLayout,
    pub lights: wgpu::BindGroupLayout,
    pub object: wgpu::BindGroupLayout,
    pub shadow_view: wgpu::BindGroupLayout,
    pub reference_io: wgpu::BindGroupLayout,
    pub reference_light: wgpu::BindGroupLayout,
}

fn uniform_entry(binding: u32, visibility: wgpu::ShaderStages, dynamic: bool) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: dynamic,
            min_binding_size: None,
        },
        count: None,
    }
}

fn texture_entry(
    binding: u32,
    visibility: wgpu::ShaderStages,
    sample_type: wgpu::TextureSampleType,
    dim: wgpu::TextureViewDimension,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Texture { sample_type, view_dimension: dim, multisampled: false },
        count: None,
    }
}

fn sampler_entry(
    binding: u32,
    visibility: wgpu::ShaderStages,
    ty: wgpu::SamplerBindingType,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry { binding, visibility, ty: wgpu::BindingType::Sampler(ty), count: None }
}

/// Group 1 of the camera and reference shaders: light(s), params, shadow maps, compare sampler.
fn shadow_inputs_layout(device: &wgpu::Device, label: &str, dynamic_light: bool) -> wgpu::BindGroupLayout {
    let all = wgpu::ShaderStages::VERTEX_FRAGMENT | wgpu::ShaderStages::COMPUTE;
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(label),
        entries: &[
            uniform_entry(0, all, dynamic_light),
            uniform_entry(1, all, false),
            texture_entry(2, all, wgpu::TextureSampleType::Depth, wgpu::TextureViewDimension::D2Array),
            sampler_entry(3, all, wgpu::SamplerBindingType::Comparison),
        ],
    })
}

impl Layouts {
    pub fn new(device: &wgpu::Device) -> Self {
        let vf = wgpu::ShaderStages::VERTEX_FRAGMENT;
        let float = |filterable| wgpu::TextureSampleType::Float { filterable };
        Self {
            frame: device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("frame"),
                entries: &[uniform_entry(0, vf, false)],
            }),
            lights: shadow_inputs_layout(device, "lights", false),
            object: device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("object"),
                entries: &[
                    uniform_entry(0, vf, false),
                    texture_entry(1, vf, float(true), wgpu::TextureViewDimension::D2),
                    sampler_entry(2, vf, wgpu::SamplerBindingType::Filtering),
                ],
            }),
            shadow_view: device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("shadow view"),
                entries: &[uniform_entry(0, wgpu::ShaderStages::VERTEX, true)],
            }),
            reference_io: device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("reference io"),
                entries: &[
                    texture_entry(
                        0,
                        wgpu::ShaderStages::COMPUTE,
                        float(false),
                        wgpu::TextureViewDimension::D2,
                    ),
                    texture_entry(
                        1,
                        wgpu::ShaderStages::COMPUTE,
                        float(false),
                        wgpu::TextureViewDimension::D2,
                    ),
                    wgpu::BindGroupLayoutEntry {
                        binding: 2,
                        visibility: wgpu::ShaderStages::COMPUTE,
                        ty: wgpu::BindingType::Buffer {
                            ty: wgpu::BufferBindingType::Storage { read_only: false },
                            has_dynamic_offset: false,
                            min_binding_size: None,
                        },
                        count: None,
                    },
                    uniform_entry(3, wgpu::ShaderStages::COMPUTE, false),
                ],
            }),
            reference_light: shadow_inputs_layout(device, "reference light", true),
        }
    }
}

/// What the shadow pipeline depends on: hardware depth bias and face culling.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub struct ShadowPipelineKey {
    pub depth_bias_constant: i32,
    pub depth_bias_slope_bits: u32,
    pub cull_front_faces: bool,
}

pub struct Pipelines {
    shadow_module: wgpu::ShaderModule,
    shadow_layout: wgpu::PipelineLayout,
    shadow: HashMap<ShadowPipelineKey, wgpu::RenderPipeline>,
    pub camera_final: wgpu::RenderPipeline,
    pub camera_analysis: wgpu::RenderPipeline,
    pub reference: wgpu::ComputePipeline,
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
        let shadow_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("shadow pass"),
            bind_group_layouts: &[Some(&layouts.shadow_view), Some(&layouts.object)],
            immediate_size: 0,
        });
        let camera_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("camera pass"),
            bind_group_layouts: &[Some(&layouts.frame), Some(&layouts.lights), Some(&layouts.object)],
            immediate_size: 0,
        });
        let reference_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("reference"),
            bind_group_layouts: &[Some(&layouts.reference_io), Some(&layouts.reference_light)],
            immediate_size: 0,
        });
        let camera_pipeline = |label: &str, entry: &str, targets: &[Option<wgpu::ColorTargetState>]| {
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
                fragment: Some(wgpu::FragmentState {
                    module: &camera_module,
                    entry_point: Some(entry),
                    compilation_options: Default::default(),
                    targets,
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        let camera_final = camera_pipeline("camera final", "fs_final", &[Some(COLOR_FORMAT.into())]);
        let analysis_target = Some(wgpu::ColorTargetState::from(ANALYSIS_FORMAT));
        let camera_analysis = camera_pipeline(
            "camera analysis",
            "fs_analysis",
            &[analysis_target.clone(), analysis_target.clone(), analysis_target],
        );
        let reference = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("reference"),
            layout: Some(&reference_layout),
            module: &reference_module,
            entry_point: Some("cs_accumulate"),
            compilation_options: Default::default(),
            cache: None,
        });
        Self {
            shadow_module,
            shadow_layout,
            shadow: HashMap::new(),
            camera_final,
            camera_analysis,
            reference,
        }
    }

    /// The shadow-pass pipeline for these settings, built on first use.
    pub fn shadow(&mut self, device: &wgpu::Device, key: ShadowPipelineKey) -> &wgpu::RenderPipeline {
        let (module, layout) = (&self.shadow_module, &self.shadow_layout);
        self.shadow.entry(key).or_insert_with(|| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some("shadow pass"),
                layout: Some(layout),
                vertex: wgpu::VertexState {
                    module,
                    entry_point: Some("vs_shadow"),
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
                fragment: None,
                multiview_mask: None,
                cache: None,
            })
        })
    }
}

//! A homework pass's pipeline: its bind group layout made from the bindings both stages
//! declare, the two translated stages, the framework's vertex layout and WebGL's state (no
//! culling, depth test LESS). A shader wgpu refuses is an error on one line, not a panic.

use super::program::TranslatedProgram;
use super::{BindingKind, HomeworkGpuError, SamplerFilter};

/// The depth buffer of the light and camera passes.
pub(super) const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// One pass's pipeline with the bindings its two stages declare.
pub(super) struct Pass {
    pub pipeline: wgpu::RenderPipeline,
    pub layout: wgpu::BindGroupLayout,
    /// (binding, name, kind) of every resource either stage declares.
    pub bindings: Vec<(u32, String, BindingKind)>,
    /// The block of the student's own uniforms (size 0: none).
    pub student_block: super::student_block::StudentBlock,
    /// Whether wgpu took the pipeline (a page's browser answers on a later frame).
    answer: crate::render::ScopeAnswer,
    label: String,
}

impl Pass {
    /// The pipeline is valid (Ready(Ok)), refused (Ready(Err), one line), or the browser has
    /// not answered yet.
    pub(super) fn ready(&mut self) -> std::task::Poll<Result<(), HomeworkGpuError>> {
        self.answer.poll().map(|error| match error {
            None => Ok(()),
            Some(e) => Err(HomeworkGpuError(format!("{}: {e}", self.label))),
        })
    }
}

impl Pass {
    pub(super) fn new(
        device: &wgpu::Device,
        program: &TranslatedProgram,
        targets: &[Option<wgpu::ColorTargetState>],
        label: &str,
    ) -> Result<Self, HomeworkGpuError> {
        let mut bindings: Vec<(u32, String, BindingKind)> = Vec::new();
        for b in program.vertex.rewritten.bindings.iter().chain(&program.fragment.rewritten.bindings) {
            if !bindings.iter().any(|(n, ..)| *n == b.binding) {
                bindings.push((b.binding, b.name.clone(), b.kind.clone()));
            }
        }
        bindings.sort_by_key(|(n, ..)| *n);
        let visibility = wgpu::ShaderStages::VERTEX_FRAGMENT;
        let entries: Vec<wgpu::BindGroupLayoutEntry> = bindings
            .iter()
            .map(|(binding, name, kind)| wgpu::BindGroupLayoutEntry {
                binding: *binding,
                visibility,
                ty: match kind {
                    BindingKind::UniformBlock => wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    // The shadow map may be the lossless one, in 32-bit floats, which no sampler
                    // filters: it binds as unfilterable, read with the nearest sampler it has.
                    BindingKind::Texture => wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: name != "uShadowMap" },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    BindingKind::Sampler(SamplerFilter::Nearest) => {
                        wgpu::BindingType::Sampler(wgpu::SamplerBindingType::NonFiltering)
                    }
                    BindingKind::Sampler(SamplerFilter::Linear) => {
                        wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering)
                    }
                },
                count: None,
            })
            .collect();
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(label),
            entries: &entries,
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(label),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let module = |wgsl: &str| {
            device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(label),
                source: wgpu::ShaderSource::Wgsl(wgsl.into()),
            })
        };
        let vertex = module(&program.vertex.wgsl);
        let fragment = module(&program.fragment.wgsl);
        let attributes = wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x2];
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(label),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &vertex,
                entry_point: Some("main"),
                compilation_options: Default::default(),
                buffers: &[Some(wgpu::VertexBufferLayout {
                    array_stride: std::mem::size_of::<crate::scene::mesh::Vertex>() as u64,
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes: &attributes,
                })],
            },
            // The framework culls nothing.
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: Some(wgpu::DepthStencilState {
                format: DEPTH_FORMAT,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Less),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &fragment,
                entry_point: Some("main"),
                compilation_options: Default::default(),
                targets,
            }),
            multiview_mask: None,
            cache: None,
        });
        let mut answer = crate::render::ScopeAnswer::new(scope.pop());
        if let std::task::Poll::Ready(Some(e)) = answer.poll() {
            return Err(HomeworkGpuError(format!("{label}: {e}")));
        }
        use super::student_block::StudentBlock;
        let student_block =
            StudentBlock::of_wgsl(&program.vertex.wgsl).larger(StudentBlock::of_wgsl(&program.fragment.wgsl));
        Ok(Self { pipeline, layout, bindings, student_block, answer, label: label.to_owned() })
    }
}

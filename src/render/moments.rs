//! The VSM moments (shaders/moments.wgsl): (depth, depth²) per block of shadow-map texels, as a
//! mip chain built by compute passes after the shadow pass, for frames that use VSM.

use super::layouts::texture_entry;
use super::targets::ShadowMaps;
use super::timing::Timer;
use crate::shadow::gpu::moments_block;

pub const MOMENTS_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rg32Float;
/// The compute shaders' workgroup side.
const WORKGROUP: u32 = 8;

/// The compute pipelines: levels 0 and 1 together from the depth maps (level 0 alone for a
/// chain of one level), each further level from the one before.
pub struct MomentsPipelines {
    from_depth_layout: wgpu::BindGroupLayout,
    levels_0_1_layout: wgpu::BindGroupLayout,
    reduce_layout: wgpu::BindGroupLayout,
    from_depth: wgpu::ComputePipeline,
    levels_0_1: wgpu::ComputePipeline,
    reduce: wgpu::ComputePipeline,
}

/// A texture array the compute passes read.
fn input_entry(binding: u32, sample_type: wgpu::TextureSampleType) -> wgpu::BindGroupLayoutEntry {
    texture_entry(binding, wgpu::ShaderStages::COMPUTE, sample_type, wgpu::TextureViewDimension::D2Array)
}

/// A level the pass writes.
const fn output_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::StorageTexture {
            access: wgpu::StorageTextureAccess::WriteOnly,
            format: MOMENTS_FORMAT,
            view_dimension: wgpu::TextureViewDimension::D2Array,
        },
        count: None,
    }
}
const OUTPUT_ENTRY: wgpu::BindGroupLayoutEntry = output_entry(2);

const INFO_ENTRY: wgpu::BindGroupLayoutEntry = wgpu::BindGroupLayoutEntry {
    binding: 3,
    visibility: wgpu::ShaderStages::COMPUTE,
    ty: wgpu::BindingType::Buffer {
        ty: wgpu::BufferBindingType::Uniform,
        has_dynamic_offset: false,
        min_binding_size: None,
    },
    count: None,
};

impl MomentsPipelines {
    pub fn new(device: &wgpu::Device, module: &wgpu::ShaderModule) -> Self {
        let from_depth_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("moments from depth"),
            entries: &[input_entry(0, wgpu::TextureSampleType::Depth), OUTPUT_ENTRY, INFO_ENTRY],
        });
        let levels_0_1_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("moments levels 0 and 1"),
            entries: &[
                input_entry(0, wgpu::TextureSampleType::Depth),
                OUTPUT_ENTRY,
                INFO_ENTRY,
                output_entry(4),
            ],
        });
        let reduce_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("moments reduce"),
            entries: &[input_entry(1, wgpu::TextureSampleType::Float { filterable: false }), OUTPUT_ENTRY],
        });
        let pipeline = |label, layout: &wgpu::BindGroupLayout, entry_point| {
            let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(label),
                bind_group_layouts: &[Some(layout)],
                immediate_size: 0,
            });
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(label),
                layout: Some(&pipeline_layout),
                module,
                entry_point: Some(entry_point),
                compilation_options: Default::default(),
                cache: None,
            })
        };
        let from_depth = pipeline("moments from depth", &from_depth_layout, "cs_moments_from_depth");
        let levels_0_1 = pipeline("moments levels 0 and 1", &levels_0_1_layout, "cs_moments_levels_0_1");
        let reduce = pipeline("moments reduce", &reduce_layout, "cs_moments_reduce");
        Self { from_depth_layout, levels_0_1_layout, reduce_layout, from_depth, levels_0_1, reduce }
    }
}

/// The moments of one shadow-map array.
pub struct Moments {
    /// Every level, for the camera pass (group 1, binding 5).
    pub view: wgpu::TextureView,
    /// Per level: what writes it (the maps, or the level before; level 1 is written with level 0
    /// where there is one) and its size in texels.
    levels: Vec<(wgpu::BindGroup, u32)>,
    /// The moments describe the maps as drawn (false once the maps are redrawn without them).
    pub current: bool,
    /// The texture, for read-back (`Renderer::read_moments`).
    pub texture: wgpu::Texture,
    /// Map texels per side of one level-0 texel.
    pub block: u32,
}

impl Moments {
    /// A single texel that stands in until a frame uses VSM: the camera pass's layout has a
    /// binding for the moments, and a 2048² array of them is about 43 MB a layer.
    pub fn placeholder(device: &wgpu::Device) -> Self {
        let texture = Self::texture(device, 1, 1, 1);
        let view = texture.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::D2Array),
            ..Default::default()
        });
        Self { view, levels: Vec::new(), current: false, texture, block: 0 }
    }

    /// Nothing but the placeholder's single texel.
    pub fn is_placeholder(&self) -> bool {
        self.levels.is_empty()
    }

    fn texture(device: &wgpu::Device, side: u32, layers: u32, level_count: u32) -> wgpu::Texture {
        device.create_texture(&wgpu::TextureDescriptor {
            label: Some("vsm moments"),
            size: wgpu::Extent3d { width: side, height: side, depth_or_array_layers: layers },
            mip_level_count: level_count,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: MOMENTS_FORMAT,
            usage: wgpu::TextureUsages::STORAGE_BINDING
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        })
    }

    pub fn new(device: &wgpu::Device, pipelines: &MomentsPipelines, maps: &ShadowMaps) -> Self {
        let block = moments_block(maps.atlas_size);
        let side = maps.atlas_size.div_ceil(block);
        let level_count = side.ilog2() + 1;
        let texture = Self::texture(device, side, maps.layers, level_count);
        let info = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("moments info"),
            size: 16,
            usage: wgpu::BufferUsages::UNIFORM,
            mapped_at_creation: true,
        });
        if let Ok(mut range) = info.slice(..).get_mapped_range_mut() {
            range.copy_from_slice(bytemuck::cast_slice(&[block, 0u32, 0, 0]));
        }
        info.unmap();
        let level_view = |level| {
            texture.create_view(&wgpu::TextureViewDescriptor {
                dimension: Some(wgpu::TextureViewDimension::D2Array),
                base_mip_level: level,
                mip_level_count: Some(1),
                ..Default::default()
            })
        };
        let views: Vec<_> = (0..level_count).map(level_view).collect();
        let levels = (0..level_count as usize)
            .map(|level| {
                let output = wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::TextureView(&views[level]),
                };
                let depth = wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(&maps.array_view),
                };
                let info_entry = wgpu::BindGroupEntry { binding: 3, resource: info.as_entire_binding() };
                let group = match level {
                    0 if level_count == 1 => device.create_bind_group(&wgpu::BindGroupDescriptor {
                        label: Some("moments level 0"),
                        layout: &pipelines.from_depth_layout,
                        entries: &[depth, output, info_entry],
                    }),
                    0 => device.create_bind_group(&wgpu::BindGroupDescriptor {
                        label: Some("moments levels 0 and 1"),
                        layout: &pipelines.levels_0_1_layout,
                        entries: &[
                            depth,
                            output,
                            info_entry,
                            wgpu::BindGroupEntry {
                                binding: 4,
                                resource: wgpu::BindingResource::TextureView(&views[1]),
                            },
                        ],
                    }),
                    _ => device.create_bind_group(&wgpu::BindGroupDescriptor {
                        label: Some("moments level"),
                        layout: &pipelines.reduce_layout,
                        entries: &[
                            wgpu::BindGroupEntry {
                                binding: 1,
                                resource: wgpu::BindingResource::TextureView(&views[level - 1]),
                            },
                            output,
                        ],
                    }),
                };
                (group, (side >> level).max(1))
            })
            .collect();
        let view = texture.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::D2Array),
            ..Default::default()
        });
        Self { view, levels, current: false, texture, block }
    }

    /// Rebuild every level for the first `layers` maps. With `timer`, the pass writes the end of
    /// span 0 (and its beginning when `begins_span`, where no shadow pass ran before it).
    pub fn encode(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        pipelines: &MomentsPipelines,
        layers: u32,
        timer: Option<&Timer>,
        begins_span: bool,
    ) {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("vsm moments"),
            timestamp_writes: timer.and_then(|t| t.compute_span_writes(0, begins_span, true)),
        });
        let fused = self.levels.len() > 1;
        for (level, (group, side)) in self.levels.iter().enumerate() {
            // Level 1 comes with level 0.
            let (pipeline, invocations) = match level {
                0 if fused => (&pipelines.levels_0_1, side.div_ceil(2)),
                0 => (&pipelines.from_depth, *side),
                1 if fused => continue,
                _ => (&pipelines.reduce, *side),
            };
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, group, &[]);
            let groups = invocations.div_ceil(WORKGROUP);
            pass.dispatch_workgroups(groups, groups, layers);
        }
        self.current = true;
    }
}

//! Bind group layouts. Bind groups by update rate: 0 per frame, 1 lights and shadow maps, 2 per
//! object (the shadow pass uses 0 = light view, 1 = object).

pub struct Layouts {
    pub frame: wgpu::BindGroupLayout,
    pub lights: wgpu::BindGroupLayout,
    /// Group 3 of the camera passes: the view's albedo cache.
    pub albedo_cache: wgpu::BindGroupLayout,
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

pub(super) fn texture_entry(
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

/// The light a shadow lookup reads (binding 0 of the shadow inputs): every light of the frame
/// at once, or one light sample per dispatch (the ground truth).
#[derive(Clone, Copy)]
enum LightBinding {
    FrameLights,
    /// A sample at a dynamic offset of a read-only storage buffer, not a uniform: lavapipe
    /// compiles a new shader variant for each distinct value of a uniform that decides a branch
    /// (directly, or through a copy used five times or more) and keeps every variant until the
    /// pipeline is destroyed, so per-dispatch values in a uniform grow the process by the
    /// sample. Storage loads are never inlined.
    SamplePerDispatch,
}

/// Group 1 of the camera and reference shaders: light(s), params, shadow maps, compare sampler,
/// kernel table, and for the camera (`camera_inputs`) the maps' VSM moments and the shadow views.
fn shadow_inputs_layout(
    device: &wgpu::Device,
    label: &str,
    light: LightBinding,
    camera_inputs: bool,
) -> wgpu::BindGroupLayout {
    let all = wgpu::ShaderStages::VERTEX_FRAGMENT | wgpu::ShaderStages::COMPUTE;
    let unfilterable = wgpu::TextureSampleType::Float { filterable: false };
    let moments = texture_entry(5, all, unfilterable, wgpu::TextureViewDimension::D2Array);
    let light_entry = match light {
        LightBinding::FrameLights => uniform_entry(0, all, false),
        LightBinding::SamplePerDispatch => wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only: true },
                has_dynamic_offset: true,
                min_binding_size: None,
            },
            count: None,
        },
    };
    let entries = [
        light_entry,
        uniform_entry(1, all, false),
        texture_entry(2, all, wgpu::TextureSampleType::Depth, wgpu::TextureViewDimension::D2Array),
        sampler_entry(3, all, wgpu::SamplerBindingType::Comparison),
        wgpu::BindGroupLayoutEntry {
            binding: 4,
            visibility: all,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        },
        moments,
        uniform_entry(6, all, false),
    ];
    let used = if camera_inputs { &entries[..] } else { &entries[..5] };
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label: Some(label), entries: used })
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
            lights: shadow_inputs_layout(device, "lights", LightBinding::FrameLights, true),
            albedo_cache: device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("albedo cache"),
                entries: &[texture_entry(
                    0,
                    wgpu::ShaderStages::FRAGMENT,
                    float(false),
                    wgpu::TextureViewDimension::D2,
                )],
            }),
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
                entries: &[uniform_entry(0, wgpu::ShaderStages::VERTEX_FRAGMENT, true)],
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
            reference_light: shadow_inputs_layout(
                device,
                "reference light",
                LightBinding::SamplePerDispatch,
                false,
            ),
        }
    }
}

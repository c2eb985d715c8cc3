//! `#[repr(C)]` mirrors of the WGSL structs in shaders/common.wgsl (keep in sync; sizes asserted below).

use crate::scene::{BiasMode, Kernel, Light, LightKind, LightSize, ShadowSettings, Technique};
use bytemuck::{Pod, Zeroable};
use glam::{Mat4, Vec3};

#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct FrameGpu {
    pub clip_from_world: [[f32; 4]; 4],
    pub camera_position: [f32; 4],
    pub ambient: [f32; 4],
    pub light_count: u32,
    pub selected_light: u32,
    pub _pad: [u32; 2],
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct LightGpu {
    pub clip_from_world: [[f32; 4]; 4],
    pub position: [f32; 4],
    pub direction: [f32; 4],
    pub color: [f32; 4],
    pub near: f32,
    pub far: f32,
    pub frustum_width_world: f32,
    pub tan_half_fov: f32,
    pub orthographic: u32,
    pub size_model: u32,
    pub light_width_world: f32,
    pub tan_half_angle: f32,
    pub map_size_texels: f32,
    pub layer: u32,
    pub atlas_scale: f32,
    pub _pad: u32,
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct ShadowParamsGpu {
    pub technique: u32,
    pub bias_mode: u32,
    pub kernel: u32,
    pub samples: u32,
    pub bias: f32,
    pub slope_bias: f32,
    pub adaptive_c: f32,
    pub normal_offset_texels: f32,
    pub radius_texels: f32,
    pub rotate_per_pixel: u32,
    pub noise_seed: u32,
    pub blocker_samples: u32,
    pub min_filter_radius_texels: f32,
    pub clamp_outside: u32,
    pub _pad: [u32; 2],
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct ObjectGpu {
    pub world_from_object: [[f32; 4]; 4],
    pub normal_from_object: [[f32; 4]; 4],
    pub base_color: [f32; 4],
    pub object_index: u32,
    pub _pad: [u32; 3],
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct ShadowViewGpu {
    pub clip_from_world: [[f32; 4]; 4],
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct ReferenceInfoGpu {
    pub width: u32,
    pub height: u32,
    pub weight: f32,
    pub _pad: u32,
}

const _: () = assert!(std::mem::size_of::<FrameGpu>() == 112);
const _: () = assert!(std::mem::size_of::<LightGpu>() == 160);
const _: () = assert!(std::mem::size_of::<ShadowParamsGpu>() == 64);
const _: () = assert!(std::mem::size_of::<ObjectGpu>() == 160);
const _: () = assert!(std::mem::size_of::<ShadowViewGpu>() == 64);
const _: () = assert!(std::mem::size_of::<ReferenceInfoGpu>() == 16);

/// Uniform buffers indexed with dynamic offsets use this stride (wgpu's minimum alignment limit).
pub const DYNAMIC_STRIDE: u64 = 256;

impl ShadowParamsGpu {
    pub fn new(s: &ShadowSettings) -> Self {
        Self {
            technique: match s.technique {
                Technique::Hard => 0,
                Technique::None => 3,
                Technique::Pcf => 1,
                Technique::Pcss => 2,
            },
            bias_mode: match s.bias_mode {
                BiasMode::None => 0,
                BiasMode::Constant => 1,
                BiasMode::Slope => 2,
                BiasMode::Adaptive => 3,
            },
            kernel: kernel_id(s.pcf_kernel),
            samples: s.samples,
            bias: s.bias,
            slope_bias: s.slope_bias,
            adaptive_c: s.adaptive_c,
            normal_offset_texels: s.normal_offset_texels,
            radius_texels: s.radius_texels,
            rotate_per_pixel: u32::from(s.rotate_per_pixel),
            noise_seed: s.noise_seed,
            blocker_samples: s.blocker_samples,
            min_filter_radius_texels: s.min_filter_radius_texels,
            clamp_outside: u32::from(s.clamp_outside),
            _pad: [0; 2],
        }
    }
}

pub fn kernel_id(k: Kernel) -> u32 {
    match k {
        Kernel::Poisson => 0,
        Kernel::Uniform => 1,
        Kernel::Vogel => 2,
        Kernel::Grid => 3,
        Kernel::Hardware => 4,
    }
}

impl LightGpu {
    /// The light at time `t`, in shadow-map `layer` of an array texture `atlas_size` texels wide.
    pub fn new(light: &Light, t_s: f32, layer: u32, atlas_size: u32) -> Self {
        Self::with_transform(
            light,
            light.clip_from_world(t_s),
            light.position_at(t_s),
            light.direction_at(t_s),
            layer,
            atlas_size,
        )
    }

    /// The light with an explicit transform (the ground truth moves it over its area).
    pub fn with_transform(
        light: &Light,
        clip_from_world: Mat4,
        position: Vec3,
        direction: Vec3,
        layer: u32,
        atlas_size: u32,
    ) -> Self {
        let (size_model, light_width_world, tan_half_angle) = match light.size {
            LightSize::Width { width_world } => (0, width_world, 0.0),
            LightSize::AngularDiameter { angular_diameter_deg } => {
                (1, 0.0, (0.5 * angular_diameter_deg.to_radians()).tan())
            }
        };
        let tan_half_fov = match light.kind {
            LightKind::Directional { .. } => 0.0,
            LightKind::Spot { fov_deg } => (0.5 * fov_deg.to_radians()).tan(),
        };
        Self {
            clip_from_world: clip_from_world.to_cols_array_2d(),
            position: position.extend(1.0).to_array(),
            direction: direction.extend(0.0).to_array(),
            color: (light.color * light.intensity).extend(1.0).to_array(),
            near: light.near,
            far: light.far,
            frustum_width_world: light.frustum_width_world(),
            tan_half_fov,
            orthographic: u32::from(light.is_orthographic()),
            size_model,
            light_width_world,
            tan_half_angle,
            map_size_texels: light.shadow_map_size as f32,
            layer,
            atlas_scale: light.shadow_map_size as f32 / atlas_size as f32,
            _pad: 0,
        }
    }
}

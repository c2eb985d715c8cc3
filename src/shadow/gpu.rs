//! The shadow model's GPU vocabulary: the light and parameter structs the shaders read and the
//! twin computes with, and the numbering of techniques, bias modes, kernels and light-size models
//! that shaders/common.wgsl shares (one source here; tests/shaders.rs holds the WGSL to it).
//! Keep the structs in sync with shaders/common.wgsl (sizes asserted below).

use crate::scene::{BiasMode, DepthStorage, Kernel, Light, LightKind, LightSize, ShadowSettings, Technique};
use bytemuck::{Pod, Zeroable};
use glam::{Mat4, Vec3};

pub const TECHNIQUE_HARD: u32 = 0;
pub const TECHNIQUE_PCF: u32 = 1;
pub const TECHNIQUE_PCSS: u32 = 2;
pub const TECHNIQUE_NONE: u32 = 3;
pub const TECHNIQUE_VSM: u32 = 4;
pub const TECHNIQUE_VSSM: u32 = 5;
pub const BIAS_NONE: u32 = 0;
pub const BIAS_CONSTANT: u32 = 1;
pub const BIAS_SLOPE: u32 = 2;
pub const BIAS_ADAPTIVE: u32 = 3;
pub const BIAS_RECEIVER_PLANE: u32 = 4;
pub const DEPTH_FLOAT32: u32 = 0;
pub const DEPTH_RGBA8: u32 = 1;
pub const KERNEL_POISSON: u32 = 0;
pub const KERNEL_UNIFORM: u32 = 1;
pub const KERNEL_VOGEL: u32 = 2;
pub const KERNEL_GRID: u32 = 3;
pub const KERNEL_HARDWARE: u32 = 4;
pub const SIZE_MODEL_WIDTH: u32 = 0;
pub const SIZE_MODEL_ANGULAR: u32 = 1;

/// Every shared constant by its WGSL name, for the test that holds shaders/common.wgsl to them.
pub const SHARED_CONSTANTS: [(&str, u32); 20] = [
    ("TECHNIQUE_HARD", TECHNIQUE_HARD),
    ("TECHNIQUE_PCF", TECHNIQUE_PCF),
    ("TECHNIQUE_PCSS", TECHNIQUE_PCSS),
    ("TECHNIQUE_VSM", TECHNIQUE_VSM),
    ("TECHNIQUE_VSSM", TECHNIQUE_VSSM),
    ("TECHNIQUE_NONE", TECHNIQUE_NONE),
    ("BIAS_NONE", BIAS_NONE),
    ("BIAS_CONSTANT", BIAS_CONSTANT),
    ("BIAS_SLOPE", BIAS_SLOPE),
    ("BIAS_ADAPTIVE", BIAS_ADAPTIVE),
    ("BIAS_RECEIVER_PLANE", BIAS_RECEIVER_PLANE),
    ("DEPTH_FLOAT32", DEPTH_FLOAT32),
    ("DEPTH_RGBA8", DEPTH_RGBA8),
    ("KERNEL_POISSON", KERNEL_POISSON),
    ("KERNEL_UNIFORM", KERNEL_UNIFORM),
    ("KERNEL_VOGEL", KERNEL_VOGEL),
    ("KERNEL_GRID", KERNEL_GRID),
    ("KERNEL_HARDWARE", KERNEL_HARDWARE),
    ("SIZE_MODEL_WIDTH", SIZE_MODEL_WIDTH),
    ("SIZE_MODEL_ANGULAR", SIZE_MODEL_ANGULAR),
];

pub fn technique_id(t: Technique) -> u32 {
    match t {
        Technique::Hard => TECHNIQUE_HARD,
        Technique::Pcf => TECHNIQUE_PCF,
        Technique::Pcss => TECHNIQUE_PCSS,
        Technique::None => TECHNIQUE_NONE,
        Technique::Vsm => TECHNIQUE_VSM,
        Technique::Vssm => TECHNIQUE_VSSM,
    }
}

pub fn bias_mode_id(b: BiasMode) -> u32 {
    match b {
        BiasMode::None => BIAS_NONE,
        BiasMode::Constant => BIAS_CONSTANT,
        BiasMode::Slope => BIAS_SLOPE,
        BiasMode::Adaptive => BIAS_ADAPTIVE,
        BiasMode::ReceiverPlane => BIAS_RECEIVER_PLANE,
    }
}

pub fn depth_storage_id(d: DepthStorage) -> u32 {
    match d {
        DepthStorage::Float32 => DEPTH_FLOAT32,
        DepthStorage::Rgba8 => DEPTH_RGBA8,
    }
}

pub fn kernel_id(k: Kernel) -> u32 {
    match k {
        Kernel::Poisson => KERNEL_POISSON,
        Kernel::Uniform => KERNEL_UNIFORM,
        Kernel::Vogel => KERNEL_VOGEL,
        Kernel::Grid => KERNEL_GRID,
        Kernel::Hardware => KERNEL_HARDWARE,
    }
}

/// The kernel a shader number names (the inverse of `kernel_id`).
pub fn kernel_from_id(id: u32) -> Kernel {
    match id {
        KERNEL_POISSON => Kernel::Poisson,
        KERNEL_UNIFORM => Kernel::Uniform,
        KERNEL_VOGEL => Kernel::Vogel,
        KERNEL_GRID => Kernel::Grid,
        _ => Kernel::Hardware,
    }
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
    /// Map texels per side of one level-0 texel of the VSM moments (1 up to MOMENTS_MAX_SIDE).
    pub moments_block: u32,
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
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
    pub search_radius_scale: f32,
    pub depth_storage: u32,
    pub ortho_near_factor: u32,
    pub vsm_min_variance: f32,
    pub vsm_bleed_reduction: f32,
    pub _pad: u32,
}

const _: () = assert!(std::mem::size_of::<LightGpu>() == 160);
const _: () = assert!(std::mem::size_of::<ShadowParamsGpu>() == 80);

impl ShadowParamsGpu {
    /// The frame filters with the VSM moments (`Technique::uses_moments`).
    pub fn uses_moments(&self) -> bool {
        self.technique == TECHNIQUE_VSM || self.technique == TECHNIQUE_VSSM
    }

    pub fn new(s: &ShadowSettings) -> Self {
        Self {
            technique: technique_id(s.technique),
            bias_mode: bias_mode_id(s.bias_mode),
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
            search_radius_scale: s.search_radius_scale,
            depth_storage: depth_storage_id(s.depth_storage),
            ortho_near_factor: u32::from(s.ortho_near_factor),
            vsm_min_variance: s.vsm_min_variance,
            vsm_bleed_reduction: s.vsm_bleed_reduction,
            _pad: 0,
        }
    }
}

/// The VSM moments keep at most this many texels per side at level 0; larger maps are averaged
/// in blocks (see shaders/moments.wgsl).
pub const MOMENTS_MAX_SIDE: u32 = 2048;

/// Map texels per side of a level-0 moments texel for an array `atlas_size` texels wide.
pub fn moments_block(atlas_size: u32) -> u32 {
    atlas_size.div_ceil(MOMENTS_MAX_SIDE).max(1)
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
            LightSize::Width { width_world } => (SIZE_MODEL_WIDTH, width_world, 0.0),
            LightSize::AngularDiameter { angular_diameter_deg } => {
                (SIZE_MODEL_ANGULAR, 0.0, (0.5 * angular_diameter_deg.to_radians()).tan())
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
            moments_block: moments_block(atlas_size),
        }
    }
}

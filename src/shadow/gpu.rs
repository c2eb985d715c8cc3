//! The shadow model's GPU vocabulary: the light and parameter structs the shaders read and the
//! twin computes with, and the numbering of techniques, bias modes, kernels and light-size models
//! that shaders/common.wgsl shares (one source here; tests/shaders.rs holds the WGSL to it).
//! Keep the structs in sync with shaders/common.wgsl (sizes asserted below).

use super::cascades::fit_cascades;
use crate::scene::{
    BiasMode, CascadeSelection, DepthStorage, Kernel, Light, LightKind, LightSize, Scene, ShadowSettings,
    Technique,
};
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
/// How a pixel picks a sun's cascade (`CascadeSelection`): the sharpest map that holds it, or the
/// slice that holds its depth along the camera's view axis.
pub const CASCADE_BY_MAP: u32 = 0;
pub const CASCADE_BY_INTERVAL: u32 = 1;
/// Shadow views of all lights together (a light owns one or more), the size of the shaders' array.
pub const MAX_SHADOW_VIEWS: usize = 24;

/// Map texels between a point and its cascade's edge for the cascade to hold it (`cascade_holds`).
pub const CASCADE_BORDER_TEXELS: u32 = 4;
/// Every shared constant by its WGSL name, for the test that holds shaders/common.wgsl to them.
pub const SHARED_CONSTANTS: [(&str, u32); 25] = [
    ("MAX_LIGHTS", crate::scene::MAX_LIGHTS as u32),
    ("CASCADE_BORDER_TEXELS", CASCADE_BORDER_TEXELS),
    ("MAX_SHADOW_VIEWS", MAX_SHADOW_VIEWS as u32),
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
    ("CASCADE_BY_MAP", CASCADE_BY_MAP),
    ("CASCADE_BY_INTERVAL", CASCADE_BY_INTERVAL),
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

/// A light as all of its shadow views share it: where it is, its colour, its size (the PCSS
/// light), and which of the frame's shadow views are its own.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct LightGpu {
    pub position: [f32; 4],
    pub direction: [f32; 4],
    pub color: [f32; 4],
    /// 1: a sun (parallel rays along `direction`); 0: rays from `position`.
    pub directional: u32,
    pub size_model: u32,
    pub light_width_world: f32,
    pub tan_half_angle: f32,
    /// Its shadow views are the frame's `first_view .. first_view + view_count`.
    pub first_view: u32,
    pub view_count: u32,
    /// A sun's cascades: CASCADE_BY_MAP or CASCADE_BY_INTERVAL (0 for the other lights).
    pub cascade_selection: u32,
    pub _pad: u32,
}

/// One depth map a light renders: where from and how it projects (`clip_from_world`, near and
/// far, width), how many texels it has and where it lies in the shadow-map array. A light owns
/// one or more; the shadow pass draws views, the lookup reads the view that covers a point.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct ShadowViewGpu {
    pub clip_from_world: [[f32; 4]; 4],
    /// Where the view looks from (a perspective view's eye), world units.
    pub origin: [f32; 4],
    pub near: f32, // world units
    pub far: f32,
    /// W: the orthographic width, or the width at the near plane, world units.
    pub frustum_width_world: f32,
    /// Perspective only; 0 for orthographic.
    pub tan_half_fov: f32,
    pub orthographic: u32,
    pub map_size_texels: f32,
    /// Its layer of the shadow-map array.
    pub layer: u32,
    /// map_size / the array texture's size (a smaller map uses the layer's top-left corner).
    pub atlas_scale: f32,
    /// Map texels per side of one level-0 texel of the VSM moments (1 up to MOMENTS_MAX_SIDE).
    pub moments_block: u32,
    /// The light that owns it (index into the frame's lights).
    pub light: u32,
    /// 1: a cube face. Its map stores the distance to `origin`, (|p - origin| - near) / (far - near),
    /// and lookups project with the face's axes (`CUBE_FACES`), not `clip_from_world`.
    pub cube: u32,
    /// Which of its light's views: a cube's face (0..6, `CUBE_FACES`) or a sun's cascade (0
    /// sharpest); they lie in layers `layer - face ..`.
    pub face: u32,
    /// A cascade: the camera's view axis as a plane, xyz its unit direction and w = -xyz . eye,
    /// so that xyz . p + w is a point's depth along the axis, world units (zero for other views).
    pub view_axis_world: [f32; 4],
    /// A cascade: where its slice of the camera's view begins and ends along that axis, world
    /// units (the split distances; zero for other views).
    pub split_near_world: f32,
    pub split_far_world: f32,
    pub _pad: [u32; 2],
}

/// A light and one of its shadow views: what one lookup reads (the twin of a pixel, a view of the
/// analysis; the ground truth binds one per sample of an area light).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct LightViewGpu {
    pub light: LightGpu,
    pub view: ShadowViewGpu,
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

const _: () = assert!(std::mem::size_of::<LightGpu>() == 80);
const _: () = assert!(std::mem::size_of::<ShadowViewGpu>() == 160);
const _: () = assert!(std::mem::size_of::<LightViewGpu>() == 240);
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

/// The lights of a scene's frame at time `t`, seen by its camera through a picture `aspect`
/// wide per unit of height (cascades follow the camera), and their shadow views, one layer of an
/// array texture `atlas_size` texels wide each, in order (light 0's views first). The one place
/// views are laid out in the array.
pub fn frame_lights(
    scene: &Scene,
    aspect: f32,
    t_s: f32,
    atlas_size: u32,
) -> (Vec<LightGpu>, Vec<ShadowViewGpu>) {
    let lights = &scene.lights;
    let mut frame_lights = Vec::with_capacity(lights.len());
    let mut views = Vec::with_capacity(lights.len());
    for (index, light) in lights.iter().enumerate() {
        let first_view = views.len() as u32;
        if light.stores_distance() {
            for face in 0..6 {
                let clip = light.cube_face_clip_from_world(face, t_s);
                let view = ShadowViewGpu::new(light, clip, first_view, atlas_size);
                views.push(ShadowViewGpu { light: index as u32, ..view.on_face(face as u32) });
            }
        } else if light.cascades.is_cascaded() && light.is_orthographic() {
            // A sun's cascades, sharpest first; `face` numbers them.
            let view_axis_world = view_axis_plane(&scene.camera);
            for (i, fit) in fit_cascades(light, &scene.camera, aspect, t_s).into_iter().enumerate() {
                let layer = views.len() as u32;
                let view = ShadowViewGpu::new(light, fit.clip_from_world, layer, atlas_size);
                views.push(ShadowViewGpu {
                    light: index as u32,
                    frustum_width_world: fit.width_world,
                    face: i as u32,
                    view_axis_world,
                    split_near_world: fit.split_world.0,
                    split_far_world: fit.split_world.1,
                    ..view
                });
            }
        } else {
            // Spot and directional lights: the one frustum of `Light::clip_from_world`.
            let view = ShadowViewGpu::new(light, light.clip_from_world(t_s), first_view, atlas_size);
            views.push(ShadowViewGpu { light: index as u32, ..view });
        }
        let count = views.len() as u32 - first_view;
        let (position, direction) = (light.position_at(t_s), light.direction_at(t_s));
        frame_lights.push(LightGpu::new(light, position, direction, first_view, count));
    }
    (frame_lights, views)
}

/// The camera's view axis as a plane (`ShadowViewGpu::view_axis_world`): the view space's z row
/// negated, since the camera looks down -z, so that it gives the depth `slice_corners` cuts at.
fn view_axis_plane(camera: &crate::scene::Camera) -> [f32; 4] {
    (-camera.view_from_world().row(2)).to_array()
}

/// How many shadow views (maps) a light of this kind renders (`frame_lights` makes them).
pub fn shadow_view_count(light: &Light) -> u32 {
    match light.kind {
        // A sun's cascades, else one frustum covers what it lights.
        LightKind::Directional { .. } => light.cascades.count,
        LightKind::Spot { .. } => 1,
        LightKind::Point => 6,
    }
}

/// How many shadow-map layers these lights' views take.
pub fn views_needed(lights: &[Light]) -> u32 {
    lights.iter().map(shadow_view_count).sum()
}

impl LightGpu {
    /// The light placed at `position`, facing `direction` (the ground truth moves it over its area).
    pub fn new(light: &Light, position: Vec3, direction: Vec3, first_view: u32, view_count: u32) -> Self {
        let (size_model, light_width_world, tan_half_angle) = match light.size {
            LightSize::Width { width_world } => (SIZE_MODEL_WIDTH, width_world, 0.0),
            LightSize::AngularDiameter { angular_diameter_deg } => {
                (SIZE_MODEL_ANGULAR, 0.0, (0.5 * angular_diameter_deg.to_radians()).tan())
            }
        };
        Self {
            position: position.extend(1.0).to_array(),
            direction: direction.extend(0.0).to_array(),
            color: (light.color * light.intensity).extend(1.0).to_array(),
            directional: u32::from(light.is_orthographic()),
            size_model,
            light_width_world,
            tan_half_angle,
            first_view,
            view_count,
            cascade_selection: match light.cascades.selection {
                CascadeSelection::ByMap => CASCADE_BY_MAP,
                CascadeSelection::ByInterval => CASCADE_BY_INTERVAL,
            },
            _pad: 0,
        }
    }
}

impl ShadowViewGpu {
    /// The light's one map seen through `clip_from_world`, in `layer` of an array texture
    /// `atlas_size` texels wide.
    /// (A point light's face: `new` with the face's matrix, then `on_face`.)
    pub fn new(light: &Light, clip_from_world: Mat4, layer: u32, atlas_size: u32) -> Self {
        // A perspective view's eye is the one point its projection sends to w = 0: clip (0, 0, 1, 0)
        // taken back to the world, homogeneous.
        let eye = clip_from_world.inverse() * glam::Vec4::Z;
        let origin = if light.is_orthographic() { Vec3::ZERO } else { eye.truncate() / eye.w };
        Self {
            clip_from_world: clip_from_world.to_cols_array_2d(),
            origin: origin.extend(1.0).to_array(),
            near: light.near,
            far: light.far,
            frustum_width_world: light.frustum_width_world(),
            tan_half_fov: light.tan_half_fov(),
            orthographic: u32::from(light.is_orthographic()),
            map_size_texels: light.shadow_map_size as f32,
            layer,
            atlas_scale: light.shadow_map_size as f32 / atlas_size as f32,
            moments_block: moments_block(atlas_size),
            light: 0,
            cube: u32::from(light.stores_distance()),
            face: 0,
            view_axis_world: [0.0; 4],
            split_near_world: 0.0,
            split_far_world: 0.0,
            _pad: [0; 2],
        }
    }

    /// This cube view moved to face `face` of the same light: the layer follows, the axes are the
    /// face's (`clip_from_world` is kept only where the shadow pass draws the face itself). The
    /// shader's `cube_face_view`.
    pub fn on_face(self, face: u32) -> Self {
        Self { layer: self.layer - self.face + face, face, ..self }
    }
}

/// Light `light` of a frame's `lights` with the first of its shadow views (each light owns at
/// least one), and that view's index in `views`: what a light's map picture, probe and views read.
pub fn first_view_of(
    lights: &[LightGpu],
    views: &[ShadowViewGpu],
    light: usize,
) -> Option<(usize, LightViewGpu)> {
    let light = *lights.get(light)?;
    let index = light.first_view as usize;
    Some((index, LightViewGpu { light, view: *views.get(index)? }))
}

impl LightViewGpu {
    /// The light at time `t` with its first view, alone in layer 0 of an array `atlas_size` wide
    /// (a twin of one light: the diagrams, the homework check).
    pub fn single(light: &Light, t_s: f32, atlas_size: u32) -> Self {
        Self {
            light: LightGpu::new(light, light.position_at(t_s), light.direction_at(t_s), 0, 1),
            view: ShadowViewGpu::new(light, light.clip_from_world(t_s), 0, atlas_size),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every light owns the views `frame_lights` gave it, each in a layer of its own, and the
    /// array has as many layers as `views_needed` says.
    #[test]
    fn each_light_owns_its_views_and_each_view_its_layer() {
        let scene = crate::scene::load_scene(&crate::shipped_path("assets/scenes/multi_light.toml"), &[])
            .expect("scene");
        assert!(scene.lights.len() > 1);
        let (lights, views) = frame_lights(&scene, 1.5, 1.5, 2048);
        assert_eq!(views.len() as u32, views_needed(&scene.lights));
        let mut layers: Vec<u32> = views.iter().map(|v| v.layer).collect();
        layers.dedup();
        assert_eq!(layers, (0..views.len() as u32).collect::<Vec<_>>());
        for (index, (light, gpu)) in scene.lights.iter().zip(&lights).enumerate() {
            assert_eq!(gpu.view_count, shadow_view_count(light));
            let owned = &views[gpu.first_view as usize..][..gpu.view_count as usize];
            assert!(owned.iter().all(|v| v.light == index as u32));
            assert_eq!(owned[0].clip_from_world, light.clip_from_world(1.5).to_cols_array_2d());
        }
    }
}

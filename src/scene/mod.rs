//! The scene: camera, objects, lights, and the shadow technique with its parameters.
//!
//! Scenes are TOML files (see `file.rs`); everything here is plain data plus the
//! transforms the renderer and the CPU twin both need. Time `t` is in seconds.

mod camera;
mod checks;
mod file;
mod light;
pub mod mesh;
pub mod parameters;
mod primitives;
mod settings;

pub use camera::{Camera, Projection};
pub(crate) use file::describe_toml_error;
pub use file::{Override, SceneError, SceneSource, load_scene, parse_scene_str};
pub use light::{
    CUBE_FACES, CascadeSelection, Cascades, Light, LightKind, LightSize, MAX_CASCADES, cube_face_of,
    safe_up as safe_up_for,
};
pub use mesh::{Material, Mesh, MeshError, MeshPart, TextureImage, Vertex};
pub use settings::{
    BiasMode, DepthStorage, Kernel, MAX_TAPS, ShadowSettings, Technique, effective_samples, filter_taps,
    grid_side,
};

use glam::{Mat4, Quat, Vec3};
use std::path::PathBuf;
use std::sync::Arc;

/// Most lights a scene may have (one shadow-map layer each; keep in sync with shaders/common.wgsl).
pub const MAX_LIGHTS: usize = 4;

#[derive(Clone, Debug)]
pub struct Object {
    /// The name in files, the command line and the probe's JSON (English in shipped scenes).
    pub name: String,
    /// The name shown to a Chinese reader (`name_zh` in the scene file), where the scene gives one.
    pub name_zh: Option<String>,
    pub mesh: Arc<Mesh>,
    /// Linear RGB used where the mesh part has no material.
    pub color: Vec3,
    pub translate: Vec3,
    pub rotate_deg: Vec3,
    pub scale: Vec3,
    /// Angular speed about each axis, degrees per second.
    pub spin_deg_per_s: Vec3,
}

impl Object {
    /// The object's name as a reader of `lang` sees it: `name_zh` in Chinese where there is one.
    pub fn label(&self, lang: crate::i18n::Lang) -> &str {
        // The scene file's own Chinese name: not a table lookup.
        match (lang, &self.name_zh) {
            (crate::i18n::Lang::Zh, Some(zh)) => zh,
            _ => &self.name,
        }
    }

    /// The object does not spin: its transform is the same at every time.
    pub fn is_still(&self) -> bool {
        self.spin_deg_per_s == Vec3::ZERO
    }

    /// Model matrix at time `t`: scale, then rotate (XYZ Euler, degrees, plus spin), then translate.
    pub fn world_from_object(&self, t_s: f32) -> Mat4 {
        let t = f64::from(t_s);
        let spin = |rate: f32| ((f64::from(rate) * t) % 360.0) as f32;
        let spun =
            Vec3::new(spin(self.spin_deg_per_s.x), spin(self.spin_deg_per_s.y), spin(self.spin_deg_per_s.z));
        let r = (self.rotate_deg + spun) * (std::f32::consts::PI / 180.0);
        let rotation = Quat::from_euler(glam::EulerRot::XYZ, r.x, r.y, r.z);
        Mat4::from_scale_rotation_translation(self.scale, rotation, self.translate)
    }

    /// World-space bounds (min, max) at time `t`: the mesh's box, transformed corner by corner.
    pub fn world_bounds(&self, t_s: f32) -> (Vec3, Vec3) {
        let world_from_object = self.world_from_object(t_s);
        let (a, b) = self.mesh.bounds();
        let mut lo = Vec3::splat(f32::INFINITY);
        let mut hi = Vec3::splat(f32::NEG_INFINITY);
        for corner in box_corners(a, b) {
            let p = world_from_object.transform_point3(corner);
            lo = lo.min(p);
            hi = hi.max(p);
        }
        (lo, hi)
    }
}

/// The eight corners of the box from `lo` to `hi`.
pub fn box_corners(lo: Vec3, hi: Vec3) -> [Vec3; 8] {
    std::array::from_fn(|i| {
        Vec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        )
    })
}

#[derive(Clone, Debug)]
pub struct Scene {
    /// The file the scene came from (None for scenes built in code).
    pub path: Option<PathBuf>,
    pub camera: Camera,
    pub objects: Vec<Object>,
    pub lights: Vec<Light>,
    pub shadow: ShadowSettings,
    /// Ambient light, linear RGB.
    pub ambient: Vec3,
}

impl Scene {
    /// The object named `name` (as a probe reports it) as a reader of `lang` sees it; the name
    /// itself where no object has it. Objects sharing a name are shown by the first one's label.
    pub fn object_label<'a>(&'a self, name: &'a str, lang: crate::i18n::Lang) -> &'a str {
        self.objects.iter().find(|o| o.name == name).map_or(name, |o| o.label(lang))
    }
}

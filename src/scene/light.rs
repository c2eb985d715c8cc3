//! Shadow-casting lights and the geometry of their shadow maps.
//!
//! Depth conventions (wgpu, depth range 0..1 [WebGPU-Coordinates]; docs/REFERENCES.md, Notation):
//! - `d` / `depth_linear`: distance from the light along its axis (a point light's cube face: the
//!   straight distance to the light, which the face stores), world units.
//! - `z` / `depth_ndc`: what the shadow map stores. Orthographic: `z = (d - near) / (far - near)`.
//!   Perspective: `z = far * (d - near) / (d * (far - near))`, so `d = near*far / (far - z*(far - near))`.

use glam::{Mat4, Quat, Vec3};

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightKind {
    /// Orthographic shadow map; `extent_world` is the half-width of the ortho frustum.
    Directional { extent_world: f32 },
    /// Perspective shadow map with a square frustum of `fov_deg`.
    Spot { fov_deg: f32 },
    /// A lamp shadowing in every direction: six 90° perspective views, the faces of a cube map,
    /// whose maps store the distance to the light [LearnOpenGL-PointShadows].
    Point,
}

/// The size model used by PCSS and the ground truth. Keep the two apart: their units differ.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightSize {
    /// Area light of this diameter at the light's position, world units [GAMES202-L3] [NVIDIA-2008].
    Width { width_world: f32 },
    /// Directional light subtending this full angle (the sun: about 0.53 degrees).
    AngularDiameter { angular_diameter_deg: f32 },
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Light {
    pub kind: LightKind,
    pub position: Vec3,
    pub target: Vec3,
    pub up: Vec3,
    /// Linear RGB.
    pub color: Vec3,
    pub intensity: f32,
    pub shadow_map_size: u32,
    pub near: f32,
    pub far: f32,
    pub size: LightSize,
    /// Orbit speed about the axis through `target` along `up`, degrees per second.
    pub orbit_deg_per_s: f32,
    /// A directional light's cascades (one: a single map over `extent_world`).
    pub cascades: Cascades,
}

/// Most cascades a directional light may have (engines stop at four; each is a map to render).
pub const MAX_CASCADES: u32 = 4;

/// How a directional light splits the camera's frustum among its maps (src/shadow/cascades.rs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cascades {
    /// Maps, sharpest first; 1 is the one map of `LightKind::Directional::extent_world`.
    pub count: u32,
    /// The split scheme: 0 uniform, 1 logarithmic, between a blend [Zhang-2006] [Zhang-2007].
    pub lambda: f32,
    /// Where the last cascade ends along the camera's view axis, world units (at most its far plane).
    pub distance_world: f32,
    /// How a pixel picks its cascade.
    pub selection: CascadeSelection,
}

impl Default for Cascades {
    fn default() -> Self {
        Self { count: 1, lambda: 0.5, distance_world: f32::INFINITY, selection: CascadeSelection::ByMap }
    }
}

/// How a pixel picks one of a sun's cascades, the two schemes [Microsoft-CSM] compares.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum CascadeSelection {
    /// The sharpest cascade whose map holds the point a few texels inside its edge. Each map
    /// covers its slice's bounding sphere, so a cascade is read well past the end of its slice.
    #[default]
    ByMap,
    /// The cascade whose slice holds the point's depth along the camera's view axis: the index
    /// changes exactly at the split distances.
    ByInterval,
}

impl CascadeSelection {
    pub const ALL: &'static [CascadeSelection] = &[CascadeSelection::ByMap, CascadeSelection::ByInterval];

    /// The name scene files, lesson steps and `--set` write (`cascade_selection = "interval"`).
    pub fn name(self) -> &'static str {
        match self {
            CascadeSelection::ByMap => "map",
            CascadeSelection::ByInterval => "interval",
        }
    }

    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.iter().copied().find(|s| s.name() == name)
    }

    /// What the inspector's combo box shows, in `lang`.
    pub fn label(self, lang: crate::i18n::Lang) -> &'static str {
        crate::i18n::tr(
            lang,
            match self {
                CascadeSelection::ByMap => "by map (the sharpest map that holds the pixel)",
                CascadeSelection::ByInterval => "by interval (view depth against the splits)",
            },
        )
    }
}

impl Cascades {
    pub fn is_cascaded(&self) -> bool {
        self.count > 1
    }
}

impl Light {
    pub fn is_orthographic(&self) -> bool {
        matches!(self.kind, LightKind::Directional { .. })
    }

    /// Its maps store the distance to the light (a point light's cube), not projected depth.
    pub fn stores_distance(&self) -> bool {
        matches!(self.kind, LightKind::Point)
    }

    /// The light's position at time `t`, after orbiting.
    pub fn position_at(&self, t_s: f32) -> Vec3 {
        // Wrapped in f64 so long times keep their precision.
        let angle = ((f64::from(self.orbit_deg_per_s) * f64::from(t_s)) % 360.0).to_radians() as f32;
        if angle == 0.0 {
            return self.position;
        }
        let axis = self.up.normalize_or(Vec3::Y);
        self.target + Quat::from_axis_angle(axis, angle) * (self.position - self.target)
    }

    /// Unit direction the light travels in (from the light towards its target) at time `t`.
    pub fn direction_at(&self, t_s: f32) -> Vec3 {
        (self.target - self.position_at(t_s)).normalize_or(Vec3::NEG_Y)
    }

    pub fn view_from_world(&self, t_s: f32) -> Mat4 {
        let eye = self.position_at(t_s);
        let forward = (self.target - eye).normalize_or(Vec3::NEG_Y);
        Mat4::look_to_rh(eye, forward, safe_up(forward, self.up))
    }

    pub fn clip_from_view(&self) -> Mat4 {
        match self.kind {
            LightKind::Directional { extent_world: e } => {
                Mat4::orthographic_rh(-e, e, -e, e, self.near, self.far)
            }
            LightKind::Spot { fov_deg } => {
                Mat4::perspective_rh(fov_deg.to_radians(), 1.0, self.near, self.far)
            }
            LightKind::Point => Mat4::perspective_rh(90f32.to_radians(), 1.0, self.near, self.far),
        }
    }

    /// The light's one view (a point light: the view towards its target; its shadow views are
    /// the cube's faces, `cube_face_clip_from_world`).
    pub fn clip_from_world(&self, t_s: f32) -> Mat4 {
        self.clip_from_view() * self.view_from_world(t_s)
    }

    /// A point light's cube face `face` (0..6: +X, -X, +Y, -Y, +Z, -Z) at time `t`.
    pub fn cube_face_clip_from_world(&self, face: usize, t_s: f32) -> Mat4 {
        let (forward, up) = CUBE_FACES[face];
        self.clip_from_view() * Mat4::look_to_rh(self.position_at(t_s), forward, up)
    }

    /// `W`: width of the shadow frustum where the map is measured, world units
    /// (orthographic: the ortho width; perspective: at the near plane).
    pub fn frustum_width_world(&self) -> f32 {
        match self.kind {
            LightKind::Directional { extent_world } => 2.0 * extent_world,
            LightKind::Spot { fov_deg } => 2.0 * self.near * (0.5 * fov_deg.to_radians()).tan(),
            LightKind::Point => 2.0 * self.near,
        }
    }

    /// tan(fov / 2) of a perspective view (1 for a cube face); 0 for orthographic.
    pub fn tan_half_fov(&self) -> f32 {
        match self.kind {
            LightKind::Directional { .. } => 0.0,
            LightKind::Spot { fov_deg } => (0.5 * fov_deg.to_radians()).tan(),
            LightKind::Point => 1.0,
        }
    }
}

/// A cube map's faces as (forward, up), in the order +X, -X, +Y, -Y, +Z, -Z. The four around
/// the horizon keep +Y up, so that a face's picture stands upright; the two poles have their up
/// towards -Z (looking up) and +Z (looking down), which lines them up with the +Z face in the
/// unfolded cross. shaders/shadow_lookup.wgsl's `cube_face_axes` is the same table.
pub const CUBE_FACES: [(Vec3, Vec3); 6] = [
    (Vec3::X, Vec3::Y),
    (Vec3::NEG_X, Vec3::Y),
    (Vec3::Y, Vec3::NEG_Z),
    (Vec3::NEG_Y, Vec3::Z),
    (Vec3::Z, Vec3::Y),
    (Vec3::NEG_Z, Vec3::Y),
];

/// The cube face a direction from the light falls in: its largest axis, signed (ties go to the
/// earlier axis, as in the shader's `cube_face_of`).
pub fn cube_face_of(direction: Vec3) -> usize {
    let a = direction.abs();
    if a.x >= a.y && a.x >= a.z {
        usize::from(direction.x < 0.0)
    } else if a.y >= a.z {
        2 + usize::from(direction.y < 0.0)
    } else {
        4 + usize::from(direction.z < 0.0)
    }
}

/// An up vector that is not parallel to `forward` (look_at needs one).
pub fn safe_up(forward: Vec3, up: Vec3) -> Vec3 {
    let up = up.normalize_or(Vec3::Y);
    if forward.cross(up).length_squared() > 1e-6 {
        up
    } else if forward.cross(Vec3::Z).length_squared() > 1e-6 {
        Vec3::Z
    } else {
        Vec3::X
    }
}

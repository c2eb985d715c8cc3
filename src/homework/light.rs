//! The light a homework is drawn with. The framework asks the student's `CalcLightMVP(translate,
//! scale)` (`lights/DirectionalLight.js`) for each object's `uLightMVP`; the student's passes use
//! each matrix as it is, whatever it is (near <= 0, mirrored axes, a perspective light). For its
//! own side (shadowlab's technique, the ground truth) shadowlab reads a light of its own out of
//! the matrix an object at the origin gets: the same frustum, placed at its near plane, where
//! the map's depth 0 is and where the homework's PCSS formula puts the light.

use crate::scene::{Light, LightKind, Scene};
use glam::{Mat3, Mat4, Vec3, Vec4};

/// GL clip space from wgpu's: z from 0..w to -w..w (the framework's matrices are GL's; the vertex
/// epilogue maps them back).
pub fn gl_from_wgpu_clip() -> Mat4 {
    Mat4::from_cols_array(&[1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, -1.0, 1.0])
}

/// Where a homework's light matrix came from.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
#[serde(untagged)]
pub enum LightFrom {
    /// The student's script, at the line of its projection call (or of its `return`).
    Script { file: String, line: usize },
    /// The check scene's own light (the framework's frustum): no script, or one that failed.
    Framework,
}

impl LightFrom {
    /// `DirectionalLight.js:37`, or `framework`.
    pub fn label(&self) -> String {
        match self {
            LightFrom::Script { file, line } => format!("{file}:{line}"),
            LightFrom::Framework => "framework".into(),
        }
    }
}

/// What a student's model matrix does instead of translate-then-scale.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ModelMatrixError {
    /// The object's translation and scale are not applied.
    Missing,
    /// Scaled after translating: the translation is scaled too.
    WrongOrder,
    /// Translated by the light's position (the template's own line).
    TranslatedByLightPosition,
    /// Something else: the matrix differs from projection * view * translate * scale.
    Different,
}

/// The light of one homework check: the matrices its passes use and where they came from.
#[derive(Clone, Debug, PartialEq)]
pub struct HomeworkLight {
    pub from: LightFrom,
    /// `uLightMVP` per scene object, GL clip conventions.
    pub clip_from_object: Vec<Mat4>,
    /// The matrix an object at the origin, unscaled, gets: the light's clip from world as built.
    pub clip_from_world: Mat4,
    /// `uLightPos`, world units (also the shading's light direction: `normalize(uLightPos)`).
    pub position: Vec3,
    /// Where the light looks (unit, world): from its position to its focal point.
    pub look_direction: Vec3,
    /// `uLightIntensity`.
    pub intensity: Vec3,
    /// What the student's model matrix does instead of translate-then-scale, where it is wrong.
    pub model_matrix: Option<ModelMatrixError>,
    /// The values the student's page gave its own uniforms, by name (empty: none known, all 0).
    pub page_uniforms: PageUniforms,
    /// Draws of the page's animation whose uLightMVP for this light did not follow what moved.
    pub stale: Vec<StaleMatrix>,
}

/// A draw of the page's animation whose `uLightMVP` did not follow what moved: it matched its
/// light's matrix times its own `uModelMatrix` on the first frames, and later matches only the
/// light, or the object, as it was then.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct StaleMatrix {
    /// Seconds of the page's animation.
    pub time_s: f64,
    /// `light`: the light moved and the draw kept its old matrix; `object`: the object moved;
    /// `none`: no draw of the page's first frames holds this light's matrix at all (time 0).
    pub moved: &'static str,
    /// The page's light, as its `lights` are numbered.
    pub light: usize,
    /// The model file the draw drew, where known.
    pub object: Option<String>,
    /// Where the page itself calls CalcLightMVP (`src/materials/PhongMaterial.js:4`).
    pub computed_at: Vec<String>,
    /// It calls it only while it loads, never in a frame.
    pub computed_only_while_loading: bool,
}

/// The uniforms a student's page set on its first frame, by the name their code gave each:
/// for the camera pass's program and the light pass's.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct PageUniforms {
    pub camera: ObjectUniforms,
    pub shadow: ObjectUniforms,
}

/// One program's uniforms by the kind of object drawn, flat numbers in WebGL's order. The
/// framework's scene is a floor and models: shadowlab's floor gets what their page set when it
/// drew its floor, every other object what it set for its models (where a kind was never drawn,
/// what most of the draws had).
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct ObjectUniforms {
    pub floor: std::collections::BTreeMap<String, Vec<f64>>,
    pub other: std::collections::BTreeMap<String, Vec<f64>>,
    /// Their own names for the drawn object's model matrix (`uLightModel`): each gets the check
    /// object's own, as their code sends each object's.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub model_matrices: Vec<String>,
}

impl ObjectUniforms {
    /// The values for `object` of the check's scene at `t_s` seconds.
    pub fn of(
        &self,
        object: &crate::scene::Object,
        t_s: f32,
    ) -> std::collections::BTreeMap<String, Vec<f64>> {
        let mut values =
            if object.name.eq_ignore_ascii_case("floor") { &self.floor } else { &self.other }.clone();
        let model: Vec<f64> =
            object.world_from_object(t_s).to_cols_array().iter().map(|v| f64::from(*v)).collect();
        for name in &self.model_matrices {
            values.insert(name.clone(), model.clone());
        }
        values
    }
}

impl HomeworkLight {
    /// The scene's light `index` as the framework would hand it over (its frustum, position and
    /// colour; `uLightIntensity` is `intensity_scale` times its colour and intensity).
    pub fn of_scene(scene: &Scene, index: usize, t_s: f32, intensity_scale: f32) -> Option<Self> {
        let light = scene.lights.get(index)?;
        let clip_from_world = gl_from_wgpu_clip() * light.clip_from_world(t_s);
        Some(Self {
            from: LightFrom::Framework,
            clip_from_object: scene
                .objects
                .iter()
                .map(|o| clip_from_world * o.world_from_object(t_s))
                .collect(),
            clip_from_world,
            position: light.position_at(t_s),
            look_direction: light.direction_at(t_s),
            intensity: intensity_scale * light.intensity * light.color,
            model_matrix: None,
            stale: Vec::new(),
            page_uniforms: PageUniforms::default(),
        })
    }
}

/// A light read out of a student's matrix, and what shadowlab had to change to hold it.
#[derive(Clone, Debug, PartialEq)]
pub struct ReadLight {
    pub light: Light,
    /// One line each: what differs between the student's frustum and shadowlab's copy.
    pub notes: Vec<String>,
}

/// Row `i` of `m`.
fn row(m: &Mat4, i: usize) -> Vec4 {
    Vec4::new(m.x_axis[i], m.y_axis[i], m.z_axis[i], m.w_axis[i])
}

/// Cosine of the angle between two vectors, 0 where one is zero.
fn cos_between(a: Vec3, b: Vec3) -> f32 {
    let n = a.length() * b.length();
    if n > 0.0 { a.dot(b) / n } else { 0.0 }
}

/// Axes this far from perpendicular (cosine) are a skewed frustum.
const SKEW_COS: f32 = 1e-3;
/// Extents this far apart (relative) are a frustum that is not square.
const SQUARE_TOLERANCE: f32 = 1e-3;

/// The light whose map is the frustum of `clip_from_world_gl` (GL clip from world, as the
/// student built it): orthographic where its last row is (0, 0, 0, w), else perspective.
/// `focal_point` (engine.js's) places the light's target on its axis; the rest (map size, width,
/// colour) comes from `like`. Err, on one line, where the matrix is no light's frustum (singular,
/// skewed, not finite, depth reversed).
pub fn read_light(clip_from_world_gl: Mat4, focal_point: Vec3, like: &Light) -> Result<ReadLight, String> {
    if !clip_from_world_gl.is_finite() {
        return Err("the matrix has entries that are not finite numbers".into());
    }
    let w = row(&clip_from_world_gl, 3);
    if w.length() == 0.0 {
        return Err("the matrix's last row is zero: no point has a clip-space w".into());
    }
    let orthographic = w.truncate().length() <= 1e-6 * w.w.abs();
    let read = if orthographic {
        read_orthographic(clip_from_world_gl * (1.0 / w.w), focal_point, like)?
    } else {
        read_perspective(clip_from_world_gl, focal_point, like)?
    };
    let l = &read.light;
    let finite = l.position.is_finite()
        && l.target.is_finite()
        && l.up.is_finite()
        && l.far.is_finite()
        && l.near.is_finite();
    if !finite || l.far <= l.near {
        return Err("the matrix gives no frustum of finite size".into());
    }
    Ok(read)
}

/// The target on the light's axis from `origin` along `forward`: level with the focal point where
/// that lies ahead within reach, else the middle of the depth range.
fn target_on_axis(origin: Vec3, forward: Vec3, focal_point: Vec3, near: f32, far: f32) -> Vec3 {
    let along = forward.dot(focal_point - origin);
    let along = if along > near && along < far { along } else { 0.5 * (near + far) };
    origin + forward * along
}

fn read_orthographic(m: Mat4, focal_point: Vec3, like: &Light) -> Result<ReadLight, String> {
    let (r0, r1, r2) = (row(&m, 0), row(&m, 1), row(&m, 2));
    let (a0, a1, a2) = (r0.truncate(), r1.truncate(), r2.truncate());
    let (sx, sy, sz) = (a0.length(), a1.length(), a2.length());
    if sx <= 0.0 || sy <= 0.0 || sz <= 0.0 {
        return Err("the matrix flattens the scene (a zero row): no frustum".into());
    }
    if [cos_between(a0, a1), cos_between(a0, a2), cos_between(a1, a2)].iter().any(|c| c.abs() > SKEW_COS) {
        return Err("the frustum is skewed (its axes are not perpendicular)".into());
    }
    // GL: depth grows away from the light, so the third row points the way the light shines.
    let forward = a2 / sz;
    let (x_axis, y_axis) = (a0 / sx, a1 / sy);
    let axes = Mat3::from_cols(a0, a1, a2).transpose();
    if axes.determinant().abs() < 1e-12 {
        return Err("the matrix is singular: no frustum".into());
    }
    // The near plane's centre: x = y = 0, z = -1 (GL).
    let centre = axes.inverse() * Vec3::new(-r0.w, -r1.w, -1.0 - r2.w);
    let far = 2.0 / sz;
    let (ex, ey) = (1.0 / sx, 1.0 / sy);
    let mut notes = Vec::new();
    let extent = ex.max(ey);
    if (ex - ey).abs() > SQUARE_TOLERANCE * extent {
        notes.push(format!(
            "the frustum is {:.1} by {:.1} world units; shadowlab's own map is square, {:.1} on a side",
            2.0 * ex,
            2.0 * ey,
            2.0 * extent
        ));
    }
    // shadowlab's view is right-handed with x = forward x up: the student's x axis, unless one
    // axis is mirrored (two mirrored axes are a half turn, which is a rotation).
    if x_axis.cross(y_axis).dot(forward) > 0.0 {
        notes.push("one axis of the frustum is mirrored; shadowlab's own map is its mirror image".into());
    }
    let light = Light {
        kind: LightKind::Directional { extent_world: extent },
        position: centre,
        target: target_on_axis(centre, forward, focal_point, 0.0, far),
        up: y_axis,
        near: 0.0,
        far,
        orbit_deg_per_s: 0.0,
        ..*like
    };
    Ok(ReadLight { light, notes })
}

fn read_perspective(m: Mat4, focal_point: Vec3, like: &Light) -> Result<ReadLight, String> {
    let w = row(&m, 3);
    let scale = w.truncate().length();
    let m = m * (1.0 / scale);
    let (r0, r1, r2, r3) = (row(&m, 0), row(&m, 1), row(&m, 2), row(&m, 3));
    let forward = r3.truncate();
    // The eye: where x, y and w all vanish.
    let rows = Mat3::from_cols(r0.truncate(), r1.truncate(), forward).transpose();
    if rows.determinant().abs() < 1e-12 {
        return Err("the matrix is singular: no frustum".into());
    }
    let eye = rows.inverse() * Vec3::new(-r0.w, -r1.w, -r3.w);
    let lateral = |a: Vec3| a - forward * a.dot(forward);
    let (a0, a1) = (lateral(r0.truncate()), lateral(r1.truncate()));
    let (sx, sy) = (a0.length(), a1.length());
    if sx <= 0.0 || sy <= 0.0 || cos_between(a0, a1).abs() > SKEW_COS {
        return Err("the frustum is skewed or flat".into());
    }
    // Along the axis z_ndc = A + B / d (GL): d_near at -1, d_far at +1.
    let a = r2.truncate().dot(forward);
    let b = r2.truncate().dot(eye) + r2.w;
    let (near, far) = (-b / (1.0 + a), b / (1.0 - a));
    if !(near > 0.0 && far > near && far.is_finite()) {
        return Err(format!("the perspective frustum's depth range is {near}..{far}: not a light's"));
    }
    let mut notes = Vec::new();
    let off_centre = r0.truncate().dot(forward).abs() / sx + r1.truncate().dot(forward).abs() / sy;
    if off_centre > 1e-3 {
        notes.push("the perspective frustum is off-centre; shadowlab's own is centred on its axis".into());
    }
    let (fov_x, fov_y) = (2.0 * (1.0 / sx).atan(), 2.0 * (1.0 / sy).atan());
    let fov = fov_x.max(fov_y);
    if (fov_x - fov_y).abs() > SQUARE_TOLERANCE * fov {
        notes.push(format!(
            "the frustum's field of view is {:.1} by {:.1} degrees; shadowlab's own is square, {:.1}",
            fov_x.to_degrees(),
            fov_y.to_degrees(),
            fov.to_degrees()
        ));
    }
    let (x_axis, y_axis) = (a0 / sx, a1 / sy);
    if x_axis.cross(y_axis).dot(forward) > 0.0 {
        notes.push("one axis of the frustum is mirrored; shadowlab's own map is its mirror image".into());
    }
    let light = Light {
        kind: LightKind::Spot { fov_deg: fov.to_degrees() },
        position: eye,
        target: target_on_axis(eye, forward, focal_point, near, far),
        up: y_axis,
        near,
        far,
        orbit_deg_per_s: 0.0,
        ..*like
    };
    Ok(ReadLight { light, notes })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::LightSize;

    fn like() -> Light {
        Light {
            kind: LightKind::Directional { extent_world: 100.0 },
            position: Vec3::new(0.0, 80.0, 80.0),
            target: Vec3::ZERO,
            up: Vec3::Y,
            color: Vec3::ONE,
            intensity: 1.0,
            shadow_map_size: 2048,
            near: 0.01,
            far: 400.0,
            size: LightSize::Width { width_world: 5.0 },
            orbit_deg_per_s: 0.0,
            cascades: Default::default(),
        }
    }

    /// gl-matrix's `ortho` and `lookAt`, written out (GL conventions) [GlMatrix-Mat4].
    fn gl_ortho(l: f32, r: f32, b: f32, t: f32, n: f32, f: f32) -> Mat4 {
        Mat4::from_cols_array(&[
            2.0 / (r - l),
            0.0,
            0.0,
            0.0,
            0.0,
            2.0 / (t - b),
            0.0,
            0.0,
            0.0,
            0.0,
            -2.0 / (f - n),
            0.0,
            -(r + l) / (r - l),
            -(t + b) / (t - b),
            -(f + n) / (f - n),
            1.0,
        ])
    }

    fn look_at(eye: Vec3, centre: Vec3) -> Mat4 {
        Mat4::look_at_rh(eye, centre, Vec3::Y)
    }

    /// shadowlab's light projects every point to the same depth and, up to the mirror the notes
    /// name, the same place as the student's matrix.
    fn assert_same_frustum(student: Mat4, read: &ReadLight, mirrored_x: bool) {
        let ours = gl_from_wgpu_clip() * read.light.clip_from_world(0.0);
        for p in [
            Vec3::ZERO,
            Vec3::new(30.0, 0.0, -20.0),
            Vec3::new(-40.0, 15.0, 10.0),
            Vec3::new(10.0, 25.0, 35.0),
        ] {
            let project = |m: Mat4| {
                let c = m * p.extend(1.0);
                c.truncate() / c.w
            };
            let (a, b) = (project(student), project(ours));
            let x = if mirrored_x { -b.x } else { b.x };
            assert!((a.x - x).abs() < 1e-4 && (a.y - b.y).abs() < 1e-4, "{p}: {a} against {b}");
            assert!((a.z - b.z).abs() < 1e-4, "{p}: depth {a} against {b}");
        }
    }

    #[test]
    fn the_templates_orthographic_light_is_read_back_exactly() {
        let m = gl_ortho(-100.0, 100.0, -100.0, 100.0, 0.01, 400.0)
            * look_at(Vec3::new(0.0, 80.0, 80.0), Vec3::ZERO);
        let read = read_light(m, Vec3::ZERO, &like()).expect("a light");
        assert_eq!(read.notes, Vec::<String>::new());
        let LightKind::Directional { extent_world } = read.light.kind else {
            panic!("{:?}", read.light.kind)
        };
        assert!((extent_world - 100.0).abs() < 1e-3, "{extent_world}");
        assert!((read.light.far - 399.99).abs() < 1e-2, "{}", read.light.far);
        // At the near plane, 0.01 from the eye towards the origin.
        let eye = Vec3::new(0.0, 80.0, 80.0);
        assert!((read.light.position - (eye - eye.normalize() * 0.01)).length() < 1e-3);
        assert!(read.light.target.length() < 1e-3, "{}", read.light.target);
        assert_same_frustum(m, &read, false);
    }

    #[test]
    fn near_zero_negative_near_a_unit_eye_and_an_off_centre_frustum_are_lights() {
        let cases = [
            gl_ortho(-100.0, 100.0, -100.0, 100.0, 0.0, 1000.0)
                * look_at(Vec3::new(0.0, 80.0, 80.0), Vec3::ZERO),
            gl_ortho(-200.0, 200.0, -200.0, 200.0, -10.0, 2000.0)
                * look_at(Vec3::new(0.0, 80.0, 80.0), Vec3::ZERO),
            gl_ortho(-100.0, 100.0, -100.0, 100.0, -100.0, 100.0)
                * look_at(Vec3::new(0.0, 80.0, 80.0).normalize(), Vec3::ZERO),
            gl_ortho(-50.0, 150.0, -80.0, 120.0, 1.0, 500.0)
                * look_at(Vec3::new(0.0, 80.0, 80.0), Vec3::ZERO),
        ];
        for m in cases {
            let read = read_light(m, Vec3::ZERO, &like()).expect("a light");
            assert!(read.notes.is_empty(), "{:?}", read.notes);
            assert_same_frustum(m, &read, false);
        }
    }

    #[test]
    fn two_mirrored_axes_are_a_half_turn_and_one_is_a_mirror() {
        let view = look_at(Vec3::new(0.0, 80.0, 80.0), Vec3::ZERO);
        let both = gl_ortho(100.0, -100.0, 100.0, -100.0, 1.0, 400.0) * view;
        let read = read_light(both, Vec3::ZERO, &like()).expect("a light");
        assert!(read.notes.is_empty(), "{:?}", read.notes);
        assert_same_frustum(both, &read, false);
        let one = gl_ortho(100.0, -100.0, -100.0, 100.0, 1.0, 400.0) * view;
        let read = read_light(one, Vec3::ZERO, &like()).expect("a light");
        assert_eq!(read.notes.len(), 1, "{:?}", read.notes);
        assert_same_frustum(one, &read, true);
    }

    #[test]
    fn a_perspective_light_is_read_back_as_a_spot_light() {
        let m = Mat4::perspective_rh_gl(60f32.to_radians(), 1.0, 1.0, 300.0)
            * look_at(Vec3::new(0.0, 80.0, 80.0), Vec3::ZERO);
        let read = read_light(m, Vec3::ZERO, &like()).expect("a light");
        assert!(read.notes.is_empty(), "{:?}", read.notes);
        let LightKind::Spot { fov_deg } = read.light.kind else { panic!("{:?}", read.light.kind) };
        assert!((fov_deg - 60.0).abs() < 1e-3, "{fov_deg}");
        assert!((read.light.near - 1.0).abs() < 1e-3 && (read.light.far - 300.0).abs() < 0.1);
        assert_same_frustum(m, &read, false);
    }

    #[test]
    fn a_matrix_that_is_no_frustum_is_refused_on_one_line() {
        let view = look_at(Vec3::new(0.0, 80.0, 80.0), Vec3::ZERO);
        let mut skewed = gl_ortho(-100.0, 100.0, -100.0, 100.0, 1.0, 400.0) * view;
        skewed.x_axis.y += 0.3;
        for m in [Mat4::ZERO, Mat4::from_cols_array(&[f32::NAN; 16]), skewed] {
            let e = read_light(m, Vec3::ZERO, &like()).expect_err("no light");
            assert!(!e.contains('\n') && e.len() > 10, "{e}");
        }
    }
}

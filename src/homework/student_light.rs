//! The student's own light: their `engine.js` makes it, their `DirectionalLight.js`'s
//! `CalcLightMVP(translate, scale)` builds each object's `uLightMVP` (both run in the student's
//! whole page, `page`, in a real JavaScript engine: QuickJS on the desktop, the browser's own in
//! the page), and
//! shadowlab reads its own copy of the frustum out of the matrix (`read_light`). A script that
//! fails says so on one line, and the check goes on with the framework's light.

use super::light::{HomeworkLight, LightFrom, ModelMatrixError, PageUniforms, read_light};
pub use super::light_source::{LightEntry, TimedCheck};
use super::light_source::{LightMatrices, load_light};
use super::page::{EngineLight, GlCall, ScriptError};
use super::program::ShaderSource;
use super::{FRAMEWORK_LIGHT_INTENSITY, HomeworkSource};
use crate::scene::{Light, LightKind, Scene};
use glam::{Mat4, Vec3};
use serde::Serialize;
use std::task::Poll;

/// The light's part of a check's report.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LightReport {
    /// `DirectionalLight.js:37` (the file and line the matrix came from), or `framework`.
    pub from: String,
    /// Why the student's script was not used, on one line (the check then uses the framework's).
    pub error: Option<String>,
    /// `uLightPos`, the focal point and up, as engine.js gives them, each with where it came from.
    pub position: [f32; 3],
    pub position_from: String,
    pub focal_point: [f32; 3],
    pub up: [f32; 3],
    /// The matrix an object at the origin gets (GL clip from world, column-major, as gl-matrix
    /// lays it out), and each object's `uLightMVP` by object name.
    pub clip_from_world: [f32; 16],
    pub clip_from_object: Vec<(String, [f32; 16])>,
    /// The gl-matrix calls that built the matrix (at the origin, unscaled).
    pub calls: Vec<CallReport>,
    /// shadowlab's copy of the frustum, for its own technique and the ground truth.
    pub frustum: FrustumReport,
    /// One line each: what shadowlab noticed or had to change.
    pub notes: Vec<String>,
    /// How each object's matrix treats its translation and scale (None: as the framework means).
    pub model_matrix: Option<ModelMatrixError>,
    /// Every light the student's page made, in order (empty where the page did not run).
    pub lights: Vec<LightEntry>,
    /// The values the student's page gave the uniforms of the camera pass's and the light
    /// pass's programs on its first frame, by the names their code uses (empty where the page
    /// did not run or drew nothing).
    pub page_uniforms: PageUniforms,
}

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CallReport {
    pub call: String,
    pub args: Vec<f64>,
    pub line: usize,
}

/// The frustum shadowlab's own side uses.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FrustumReport {
    pub kind: &'static str,
    /// Orthographic: the map's width; perspective: its field of view, degrees.
    pub width_world: Option<f32>,
    pub fov_deg: Option<f32>,
    /// The near plane's centre, and the depth range from it, world units.
    pub near_centre: [f32; 3],
    pub depth_range_world: f32,
    /// One texel's width across the light at the focal point, world units.
    pub texel_world: f32,
    /// The share of the map's [0, 1] depth the scene's objects occupy under the student's matrix
    /// (the rest of the depth precision is spent on empty space).
    pub scene_depth_share: Option<f32>,
}

/// Under this share of the depth range a note says the precision goes to empty space.
const DEPTH_SHARE_NOTE: f32 = 0.25;

/// The [0, 1] depth the scene's objects span under `clip_from_world` (GL clip conventions),
/// from their bounding boxes; None where a corner is behind a perspective light's eye.
fn scene_depth_share(clip_from_world: Mat4, scene: &Scene, t_s: f32) -> Option<f32> {
    let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
    for object in &scene.objects {
        let (a, b) = object.world_bounds(t_s);
        for corner in crate::scene::box_corners(a, b) {
            let clip = clip_from_world * corner.extend(1.0);
            if clip.w <= 0.0 {
                return None;
            }
            let depth = (0.5 * clip.z / clip.w + 0.5).clamp(0.0, 1.0);
            (lo, hi) = (lo.min(depth), hi.max(depth));
        }
    }
    (hi >= lo).then_some(hi - lo)
}

/// The frustum's report with the depth the scene spans under the student's matrix, and a note
/// where most of the depth range holds nothing.
fn with_depth_share(
    mut frustum: FrustumReport,
    clip_from_world: Mat4,
    scene: &Scene,
    t_s: f32,
    notes: &mut Vec<String>,
) -> FrustumReport {
    frustum.scene_depth_share = scene_depth_share(clip_from_world, scene, t_s);
    if let Some(share) = frustum.scene_depth_share.filter(|s| *s < DEPTH_SHARE_NOTE) {
        notes.push(format!(
            "the scene spans {:.0}% of the light's depth range ({:.0} of {:.0} world units): the rest of the map's depth precision is spent on empty space; near and far closer to the scene keep it",
            100.0 * share,
            share * frustum.depth_range_world,
            frustum.depth_range_world
        ));
    }
    frustum
}

/// The light a homework is checked with, and the scene whose light `index` is shadowlab's copy.
pub struct StudentLight {
    pub light: HomeworkLight,
    pub scene: Scene,
    pub report: LightReport,
    /// Why the check does not judge this submission at all (its page builds passes the check
    /// cannot), on one line naming where.
    pub refused: Option<String>,
}

/// Each scene object's name with its matrix, as the report lists them.
fn named_matrices(scene: &Scene, matrices: &[Mat4]) -> Vec<(String, [f32; 16])> {
    scene.objects.iter().zip(matrices).map(|(o, m)| (o.name.clone(), cols(*m))).collect()
}

fn cols(m: Mat4) -> [f32; 16] {
    m.to_cols_array()
}

fn vec3(v: [f64; 3]) -> Vec3 {
    Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32)
}

/// Two matrices project the same (relative difference of their entries under `tolerance`).
fn same(a: Mat4, b: Mat4) -> bool {
    let scale =
        a.to_cols_array().iter().chain(&b.to_cols_array()).fold(0.0f32, |m, v| m.max(v.abs())).max(1e-6);
    a.to_cols_array().iter().zip(b.to_cols_array()).all(|(x, y)| (x - y).abs() <= 1e-4 * scale)
}

/// How `matrix` (an object's) relates to `clip_from_world` for an object placed by `t` and `s`.
fn model_matrix(
    matrix: Mat4,
    clip_from_world: Mat4,
    t: Vec3,
    s: Vec3,
    light_position: Vec3,
) -> Option<ModelMatrixError> {
    let (translate, scale) = (Mat4::from_translation(t), Mat4::from_scale(s));
    if same(matrix, clip_from_world * translate * scale) {
        return None;
    }
    if t == Vec3::ZERO && s == Vec3::ONE {
        return Some(ModelMatrixError::Different);
    }
    Some(if same(matrix, clip_from_world) {
        ModelMatrixError::Missing
    } else if same(matrix, clip_from_world * scale * translate) {
        ModelMatrixError::WrongOrder
    } else if same(matrix, clip_from_world * Mat4::from_translation(light_position) * scale) {
        ModelMatrixError::TranslatedByLightPosition
    } else {
        ModelMatrixError::Different
    })
}

/// The frustum shadowlab holds as a report.
fn frustum_report(light: &Light, focal_point: Vec3) -> FrustumReport {
    let depth_range_world = light.far - light.near;
    let (kind, width_world, fov_deg) = match light.kind {
        LightKind::Directional { extent_world } => ("orthographic", Some(2.0 * extent_world), None),
        LightKind::Spot { fov_deg } => ("perspective", None, Some(fov_deg)),
        LightKind::Point => ("cube", None, Some(90.0)),
    };
    let distance = (focal_point - light.position).dot(light.direction_at(0.0)).max(light.near);
    let texel_world = match light.kind {
        LightKind::Directional { extent_world } => 2.0 * extent_world / light.shadow_map_size as f32,
        LightKind::Spot { .. } | LightKind::Point => {
            2.0 * distance * light.tan_half_fov() / light.shadow_map_size as f32
        }
    };
    FrustumReport {
        kind,
        width_world,
        fov_deg,
        near_centre: light.position.to_array(),
        depth_range_world,
        texel_world,
        scene_depth_share: None,
    }
}

/// The page's lights as the report lists them: the checked one says where its matrix comes from;
/// where the page made none the check could use, the light it used instead is listed too.
fn listed_lights(lights: Vec<LightEntry>, used: &HomeworkLight) -> Vec<LightEntry> {
    if lights.is_empty() {
        return lights;
    }
    let mut listed: Vec<LightEntry> = lights
        .into_iter()
        .map(|l| if l.checked { LightEntry { from: used.from.label(), ..l } } else { l })
        .collect();
    if !listed.iter().any(|l| l.checked) {
        listed.insert(
            0,
            LightEntry {
                kind: "DirectionalLight".into(),
                from: used.from.label(),
                made_at: "framework".into(),
                position: Some(used.position.to_array()),
                checked: true,
                error: None,
                findings: None,
                light_width: None,
                moved_at_s: Vec::new(),
                at_times: Vec::new(),
            },
        );
    }
    listed
}

/// An object the framework could not place by translation and scale alone.
fn rotated(object: &crate::scene::Object) -> bool {
    object.rotate_deg != Vec3::ZERO || !object.is_still()
}

/// Run the submission's light scripts for `scene` (its light `index` is the framework's) at
/// `t_s`: the student's light and shadowlab's copy of it, or the framework's with why. Pending
/// in the browser until the page's Worker has run their page (the desktop answers at once).
pub fn student_light(
    source: &HomeworkSource,
    scene: &Scene,
    index: usize,
    t_s: f32,
) -> Poll<Option<StudentLight>> {
    student_light_of(source, scene, index, t_s, None)
}

/// One of the page's lights (as the report's `lights` number them), as the page loaded or at
/// `time_s` seconds of its animation (one of the light's `moved_at_s`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PageLight {
    pub index: usize,
    pub time_s: Option<f64>,
}

/// As `student_light`, for the page's light `page_light` (None: the one the check uses first).
/// None for a light of the page without matrices then.
pub fn student_light_of(
    source: &HomeworkSource,
    scene: &Scene,
    index: usize,
    t_s: f32,
    page_light: Option<PageLight>,
) -> Poll<Option<StudentLight>> {
    let Some(script) = &source.light_script else {
        return Poll::Ready(framework_light(scene, index, t_s, None, Vec::new(), Vec::new()));
    };
    // The objects whose matrices the page computes: one at the origin, unscaled (the light's
    // own matrix), and each object the framework would place by translation and scale.
    let placed =
        |o: &crate::scene::Object| (o.translate.as_dvec3().to_array(), o.scale.as_dvec3().to_array());
    let objects: Vec<([f64; 3], [f64; 3])> = std::iter::once(([0.0; 3], [1.0; 3]))
        .chain(scene.objects.iter().filter(|o| !rotated(o)).map(placed))
        .collect();
    load_light(script, source.engine.as_ref(), &source.page, &objects).map(|(engine, loaded)| {
        light_of_page(source, script, scene, (index, t_s), page_light, engine, loaded)
    })
}

/// The framework's light for `scene`'s light `index`, with why the student's was not used
/// (`error`), the notes so far and the lights their page made.
/// The framework's light standing in for one the page's CalcLightMVP could not give, still
/// refused where the page is (a float-texture page is not judged, whatever light it has).
fn refused_too(light: Option<StudentLight>, refused: Option<String>) -> Option<StudentLight> {
    light.map(|l| StudentLight { refused, ..l })
}

fn framework_light(
    scene: &Scene,
    index: usize,
    t_s: f32,
    error: Option<String>,
    mut notes: Vec<String>,
    mut lights: Vec<LightEntry>,
) -> Option<StudentLight> {
    let light = HomeworkLight::of_scene(scene, index, t_s, FRAMEWORK_LIGHT_INTENSITY)?;
    let shadowlab = scene.lights.get(index)?;
    if error.is_some() {
        notes.push("checked with the framework's own light instead".into());
    }
    for entry in lights.iter_mut().filter(|l| l.checked) {
        entry.checked = false;
        entry.error = entry.error.take().or_else(|| error.clone());
    }
    let report = LightReport {
        from: LightFrom::Framework.label(),
        error,
        position: light.position.to_array(),
        position_from: "framework".into(),
        focal_point: shadowlab.target.to_array(),
        up: shadowlab.up.to_array(),
        clip_from_world: cols(light.clip_from_world),
        clip_from_object: named_matrices(scene, &light.clip_from_object),
        calls: Vec::new(),
        frustum: with_depth_share(
            frustum_report(shadowlab, shadowlab.target),
            light.clip_from_world,
            scene,
            t_s,
            &mut notes,
        ),
        notes,
        model_matrix: None,
        lights,
        page_uniforms: PageUniforms::default(),
    };
    Some(StudentLight { light, scene: scene.clone(), report, refused: None })
}

/// The student's light from their page's run (`engine`: the light engine.js made; `loaded`:
/// each object's matrix, or why there is none).
fn light_of_page(
    source: &HomeworkSource,
    script: &ShaderSource,
    scene: &Scene,
    (index, t_s): (usize, f32),
    page_light: Option<PageLight>,
    engine: EngineLight,
    loaded: Result<Box<dyn LightMatrices>, ScriptError>,
) -> Option<StudentLight> {
    let mut notes = engine.notes.clone();
    let mut loaded = match loaded {
        Ok(l) => l,
        Err(e) => return framework_light(scene, index, t_s, Some(e.to_string()), notes, Vec::new()),
    };
    notes.extend(loaded.notes().iter().cloned());
    let refused = loaded.refusal();
    let mut lights = loaded.lights();
    // The page's light this check is of (as its `lights` are numbered).
    let page_index = page_light.map(|p| p.index).or_else(|| lights.iter().position(|l| l.checked));
    let stale: Vec<_> = loaded.stale().into_iter().filter(|s| Some(s.light) == page_index).collect();
    let engine = match page_light {
        None => engine,
        Some(wanted) => {
            let engine = loaded.select(wanted.index, wanted.time_s)?;
            for (i, l) in lights.iter_mut().enumerate() {
                l.checked = i == wanted.index;
            }
            engine
        }
    };
    let unchecked: Vec<String> =
        lights.iter().filter(|l| !l.checked).map(|l| format!("{} ({})", l.made_at, l.kind)).collect();
    if !unchecked.is_empty() {
        notes.push(format!(
            "this check is of one of the page's lights; the others: {} (each with a CalcLightMVP gets a check of its own from `shadowlab homework`)",
            unchecked.join(", ")
        ));
    }
    let at_origin = match loaded.light_matrix([0.0; 3], [1.0; 3]) {
        Ok(m) => m,
        Err(e) => {
            return refused_too(
                framework_light(scene, index, t_s, Some(e.to_string()), notes, lights),
                refused,
            );
        }
    };
    let clip_from_world = Mat4::from_cols_array(&at_origin.clip_from_object);
    let position = vec3(engine.position.value);
    let focal_point = vec3(engine.focal_point.value);
    let mut clip_from_object = Vec::new();
    let mut model = None;
    for object in &scene.objects {
        if rotated(object) {
            // The framework never rotates an object: such an object (a scene of one's own) gets
            // the light's matrix times its whole model matrix.
            clip_from_object.push(clip_from_world * object.world_from_object(t_s));
            continue;
        }
        let (t, s) = (object.translate, object.scale);
        let matrix = match loaded.light_matrix(t.as_dvec3().to_array(), s.as_dvec3().to_array()) {
            Ok(m) => Mat4::from_cols_array(&m.clip_from_object),
            Err(e) => {
                return refused_too(
                    framework_light(scene, index, t_s, Some(e.to_string()), notes, lights),
                    refused,
                );
            }
        };
        if model.is_none() {
            model = model_matrix(matrix, clip_from_world, t, s, position);
        }
        clip_from_object.push(matrix);
    }
    let projection = at_origin.calls.iter().rev().find(|c| {
        matches!(
            c.name.as_str(),
            "mat4.ortho"
                | "mat4.perspective"
                | "mat4.frustum"
                | "THREE.Matrix4.makeOrthographic"
                | "THREE.Matrix4.makePerspective"
                | "THREE.OrthographicCamera"
                | "THREE.PerspectiveCamera"
        )
    });
    // The projection's call, in whichever of their scripts the light's class is (a PointLight's
    // CalcLightMVP lives in PointLight.js); else the `return` of DirectionalLight.js's method.
    let (projection_file, projection_line) = match projection {
        Some(c) if !c.file.is_empty() => (c.file.clone(), c.line),
        Some(c) => (script.name.clone(), c.line),
        None => (script.name.clone(), at_origin.return_line),
    };
    let like = scene.lights.get(index)?;
    let (shadowlab_scene, frustum) = match read_light(clip_from_world, focal_point, like) {
        Ok(read) => {
            notes.extend(read.notes);
            let mut s = scene.clone();
            s.lights[index] = read.light;
            (s, frustum_report(&read.light, focal_point))
        }
        Err(e) => {
            notes.push(format!("shadowlab's own side cannot hold this light ({e}); it uses the framework's"));
            (scene.clone(), frustum_report(like, like.target))
        }
    };
    let frustum = with_depth_share(frustum, clip_from_world, scene, t_s, &mut notes);
    let engine_intensity = (engine.intensity.value as f32) * vec3(engine.color.value);
    let light = HomeworkLight {
        from: LightFrom::Script { file: projection_file, line: projection_line },
        clip_from_object,
        clip_from_world,
        position,
        look_direction: (focal_point - position).normalize_or_zero(),
        intensity: engine_intensity,
        model_matrix: model,
        stale,
        page_uniforms: PageUniforms {
            camera: loaded.uniforms(&source.files.phong_fragment.text),
            shadow: loaded.uniforms(&source.files.shadow_fragment.text),
        },
    };
    let report = LightReport {
        from: light.from.label(),
        error: None,
        position: position.to_array(),
        position_from: if engine.position.line > 0 {
            format!("{}:{}", engine.position.file, engine.position.line)
        } else {
            "framework".into()
        },
        focal_point: focal_point.to_array(),
        up: vec3(engine.up.value).to_array(),
        clip_from_world: cols(clip_from_world),
        clip_from_object: named_matrices(scene, &light.clip_from_object),
        calls: at_origin
            .calls
            .iter()
            .map(|c: &GlCall| CallReport { call: c.name.clone(), args: c.args.clone(), line: c.line })
            .collect(),
        frustum,
        notes,
        model_matrix: model,
        lights: listed_lights(lights, &light),
        page_uniforms: light.page_uniforms.clone(),
    };
    Some(StudentLight { light, scene: shadowlab_scene, report, refused })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_model_matrix_is_told_apart_from_its_usual_mistakes() {
        let view = Mat4::orthographic_rh_gl(-100.0, 100.0, -100.0, 100.0, 1.0, 400.0)
            * Mat4::look_at_rh(Vec3::new(0.0, 80.0, 80.0), Vec3::ZERO, Vec3::Y);
        let (t, s, eye) = (Vec3::new(40.0, 0.0, -40.0), Vec3::splat(10.0), Vec3::new(0.0, 80.0, 80.0));
        let (tm, sm) = (Mat4::from_translation(t), Mat4::from_scale(s));
        assert_eq!(model_matrix(view * tm * sm, view, t, s, eye), None);
        assert_eq!(model_matrix(view, view, t, s, eye), Some(ModelMatrixError::Missing));
        assert_eq!(model_matrix(view * sm * tm, view, t, s, eye), Some(ModelMatrixError::WrongOrder));
        assert_eq!(
            model_matrix(view * Mat4::from_translation(eye) * sm, view, t, s, eye),
            Some(ModelMatrixError::TranslatedByLightPosition)
        );
        assert_eq!(model_matrix(view * tm, view, t, s, eye), Some(ModelMatrixError::Different));
    }
}

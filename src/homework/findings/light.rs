//! Findings on the light the student built: a model matrix that does not place the objects, and
//! a frustum that leaves out what the camera sees.

use super::ids;
use super::{FindingKind, Found, Judged};
use crate::homework::ModelMatrixError;
use crate::i18n::{Lang, fill, tr};
use std::collections::BTreeMap;

/// `light_frustum_clips`: more than this share of an object's pixels lie outside the frustum.
const CLIPPED_SHARE: f64 = 0.02;
/// Where the shader takes what lies outside the map as lit, more than this share of the
/// framework's floor outside the frustum is named: the framework's own light (±100 from
/// (0, 80, 80)) leaves its x edges out, 10.5% of the floor, where nothing stands.
const OUTSIDE_LIT_SHARE: f64 = 0.25;

/// The objects' `uLightMVP` is not projection * view * translate * scale: the map and the lookups
/// put the objects somewhere else.
pub const LIGHT_MODEL_MATRIX: FindingKind =
    FindingKind { id: ids::LIGHT_MODEL_MATRIX, lesson: "hard-shadows", step: 1, judge: light_model_matrix };

fn light_model_matrix(j: &Judged<'_>, _: &[super::Finding], lang: Lang) -> Option<Found> {
    let error = j.e.light.model_matrix?;
    let what = match error {
        ModelMatrixError::Missing => {
            "the objects' translation and scale are never applied: every object is drawn into the map where its model file puts it, at the origin and unscaled"
        }
        ModelMatrixError::WrongOrder => {
            "the scale is applied after the translation, so the translation is scaled too: mat4.translate, then mat4.scale, on the same matrix (or T * S)"
        }
        ModelMatrixError::TranslatedByLightPosition => {
            "the objects are translated by the light's position (this.lightPos) instead of their own translation: the template's own line, kept"
        }
        ModelMatrixError::Different => "the matrix is not projection * view * translate * scale",
    };
    Some(Found::new(
        Some("CalcLightMVP"),
        BTreeMap::from([("model_matrix_error", error as u8 as f64)]),
        fill(
            lang,
            "Your CalcLightMVP does not place the objects as the framework does: {}. The light pass and the lookups both use that matrix, so the shadows fall where the objects are not.",
            &[&tr(lang, what)],
        ),
    ))
}

/// An orthographic map whose projection direction (the one along which its x and y stay put)
/// is this far from where the light looks is off: every rigid view gives 0 (0.00 degrees on
/// every light of both development sets).
const DIRECTION_OFF_DEGREES: f32 = 2.0;

/// The map projects the scene along another direction than the light looks: the shadows fall
/// one way while the shading is lit from another.
pub const LIGHT_DIRECTION_OFF: FindingKind =
    FindingKind { id: ids::LIGHT_DIRECTION_OFF, lesson: "hard-shadows", step: 1, judge: light_direction_off };

fn light_direction_off(j: &Judged<'_>, earlier: &[super::Finding], lang: Lang) -> Option<Found> {
    if super::has(earlier, ids::LIGHT_MODEL_MATRIX) {
        return None;
    }
    let m = j.e.light.clip_from_world;
    let w = m.row(3);
    if w.truncate().length() > 1e-6 * w.w.abs().max(1e-6) {
        return None;
    }
    let look = j.e.light.look_direction;
    let along = m.row(0).truncate().cross(m.row(1).truncate()).normalize_or_zero();
    let along = if along.dot(look) < 0.0 { -along } else { along };
    if along == glam::Vec3::ZERO || look == glam::Vec3::ZERO {
        return None;
    }
    let degrees = along.dot(look).clamp(-1.0, 1.0).acos().to_degrees();
    if degrees < DIRECTION_OFF_DEGREES {
        return None;
    }
    let mut figures = BTreeMap::from([("angle_degrees", f64::from(degrees))]);
    for (key, v) in [("along_x", along.x), ("along_y", along.y), ("along_z", along.z)] {
        figures.insert(key, f64::from(v));
    }
    Some(Found::new(
        Some("CalcLightMVP"),
        figures,
        fill(
            lang,
            "Your light's map projects the scene along ({:.2}, {:.2}, {:.2}), {:.1} degrees from where the light looks, from its position to its focal point: ({:.2}, {:.2}, {:.2}). Shadows fall along the first while the shading is lit along the second. A view matrix is a rotation and a translation, and yours ({}) is not: a product summed into a matrix that starts as mat4.create(), the identity, instead of zeros has the identity added, for one.",
            &[&along.x, &along.y, &along.z, &degrees, &look.x, &look.y, &look.z, &j.e.light.from],
        ),
    ))
}

/// Surfaces the camera sees lie outside the student's light frustum (beside, before the near
/// plane or beyond the far one): their lookups read outside the map.
pub const LIGHT_FRUSTUM_CLIPS: FindingKind =
    FindingKind { id: ids::LIGHT_FRUSTUM_CLIPS, lesson: "hard-shadows", step: 4, judge: light_frustum_clips };

fn light_frustum_clips(j: &Judged<'_>, earlier: &[super::Finding], lang: Lang) -> Option<Found> {
    if super::has(earlier, ids::LIGHT_MODEL_MATRIX) {
        return None;
    }
    let names = j.e.light.object_names;
    let mut seen = vec![0usize; names.len()];
    let mut outside = vec![0usize; names.len()];
    for &i in &j.shaded {
        let (Some(o), Some(r)) = (j.e.objects[i], j.receivers[i]) else { continue };
        if o < seen.len() {
            seen[o] += 1;
            outside[o] += usize::from(!r.inside());
        }
    }
    let share = |o: usize| outside[o] as f64 / seen[o].max(1) as f64;
    let Some(worst) =
        (0..names.len()).filter(|&o| share(o) > CLIPPED_SHARE).max_by(|&a, &b| share(a).total_cmp(&share(b)))
    else {
        return framework_floor_clipped(j, lang);
    };
    let total = outside.iter().sum::<usize>();
    Some(Found::new(
        Some("CalcLightMVP"),
        BTreeMap::from([
            ("clipped_share", j.share(total)),
            ("worst_object_clipped_share", share(worst)),
            ("clipped_pixels", total as f64),
        ]),
        fill(
            lang,
            "{:.1}% of what the camera sees lies outside your light's frustum, most of it on the {} ({:.0}% of it): the map has nothing there, and its lookups read outside [0, 1]. Make the orthographic box wide and deep enough for the scene (left/right/bottom/top, near and far).",
            &[&(100.0 * j.share(total)), &names[worst], &(100.0 * share(worst))],
        ),
    ))
}

/// The check scene fits the student's light, but the framework's own floor, where their page
/// draws it, does not: a band of it is dark for the frustum alone.
fn framework_floor_clipped(j: &Judged<'_>, lang: Lang) -> Option<Found> {
    let unwritten_lit = super::source_lines::unwritten_texel_lit(j.e.fragment_source).is_some();
    let floor = super::framework_floor::coverage(j.e.light.clip_from_world, unwritten_lit)?;
    if let Some(line) = super::source_lines::outside_map_lit(j.e.fragment_source) {
        return (floor.outside_share > OUTSIDE_LIT_SHARE).then(|| floor_outside_lit(&floor, line, lang));
    }
    if floor.dark_share <= CLIPPED_SHARE {
        return None;
    }
    let figures = BTreeMap::from([
        ("framework_floor_dark_share", floor.dark_share),
        ("framework_floor_beyond_far_share", floor.beyond_far_share),
        ("framework_floor_dark_z_min", f64::from(floor.z_range.0)),
        ("framework_floor_dark_z_max", f64::from(floor.z_range.1)),
        ("framework_floor_dark_x_min", f64::from(floor.x_range.0)),
        ("framework_floor_dark_x_max", f64::from(floor.x_range.1)),
    ]);
    let cause = if floor.beyond_far_share > 0.5 {
        tr(
            lang,
            "it lies beyond your far plane, so its own depth is over 1 and every texel is in front of it",
        )
    } else {
        tr(
            lang,
            "it lies outside your box's sides, and its lookups wrap (REPEAT) to texels the floor never wrote, which read 0: a blocker at the light",
        )
    };
    Some(Found::new(
        Some("CalcLightMVP"),
        figures,
        fill(
            lang,
            "On the framework's own scene your light leaves {:.0}% of the floor dark: the band from z = {:.0} to {:.0} (x {:.0} to {:.0} world units; the floor spans z -142 to 82 and x -112 to 112, as the framework's engine.js lays it out). There {}. shadowlab's check scene fits inside your frustum, so nothing else shows it; in your own page it is a black band across the floor. Make the box wide and deep enough for the framework's floor (left/right/bottom/top, near and far).",
            &[
                &(100.0 * floor.dark_share),
                &floor.z_range.0,
                &floor.z_range.1,
                &floor.x_range.0,
                &floor.x_range.1,
                &cause,
            ],
        ),
    ))
}

/// The framework's floor reaches outside the student's frustum, and their shader takes what lies
/// outside the map as lit (line `line`): no black band, but no shadow can fall there.
fn floor_outside_lit(floor: &super::framework_floor::FloorCoverage, line: usize, lang: Lang) -> Found {
    Found::new(
        Some("CalcLightMVP"),
        BTreeMap::from([
            ("framework_floor_outside_share", floor.outside_share),
            ("outside_lit_line", line as f64),
            ("framework_floor_outside_z_min", f64::from(floor.outside_z_range.0)),
            ("framework_floor_outside_z_max", f64::from(floor.outside_z_range.1)),
            ("framework_floor_outside_x_min", f64::from(floor.outside_x_range.0)),
            ("framework_floor_outside_x_max", f64::from(floor.outside_x_range.1)),
        ]),
        fill(
            lang,
            "On the framework's own scene {:.0}% of the floor lies outside your light's frustum (z = {:.0} to {:.0}, x {:.0} to {:.0} world units; the floor spans z -142 to 82 and x -112 to 112, as the framework's engine.js lays it out). Your line {} takes whatever lies outside the map as lit, so there is no black band, but no shadow can fall there: an object standing there casts none. Make the frustum wide and deep enough for the framework's floor.",
            &[
                &(100.0 * floor.outside_share),
                &floor.outside_z_range.0,
                &floor.outside_z_range.1,
                &floor.outside_x_range.0,
                &floor.outside_x_range.1,
                &line,
            ],
        ),
    )
}

/// The page's animation moves the light or an object, and the `uLightMVP` its draws get does not
/// follow: the shadows stay where they were. Read from the page's own draws (driver.js), at the
/// times the check looks again.
pub const LIGHT_MATRIX_STALE: FindingKind =
    FindingKind { id: ids::LIGHT_MATRIX_STALE, lesson: "multi-light", step: 4, judge: light_matrix_stale };

fn light_matrix_stale(j: &Judged<'_>, earlier: &[super::Finding], lang: Lang) -> Option<Found> {
    if super::has(earlier, ids::LIGHT_NOT_DRAWN) {
        return None;
    }
    let moved = || j.e.light.stale.iter().filter(|s| s.moved != "none");
    let first = moved().min_by(|a, b| a.time_s.total_cmp(&b.time_s))?;
    let light_moved = j.e.light.stale.iter().find(|s| s.moved == "light");
    let objects: Vec<String> = {
        let mut names: Vec<String> =
            j.e.light.stale.iter().filter(|s| s.moved == "object").filter_map(|s| s.object.clone()).collect();
        names.dedup();
        names
    };
    let computed = computed_where(first, lang);
    let what = match (light_moved, objects.is_empty()) {
        (Some(_), _) => fill(
            lang,
            "From {:.1} s of your page's animation the light has moved, but the uLightMVP its draws get is the one of where it was when the page loaded: {}. The light pass and the lookups keep the old light while the shading follows the new one, so the shadows do not move with it.",
            &[&first.time_s, &computed],
        ),
        (None, false) => fill(
            lang,
            "From {:.1} s of your page's animation {} moves (its uModelMatrix changes), but its uLightMVP still places it where it was loaded: {}. Its shadow stays where it was, and it shadows itself as if it had not moved.",
            &[&first.time_s, &objects.join(", "), &computed],
        ),
        (None, true) => return None,
    };
    let mut figures = BTreeMap::from([
        ("first_time_s", first.time_s),
        ("stale_draws", moved().count() as f64),
        ("light_moved", f64::from(u8::from(light_moved.is_some()))),
    ]);
    figures.insert("objects_moved", objects.len() as f64);
    Some(Found::new(
        Some("CalcLightMVP"),
        figures,
        what + " "
            + tr(
                lang,
                "Compute uLightMVP again each frame, after the light or the object moves, for both passes.",
            ),
    ))
}

/// The places the page calls CalcLightMVP, as a finding lists them in `lang`.
fn places(at: &[String], lang: Lang) -> String {
    at.join(", ").replace(" (the framework's)", tr(lang, " (the framework's)"))
}

/// Where the page computes its light matrices, as a finding says it.
fn computed_where(stale: &crate::homework::light::StaleMatrix, lang: Lang) -> String {
    if stale.computed_at.is_empty() {
        tr(lang, "your page never calls CalcLightMVP itself").to_string()
    } else if stale.computed_only_while_loading {
        fill(
            lang,
            "your page calls CalcLightMVP only while it loads ({}), never in a frame",
            &[&places(&stale.computed_at, lang)],
        )
    } else {
        fill(
            lang,
            "your page calls CalcLightMVP at {}, but not for these draws",
            &[&places(&stale.computed_at, lang)],
        )
    }
}

/// A page with several lights never draws with this one's matrix: no uniform of any draw of its
/// first frames holds it (the framework's materials compute uLightMVP for the first light only).
pub const LIGHT_NOT_DRAWN: FindingKind =
    FindingKind { id: ids::LIGHT_NOT_DRAWN, lesson: "multi-light", step: 1, judge: light_not_drawn };

fn light_not_drawn(j: &Judged<'_>, _: &[super::Finding], lang: Lang) -> Option<Found> {
    let none = j.e.light.stale.iter().find(|s| s.moved == "none")?;
    let computed = match none.computed_at.as_slice() {
        [] => computed_where(none, lang),
        at => fill(lang, "your page calls CalcLightMVP at {}, for another light", &[&places(at, lang)]),
    };
    Some(Found::new(
        Some("CalcLightMVP"),
        BTreeMap::from([("draws_with_its_matrix", 0.0)]),
        fill(
            lang,
            "Your page never draws with this light's matrix: no uniform of any draw holds its CalcLightMVP ({}). Its shadow map is drawn with another light's matrix, or not at all, so the shadows your page shows for it are another light's. Give each light its own materials (or uniforms) with its own uLightMVP and its own map, for both passes. What shadowlab shows for this light is what your shaders would do if it were drawn.",
            &[&computed],
        ),
    ))
}

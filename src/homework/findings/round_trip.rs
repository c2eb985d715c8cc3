//! The framework's RGBA8 round trip on its own floor. Its `pack` steps by 1/256 a channel while
//! each 8-bit channel stores k/255: read back with the 1/256 `unpack`, a depth under 0.5 comes
//! back a little too far (a bias of its own, d / 255 or so), and a depth of 0.5 or more up to
//! 1/510 too near. With the framework's light (far 400) the far end of its floor lies past 0.5:
//! a surface there reads its own texel as in front of itself by more than a smaller bias, and
//! the far floor strip acnes in the student's page, while shadowlab's check scene (nearer the
//! light) shows nothing.

use super::framework_floor::{FLOOR_MAX, FLOOR_MIN};
use super::ids;
use super::{FindingKind, Found, Judged};
use crate::i18n::{Lang, fill};
use glam::{Mat4, Vec2, Vec3, Vec3Swizzles, Vec4Swizzles};
use std::collections::BTreeMap;

/// More than this share of the framework's floor acnes.
const ACNE_SHARE: f64 = 0.02;
/// Floor points looked at, a side.
const SAMPLES: usize = 128;

/// What the framework's pack, an RGBA8 texture and its unpack give back for depth `d`, minus `d`
/// (negative: read nearer than written); [`crate::shadow::rgba8_round_trip`] is the twin's own.
fn framework_round_trip_error(d: f32) -> f32 {
    crate::shadow::rgba8_round_trip(d) - d
}

/// The student's map is packed with 256 steps a channel (the framework's `pack`): in the lossless
/// map (the pack's output kept in floats), the first channel of a written texel lies on the
/// 1/256 grid, not the 1/255 one a base-255 pack leaves it on.
fn packs_in_256(j: &Judged<'_>) -> bool {
    let Some(map) = j.e.lossless_map else { return false };
    let on_grid = |v: f32, steps: f32| ((v * steps) - (v * steps).round()).abs() < 1e-3;
    let (mut in_256, mut in_255) = (0usize, 0usize);
    for texel in map.texels.iter().step_by(97) {
        let r = texel[0];
        if r > 0.0 && r < 1.0 {
            in_256 += usize::from(on_grid(r, 256.0) && !on_grid(r, 255.0));
            in_255 += usize::from(on_grid(r, 255.0) && !on_grid(r, 256.0));
        }
    }
    in_256 >= 50 && in_256 > 4 * in_255
}

/// Where the framework's floor acnes: the share of it inside the light, and the acne's [0, 1]
/// depth and world z ranges.
struct FloorAcne {
    share: f64,
    depths: (f32, f32),
    z: (f32, f32),
}

/// The share of the framework's floor inside the light whose own texel reads in front of it by
/// more than `bias`, and the depth and z ranges of those points.
fn acne_on_floor(clip_from_world: Mat4, bias: f64) -> Option<FloorAcne> {
    let (mut seen, mut acne) = (0usize, 0usize);
    let (mut depths, mut z) = ((f32::INFINITY, f32::NEG_INFINITY), (f32::INFINITY, f32::NEG_INFINITY));
    for k in 0..SAMPLES * SAMPLES {
        let f = (Vec2::new((k % SAMPLES) as f32, (k / SAMPLES) as f32) + 0.5) / SAMPLES as f32;
        let p = Vec3::new(
            FLOOR_MIN.x + f.x * (FLOOR_MAX.x - FLOOR_MIN.x),
            0.0,
            FLOOR_MIN.z + f.y * (FLOOR_MAX.z - FLOOR_MIN.z),
        );
        let clip = clip_from_world * p.extend(1.0);
        if clip.w <= 1e-6 {
            continue;
        }
        let ndc = clip.xyz() / clip.w;
        let (uv, d) = (ndc.xy() * 0.5 + 0.5, ndc.z * 0.5 + 0.5);
        if !(0.0..=1.0).contains(&uv.x) || !(0.0..=1.0).contains(&uv.y) || !(0.0..1.0).contains(&d) {
            continue;
        }
        seen += 1;
        if f64::from(framework_round_trip_error(d)) + bias < 0.0 {
            acne += 1;
            depths = (depths.0.min(d), depths.1.max(d));
            z = (z.0.min(p.z), z.1.max(p.z));
        }
    }
    (seen > 0).then(|| FloorAcne { share: acne as f64 / seen as f64, depths, z })
}

/// The far floor of the framework's scene acnes under the student's light: the framework's
/// round trip reads it nearer than itself by more than the student's bias.
pub const ROUND_TRIP_ACNE: FindingKind =
    FindingKind { id: ids::ROUND_TRIP_ACNE, lesson: "hard-shadows", step: 3, judge: round_trip_acne };

fn round_trip_acne(j: &Judged<'_>, earlier: &[super::Finding], lang: Lang) -> Option<Found> {
    if super::has(earlier, ids::LIGHT_MODEL_MATRIX)
        || super::has(earlier, ids::DEPTH_ROUND_TRIP_WRONG)
        || !packs_in_256(j)
    {
        return None;
    }
    // The bias of the tests that decide the visibility (useShadowMap's, or PCF's and PCSS's own):
    // the smallest constant added to a depth in them; none: 0. A bias the code computes cannot be told here.
    let source = j.e.fragment_source;
    if !super::source_lines::computed_biases(source).is_empty() {
        return None;
    }
    let deciding: &[&str] = match j.e.visibility_function {
        Some(1) => &["useShadowMap"],
        Some(2) => &["PCF"],
        Some(3) => &["PCF", "PCSS"],
        _ => return None,
    };
    // Where none of those tests depth itself (PCF calling useShadowMap per tap), every test counts.
    let testing = super::source_lines::functions_with_depth_tests(source);
    let decides = |f: &str| !deciding.iter().any(|d| testing.contains(d)) || deciding.contains(&f);
    let bias = super::source_lines::depth_test_constants(source)
        .into_iter()
        .filter(|c| c.added && c.function.is_some_and(decides))
        .map(|c| c.value)
        .fold(f64::INFINITY, f64::min);
    let bias = if bias.is_finite() { bias } else { 0.0 };
    let FloorAcne { share, depths, z } = acne_on_floor(j.e.light.clip_from_world, bias)?;
    if share <= ACNE_SHARE {
        return None;
    }
    let worst = (0..=1000)
        .map(|k| f64::from(framework_round_trip_error(depths.0 + (depths.1 - depths.0) * k as f32 / 1000.0)))
        .fold(0.0f64, f64::min);
    Some(Found::new(
        Some("pack"),
        BTreeMap::from([
            ("framework_floor_acne_share", share),
            ("bias_depth", bias),
            ("round_trip_error_depth", -worst),
            ("acne_depth_from", f64::from(depths.0)),
            ("acne_z_min", f64::from(z.0)),
            ("acne_z_max", f64::from(z.1)),
        ]),
        fill(
            lang,
            "On the framework's own floor your light puts the far end (z = {:.0} to {:.0} world units, {:.0}% of the floor) at depth {:.3} and over. There the framework's pack, stored in 8-bit channels (k/255) and read back with 1/256 steps, reads every depth up to {:.4} too near, more than your bias of {:.4}: the floor shadows itself (acne) in your page, though shadowlab's check scene, nearer the light, shows nothing. A bias of {:.4} or more, a far plane nearer the scene (depths under 0.5 read a little too far instead), or a pack and unpack in base 255 remove it.",
            &[&z.0, &z.1, &(100.0 * share), &depths.0, &(-worst), &bias, &(-worst)],
        ),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_far_floor_acnes_under_the_frameworks_light_with_a_bias_under_the_round_trip() {
        let light = Mat4::orthographic_rh_gl(-100.0, 100.0, -100.0, 100.0, 0.01, 400.0)
            * Mat4::look_at_rh(Vec3::new(0.0, 80.0, 80.0), Vec3::ZERO, Vec3::Y);
        // The floor runs to 213 world units from the light: depths to 0.533.
        let FloorAcne { share, depths, z } = acne_on_floor(light, 0.001).expect("a floor");
        assert!(share > 0.02 && depths.0 >= 0.5 && z.1 < -100.0, "{share} {depths:?} {z:?}");
        // A bias over the worst error: nothing.
        assert_eq!(acne_on_floor(light, 0.0025).expect("a floor").share, 0.0);
        // Far 500: every depth under 0.5.
        let far = Mat4::orthographic_rh_gl(-100.0, 100.0, -100.0, 100.0, 0.01, 500.0)
            * Mat4::look_at_rh(Vec3::new(0.0, 80.0, 80.0), Vec3::ZERO, Vec3::Y);
        assert_eq!(acne_on_floor(far, 0.0).expect("a floor").share, 0.0);
    }
}

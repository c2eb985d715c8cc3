//! Findings on where the shadows are: missing, not dark, detached from their blockers, on lit
//! surfaces (acne), or made by texels the framework never cleared.

use super::ids;
use super::{FindingKind, Found, Judged, LIT, UMBRA, has, mean};
use crate::i18n::{Lang, fill};
use std::collections::BTreeMap;

/// `umbra_not_dark`: the student's mean visibility over the ground truth's umbra above this.
const UMBRA_MEAN_LIMIT: f64 = 0.25;
/// `shadows_missing` (instead of `umbra_not_dark`): the umbra's mean visibility above this.
const SHADOWS_MISSING_MEAN: f64 = 0.9;
/// The umbra is judged on surfaces whose N.L is above this: a surface turned away from the light
/// is dark in the shading whatever its visibility (the undersides of the bunnies), and a shader
/// may well skip its lookup there.
const UMBRA_FACING: f32 = 0.05;
/// `self_shadowing`: surfaces facing the light that the ground truth lights fully, darkened
/// (visibility below 0.5) on more than this share.
const ACNE_SHARE: f64 = 0.02;
/// Surfaces with N.L above this face the light squarely (acne is judged there apart).
const SQUARELY: f32 = 0.9;
/// Acne is judged over at least this many lit pixels.
const ACNE_PIXELS: usize = 300;
/// `depends_on_uncleared_map`: more than this share of shaded pixels change visibility by more
/// than 0.1 when the map starts white.
const UNCLEARED_SHARE: f64 = 0.005;
/// `peter_panning`: a slab's shadow counts as gone where its core's mean visibility is above this.
const SHADOW_GONE: f32 = 0.5;

fn percent(share: f64) -> f64 {
    100.0 * share
}

/// The student's mean visibility over the ground truth's umbra on surfaces facing the light
/// (clamped to [0, 1]: a sum left undivided would weigh its count of lit taps).
pub fn umbra_mean(j: &Judged<'_>) -> Option<f64> {
    mean(
        j.finite
            .iter()
            .filter(|&&(i, _)| j.truth(i) <= UMBRA && j.e.facing[i].is_some_and(|c| c > UMBRA_FACING))
            .map(|&(_, v)| f64::from(v.clamp(0.0, 1.0))),
    )
}

fn judged_on_numbers(earlier: &[super::Finding]) -> bool {
    has(earlier, ids::VISIBILITY_OUT_OF_RANGE) || has(earlier, ids::VISIBILITY_SCALED)
}

/// Where the ground truth is in full shadow the student's is lit: the lookups never meet the
/// blockers (coordinates in NDC, depths in other units, the wrong matrix).
pub const SHADOWS_MISSING: FindingKind =
    FindingKind { id: ids::SHADOWS_MISSING, lesson: "hard-shadows", step: 2, judge: shadows_missing };

fn shadows_missing(j: &Judged<'_>, earlier: &[super::Finding], lang: Lang) -> Option<Found> {
    let umbra = umbra_mean(j).filter(|m| *m > SHADOWS_MISSING_MEAN)?;
    if has(earlier, ids::LIGHT_MODEL_MATRIX) {
        return None;
    }
    Some(Found::new(
        None,
        BTreeMap::from([("umbra_mean", umbra), ("ground_truth_umbra_mean", 0.0)]),
        fill(
            lang,
            "Where the ground truth is in full shadow, your visibility averages {:.2}: the shadows are missing. The lookups do not meet the blockers: coordinates in the wrong space (NDC in [-1, 1] where the map wants [0, 1]), depths compared in different units, or the wrong matrix.",
            &[&umbra],
        ),
    ))
}

/// Where no point of the light reaches, the student's visibility averages above
/// `UMBRA_MEAN_LIMIT`: a filter reaching far past the blocker.
pub const UMBRA_NOT_DARK: FindingKind =
    FindingKind { id: ids::UMBRA_NOT_DARK, lesson: "pcss", step: 6, judge: umbra_not_dark };

fn umbra_not_dark(j: &Judged<'_>, earlier: &[super::Finding], lang: Lang) -> Option<Found> {
    // A bias that takes a slab's shadow away lights the umbra near contact too: that finding's.
    if has(earlier, ids::SHADOWS_MISSING)
        || has(earlier, ids::PETER_PANNING)
        || has(earlier, ids::LIGHT_MODEL_MATRIX)
        || judged_on_numbers(earlier)
    {
        return None;
    }
    // A filter radius that ignores the blocker reaches past a near one: that finding's cause.
    if super::filter_radius::ignored_blocker(j).is_some() {
        return None;
    }
    let umbra = umbra_mean(j).filter(|m| *m > UMBRA_MEAN_LIMIT)?;
    let mut figures = BTreeMap::from([("umbra_mean", umbra), ("ground_truth_umbra_mean", 0.0)]);
    if let Some(found) = blocked_counts_as(j, &mut figures, lang) {
        return Some(found);
    }
    let mut explanation = fill(
        lang,
        "Where no point of the light reaches (the ground truth is 0), your visibility averages {:.2}. A filter that reaches far past the blocker does this: a light size in world units used as a size in uv (or texels).",
        &[&umbra],
    );
    // The light PCSS behaves as, and the constant that sets it where one does.
    let mut function = None;
    if let Some(width_uv) = super::pcss_steps::light_width_behaved_as_uv(j) {
        function = Some("PCSS");
        figures.insert("light_width_uv", f64::from(width_uv));
        explanation += " ";
        match super::source_lines::world_per_uv(j) {
            Some(per_uv) => {
                figures.insert("light_width_world", f64::from(width_uv * per_uv));
                explanation += &fill(
                    lang,
                    "Your PCSS filters as a light {:.3} wide in the map's uv ({:.1} world units; the whole map is 1, {:.0} world units).",
                    &[&width_uv, &(width_uv * per_uv), &per_uv],
                );
            }
            None => {
                explanation += &fill(
                    lang,
                    "Your PCSS filters as a light {:.3} wide in the map's uv (the whole map is 1).",
                    &[&width_uv],
                )
            }
        }
        if let Some(c) = super::source_lines::constant_near(j.e.fragment_source, &[width_uv, 0.5 * width_uv])
        {
            figures.insert("light_line", c.line as f64);
            explanation += " ";
            explanation += &fill(lang, "That is `{}` on line {}.", &[&c.text, &c.line]);
        }
    }
    Some(Found::new(function, figures, explanation))
}

/// The umbra's visibility is one number at nearly every point of it (within this much)...
const UMBRA_ONE_VALUE: f32 = 0.02;
/// ...at this share of its points: what a blocked tap counts, not a filter's reach.
const UMBRA_ONE_VALUE_SHARE: f64 = 0.8;

/// Where the umbra's visibility is one number, a blocked point counts that much: named with the
/// constant that says so where the shader has one.
fn blocked_counts_as(j: &Judged<'_>, figures: &mut BTreeMap<&'static str, f64>, lang: Lang) -> Option<Found> {
    let umbra: Vec<f32> = j
        .finite
        .iter()
        .filter(|&&(i, _)| j.truth(i) <= UMBRA && j.e.facing[i].is_some_and(|c| c > UMBRA_FACING))
        .map(|&(_, v)| v)
        .collect();
    let value = super::median(umbra.clone())?;
    let at_value = umbra.iter().filter(|v| (*v - value).abs() <= UMBRA_ONE_VALUE).count();
    let share = at_value as f64 / umbra.len().max(1) as f64;
    if share < UMBRA_ONE_VALUE_SHARE || umbra.len() < 100 {
        return None;
    }
    figures.insert("umbra_at_one_value_share", share);
    figures.insert("umbra_value", f64::from(value));
    let mut explanation = fill(
        lang,
        "Where no point of the light reaches (the ground truth is 0), your visibility is {:.2} at {:.0}% of the points: a tap (or a point) that finds a blocker counts {:.2} there, not 0.",
        &[&value, &(100.0 * share), &value],
    );
    let visibility =
        j.e.visibility_function.and_then(|k| crate::homework::RECORDED_FUNCTIONS.get(k.checked_sub(1)?));
    let constant = super::formula_lines::blocked_value(j.e.fragment_source, value, visibility.copied());
    if let Some((text, line, function)) = &constant {
        figures.insert("blocked_value_line", *line as f64);
        explanation += " ";
        explanation += &fill(lang, "That is `{}` on line {}, in {}.", &[text, line, function]);
    }
    explanation += " ";
    explanation += crate::i18n::tr(
        lang,
        "A shadow is where the light's direct light does not arrive: visibility 0. Light that still reaches a shadowed point (ambient) belongs in the shading, where it lights the umbra of every light alike.",
    );
    Some(Found::new(constant.map(|c| c.2), figures.clone(), explanation))
}

/// The lowest slab's shadow is gone while the higher ones are there: a bias so large that a
/// blocker that close to a surface no longer shadows it.
pub const PETER_PANNING: FindingKind =
    FindingKind { id: ids::PETER_PANNING, lesson: "bias", step: 2, judge: peter_panning };

fn peter_panning(j: &Judged<'_>, earlier: &[super::Finding], lang: Lang) -> Option<Found> {
    // A slab outside a clipped frustum loses its shadow to the frustum, not to a bias; a band of
    // the framework's own floor outside it says nothing of the check scene, which fits.
    let check_scene_clipped =
        earlier.iter().any(|f| f.id == ids::LIGHT_FRUSTUM_CLIPS && f.figures.contains_key("clipped_share"));
    if has(earlier, ids::SHADOWS_MISSING)
        || has(earlier, ids::LIGHT_MODEL_MATRIX)
        || check_scene_clipped
        || judged_on_numbers(earlier)
    {
        return None;
    }
    let slabs = &j.e.light.width?.slabs;
    let gone = |s: &&super::super::SlabShadow| s.core_visibility.is_some_and(|v| v > SHADOW_GONE);
    let there = |s: &&super::super::SlabShadow| s.core_visibility.is_some_and(|v| v <= SHADOW_GONE);
    let lowest = slabs.iter().min_by(|a, b| a.gap_world.total_cmp(&b.gap_world))?;
    if !gone(&lowest) || !slabs.iter().any(|s| there(&s)) {
        return None;
    }
    // The bias lies between the largest gap that lost its shadow and the smallest that kept it.
    let lost = slabs.iter().filter(gone).map(|s| s.gap_world).fold(0.0f32, f32::max);
    let kept = slabs.iter().filter(there).map(|s| s.gap_world).fold(f32::INFINITY, f32::min);
    // A bias hides a blocker that near from the blocker search too; where the search sees it, the
    // shadow is lost downstream (a filter far wider than the blocker dilutes it).
    let per_world = super::source_lines::depth_per_world(j);
    if let Some(per_world) = per_world
        && super::pcss_steps::search_sees_blockers_within(j, lost * per_world) == Some(true)
    {
        return None;
    }
    let mut figures =
        BTreeMap::from([("bias_at_least_world", f64::from(lost)), ("bias_under_world", f64::from(kept))]);
    for (key, s) in super::SLAB_KEYS.iter().zip(slabs) {
        if let Some(v) = s.core_visibility {
            figures.insert(key.core_visibility, f64::from(v));
        }
    }
    let mut explanation = fill(
        lang,
        "The {} casts no shadow: a blocker {:.1} world units above the floor (along the light) does not shadow it, while one {:.1} above does. Your depth bias is that large: shadows come loose from what casts them (peter panning).",
        &[&lowest.name, &lost, &kept],
    );
    // In the student's own units: their light's depth range, and the constant that is that bias.
    let mut function = None;
    if let Some(per_world) = super::source_lines::depth_per_world(j) {
        let (low, high) = (f64::from(lost * per_world), f64::from(kept * per_world));
        let range = 1.0 / per_world;
        figures.insert("light_depth_range_world", f64::from(range));
        figures.insert("bias_at_least_depth", low);
        figures.insert("bias_under_depth", high);
        explanation += " ";
        explanation += &fill(
            lang,
            "Your light's depth runs over {:.0} world units, so that is a bias of {:.4} to {:.4} in [0, 1] depth.",
            &[&range, &low, &high],
        );
        // A shadow comes loose a little beyond the bias where a filter softens its edge: the
        // constants within the slabs' bounds, a fifth either way.
        let constants = super::source_lines::depth_test_constants(j.e.fragment_source);
        // Each constant once, where it is written (a `#define` read by several tests: its first).
        let mut fitting: Vec<super::source_lines::Constant> =
            constants.iter().filter(|c| (0.8 * low..=1.2 * high).contains(&c.value)).cloned().collect();
        let mut named = std::collections::HashSet::new();
        fitting.retain(|c| named.insert((c.line, c.text.clone())));
        // The largest, the first of equals.
        let largest = constants.iter().max_by(|a, b| a.value.total_cmp(&b.value).then(b.line.cmp(&a.line)));
        if let Some(first) = fitting.first() {
            function = first.function;
            figures.insert("bias_line", first.line as f64);
            figures.insert("bias_written", first.value);
            let named: Vec<String> = fitting
                .iter()
                .take(3)
                .map(|c| {
                    let world = c.value / f64::from(per_world);
                    let place = c.function.map_or(String::new(), |f| format!(", {f}"));
                    fill(lang, "`{}` (line {}{}: {:.1} world units)", &[&c.text, &c.line, &place, &world])
                })
                .collect();
            explanation += " ";
            explanation += &fill(
                lang,
                "In your shader: {}. A bias of a texel's depth slope or two is enough; with this light that is far under 1 world unit.",
                &[&named.join(", ")],
            );
        } else if let Some(first) = super::source_lines::computed_biases(j.e.fragment_source).first() {
            // No number written is that large, but a bias the code computes is in the tests.
            function = Some(first.function);
            figures.insert("bias_line", first.line as f64);
            explanation += " ";
            explanation += &fill(
                lang,
                "Your depth tests use a bias your code computes: `{} = {}` (line {}, {}). It comes to at least {:.4} in [0, 1] depth here; a bias of a texel's depth slope or two is enough, far under 1 world unit with this light.",
                &[&first.name, &first.expression, &first.line, &first.function, &low],
            );
        } else if let Some(c) = largest.filter(|c| c.value < 0.8 * low) {
            // What the code writes is too small to lose these shadows: say so rather than have the
            // student shrink a bias that is not the cause.
            let world = c.value / f64::from(per_world);
            explanation += " ";
            explanation += &fill(
                lang,
                "No constant in your depth tests is that large (the largest, `{}` on line {}, is {:.1} world units): look for a bias your code computes, or for what else loses the shadow (a filter much wider than the blocker dilutes it).",
                &[&c.text, &c.line, &world],
            );
        }
    }
    Some(Found::new(function, figures, explanation))
}

/// Surfaces facing the light and fully lit in the ground truth are dark in the student's:
/// acne, a surface shadowing itself.
pub const SELF_SHADOWING: FindingKind =
    FindingKind { id: ids::SELF_SHADOWING, lesson: "bias", step: 1, judge: self_shadowing };

fn self_shadowing(j: &Judged<'_>, earlier: &[super::Finding], lang: Lang) -> Option<Found> {
    // Acne darkens lit surfaces in a picture whose shadows are otherwise right; where the umbra
    // is wrong too, the whole lookup is, and the findings above say so. A lit area scaled down is
    // darkened everywhere, by the divisor: the scale's finding.
    if has(earlier, ids::SHADOWS_MISSING)
        || has(earlier, ids::UMBRA_NOT_DARK)
        || has(earlier, ids::VISIBILITY_SCALED)
        || has(earlier, ids::LIGHT_MODEL_MATRIX)
    {
        return None;
    }
    // Judged apart where the surface faces the light squarely: a bias that grows with the angle
    // (slope-scaled, with no constant part) is 0 there, and acne shows only there.
    let darkened = |facing: &dyn Fn(f32) -> bool| {
        let lit: Vec<f32> = j
            .finite
            .iter()
            // Darkening the uncleared map explains is that finding's, not acne.
            // Outside the light's frustum the map has nothing to say: that is the frustum's finding.
            .filter(|&&(i, _)| {
                j.sound(i) && !j.changes_over_white(i, 0.1) && j.receivers[i].is_some_and(|r| r.inside())
            })
            .filter(|&&(i, _)| j.truth(i) >= LIT && j.e.facing[i].is_some_and(facing))
            .map(|&(_, v)| v)
            .collect();
        // A visibility above 1 stays in: a lit surface that reads more than lit is not darkened.
        let share = lit.iter().filter(|v| **v < 0.5).count() as f64 / lit.len().max(1) as f64;
        (share, lit.len())
    };
    let (slanted, slanted_pixels) = darkened(&|c| c > super::FACING && c <= SQUARELY);
    let (square, square_pixels) = darkened(&|c| c > SQUARELY);
    let acne = |(share, pixels): (f64, usize)| pixels >= ACNE_PIXELS && share > ACNE_SHARE;
    (acne((slanted, slanted_pixels)) || acne((square, square_pixels))).then(|| {
        let worst = if acne((slanted, slanted_pixels)) { slanted.max(square) } else { square };
        Found::new(
            None,
            BTreeMap::from([
                ("darkened_share", slanted.max(square)),
                ("darkened_share_facing_squarely", square),
                ("lit_facing_pixels", (slanted_pixels + square_pixels) as f64),
            ]),
            fill(
                lang,
                "{:.1}% of the surfaces that face the light and are fully lit in the ground truth are dark in yours: shadow acne, the surface shadowing itself. Compare with a bias (the receiver's depth minus a small amount), or a larger one; a bias that is 0 where a surface faces the light squarely (max(c (1 - N.L), 0)) leaves acne there.",
                &[&percent(worst)],
            ),
        )
    })
}

/// The share of shaded pixels whose visibility changes by more than 0.1 over a white map.
pub fn uncleared_share(j: &Judged<'_>) -> f64 {
    j.share(j.shaded.iter().filter(|&&i| j.sound(i) && j.changes_over_white(i, 0.1)).count())
}

/// More than `UNCLEARED_SHARE` of the picture changes when the map starts white: lookups land
/// on texels the framework never cleared.
pub const DEPENDS_ON_UNCLEARED_MAP: FindingKind = FindingKind {
    id: ids::DEPENDS_ON_UNCLEARED_MAP,
    lesson: "hard-shadows",
    step: 3,
    judge: depends_on_uncleared_map,
};

fn depends_on_uncleared_map(j: &Judged<'_>, earlier: &[super::Finding], lang: Lang) -> Option<Found> {
    // Objects put elsewhere by the light's own model matrix, or outside its frustum, and radii
    // that are not numbers read texels nothing covers: those findings say why.
    if has(earlier, ids::LIGHT_MODEL_MATRIX)
        || has(earlier, ids::LIGHT_FRUSTUM_CLIPS)
        || has(earlier, ids::FILTER_RADIUS_NOT_FINITE)
        || super::functions::search_broken(earlier)
    {
        return None;
    }
    let share = uncleared_share(j);
    (share > UNCLEARED_SHARE).then(|| {
        Found::new(
            None,
            BTreeMap::from([("changed_share", share)]),
            fill(
                lang,
                "{:.1}% of the picture changes when the shadow map starts white instead of 0. The framework never clears its map: texels no object covers read depth 0, which counts as a blocker. Your lookups land there (outside [0, 1] uv, or far from the pixel).",
                &[&percent(share)],
            ),
        )
    })
}

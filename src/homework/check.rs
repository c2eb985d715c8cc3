//! What a homework gets wrong, found by comparing, pixel by pixel, the visibility the student's
//! shader returned with the ground truth (hard shadows averaged over the light), with shadowlab's
//! own technique at the same settings, and with itself over a map cleared to white.
//!
//! Each finding carries the figures that show it, a sentence on the likely cause and the lesson
//! step that teaches it. The thresholds are set so that a correct solution has none on the
//! shipped scene and each classic mistake has exactly its own (tests/homework_check.rs).

use super::HomeworkImages;
use crate::i18n::{Lang, fill};
use serde::Serialize;
use std::collections::BTreeMap;

/// Ground truth at or below this: the umbra; at or above `LIT`: fully lit.
const UMBRA: f32 = 0.02;
const LIT: f32 = 0.98;
/// A visibility strictly between these is soft (in a penumbra).
const SOFT: (f32, f32) = (0.05, 0.95);
/// `nan_visibility`: more than this share of shaded pixels.
const NAN_SHARE: f64 = 0.001;
/// `visibility_out_of_range`: a visibility below -`RANGE_EPS` or above 1 + `RANGE_EPS` is outside
/// [0, 1]; the slack is for float sums of weights meant to total 1.
const RANGE_EPS: f32 = 1e-3;
/// `visibility_out_of_range`: more than this share of the pixels with a finite visibility.
const OUT_OF_RANGE_SHARE: f64 = 0.001;
/// `visibility_scaled`: the student's visibility is shadowlab's times a constant k (least squares)
/// that is off 1 by more than this...
const SCALE_OFF: f64 = 0.1;
/// ...the scaled picture's mean |v - k s| under this share of the unscaled one's mean |v - s| (the
/// scale explains the difference)...
const SCALE_FIT_GAIN: f64 = 0.25;
/// ...and its R^2 (1 - sum (v - k s)^2 / sum (v - mean v)^2) at least this: the scaled picture has
/// the student's shadows. A picture flat whatever shadowlab's shows (a filter spanning the map)
/// is not a scale, however close its mean is to k s.
const SCALE_R2: f64 = 0.8;
/// `umbra_not_dark`: the student's mean visibility over the ground truth's umbra above this.
const UMBRA_MEAN_LIMIT: f64 = 0.25;
/// `shadows_missing` (instead of `umbra_not_dark`): the umbra's mean visibility above this.
const SHADOWS_MISSING_MEAN: f64 = 0.9;
/// `no_penumbra`: the student's soft pixels fewer than this share of the ground truth's.
const PENUMBRA_SHARE_LIMIT: f64 = 0.25;
/// `no_penumbra` is judged where the ground truth has at least this many soft pixels.
const PENUMBRA_PIXELS_MIN: u64 = 200;
/// `self_shadowing`: surfaces facing the light (N.L above `FACING`) that the ground truth lights
/// fully, darkened (visibility below 0.5) on more than this share.
const FACING: f32 = 0.3;
const ACNE_SHARE: f64 = 0.02;
/// `depends_on_uncleared_map`: more than this share of shaded pixels change visibility by more
/// than 0.1 when the map starts white.
const UNCLEARED_SHARE: f64 = 0.005;

/// One thing a check found.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Finding {
    pub id: &'static str,
    /// The figures that show it, by name.
    pub figures: BTreeMap<&'static str, f64>,
    /// What was seen and its likely cause, one or two sentences.
    pub explanation: String,
    /// The lesson step that teaches it: the lesson's id and the step, from 1.
    pub lesson: &'static str,
    pub step: usize,
}

/// The comparison's figures, whatever was found.
#[derive(Clone, Debug, Default, Serialize, PartialEq)]
pub struct Figures {
    /// Pixels the student's shader ran at.
    pub shaded_pixels: u64,
    /// Of those, pixels with a visibility (a recorded function returned one from `main`'s level).
    pub pixels_with_visibility: u64,
    /// Share of shaded pixels whose visibility is NaN or infinite.
    pub nan_fraction: f64,
    /// Mean |student - shadowlab's technique| and |student - ground truth| over the pixels with a
    /// finite visibility.
    pub mean_abs_difference: Option<f64>,
    pub mean_abs_difference_to_ground_truth: Option<f64>,
    /// The student's mean visibility where the ground truth is fully lit, and in its umbra.
    pub lit_area_mean: Option<f64>,
    pub umbra_mean: Option<f64>,
    /// Soft pixels (0.05 < v < 0.95): the ground truth's and the student's.
    pub penumbra_pixels_ground_truth: u64,
    pub penumbra_pixels: u64,
    /// Share of shaded pixels whose visibility changes by more than 0.1 over a white map.
    pub uncleared_map_share: f64,
    /// The penumbra's width across the shadow's edge at `penumbra_pixel` (the ground truth's soft
    /// pixel nearest the picture's centre), world units: the student's and the ground truth's.
    pub penumbra_pixel: Option<(u32, u32)>,
    pub penumbra_width_world: Option<f32>,
    pub penumbra_width_world_ground_truth: Option<f32>,
}

/// The per-pixel inputs of a check, all of one view's size, rows top first.
pub struct CheckInputs<'a> {
    /// The homework over the framework's map (0 where nothing was drawn) and over a white one.
    pub student: &'a HomeworkImages,
    pub student_white_map: &'a HomeworkImages,
    /// shadowlab's technique at the same settings, and the ground truth, per pixel.
    pub shadowlab: &'a [f32],
    pub ground_truth: &'a [f32],
    /// N.L towards the checked light per pixel (None: no surface).
    pub facing: &'a [Option<f32>],
    /// The function (1-based in `RECORDED_FUNCTIONS`) `main` takes its visibility from.
    pub visibility_function: Option<usize>,
    /// The world position under each pixel (None: no surface).
    pub positions: &'a [Option<glam::Vec3>],
}

/// The penumbra's width at `pixel` (the student's, the ground truth's), world units, across the
/// ground truth's edge there; None where the ground truth has no edge at that pixel.
pub fn penumbra_widths(
    student: &HomeworkImages,
    ground_truth: &[f32],
    positions: &[Option<glam::Vec3>],
    pixel: (u32, u32),
) -> Option<(f32, f32)> {
    let field = super::penumbra::Field { width: student.width, height: student.height, positions };
    let truth = |i: usize| student.covered(i).then(|| ground_truth[i]);
    let theirs = |i: usize| student.visibility(i);
    let dir = field.across(&truth, pixel)?;
    let truth_width = field.width_along(&truth, pixel, dir, 3);
    Some((field.width_along(&theirs, pixel, dir, 20), truth_width))
}

/// A visibility fitted as a constant times shadowlab's.
#[derive(Clone, Copy, Debug, PartialEq)]
struct ScaleFit {
    /// k = sum v s / sum s^2, least squares.
    scale: f64,
    /// Mean |v - k s| and mean |v - s|.
    fit_error: f64,
    unscaled_error: f64,
    /// 1 - sum (v - k s)^2 / sum (v - mean v)^2; None where the student's picture is flat.
    r_squared: Option<f64>,
    pixels: usize,
}

/// The least-squares k of `v = k s` over pairs (v, s); None where shadowlab's values are all 0.
fn fit_scale(pairs: &[(f32, f32)]) -> Option<ScaleFit> {
    let pairs: Vec<(f64, f64)> = pairs.iter().map(|&(v, s)| (f64::from(v), f64::from(s))).collect();
    let (vs, ss) = pairs.iter().fold((0.0, 0.0), |(vs, ss), &(v, s)| (vs + v * s, ss + s * s));
    if ss <= 0.0 {
        return None;
    }
    let scale = vs / ss;
    let fit_error = mean(pairs.iter().map(|&(v, s)| (v - scale * s).abs()))?;
    let unscaled_error = mean(pairs.iter().map(|&(v, s)| (v - s).abs()))?;
    let v_mean = mean(pairs.iter().map(|&(v, _)| v))?;
    let spread: f64 = pairs.iter().map(|&(v, _)| (v - v_mean).powi(2)).sum();
    let residual: f64 = pairs.iter().map(|&(v, s)| (v - scale * s).powi(2)).sum();
    let r_squared = (spread > 0.0).then(|| 1.0 - residual / spread);
    Some(ScaleFit { scale, fit_error, unscaled_error, r_squared, pixels: pairs.len() })
}

fn mean(values: impl Iterator<Item = f64>) -> Option<f64> {
    let (sum, n) = values.fold((0.0, 0u64), |(s, n), v| (s + v, n + 1));
    (n > 0).then(|| sum / n as f64)
}

/// The figures and the findings of a check, in `lang`.
pub fn check(inputs: &CheckInputs<'_>, lang: Lang) -> (Figures, Vec<Finding>) {
    let student = inputs.student;
    let pixels = student.calls.len();
    let shaded: Vec<usize> = (0..pixels).filter(|&i| student.covered(i)).collect();
    let visible: Vec<(usize, f32)> =
        shaded.iter().filter_map(|&i| student.visibility(i).map(|v| (i, v))).collect();
    let finite: Vec<(usize, f32)> = visible.iter().copied().filter(|(_, v)| v.is_finite()).collect();
    let non_finite = visible.len() - finite.len();
    let mut f = Figures {
        shaded_pixels: shaded.len() as u64,
        pixels_with_visibility: visible.len() as u64,
        nan_fraction: if shaded.is_empty() { 0.0 } else { non_finite as f64 / shaded.len() as f64 },
        ..Figures::default()
    };
    let truth = |i: usize| inputs.ground_truth[i];
    f.mean_abs_difference = mean(finite.iter().map(|&(i, v)| f64::from((v - inputs.shadowlab[i]).abs())));
    f.mean_abs_difference_to_ground_truth =
        mean(finite.iter().map(|&(i, v)| f64::from((v - truth(i)).abs())));
    f.lit_area_mean = mean(finite.iter().filter(|&&(i, _)| truth(i) >= LIT).map(|&(_, v)| f64::from(v)));
    f.umbra_mean = mean(finite.iter().filter(|&&(i, _)| truth(i) <= UMBRA).map(|&(_, v)| f64::from(v)));
    let soft = |v: f32| v > SOFT.0 && v < SOFT.1;
    f.penumbra_pixels_ground_truth = finite.iter().filter(|&&(i, _)| soft(truth(i))).count() as u64;
    f.penumbra_pixels = finite.iter().filter(|&&(_, v)| soft(v)).count() as u64;
    // A pixel where a recorded function returned NaN is explained by that: the checks below
    // leave it out (NaN lookups land anywhere).
    let sound = |i: usize| {
        let ran = student.calls[i][0];
        (0..4).all(|k| ran & (1 << k) == 0 || student.returned[i][k].is_finite())
    };
    // Whether the visibility changes by more than `by` over a white map.
    let changes_over_white = |i: usize, by: f32| {
        let (a, b) = (student.visibility(i), inputs.student_white_map.visibility(i));
        match (a, b) {
            (Some(a), Some(b)) if a.is_finite() && b.is_finite() => (a - b).abs() > by,
            (Some(a), Some(b)) => a.is_finite() != b.is_finite(),
            (a, b) => a.is_some() != b.is_some(),
        }
    };
    let depends_on_clear = |i: usize| changes_over_white(i, 0.1);
    let changed = shaded.iter().filter(|&&i| sound(i) && depends_on_clear(i)).count();
    f.uncleared_map_share = if shaded.is_empty() { 0.0 } else { changed as f64 / shaded.len() as f64 };
    let field =
        super::penumbra::Field { width: student.width, height: student.height, positions: inputs.positions };
    f.penumbra_pixel = super::penumbra::default_pixel(&field, &|i| student.covered(i).then(|| truth(i)));
    let widths = |p| penumbra_widths(student, inputs.ground_truth, inputs.positions, p);
    if let Some((theirs, truth_width)) = f.penumbra_pixel.and_then(widths) {
        (f.penumbra_width_world, f.penumbra_width_world_ground_truth) = (Some(theirs), Some(truth_width));
    }

    let mut findings = Vec::new();
    let percent = |share: f64| 100.0 * share;
    let in_range = |v: f32| (-RANGE_EPS..=1.0 + RANGE_EPS).contains(&v);
    let out_of_range = finite.iter().filter(|&&(_, v)| !in_range(v)).count();
    let out_of_range_share = out_of_range as f64 / finite.len().max(1) as f64;
    let range_wrong = out_of_range_share > OUT_OF_RANGE_SHARE;
    let nan_blocker = shaded
        .iter()
        .filter(|&&i| student.calls[i][0] & 8 != 0 && !student.returned[i][3].is_finite())
        .count();
    let nan_blocker_share = nan_blocker as f64 / shaded.len().max(1) as f64;
    if nan_blocker_share > NAN_SHARE {
        findings.push(Finding {
            id: "nan_blocker_depth",
            figures: BTreeMap::from([("nan_blocker_fraction", nan_blocker_share), ("nan_blocker_pixels", nan_blocker as f64)]),
            explanation: fill(
                lang,
                "findBlocker returned NaN or an infinite depth at {:.1}% of the shaded pixels: it divides by the number of blockers found, which is 0 where the light is not blocked. Return a \"no blocker\" value there, and have PCSS treat it as lit.",
                &[&percent(nan_blocker_share)],
            ),
            lesson: "pcss",
            step: 3,
        });
    }
    if f.nan_fraction > NAN_SHARE {
        findings.push(Finding {
            id: "nan_visibility",
            figures: BTreeMap::from([("nan_fraction", f.nan_fraction), ("nan_pixels", non_finite as f64)]),
            explanation: fill(
                lang,
                "{:.1}% of the shaded pixels got a visibility that is NaN or infinite. The usual cause: findBlocker divides the blockers' depth sum by their count when no blocker was found (0 / 0).",
                &[&percent(f.nan_fraction)],
            ),
            lesson: "pcss",
            step: 3,
        });
    }
    if range_wrong {
        let (low, high) = finite
            .iter()
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(low, high), &(_, v)| (low.min(v), high.max(v)));
        let mut figures = BTreeMap::from([
            ("out_of_range_share", out_of_range_share),
            ("out_of_range_pixels", out_of_range as f64),
            ("visibility_min", f64::from(low)),
            ("visibility_max", f64::from(high)),
        ]);
        if let Some(lit) = f.lit_area_mean {
            figures.insert("lit_area_mean", lit);
        }
        findings.push(Finding {
            id: "visibility_out_of_range",
            figures,
            explanation: fill(
                lang,
                "{:.1}% of the visibilities your shader returned lie outside [0, 1], from {:.2} to {:.2}. Visibility is the share of the light a point sees: a filter must divide its sum of 0/1 tests by the number of tests it summed, not by another count (PCF_NUM_SAMPLES - 8), and not leave it undivided.",
                &[&percent(out_of_range_share), &low, &high],
            ),
            lesson: "pcf",
            step: 2,
        });
    }
    // A visibility scaled by a constant (a PCF sum divided by a count other than its number of
    // taps, or divided twice) is fitted where the comparison is sound: finite, no recorded
    // function NaN, and no uncovered texel read (the visibility does not change at all over a
    // white map: a change of 0.1 would let a sum divided by 32 hide one). Under PCSS the fit keeps
    // to the pixels where the student's PCF ran: where findBlocker found no blocker PCSS returns
    // its lit value unfiltered, with no sum to divide.
    let filtered = |i: usize| student.calls[i][0] & 2 != 0;
    let comparable: Vec<(usize, f32)> =
        finite.iter().copied().filter(|&(i, _)| sound(i) && !changes_over_white(i, 0.0)).collect();
    let through_filter =
        inputs.visibility_function == Some(3) && comparable.iter().any(|&(i, _)| filtered(i));
    let fitted: Vec<(f32, f32)> = comparable
        .iter()
        .filter(|&&(i, _)| !through_filter || filtered(i))
        .map(|&(i, v)| (v, inputs.shadowlab[i]))
        .collect();
    let scale_fit = fit_scale(&fitted);
    // A scale above 1 puts the lit area above 1: the range's finding speaks for it, alone (its
    // figures say by how much, and a sum left undivided is a scale of 32 with no divisor to
    // name). On a scene with a lit area a scale above 1 cannot stay inside [0, 1].
    let scaled = scale_fit.filter(|fit| {
        !range_wrong
            && fit.scale > 0.0
            && (fit.scale - 1.0).abs() > SCALE_OFF
            && fit.fit_error < SCALE_FIT_GAIN * fit.unscaled_error
            && fit.r_squared.is_some_and(|r2| r2 >= SCALE_R2)
    });
    if let Some(fit) = scaled {
        let mut figures = BTreeMap::from([
            ("scale", fit.scale),
            ("one_over_scale", 1.0 / fit.scale),
            ("fit_mean_abs_error", fit.fit_error),
            ("unscaled_mean_abs_error", fit.unscaled_error),
            ("fitted_pixels", fit.pixels as f64),
        ]);
        if let Some(r2) = fit.r_squared {
            figures.insert("r_squared", r2);
        }
        if let Some(lit) = f.lit_area_mean {
            figures.insert("lit_area_mean", lit);
        }
        findings.push(Finding {
            id: "visibility_scaled",
            figures,
            explanation: fill(
                lang,
                "Your visibility is shadowlab's times {:.3} (divided once more by {:.1}): a fully lit point reads {:.3}, not 1. Visibility is the share of the light a point sees, so where all of it is seen it must be 1: the sum of the 0/1 tests is divided twice (is {:.1} one of your sample counts?), or by a count other than the number of tests summed (PCF_NUM_SAMPLES * 2), or multiplied by a weight.",
                &[&fit.scale, &(1.0 / fit.scale), &fit.scale, &(1.0 / fit.scale)],
            ),
            lesson: "pcf",
            step: 2,
        });
    }
    // The umbra is judged on how dark it is: a visibility above 1 counts as fully lit (1), below 0
    // as dark (0). Unclamped, a sum left undivided would weigh its count of lit taps (3 of 32
    // weighs 3) and the umbra would read as missing; the wrong count is the finding above's.
    let umbra_mean =
        mean(finite.iter().filter(|&&(i, _)| truth(i) <= UMBRA).map(|&(_, v)| f64::from(v.clamp(0.0, 1.0))));
    let shadows_missing = umbra_mean.is_some_and(|m| m > SHADOWS_MISSING_MEAN);
    if let Some(umbra) = umbra_mean.filter(|_| shadows_missing) {
        findings.push(Finding {
            id: "shadows_missing",
            figures: BTreeMap::from([("umbra_mean", umbra), ("ground_truth_umbra_mean", 0.0)]),
            explanation: fill(
                lang,
                "Where the ground truth is in full shadow, your visibility averages {:.2}: the shadows are missing. The lookups do not meet the blockers: coordinates in the wrong space (NDC in [-1, 1] where the map wants [0, 1]), depths compared in different units, or the wrong matrix.",
                &[&umbra],
            ),
            lesson: "hard-shadows",
            step: 2,
        });
    } else if let Some(umbra) = umbra_mean.filter(|m| *m > UMBRA_MEAN_LIMIT) {
        findings.push(Finding {
            id: "umbra_not_dark",
            figures: BTreeMap::from([("umbra_mean", umbra), ("ground_truth_umbra_mean", 0.0)]),
            explanation: fill(
                lang,
                "Where no point of the light reaches (the ground truth is 0), your visibility averages {:.2}. A filter that reaches far past the blocker does this: a light size in world units used as a size in uv (or texels).",
                &[&umbra],
            ),
            lesson: "pcss",
            step: 6,
        });
    }
    let soft_share = f.penumbra_pixels as f64 / f.penumbra_pixels_ground_truth.max(1) as f64;
    // Soft pixels are counted on [0, 1]: out of it they measure the divisor, not the filter (a sum
    // left undivided is never between 0 and 1); scaled, they measure the scale (a sum divided
    // twice is never above 1/32).
    if inputs.visibility_function == Some(3)
        && !shadows_missing
        && !range_wrong
        && scaled.is_none()
        && f.penumbra_pixels_ground_truth >= PENUMBRA_PIXELS_MIN
        && soft_share < PENUMBRA_SHARE_LIMIT
    {
        findings.push(Finding {
            id: "no_penumbra",
            figures: BTreeMap::from([
                ("penumbra_pixels", f.penumbra_pixels as f64),
                ("penumbra_pixels_ground_truth", f.penumbra_pixels_ground_truth as f64),
            ]),
            explanation: fill(
                lang,
                "The ground truth has {} pixels in a penumbra, your shadows {}: the edges are as sharp as a hard shadow. Usually the filter is under a texel wide (a light size or filter radius far too small for the map), or the penumbra estimate is lost before filtering.",
                &[&f.penumbra_pixels_ground_truth, &f.penumbra_pixels],
            ),
            lesson: "pcss",
            step: 5,
        });
    }
    let facing_lit: Vec<f32> = finite
        .iter()
        // Darkening the uncleared map explains is that finding's, not acne.
        .filter(|&&(i, _)| sound(i) && !depends_on_clear(i))
        .filter(|&&(i, _)| truth(i) >= LIT && inputs.facing[i].is_some_and(|c| c > FACING))
        .map(|&(_, v)| v)
        .collect();
    // A visibility above 1 stays in: a lit surface that reads more than lit is not darkened.
    let acne = facing_lit.iter().filter(|v| **v < 0.5).count() as f64 / facing_lit.len().max(1) as f64;
    // Acne darkens lit surfaces in a picture whose shadows are otherwise right; where the umbra
    // is wrong too, the whole lookup is, and the findings above say so.
    let umbra_right = umbra_mean.is_none_or(|m| m <= UMBRA_MEAN_LIMIT);
    // A lit area scaled down is darkened everywhere, by the divisor: the scale's finding.
    if umbra_right && scaled.is_none() && acne > ACNE_SHARE {
        findings.push(Finding {
            id: "self_shadowing",
            figures: BTreeMap::from([("darkened_share", acne), ("lit_facing_pixels", facing_lit.len() as f64)]),
            explanation: fill(
                lang,
                "{:.1}% of the surfaces that face the light and are fully lit in the ground truth are dark in yours: shadow acne, the surface shadowing itself. Compare with a bias (the receiver's depth minus a small amount), or a larger one.",
                &[&percent(acne)],
            ),
            lesson: "bias",
            step: 1,
        });
    }
    if f.uncleared_map_share > UNCLEARED_SHARE {
        findings.push(Finding {
            id: "depends_on_uncleared_map",
            figures: BTreeMap::from([("changed_share", f.uncleared_map_share)]),
            explanation: fill(
                lang,
                "{:.1}% of the picture changes when the shadow map starts white instead of 0. The framework never clears its map: texels no object covers read depth 0, which counts as a blocker. Your lookups land there (outside [0, 1] uv, or far from the pixel).",
                &[&percent(f.uncleared_map_share)],
            ),
            lesson: "hard-shadows",
            step: 3,
        });
    }
    (f, findings)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 20x20 picture every pixel of which called PCSS (from `main`) and findBlocker.
    fn images(visibility: impl Fn(usize) -> f32) -> HomeworkImages {
        let n = 400;
        HomeworkImages {
            width: 20,
            height: 20,
            color: vec![[0.5, 0.5, 0.5, 1.0]; n],
            returned: (0..n).map(|i| [0.0, 0.0, visibility(i), 0.2]).collect(),
            calls: vec![[0b1100, 3, 2, 1]; n],
        }
    }

    /// The findings of `student` where shadowlab's technique is the ground truth, every surface
    /// facing the light.
    fn findings(student: &HomeworkImages, truth: &[f32], lang: Lang) -> Vec<Finding> {
        let facing = vec![Some(1.0); truth.len()];
        let inputs = CheckInputs {
            student,
            student_white_map: student,
            shadowlab: truth,
            ground_truth: truth,
            facing: &facing,
            visibility_function: Some(3),
            positions: &[],
        };
        check(&inputs, lang).1
    }

    fn ids(student: &HomeworkImages, truth: &[f32]) -> Vec<&'static str> {
        findings(student, truth, Lang::En).iter().map(|f| f.id).collect()
    }

    #[test]
    fn nan_and_infinite_visibility_are_found_and_left_out_of_the_means() {
        let truth: Vec<f32> = (0..400).map(|i| if i < 100 { 0.0 } else { 1.0 }).collect();
        let student = images(|i| match i {
            100..=109 => f32::NAN,
            110 => f32::INFINITY,
            _ => truth[i],
        });
        assert_eq!(ids(&student, &truth), ["nan_visibility"]);
        let inputs = CheckInputs {
            student: &student,
            student_white_map: &student,
            shadowlab: &truth,
            ground_truth: &truth,
            facing: &[Some(1.0); 400],
            visibility_function: Some(3),
            positions: &[],
        };
        let (figures, _) = check(&inputs, Lang::En);
        assert!((figures.nan_fraction - 11.0 / 400.0).abs() < 1e-12);
        assert_eq!(figures.mean_abs_difference_to_ground_truth, Some(0.0));
    }

    #[test]
    fn a_grey_umbra_is_not_dark_and_a_white_one_is_missing() {
        let truth: Vec<f32> = (0..400).map(|i| if i < 100 { 0.0 } else { 1.0 }).collect();
        let grey = images(|i| if i < 100 { 0.5 } else { 1.0 });
        assert_eq!(ids(&grey, &truth), ["umbra_not_dark"]);
        let white = images(|_| 1.0);
        assert_eq!(ids(&white, &truth), ["shadows_missing"]);
        let right = images(|i| truth[i]);
        assert_eq!(ids(&right, &truth), Vec::<&str>::new());
    }

    #[test]
    fn a_visibility_above_1_or_below_0_is_out_of_range_and_only_that() {
        let truth: Vec<f32> = (0..400).map(|i| if i < 100 { 0.0 } else { 1.0 }).collect();
        // A sum of 32 tests divided by 24: lit reads 4/3.
        let above = images(|i| truth[i] * 32.0 / 24.0);
        assert_eq!(ids(&above, &truth), ["visibility_out_of_range"]);
        let below = images(|i| if i < 100 { -0.5 } else { 1.0 });
        assert_eq!(ids(&below, &truth), ["visibility_out_of_range"]);
        // A float's rounding off 0 or 1 is in range.
        let rounded = images(|i| if i < 100 { -0.0005 } else { 1.0005 });
        assert_eq!(ids(&rounded, &truth), Vec::<&str>::new());

        let inputs = |student| CheckInputs {
            student,
            student_white_map: student,
            shadowlab: &truth,
            ground_truth: &truth,
            facing: &[Some(1.0); 400],
            visibility_function: Some(3),
            positions: &[],
        };
        let (_, findings) = check(&inputs(&above), Lang::En);
        let figures = &findings[0].figures;
        assert_eq!(figures["out_of_range_share"], 0.75);
        assert_eq!(figures["out_of_range_pixels"], 300.0);
        assert_eq!((figures["visibility_min"], figures["visibility_max"]), (0.0, f64::from(32.0f32 / 24.0)));
        assert_eq!(figures["lit_area_mean"], f64::from(32.0f32 / 24.0));
        assert_eq!((findings[0].lesson, findings[0].step), ("pcf", 2));
        let explanation = &findings[0].explanation;
        assert!(explanation.starts_with("75.0% of the visibilities"), "{explanation}");
        let (_, findings) = check(&inputs(&below), Lang::Zh);
        assert_eq!(findings[0].figures["visibility_min"], -0.5);
        let explanation = &findings[0].explanation;
        assert!(explanation.contains("25.0%") && explanation.contains("-0.50"), "{explanation}");
    }

    /// Tests summed and never divided: the umbra's one lit tap reads 1 and its soft pixels none,
    /// which is the range's finding, not missing shadows or a missing penumbra.
    #[test]
    fn an_undivided_sum_is_out_of_range_not_missing_shadows_or_penumbra() {
        let truth: Vec<f32> = (0..400)
            .map(|i| match i {
                0..100 => 0.0,
                100..300 => 0.5,
                _ => 1.0,
            })
            .collect();
        let undivided = images(|i| match i {
            0..100 if i % 10 == 0 => 16.0,
            0..100 => 0.0,
            100..300 => 16.0,
            _ => 32.0,
        });
        assert_eq!(ids(&undivided, &truth), ["visibility_out_of_range"]);
        // Divided right, the same picture has its penumbra.
        let divided = images(|i| undivided.returned[i][2] / 32.0);
        assert_eq!(ids(&divided, &truth), Vec::<&str>::new());
    }

    /// An umbra, 200 soft pixels (enough to judge a penumbra) and a lit area.
    fn soft_truth() -> Vec<f32> {
        (0..400)
            .map(|i| match i {
                0..100 => 0.0,
                100..300 => 0.5,
                _ => 1.0,
            })
            .collect()
    }

    /// A PCF sum divided twice (k = 1/32: no soft pixel, lit surfaces dark) or by twice its count
    /// (k = 0.5): the scale's finding alone, not a missing penumbra or acne.
    #[test]
    fn a_visibility_scaled_by_a_constant_is_scaled_and_only_that() {
        let truth = soft_truth();
        for k in [1.0 / 32.0, 0.5] {
            let scaled = images(|i| truth[i] * k);
            assert_eq!(ids(&scaled, &truth), ["visibility_scaled"], "k = {k}");
            let found = findings(&scaled, &truth, Lang::En);
            let figures = &found[0].figures;
            assert!((figures["scale"] - f64::from(k)).abs() < 1e-6, "k = {k}: {figures:?}");
            assert!((figures["one_over_scale"] - 1.0 / f64::from(k)).abs() < 1e-3, "k = {k}: {figures:?}");
            assert!(figures["fit_mean_abs_error"] < 1e-6 && figures["r_squared"] > 0.999, "{figures:?}");
            assert!((figures["unscaled_mean_abs_error"] - 0.5 * f64::from(1.0 - k)).abs() < 1e-6);
            assert_eq!(figures["lit_area_mean"], f64::from(k));
            assert_eq!(figures["fitted_pixels"], 400.0);
            assert_eq!((found[0].lesson, found[0].step), ("pcf", 2));
        }
        let twice = images(|i| truth[i] / 32.0);
        let explanation = &findings(&twice, &truth, Lang::En)[0].explanation;
        assert!(
            explanation.starts_with("Your visibility is shadowlab's times 0.031 (divided once more by 32.0)"),
            "{explanation}"
        );
        let explanation = &findings(&twice, &truth, Lang::Zh)[0].explanation;
        assert!(explanation.contains("0.031 倍") && explanation.contains("32.0"), "{explanation}");
        // Scaled above 1, the lit area leaves [0, 1]: the range's finding speaks for it.
        let above = images(|i| truth[i] * 32.0 / 24.0);
        assert_eq!(ids(&above, &truth), ["visibility_out_of_range"]);
    }

    /// PCSS returns 1 unfiltered where findBlocker finds no blocker: those pixels are not
    /// divided, and the scale is fitted where PCF ran.
    #[test]
    fn under_pcss_the_scale_is_fitted_where_the_filter_ran() {
        let truth = soft_truth();
        let no_blocker = |i: usize| i >= 360;
        let mut twice = images(|i| if no_blocker(i) { 1.0 } else { truth[i] / 32.0 });
        for (i, calls) in twice.calls.iter_mut().enumerate() {
            // PCSS and findBlocker ran everywhere, PCF where a blocker was found.
            calls[0] = if no_blocker(i) { 0b1100 } else { 0b1110 };
        }
        assert_eq!(ids(&twice, &truth), ["visibility_scaled"]);
        let found = findings(&twice, &truth, Lang::En);
        let figures = &found[0].figures;
        assert_eq!((figures["scale"], figures["fitted_pixels"]), (1.0 / 32.0, 360.0));
        assert_eq!(figures["lit_area_mean"], (60.0 / 32.0 + 40.0) / 100.0);
        // Where no PCF is recorded the fit is over every pixel, and the forty that read 1 spoil it.
        let everywhere = images(|i| twice.returned[i][2]);
        assert!(!ids(&everywhere, &truth).contains(&"visibility_scaled"));
    }

    /// A right solution differs from shadowlab's by noise, a few hundredths around the edges: no
    /// scale; nor is a picture flat whatever shadowlab's shows one, however close its mean.
    #[test]
    fn a_right_or_flat_visibility_is_not_scaled() {
        let truth = soft_truth();
        let shadowlab: Vec<f32> =
            truth.iter().enumerate().map(|(i, &t)| t + 0.02 * (i % 3) as f32 - 0.02).collect();
        let shadowlab: Vec<f32> = shadowlab.iter().map(|s| s.clamp(0.0, 1.0)).collect();
        let right = images(|i| truth[i]);
        let facing = [Some(1.0); 400];
        let inputs = CheckInputs {
            student: &right,
            student_white_map: &right,
            shadowlab: &shadowlab,
            ground_truth: &truth,
            facing: &facing,
            visibility_function: Some(3),
            positions: &[],
        };
        assert_eq!(check(&inputs, Lang::En).1, []);
        // Lit reads 0.6, and so does the umbra: the scaled picture's mean error is a twentieth of
        // the unscaled one's, but the scale has not the student's shadow (R^2 far under 0).
        let truth: Vec<f32> = (0..400).map(|i| if i < 10 { 0.0 } else { 1.0 }).collect();
        let flat = images(|i| 0.6 + 0.01 * (i % 2) as f32);
        assert_eq!(ids(&flat, &truth), ["umbra_not_dark"]);
    }

    #[test]
    fn lit_surfaces_darkened_where_the_shadows_are_right_are_acne() {
        let truth: Vec<f32> = (0..400).map(|i| if i < 100 { 0.0 } else { 1.0 }).collect();
        let acne = images(|i| if i < 100 || i % 3 == 0 { 0.0 } else { 1.0 });
        assert_eq!(ids(&acne, &truth), ["self_shadowing"]);
    }
}

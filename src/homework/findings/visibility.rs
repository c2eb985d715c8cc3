//! Findings on the visibility as a number: NaN, outside [0, 1], or shadowlab's times a constant.

use super::ids;
use super::{FindingKind, Found, Judged, has, mean};
use crate::i18n::{Lang, fill};
use std::collections::BTreeMap;

/// `nan_visibility`, `nan_blocker_depth`: more than this share of shaded pixels.
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

fn percent(share: f64) -> f64 {
    100.0 * share
}

/// findBlocker returned NaN (0 / 0 where it found no blocker): a mistake where the visibility is
/// NaN there too, latent where PCSS catches it.
pub const NAN_BLOCKER_DEPTH: FindingKind =
    FindingKind { id: ids::NAN_BLOCKER_DEPTH, lesson: "pcss", step: 3, judge: nan_blocker_depth };

fn nan_blocker_depth(j: &Judged<'_>, _: &[super::Finding], lang: Lang) -> Option<Found> {
    let s = j.e.student;
    let nan: Vec<usize> =
        j.shaded.iter().copied().filter(|&i| s.ran(i, 3) && !s.returned[i][3].is_finite()).collect();
    let share = j.share(nan.len());
    if share <= NAN_SHARE {
        return None;
    }
    // Where PCSS catches the NaN, the visibility there is what the ground truth says (lit: no
    // blocker was found); where it does not, the NaN reaches the filter and the lookups.
    let off = super::mean(nan.iter().map(|&i| match s.visibility(i) {
        Some(v) if v.is_finite() => f64::from((v.clamp(0.0, 1.0) - j.truth(i)).abs()),
        _ => 1.0,
    }))
    .unwrap_or(1.0);
    let figures = BTreeMap::from([
        ("nan_blocker_fraction", share),
        ("nan_blocker_pixels", nan.len() as f64),
        ("visibility_off_there", off),
    ]);
    let latent = off < 0.05;
    let explanation = if latent {
        fill(
            lang,
            "findBlocker returns NaN at {:.1}% of the shaded pixels: it divides by the number of blockers found, which is 0 where the light is not blocked. PCSS catches it before it reaches the picture, so nothing shows today; return a \"no blocker\" value there all the same.",
            &[&percent(share)],
        )
    } else {
        fill(
            lang,
            "findBlocker returned NaN or an infinite depth at {:.1}% of the shaded pixels: it divides by the number of blockers found, which is 0 where the light is not blocked. Return a \"no blocker\" value there, and have PCSS treat it as lit.",
            &[&percent(share)],
        )
    };
    Some(Found { function: Some("findBlocker"), figures, explanation, latent })
}

/// The visibility is NaN or infinite on more than `NAN_SHARE` of the pixels (not explained by a
/// NaN findBlocker, which names it).
pub const NAN_VISIBILITY: FindingKind =
    FindingKind { id: ids::NAN_VISIBILITY, lesson: "pcss", step: 3, judge: nan_visibility };

fn nan_visibility(j: &Judged<'_>, earlier: &[super::Finding], lang: Lang) -> Option<Found> {
    let share = j.share(j.non_finite);
    let named =
        earlier.iter().any(|f| f.id == ids::NAN_BLOCKER_DEPTH && f.severity == super::Severity::Mistake);
    if share <= NAN_SHARE || named {
        return None;
    }
    let figures = BTreeMap::from([("nan_fraction", share), ("nan_pixels", j.non_finite as f64)]);
    let function = first_non_finite(j);
    let explanation = match function {
        Some(function) => fill(
            lang,
            "{} returned NaN or infinity at {:.1}% of the shaded pixels, and the visibility with it: it divides by something that is 0 there (a count of taps, a sum of weights, a depth). Count what the division means, and give the case where it is 0 a value of its own.",
            &[&function, &percent(share)],
        ),
        None => fill(
            lang,
            "{:.1}% of the shaded pixels got a visibility that is NaN or infinite. The usual cause: findBlocker divides the blockers' depth sum by their count when no blocker was found (0 / 0).",
            &[&percent(share)],
        ),
    };
    Some(Found::new(function, figures, explanation))
}

/// The innermost recorded function that returned NaN or infinity at most of the pixels whose
/// visibility is not finite: where the non-finite number was made (None: none returned one).
fn first_non_finite(j: &Judged<'_>) -> Option<&'static str> {
    let s = j.e.student;
    // findBlocker, then PCF (PCSS's filter), then the functions `main` takes a visibility from.
    const INNERMOST_FIRST: [usize; 4] = [3, 1, 0, 2];
    let mut votes = [0usize; 4];
    for &i in &j.shaded {
        if s.visibility(i).is_some_and(f32::is_finite) {
            continue;
        }
        if let Some(k) = INNERMOST_FIRST.into_iter().find(|&k| s.ran(i, k) && !s.returned[i][k].is_finite()) {
            votes[k] += 1;
        }
    }
    (0..4).max_by_key(|&k| votes[k]).filter(|&k| votes[k] > 0).map(|k| crate::homework::RECORDED_FUNCTIONS[k])
}

fn in_range(v: f32) -> bool {
    (-RANGE_EPS..=1.0 + RANGE_EPS).contains(&v)
}

/// More than `OUT_OF_RANGE_SHARE` of the visibilities lie outside [0, 1]: a PCF sum of 0/1 tests
/// divided by a count other than its taps, or not at all.
pub const VISIBILITY_OUT_OF_RANGE: FindingKind =
    FindingKind { id: ids::VISIBILITY_OUT_OF_RANGE, lesson: "pcf", step: 2, judge: visibility_out_of_range };

fn visibility_out_of_range(j: &Judged<'_>, _: &[super::Finding], lang: Lang) -> Option<Found> {
    let out = j.finite.iter().filter(|&&(_, v)| !in_range(v)).count();
    let share = out as f64 / j.finite.len().max(1) as f64;
    if share <= OUT_OF_RANGE_SHARE {
        return None;
    }
    let (low, high) =
        j.finite.iter().fold((f32::INFINITY, f32::NEG_INFINITY), |(l, h), &(_, v)| (l.min(v), h.max(v)));
    let mut figures = BTreeMap::from([
        ("out_of_range_share", share),
        ("out_of_range_pixels", out as f64),
        ("visibility_min", f64::from(low)),
        ("visibility_max", f64::from(high)),
    ]);
    if let Some(lit) = lit_area_mean(j) {
        figures.insert("lit_area_mean", lit);
    }
    Some(Found::new(
        None,
        figures,
        fill(
            lang,
            "{:.1}% of the visibilities your shader returned lie outside [0, 1], from {:.2} to {:.2}. Visibility is the share of the light a point sees: a filter must divide its sum of 0/1 tests by the number of tests it summed, not by another count (PCF_NUM_SAMPLES - 8), and not leave it undivided.",
            &[&percent(share), &low, &high],
        ),
    ))
}

/// The student's mean visibility where the ground truth is fully lit.
pub fn lit_area_mean(j: &Judged<'_>) -> Option<f64> {
    mean(j.finite.iter().filter(|&&(i, _)| j.truth(i) >= super::LIT).map(|&(_, v)| f64::from(v)))
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

/// The visibility, inside [0, 1], is shadowlab's times a constant k off 1 by more than
/// `SCALE_OFF`: a PCF sum divided twice, or by a count other than its taps.
pub const VISIBILITY_SCALED: FindingKind =
    FindingKind { id: ids::VISIBILITY_SCALED, lesson: "pcf", step: 2, judge: visibility_scaled };

fn visibility_scaled(j: &Judged<'_>, earlier: &[super::Finding], lang: Lang) -> Option<Found> {
    // A scale above 1 puts the lit area above 1: the range's finding speaks for it, alone.
    if has(earlier, ids::VISIBILITY_OUT_OF_RANGE) {
        return None;
    }
    // Fitted where the comparison is sound: finite, no recorded function NaN, and no uncovered
    // texel read (no change at all over a white map: a change of 0.1 would let a sum divided by
    // 32 hide one). Under PCSS, where the student's PCF ran: where findBlocker found no blocker
    // PCSS returns its lit value unfiltered, with no sum to divide.
    let s = j.e.student;
    let comparable: Vec<(usize, f32)> =
        j.finite.iter().copied().filter(|&(i, _)| j.sound(i) && !j.changes_over_white(i, 0.0)).collect();
    let through_filter = j.pcss() && comparable.iter().any(|&(i, _)| s.ran(i, 1));
    let pairs: Vec<(f32, f32)> = comparable
        .iter()
        .filter(|&&(i, _)| !through_filter || s.ran(i, 1))
        .map(|&(i, v)| (v, j.e.shadowlab[i]))
        .collect();
    let fit = fit_scale(&pairs).filter(|fit| {
        fit.scale > 0.0
            && (fit.scale - 1.0).abs() > SCALE_OFF
            && fit.fit_error < SCALE_FIT_GAIN * fit.unscaled_error
            && fit.r_squared.is_some_and(|r2| r2 >= SCALE_R2)
    })?;
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
    if let Some(lit) = lit_area_mean(j) {
        figures.insert("lit_area_mean", lit);
    }
    Some(Found::new(
        None,
        figures,
        fill(
            lang,
            "Your visibility is shadowlab's times {:.3} (divided once more by {:.1}): a fully lit point reads {:.3}, not 1. Visibility is the share of the light a point sees, so where all of it is seen it must be 1: the sum of the 0/1 tests is divided twice (is {:.1} one of your sample counts?), or by a count other than the number of tests summed (PCF_NUM_SAMPLES * 2), or multiplied by a weight.",
            &[&fit.scale, &(1.0 / fit.scale), &fit.scale, &(1.0 / fit.scale)],
        ),
    ))
}

//! Whether PCSS's filter radius follows similar triangles in the two depths it is made of. Under
//! a blocker, the light's half width a radius implies, h = r d_b / (d_r - d_b) (uv), is the same
//! number at every receiver for a sound PCSS on an orthographic light, whose [0, 1] depth is a
//! distance along the light [Fernando-2005]. Fitted over the points under blockers as
//! h = C d_r^a d_b^b, the exponents tell the laws apart: (d_r - d_b) / d_b gives a = b = 0;
//! divided by d_r instead, h = w d_b / d_r (a = -1, b = 1); no division at all, h = w d_b
//! (b = 1); divided by d_r as well, the NVIDIA sample's perspective factor near / z_r on an
//! orthographic light, h = w / d_r (a = -1). The function values are exact, so a span of 20% in
//! depth under the check scene's slabs tells them apart (R^2 near 1 for these laws, near 0 for a
//! sound PCSS's noise), where the slabs' penumbra widths alone cannot: the blocker's distance
//! changes only 1.5x over them. Radii held at a least or largest value are left out, and a power
//! no named law has is said only where it explains nearly all (a blocker search that counts the
//! receiver skews its return with the receiver's depth a little).

use super::formula_lines::{receiver_division, world_light_size};
use super::functions::texel_uv;
use super::ids;
use super::pcss_steps::{implied_light_halves, judged};
use super::{FindingKind, Found, Judged, has};
use crate::i18n::{Lang, fill, tr};
use std::collections::BTreeMap;

const PCSS: &str = "PCSS";

/// At least this many points under blockers.
const MIN_POINTS: usize = 100;
/// A power is fitted to no fewer points than this (the values are the functions' own, exact).
const MIN_FIT_POINTS: usize = 50;
/// The receivers' (or the blockers') depths under blockers span at least this much, ln(p90 / p10)
/// (about 10%; the check scene's slabs give 20%)...
const MIN_LOG_SPREAD: f64 = 0.1;
/// ...the fit explains this share of the half widths' variance (a sound PCSS's are noise about
/// one number: R^2 under 0.05 on the development sets, 0.75-1.0 where the law is wrong)...
const LAW_R2: f64 = 0.5;
/// ...and an exponent is at least this far from a light's 0.
const LAW_EXPONENT: f64 = 0.5;
/// A filter radius held at one value at more than this share of the points is held at a bound.
const AT_BOUND_SHARE: f64 = 0.05;
/// A power no named law has explains at least this share.
const UNNAMED_LAW_R2: f64 = 0.9;
/// An exponent this close to -1, 0 or 1 names the law.
const EXPONENT_NEAR: f64 = 0.3;

/// PCSS's filter radius depends on the receiver's or the blocker's depth other than through
/// (d_r - d_b) / d_b.
pub const PENUMBRA_LAW_WRONG: FindingKind =
    FindingKind { id: ids::PENUMBRA_LAW_WRONG, lesson: "pcss", step: 7, judge: penumbra_law_wrong };

/// h = C d_r^a d_b^b, least squares in logs.
pub(super) struct PowerFit {
    pub a: f64,
    pub b: f64,
    pub r_squared: f64,
}

pub(super) fn power_fit(points: &[(f32, f32, f32)]) -> Option<PowerFit> {
    let logs: Vec<[f64; 3]> = points
        .iter()
        .filter(|(r, b, h)| *r > 0.0 && *b > 0.0 && *h > 0.0)
        .map(|&(r, b, h)| [f64::from(r).ln(), f64::from(b).ln(), f64::from(h).ln()])
        .collect();
    let n = logs.len() as f64;
    let mean = |k: usize| logs.iter().map(|l| l[k]).sum::<f64>() / n;
    let (mr, mb, mh) = (mean(0), mean(1), mean(2));
    let cov =
        |p: usize, q: usize, mp: f64, mq: f64| logs.iter().map(|l| (l[p] - mp) * (l[q] - mq)).sum::<f64>();
    let (srr, sbb, srb) = (cov(0, 0, mr, mr), cov(1, 1, mb, mb), cov(0, 1, mr, mb));
    let (srh, sbh, shh) = (cov(0, 2, mr, mh), cov(1, 2, mb, mh), cov(2, 2, mh, mh));
    let det = srr * sbb - srb * srb;
    if logs.len() < MIN_FIT_POINTS || det.abs() < 1e-12 * (srr * sbb).max(1e-30) || shh <= 0.0 {
        return None;
    }
    let a = (srh * sbb - sbh * srb) / det;
    let b = (sbh * srr - srh * srb) / det;
    let residual: f64 =
        logs.iter().map(|l| (l[2] - mh - a * (l[0] - mr) - b * (l[1] - mb)).powi(2)).sum::<f64>();
    Some(PowerFit { a, b, r_squared: 1.0 - residual / shh })
}

/// The points whose filter radius is not held at a bound: a least radius (a couple of texels,
/// so that a hard edge is still filtered) or a largest one is a choice, not a law. A bound shows
/// as a share of the radii at one value: within 2% of the smallest (or the largest) radius at
/// more than `AT_BOUND_SHARE` of the points. (receiver's depth, blocker's depth, half width.)
pub(super) fn unclamped(points: Vec<(f32, f32, f32, f32)>) -> Vec<(f32, f32, f32)> {
    let radii = || points.iter().map(|p| p.3).filter(|r| r.is_finite());
    let (least, most) = (radii().fold(f32::INFINITY, f32::min), radii().fold(0.0, f32::max));
    let share =
        |at: &dyn Fn(f32) -> bool| radii().filter(|&r| at(r)).count() as f64 / points.len().max(1) as f64;
    let at_least = |r: f32| r <= least * 1.02;
    let at_most = |r: f32| r >= most * 0.98;
    let floor = share(&at_least) > AT_BOUND_SHARE;
    let ceiling = share(&at_most) > AT_BOUND_SHARE;
    points
        .iter()
        .filter(|p| !((floor && at_least(p.3)) || (ceiling && at_most(p.3))))
        .map(|p| (p.0, p.1, p.2))
        .collect()
}

pub(super) fn percentiles(mut values: Vec<f32>) -> (f32, f32) {
    values.sort_by(f32::total_cmp);
    let at = |p: f64| values[((values.len() - 1) as f64 * p) as usize];
    (at(0.1), at(0.9))
}

/// The light is orthographic: its matrix keeps w = 1 (a perspective light's [0, 1] depth is not
/// a distance, and its uv per world unit changes with it).
pub(super) fn orthographic(j: &Judged<'_>) -> bool {
    let w = j.e.light.clip_from_world.row(3);
    w.truncate().length() < 1e-6 * w.w.abs().max(1e-6)
}

fn penumbra_law_wrong(j: &Judged<'_>, earlier: &[super::Finding], lang: Lang) -> Option<Found> {
    let explained = [
        ids::BLOCKER_DEPTH_WRONG,
        ids::PENUMBRA_ESTIMATE_WRONG,
        ids::FILTER_RADIUS_NOT_FINITE,
        ids::FILTER_IGNORES_BLOCKER,
    ];
    if !judged(j, earlier)
        || super::functions::search_broken(earlier)
        || explained.iter().any(|id| has(earlier, id))
        || has(earlier, ids::SAMPLES_NOT_AROUND_RECEIVER)
        || !orthographic(j)
    {
        return None;
    }
    let points = unclamped(implied_light_halves(j));
    if points.len() < MIN_POINTS {
        return None;
    }
    let fit = power_fit(&points)?;
    let (r10, r90) = percentiles(points.iter().map(|p| p.0).collect());
    let (b10, b90) = percentiles(points.iter().map(|p| p.1).collect());
    // The depths span enough to fit a power, the fit explains the half widths, and an exponent
    // is not a light's 0.
    let spread = f64::from(r90 / r10).ln().max(f64::from(b90 / b10).ln());
    if spread < MIN_LOG_SPREAD || fit.r_squared < LAW_R2 || fit.a.abs().max(fit.b.abs()) < LAW_EXPONENT {
        return None;
    }
    let near = |x: f64, to: f64| (x - to).abs() <= EXPONENT_NEAR;
    let law = if near(fit.a, -1.0) && near(fit.b, 0.0) {
        Some(
            "It is divided by the receiver's depth as well: r = (w/2) (d_r - d_b) / (d_b d_r). That is the perspective light's near / z_r of the NVIDIA sample; an orthographic light's [0, 1] depth is a distance along the light, and its map's uv does not shrink with it.",
        )
    } else if near(fit.a, -1.0) && near(fit.b, 1.0) {
        Some(
            "It is divided by the receiver's depth instead of the blocker's: r = (w/2) (d_r - d_b) / d_r, the right radius times d_b / d_r: right where a blocker touches its receiver, too narrow the higher the blocker.",
        )
    } else if near(fit.a, 0.0) && near(fit.b, 1.0) {
        Some("It is not divided by the blocker's depth: r = (w/2) (d_r - d_b).")
    } else {
        None
    };
    // A law of its own is named; another power must explain nearly all (a findBlocker that
    // counts the receiver skews its return with the receiver's depth, a little).
    if law.is_none() && fit.r_squared < UNNAMED_LAW_R2 {
        return None;
    }
    let texel = texel_uv(j);
    let (h10, h90) = percentiles(points.iter().map(|p| p.2).collect());
    let mut figures = BTreeMap::from([
        ("receiver_depth_exponent", fit.a),
        ("blocker_depth_exponent", fit.b),
        ("r_squared", fit.r_squared),
        ("light_half_width_texels_p10", f64::from(h10 / texel)),
        ("light_half_width_texels_p90", f64::from(h90 / texel)),
        ("receiver_depth_p10", f64::from(r10)),
        ("receiver_depth_p90", f64::from(r90)),
        ("points", points.len() as f64),
    ]);
    let mut explanation = fill(
        lang,
        "PCSS's filter radius r does not follow similar triangles: the light's half width it implies under blockers, r d_b / (d_r - d_b), is no one light's. It goes from {:.1} to {:.1} texels (10th to 90th percentile) and follows d_r^{:.2} d_b^{:.2} (R^2 {:.2}; receivers' depths {:.3} to {:.3}), where a light's is the same everywhere.",
        &[&(h10 / texel), &(h90 / texel), &fit.a, &fit.b, &fit.r_squared, &r10, &r90],
    );
    if let Some(law) = law {
        explanation += " ";
        explanation += tr(lang, law);
    }
    let divides_by_receiver = fit.a < -0.5;
    if let Some((line, code)) =
        divides_by_receiver.then(|| receiver_division(j.e.fragment_source, PCSS)).flatten()
    {
        figures.insert("line", line as f64);
        explanation += " ";
        explanation += &fill(lang, "Line {} divides by the receiver's depth: `{}`.", &[&line, &code]);
    }
    explanation += " ";
    explanation += tr(
        lang,
        "By similar triangles r = (w_light / 2) (d_r - d_b) / d_b, nothing more; on screen the penumbrae are not those of one light, wider or narrower with the receiver's distance.",
    );
    if let Some(width) = j.e.light.width.and_then(|w| w.measured_width_world())
        && let Some((name, line, value)) = world_light_size(j.e.fragment_source)
        && (width / value).max(value / width) > 2.0
    {
        figures.insert("implied_light_width_world", f64::from(width));
        figures.insert("light_size_line", line as f64);
        explanation += " ";
        explanation += &fill(
            lang,
            "The slabs' penumbrae are those of a light about {:.1} world units wide, where your {} on line {} is {}.",
            &[&width, &name, &line, &value],
        );
    }
    Some(Found::new(Some(PCSS), figures, explanation))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn points(law: impl Fn(f32, f32) -> f32) -> Vec<(f32, f32, f32)> {
        let mut out = Vec::new();
        for i in 0..20 {
            for k in 0..10 {
                let d_r = 0.05 + 0.01 * i as f32;
                let d_b = d_r * (0.6 + 0.035 * k as f32 + 0.0013 * i as f32);
                let r = law(d_r, d_b);
                out.push((d_r, d_b, r * d_b / (d_r - d_b)));
            }
        }
        out
    }

    #[test]
    fn the_exponents_tell_the_laws_apart() {
        let w = 0.01;
        type Law<'a> = &'a dyn Fn(f32, f32) -> f32;
        let cases: [(Law, f64, f64); 4] = [
            (&|r, b| w * (r - b) / b, 0.0, 0.0),
            (&|r, b| w * (r - b) / (b * r), -1.0, 0.0),
            (&|r, b| w * (r - b) / r, -1.0, 1.0),
            (&|r, b| w * (r - b), 0.0, 1.0),
        ];
        for (law, a, b) in cases {
            let fit = power_fit(&points(law)).expect("a fit");
            assert!((fit.a - a).abs() < 1e-3 && (fit.b - b).abs() < 1e-3, "{} {} vs {a} {b}", fit.a, fit.b);
        }
    }

    #[test]
    fn radii_held_at_a_least_value_are_left_out_and_the_rest_kept() {
        // A sound law, r = 0.01 (d_r - d_b) / d_b, held at no less than 0.002 uv.
        let held: Vec<(f32, f32, f32, f32)> = points(|r, b| 0.01 * (r - b) / b)
            .into_iter()
            .map(|(d_r, d_b, _)| {
                let r = (0.01 * (d_r - d_b) / d_b).max(0.002);
                (d_r, d_b, r * d_b / (d_r - d_b), r)
            })
            .collect();
        // Within 2% of the least radius counts as held there.
        let at_least = held.iter().filter(|p| p.3 <= 0.002 * 1.02).count();
        assert!(at_least > 10 && at_least < held.len() / 2, "{at_least}");
        let kept = unclamped(held.clone());
        assert_eq!(kept.len(), held.len() - at_least);
        let fit = power_fit(&kept).expect("a fit");
        assert!(fit.a.abs() < 1e-3 && fit.b.abs() < 1e-3, "{} {}", fit.a, fit.b);
    }
}

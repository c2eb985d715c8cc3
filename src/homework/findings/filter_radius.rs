//! Two things PCSS's filter radius can get wrong while each step on its own looks sound: the
//! radius does not use the blocker at all (a penumbra computed and never read, a radius from
//! the receiver's depth alone), and the filter behaves as a light of another size than the one
//! the blocker search looks for (one length turned into uv two ways). Both are judged on the
//! student's own function values under the check scene's blockers.

use super::formula_lines::{unused_from_blocker, uv_divisor};
use super::functions::texel_uv;
use super::ids;
use super::pcss_steps::{implied_light_halves, judged, searched_light_halves};
use super::penumbra_law::{orthographic, percentiles, power_fit, unclamped};
use super::{FindingKind, Found, Judged, has, median};
use crate::i18n::{Lang, fill, tr};
use std::collections::BTreeMap;

const PCSS: &str = "PCSS";

/// At least this many points under blockers (the values are the functions' own, exact).
const MIN_POINTS: usize = 50;
/// The blockers' relative heights (d_r - d_b) / d_b span at least this much, ln(p90 / p10):
/// the check scene's slabs give 2.5 (gaps 4-35 world units at 66-97 from the light).
const MIN_RATIO_LOG_SPREAD: f64 = 0.7;
/// One radius everywhere: this share of the radii within 2% of their median...
const CONSTANT_SHARE: f64 = 0.9;
/// ...or the radius's power of (d_r - d_b) / d_b under this (a sound PCSS's is 1).
const IGNORES_EXPONENT: f64 = 0.25;
/// A radius the receiver's depth explains this well follows it alone.
const RECEIVER_ALONE_R2: f64 = 0.9;
/// The light the blocker search looks for is this many times the one the filter behaves as.
const SEARCH_OVER_FILTER: f32 = 3.0;

/// PCSS's filter radius is the same whatever the blocker: no contact hardening, by construction.
pub const FILTER_IGNORES_BLOCKER: FindingKind =
    FindingKind { id: ids::FILTER_IGNORES_BLOCKER, lesson: "pcss", step: 5, judge: filter_ignores_blocker };

/// How PCSS's filter radius depends on the blocker, under the check scene's blockers.
pub(super) enum BlockerDependence {
    /// One radius (uv) at this share of the points.
    Constant { radius_uv: f32, share: f64 },
    /// The radius's powers of d_r (`a`) and of (d_r - d_b) / d_b (`b`, 1 for similar triangles).
    Fitted(super::penumbra_law::PowerFit),
}

/// The filter radius's dependence on the blocker where it ignores it: one radius everywhere, or
/// a power of (d_r - d_b) / d_b near 0. None where it follows the blocker, or where the points
/// cannot tell (too few, too little spread in the blockers' heights, a perspective light).
/// (dependence, (d_r - d_b) / d_b's 10th and 90th percentiles, points.)
pub(super) fn ignored_blocker(j: &Judged<'_>) -> Option<(BlockerDependence, (f32, f32), usize)> {
    if !j.pcss() || !orthographic(j) {
        return None;
    }
    // (receiver's depth, blocker's depth, filter radius (uv)) under blockers.
    let points: Vec<(f32, f32, f32)> = implied_light_halves(j)
        .into_iter()
        .filter(|p| p.3.is_finite() && p.3 > 0.0)
        .map(|(z_r, z_b, _, filter)| (z_r, z_b, filter))
        .collect();
    if points.len() < MIN_POINTS {
        return None;
    }
    let ratio = |&(z_r, z_b, _): &(f32, f32, f32)| (z_r - z_b) / z_b;
    let (q10, q90) = percentiles(points.iter().map(ratio).collect());
    if q10 <= 0.0 || f64::from(q90 / q10).ln() < MIN_RATIO_LOG_SPREAD {
        return None;
    }
    let typical = median(points.iter().map(|p| p.2).collect())?;
    let share =
        points.iter().filter(|p| (p.2 / typical - 1.0).abs() <= 0.02).count() as f64 / points.len() as f64;
    if share > CONSTANT_SHARE {
        return Some((BlockerDependence::Constant { radius_uv: typical, share }, (q10, q90), points.len()));
    }
    // Radii held at a least or largest value are a choice, not the law: left out.
    let free = unclamped(points.iter().map(|&(z_r, z_b, f)| (z_r, z_b, f, f)).collect());
    let fit = power_fit(&free.iter().map(|p| (p.0, ratio(p), p.2)).collect::<Vec<_>>())?;
    (fit.b.abs() < IGNORES_EXPONENT).then_some((BlockerDependence::Fitted(fit), (q10, q90), points.len()))
}

fn filter_ignores_blocker(j: &Judged<'_>, earlier: &[super::Finding], lang: Lang) -> Option<Found> {
    let explained = [ids::BLOCKER_DEPTH_WRONG, ids::PENUMBRA_ESTIMATE_WRONG, ids::FILTER_RADIUS_NOT_FINITE];
    if !judged(j, earlier)
        || explained.iter().any(|id| has(earlier, id))
        || has(earlier, ids::SAMPLES_NOT_AROUND_RECEIVER)
    {
        return None;
    }
    let (dependence, (q10, q90), points) = ignored_blocker(j)?;
    let texel = texel_uv(j);
    let mut figures = BTreeMap::from([
        ("blocker_ratio_p10", f64::from(q10)),
        ("blocker_ratio_p90", f64::from(q90)),
        ("points", points as f64),
    ]);
    let mut explanation = match dependence {
        BlockerDependence::Constant { radius_uv, share } => {
            figures.insert("filter_radius_texels", f64::from(radius_uv / texel));
            figures.insert("one_radius_share", share);
            fill(
                lang,
                "PCSS filters with one radius whatever the blocker: {:.1} texels at {:.0}% of the points under blockers, where (d_r - d_b) / d_b goes from {:.2} to {:.2}.",
                &[&(radius_uv / texel), &(100.0 * share), &q10, &q90],
            )
        }
        BlockerDependence::Fitted(fit) => {
            figures.insert("blocker_ratio_exponent", fit.b);
            figures.insert("receiver_depth_exponent", fit.a);
            figures.insert("r_squared", fit.r_squared);
            let mut seen = fill(
                lang,
                "PCSS's filter radius does not follow the blocker: under blockers, where (d_r - d_b) / d_b goes from {:.2} to {:.2}, the radius goes as its power {:.2}, where similar triangles make it 1.",
                &[&q10, &q90, &fit.b],
            );
            if fit.r_squared >= RECEIVER_ALONE_R2 && fit.a.abs() >= 0.5 {
                seen += " ";
                seen += &fill(lang, "It follows the receiver's depth alone (R^2 {:.2}).", &[&fit.r_squared]);
            }
            seen
        }
    };
    if let Some((line, name)) = unused_from_blocker(j.e.fragment_source) {
        figures.insert("line", line as f64);
        explanation += " ";
        explanation += &fill(
            lang,
            "Line {} computes `{}` from the blocker's depth, but nothing reads it: the filter is sized without it.",
            &[&line, &name],
        );
    }
    explanation += " ";
    explanation += tr(
        lang,
        "By similar triangles the filter radius is (w_light / 2) (d_r - d_b) / d_b: it is what makes a shadow hard where its blocker touches the receiver and soft where the blocker is high. Without it PCSS is PCF with a radius of its own.",
    );
    Some(Found::new(Some(PCSS), figures, explanation))
}

/// The blocker search looks for a light several times wider than the one the filter behaves
/// as: one light size turned into uv two ways.
pub const SEARCH_AND_FILTER_LIGHTS_DIFFER: FindingKind = FindingKind {
    id: ids::SEARCH_AND_FILTER_LIGHTS_DIFFER,
    lesson: "pcss",
    step: 6,
    judge: search_and_filter_lights_differ,
};

fn search_and_filter_lights_differ(j: &Judged<'_>, earlier: &[super::Finding], lang: Lang) -> Option<Found> {
    let explained = [
        ids::BLOCKER_DEPTH_WRONG,
        ids::PENUMBRA_ESTIMATE_WRONG,
        ids::FILTER_RADIUS_NOT_FINITE,
        ids::FILTER_IGNORES_BLOCKER,
        ids::PENUMBRA_LAW_WRONG,
        ids::SAMPLES_NOT_AROUND_RECEIVER,
    ];
    if !judged(j, earlier)
        || super::functions::search_broken(earlier)
        || has(earlier, ids::SEARCH_RADIUS_WRONG)
        || explained.iter().any(|id| has(earlier, id))
        || !orthographic(j)
    {
        return None;
    }
    let texel = texel_uv(j);
    let points: Vec<(f32, f32)> = searched_light_halves(j)
        .into_iter()
        .filter(|(search, half)| search.is_finite() && *search >= texel && half.is_finite() && *half > 0.0)
        .collect();
    if points.len() < MIN_POINTS {
        return None;
    }
    // The framework's PCSS searches LIGHT_SIZE_UV (z_r - near) / z_r, nearly the light's half
    // width itself on an orthographic map, and its filter implies that same half width.
    let search = median(points.iter().map(|p| p.0).collect())?;
    let half = median(points.iter().map(|p| p.1).collect())?;
    let times = search / half;
    if times < SEARCH_OVER_FILTER {
        return None;
    }
    let mut figures = BTreeMap::from([
        ("search_radius_texels_median", f64::from(search / texel)),
        ("filter_light_half_width_texels_median", f64::from(half / texel)),
        ("search_over_filter", f64::from(times)),
        ("points", points.len() as f64),
    ]);
    let mut explanation = fill(
        lang,
        "findBlocker searches {:.1} texels around the receiver, a light's half width, but PCSS's filter behaves as a light {:.1} times narrower: its radius r = (w_light / 2) (d_r - d_b) / d_b, solved with findBlocker's own d_b, gives a half width of {:.1} texels. One light has one size in uv; the penumbrae come out {:.1} times narrower than the light the search looks for.",
        &[&(search / texel), &times, &(half / texel), &times],
    );
    if let Some(per_uv) = super::source_lines::world_per_uv(j) {
        figures.insert("search_light_width_world", f64::from(2.0 * search * per_uv));
        figures.insert("filter_light_width_world", f64::from(2.0 * half * per_uv));
        explanation += " ";
        explanation += &fill(
            lang,
            "In world units: a light {:.1} wide for the search, {:.1} for the filter.",
            &[&(2.0 * search * per_uv), &(2.0 * half * per_uv)],
        );
    }
    // Where the two turn their lengths into uv with different divisors, the lines that do.
    let filter_line =
        uv_divisor(j.e.fragment_source, PCSS).or_else(|| uv_divisor(j.e.fragment_source, "PCF"));
    if let (Some((s_line, s_div, _)), Some((f_line, f_div, f_code))) =
        (uv_divisor(j.e.fragment_source, "findBlocker"), filter_line)
        && s_div != f_div
    {
        figures.insert("search_line", s_line as f64);
        figures.insert("line", f_line as f64);
        explanation += " ";
        explanation += &fill(
            lang,
            "Line {} turns the search's radius into uv with `/ {}`, line {} the filter's with `/ {}`: `{}`. Use the one that matches the unit the radius is in.",
            &[&s_line, &s_div, &f_line, &f_div, &f_code],
        );
    }
    Some(Found::new(Some(PCSS), figures, explanation))
}

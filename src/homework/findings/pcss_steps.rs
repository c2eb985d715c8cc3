//! PCSS's steps, each judged on the student's own inputs: whether findBlocker's search reaches as
//! far as the light their filter behaves as, whether what it returns is the blockers' depth the
//! twin finds over the same disk of shadowlab's map, and whether the filter radius PCSS hands on
//! follows (d_r - d_b) / d_b from findBlocker's own return. Each names the function, the quantity
//! (theirs and the expected one) and, where the code shows it, the line.

use super::functions::{FIND_BLOCKER, PCF, PCSS, texel_uv};
use super::ids;
use super::source_lines::{reads_map_in, return_of, sample_array_read_unfilled};
use super::{FindingKind, Found, Judged, has, median};
use crate::i18n::{Lang, fill};
use std::collections::BTreeMap;

/// A blocker this far in front of its receiver ([0, 1] depth) is one (the packing's rounding and
/// the receiver plane's slope over a texel stay under it).
const GAP: f32 = 0.002;
/// `search_radius_wrong` (reads at the receiver only): findBlocker's reads all lie under half a
/// texel from the receiver at more than this share of the pixels it ran at...
const AT_RECEIVER_SHARE: f64 = 0.95;
/// ...while PCSS's filter reaches a texel or more at more than this share (a tiny light's
/// search and filter are both that small: `no_penumbra`).
const FILTER_REACHES_SHARE: f64 = 0.2;
/// `search_radius_wrong` (too small for the light): the blockers that shade a receiver lie up to
/// more than this many times the search radius from it (by the light its filter behaves as)...
const REACH_OVER_SEARCH: f32 = 1.5;
/// ...at more than this share of the points under a blocker.
const MISSED_SHARE: f64 = 0.25;
/// `blocker_depth_wrong`: where the twin finds at least this share of the student's disk blocked...
const MOSTLY_BLOCKED: f32 = 0.5;
/// ...findBlocker's return lies outside [blockers - a quarter of the gap, receiver + a quarter]
/// at more than this share of them (the receiver's own texels pull an average towards the
/// receiver, never past it: that is `receiver_counts_as_blocker`).
const NOT_A_BLOCKER_SHARE: f64 = 0.5;
/// `penumbra_estimate_wrong`: the filter radius is under a texel at more than this share of the
/// points under blockers where the student's own light (the 90th percentile of the half widths
/// their radii imply, r d_b / (d_r - d_b)) asks for two texels or more.
const COLLAPSED_SHARE: f64 = 0.3;

/// One pixel's PCSS as the student's functions ran it.
struct Step {
    pixel: usize,
    /// findBlocker's farthest read and what it returned.
    search_uv: f32,
    z_blocker: f32,
    z_receiver: f32,
    /// The farthest read of the filter PCSS ran (PCF's, or PCSS's own).
    filter_uv: f32,
}

impl Step {
    /// How far from the receiver (uv) the blockers that shade it can lie, by the light the filter
    /// radius implies: the light's disk seen from the receiver, cut by the blockers' plane,
    /// (w_light / 2) (d_r - d_b) / d_r, that is r d_b / d_r.
    fn reach_uv(&self) -> Option<f32> {
        self.light_half_uv().map(|_| self.filter_uv * self.z_blocker / self.z_receiver)
    }

    /// The light's half width (uv) the filter radius implies by similar triangles, where
    /// findBlocker returned a blocker in front of the receiver.
    fn light_half_uv(&self) -> Option<f32> {
        let gap = self.z_receiver - self.z_blocker;
        (self.z_blocker > 0.0 && gap > GAP && self.filter_uv.is_finite())
            .then(|| self.filter_uv * self.z_blocker / gap)
    }
}

fn steps(j: &Judged<'_>) -> Vec<Step> {
    let taps = &j.e.taps.taps;
    let s = j.e.student;
    j.shaded
        .iter()
        .filter(|&&i| s.ran(i, FIND_BLOCKER) && j.sound(i) && j.faces_light(i))
        .filter_map(|&i| {
            let r = j.receivers[i].filter(|r| r.inside())?;
            let filter = [PCF, PCSS].into_iter().map(|k| taps[i][k]).find(|t| t.reads >= 4.0)?;
            Some(Step {
                pixel: i,
                search_uv: taps[i][FIND_BLOCKER].max_offset_uv,
                z_blocker: s.returned[i][FIND_BLOCKER],
                z_receiver: r.depth,
                filter_uv: filter.max_offset_uv,
            })
        })
        .collect()
}

/// The steps where the twin finds real blockers over the student's disk (a fifth of it or more,
/// well in front of the receiver): a sloped floor's own nearer texels, which a flat bias lets a
/// wide search count, are not what a penumbra is made of.
fn steps_under_blockers<'s>(j: &Judged<'_>, steps: &'s [Step]) -> Vec<&'s Step> {
    let by_pixel: std::collections::HashMap<usize, &Step> = steps.iter().map(|s| (s.pixel, s)).collect();
    j.twin()
        .iter()
        .filter(|(_, t)| t.blocked >= 0.2 && t.z_receiver - t.z_blocker > 2.0 * GAP)
        .filter_map(|(i, _)| by_pixel.get(i).copied())
        .filter(|s| s.light_half_uv().is_some())
        .collect()
}

/// The light's half widths (uv) the filter radii imply under blockers.
fn light_halves(j: &Judged<'_>, steps: &[Step]) -> Vec<f32> {
    steps_under_blockers(j, steps).iter().filter_map(|s| s.light_half_uv()).collect()
}

/// Under real blockers: (the receiver's depth, findBlocker's return, the light's half width
/// (uv) the filter radius implies there, the filter radius (uv)), all from the student's own
/// functions.
pub(super) fn implied_light_halves(j: &Judged<'_>) -> Vec<(f32, f32, f32, f32)> {
    let steps = steps(j);
    steps_under_blockers(j, &steps)
        .iter()
        .filter_map(|s| Some((s.z_receiver, s.z_blocker, s.light_half_uv()?, s.filter_uv)))
        .collect()
}

/// Under real blockers: (findBlocker's farthest read (uv), the light's half width (uv) the
/// filter radius implies there).
pub(super) fn searched_light_halves(j: &Judged<'_>) -> Vec<(f32, f32)> {
    let steps = steps(j);
    steps_under_blockers(j, &steps).iter().filter_map(|s| Some((s.search_uv, s.light_half_uv()?))).collect()
}

fn percentile(values: &mut [f32], p: f64) -> Option<f32> {
    values.sort_by(f32::total_cmp);
    values.get(((values.len().max(1) - 1) as f64 * p) as usize).copied()
}

pub(super) fn judged(j: &Judged<'_>, earlier: &[super::Finding]) -> bool {
    j.pcss() && !has(earlier, ids::SHADOWS_MISSING) && !has(earlier, ids::LIGHT_MODEL_MATRIX)
}

/// findBlocker's search does not reach the light: every read on the receiver's own texel while
/// the filter spreads, or a radius a fraction of the light's half width the filter behaves as.
pub const SEARCH_MISSES_LIGHT: FindingKind =
    FindingKind { id: ids::SEARCH_RADIUS_WRONG, lesson: "pcss", step: 2, judge: search_misses_light };

fn search_misses_light(j: &Judged<'_>, earlier: &[super::Finding], lang: Lang) -> Option<Found> {
    if !judged(j, earlier)
        || has(earlier, ids::SEARCH_RADIUS_WRONG)
        || has(earlier, ids::FILTER_RADIUS_NOT_FINITE)
    {
        return None;
    }
    let steps = steps(j);
    if steps.len() < 100 {
        return None;
    }
    let texel = texel_uv(j);
    let n = steps.len() as f64;
    let at_receiver = steps.iter().filter(|s| s.search_uv < 0.5 * texel).count() as f64 / n;
    let filter_reaches = steps.iter().filter(|s| s.filter_uv >= texel).count() as f64 / n;
    let mut filters: Vec<f32> = steps.iter().map(|s| s.filter_uv).filter(|f| f.is_finite()).collect();
    if at_receiver > AT_RECEIVER_SHARE && filter_reaches > FILTER_REACHES_SHARE {
        let filter_p90 = percentile(&mut filters, 0.9)? / texel;
        let mut figures = BTreeMap::from([
            ("reads_at_receiver_share", at_receiver),
            ("filter_radius_texels_p90", f64::from(filter_p90)),
        ]);
        let mut explanation = fill(
            lang,
            "findBlocker reads the map only at the receiver's own texel at {:.0}% of the pixels (every read within half a texel of it), while PCSS's filter then reaches up to {:.1} texels: the search sees no blocker beside the receiver, so the penumbra starts only where the receiver's own texel is blocked.",
            &[&(100.0 * at_receiver), &filter_p90],
        );
        if let Some((array, line)) = sample_array_read_unfilled(j.e.fragment_source, "findBlocker") {
            figures.insert("unfilled_read_line", line as f64);
            explanation += " ";
            explanation += &fill(
                lang,
                "Line {} reads `{}` before anything fills it (nothing that writes it runs before findBlocker): every offset is 0. Fill the samples at the start of findBlocker.",
                &[&line, &array],
            );
        }
        return Some(Found::new(Some("findBlocker"), figures, explanation));
    }
    // Where the blockers that shade a receiver lie farther than the search reaches.
    let under = steps_under_blockers(j, &steps);
    let searched: Vec<&&Step> =
        under.iter().filter(|s| s.search_uv.is_finite() && s.search_uv >= 0.5 * texel).collect();
    if searched.len() < 50 {
        return None;
    }
    let missed: Vec<&&&Step> = searched
        .iter()
        .filter(|s| s.reach_uv().is_some_and(|r| r > REACH_OVER_SEARCH * s.search_uv))
        .collect();
    let share = missed.len() as f64 / searched.len() as f64;
    if share <= MISSED_SHARE {
        return None;
    }
    let search = median(searched.iter().map(|s| s.search_uv).collect())?;
    let reach = percentile(&mut searched.iter().filter_map(|s| s.reach_uv()).collect::<Vec<_>>(), 0.9)?;
    let light = median(searched.iter().filter_map(|s| s.light_half_uv()).collect())?;
    let mut figures = BTreeMap::from([
        ("search_radius_texels_median", f64::from(search / texel)),
        ("blockers_reach_texels_p90", f64::from(reach / texel)),
        ("light_half_width_texels_median", f64::from(light / texel)),
        ("missed_share", share),
    ]);
    let mut explanation = fill(
        lang,
        "findBlocker searches {:.1} texels around the receiver, but at {:.0}% of the points under a blocker the blockers that shade the receiver lie farther, up to {:.1} texels away: the light PCSS's filter behaves as ({:.1} texels wide: its radius r = (w_light / 2) (d_r - d_b) / d_b solved with findBlocker's own d_b) reaches the blockers' plane within (w_light / 2) (d_r - d_b) / d_r of the receiver. Search the light's half width (in the map's uv), which covers every blocker depth.",
        &[&(search / texel), &(100.0 * share), &(reach / texel), &(2.0 * light / texel)],
    );
    if let Some(per_uv) = super::source_lines::world_per_uv(j) {
        figures.insert("light_width_world", f64::from(2.0 * light * per_uv));
        explanation += " ";
        explanation += &fill(
            lang,
            "That light is {:.1} world units wide. The blockers the search misses are the ones that shade the outer penumbra: it ends too soon, hard, where the search stops.",
            &[&(2.0 * light * per_uv)],
        );
    }
    Some(Found::new(Some("findBlocker"), figures, explanation))
}

/// findBlocker returns a depth no blocker has where most of the disk it searched is blocked: a
/// constant from an early return, a "no blocker" value where there are blockers.
pub const BLOCKER_DEPTH_WRONG: FindingKind =
    FindingKind { id: ids::BLOCKER_DEPTH_WRONG, lesson: "pcss", step: 3, judge: blocker_depth_wrong };

fn blocker_depth_wrong(j: &Judged<'_>, earlier: &[super::Finding], lang: Lang) -> Option<Found> {
    if !judged(j, earlier)
        || super::functions::search_broken(earlier)
        || has(earlier, ids::RECEIVER_COUNTS_AS_BLOCKER)
    {
        return None;
    }
    // A bias that loses the nearest blockers (peter panning) loses them here too: only gaps over it.
    let bias = earlier
        .iter()
        .find(|f| f.id == ids::PETER_PANNING)
        .and_then(|f| f.figures.get("bias_under_depth"))
        .map_or(0.0, |b| *b as f32);
    let (mut compared, mut off) = (0usize, Vec::new());
    let mut blockers = Vec::new();
    for (i, search) in j.twin() {
        let gap = search.z_receiver - search.z_blocker;
        if search.blocked < MOSTLY_BLOCKED || gap <= GAP.max(bias) {
            continue;
        }
        compared += 1;
        blockers.push(search.z_blocker);
        let returned = j.e.student.returned[*i][FIND_BLOCKER];
        let tolerance = (0.25 * gap).max(GAP);
        if !(search.z_blocker - tolerance..=search.z_receiver + tolerance).contains(&returned) {
            off.push(returned);
        }
    }
    let share = off.len() as f64 / compared.max(1) as f64;
    if compared < 50 || share <= NOT_A_BLOCKER_SHARE {
        return None;
    }
    let (returned, blocker) = (median(off.clone())?, median(blockers)?);
    // The value most of the wrong returns are, where one is.
    let same = off.iter().filter(|v| (**v - returned).abs() < 1e-4).count() as f64 / off.len() as f64;
    let mut figures = BTreeMap::from([
        ("not_a_blocker_share", share),
        ("returned_median", f64::from(returned)),
        ("twin_blocker_depth_median", f64::from(blocker)),
        ("points", compared as f64),
    ]);
    let mut explanation = fill(
        lang,
        "findBlocker returns {:.3} (the median) at {:.0}% of the points where most of the disk it searched is blocked, where the blockers' average depth is {:.3} (the median, in [0, 1] depth, from shadowlab's map over the same disk).",
        &[&returned, &(100.0 * share), &blocker],
    );
    if same > 0.5
        && let Some((line, condition)) = return_of(j.e.fragment_source, "findBlocker", returned)
    {
        figures.insert("return_line", line as f64);
        explanation += " ";
        explanation += &match condition {
            Some(c) => fill(
                lang,
                "That is the return on line {}, taken whenever the test on line {} holds: it holds where it should not.",
                &[&line, &c],
            ),
            None => fill(lang, "That is the return on line {}.", &[&line]),
        };
    }
    explanation += " ";
    explanation += crate::i18n::tr(
        lang,
        "PCSS then sizes the penumbra from a depth that is no blocker's: it no longer widens with the distance from blocker to receiver.",
    );
    Some(Found::new(Some("findBlocker"), figures, explanation))
}

/// The filter radius PCSS hands on collapses where findBlocker found blockers well in front of
/// the receiver: the penumbra estimate does not use the receiver's own depth.
pub const PENUMBRA_ESTIMATE_WRONG: FindingKind =
    FindingKind { id: ids::PENUMBRA_ESTIMATE_WRONG, lesson: "pcss", step: 5, judge: penumbra_estimate_wrong };

fn penumbra_estimate_wrong(j: &Judged<'_>, earlier: &[super::Finding], lang: Lang) -> Option<Found> {
    if !judged(j, earlier)
        || super::functions::search_broken(earlier)
        || has(earlier, ids::BLOCKER_DEPTH_WRONG)
        || has(earlier, ids::FILTER_RADIUS_NOT_FINITE)
    {
        return None;
    }
    let steps = steps(j);
    let mut lights = light_halves(j, &steps);
    if lights.len() < 50 {
        return None;
    }
    let texel = texel_uv(j);
    let usual = percentile(&mut lights, 0.9)?;
    if usual < 2.0 * texel {
        return None;
    }
    // Where the student's own light (its usual half width) asks for a filter of two texels or
    // more, the radius handed on is under a texel: the estimate lost the distance to the receiver.
    // (A constant or clamped radius is not under a texel there: that is no_contact_hardening's.)
    let asked: Vec<&Step> = steps_under_blockers(j, &steps)
        .into_iter()
        .filter(|s| usual * (s.z_receiver - s.z_blocker) / s.z_blocker >= 2.0 * texel)
        .collect();
    if asked.len() < 50 {
        return None;
    }
    let collapsed = asked.iter().filter(|s| s.filter_uv < texel).count() as f64 / asked.len() as f64;
    if collapsed <= COLLAPSED_SHARE {
        return None;
    }
    let mut figures = BTreeMap::from([
        ("collapsed_share", collapsed),
        ("light_half_width_texels_p90", f64::from(usual / texel)),
        ("points", asked.len() as f64),
    ]);
    let mut explanation = fill(
        lang,
        "PCSS hands its filter a radius that collapses at {:.0}% of the points under a blocker (findBlocker's own blockers in front of the receiver): there it is under a texel where the same light (r d_b / (d_r - d_b), the light's half width, {:.1} texels at the 90th percentile) asks for two or more. By similar triangles r = (w_light / 2) (d_r - d_b) / d_b with d_r the receiver's own depth: it is small only where the blocker touches the receiver.",
        &[&(100.0 * collapsed), &(usual / texel)],
    );
    if let Some(line) = reads_map_in(j.e.fragment_source, "PCSS") {
        figures.insert("map_read_line", line as f64);
        explanation += " ";
        explanation += &fill(
            lang,
            "PCSS reads the map itself on line {}: a depth read at the receiver's uv is the nearest occluder's, not the receiver's; use the receiver's own depth (coords.z).",
            &[&line],
        );
    }
    explanation += " ";
    explanation += crate::i18n::tr(
        lang,
        "On screen, the part of each penumbra inside the hard shadow's edge is dark and hard.",
    );
    Some(Found::new(Some("PCSS"), figures, explanation))
}

/// Whether findBlocker sees blockers as near their receiver as `gap_depth` ([0, 1] depth): at
/// the points where most of its disk is blocked by one that near, it returns a depth among the
/// blockers' (None: too few such points, or no PCSS). A bias that large would hide them from it.
pub(crate) fn search_sees_blockers_within(j: &Judged<'_>, gap_depth: f32) -> Option<bool> {
    if !j.pcss() {
        return None;
    }
    let (mut near, mut seen) = (0usize, 0usize);
    for (i, t) in j.twin() {
        let gap = t.z_receiver - t.z_blocker;
        if t.blocked < MOSTLY_BLOCKED || gap <= GAP || gap > gap_depth {
            continue;
        }
        near += 1;
        let returned = j.e.student.returned[*i][FIND_BLOCKER];
        seen += usize::from((returned - t.z_blocker).abs() <= (0.25 * gap).max(GAP));
    }
    (near >= 20).then(|| seen as f64 / near as f64 > 0.7)
}

/// The light's width PCSS's filter behaves as, in uv of the map, where real blockers are (the
/// median of 2 r d_b / (d_r - d_b)).
pub(crate) fn light_width_behaved_as_uv(j: &Judged<'_>) -> Option<f32> {
    if !j.pcss() {
        return None;
    }
    let lights = light_halves(j, &steps(j));
    (lights.len() >= 50).then(|| 2.0 * median(lights).unwrap_or(f32::NAN)).filter(|w| w.is_finite())
}

/// `unpack_loses_depth`: where the disk findBlocker searched is blocked (95% or more of it: the
/// twin's grid rarely finds more at a slab's edge texels), its return over
/// the lossless map (every bit the pack wrote kept) is off the blockers' average depth on
/// shadowlab's map by more than this (the median, signed). A sound unpack is off by the sampling
/// of a sloped blocker, well under it; reading `.r` alone truncates to 1/256, about -1/512.
const UNPACK_SHIFT: f32 = 1e-3;
/// The umbra's pixels the twin searches for it, at most.
const UMBRA_PIXELS: usize = 2000;

/// The student's unpack loses depth the pack stored: findBlocker, reading a map that keeps every
/// bit, returns the blockers' depth shifted where its whole disk is blocked.
pub const UNPACK_LOSES_DEPTH: FindingKind = FindingKind {
    id: ids::DEPTH_ROUND_TRIP_WRONG,
    lesson: "hard-shadows",
    step: 3,
    judge: unpack_loses_depth,
};

fn unpack_loses_depth(j: &Judged<'_>, earlier: &[super::Finding], lang: Lang) -> Option<Found> {
    if !judged(j, earlier)
        || has(earlier, ids::DEPTH_ROUND_TRIP_WRONG)
        || super::functions::search_broken(earlier)
    {
        return None;
    }
    let twin = j.e.twin?;
    let (taps, lossless) = (&j.e.taps.taps, j.e.lossless);
    let umbra: Vec<usize> = j
        .shaded
        .iter()
        .copied()
        .filter(|&i| {
            j.truth(i) <= super::UMBRA
                && j.faces_light(i)
                && lossless.ran(i, FIND_BLOCKER)
                && lossless.returned[i][FIND_BLOCKER].is_finite()
                && taps[i][FIND_BLOCKER].reads >= 2.0
                && taps[i][FIND_BLOCKER].max_offset_uv.is_finite()
                && j.receivers[i].is_some_and(|r| r.inside())
        })
        .collect();
    let step = umbra.len().div_ceil(UMBRA_PIXELS).max(1);
    let shifts: Vec<f32> = umbra
        .iter()
        .step_by(step)
        .filter_map(|&i| {
            let (p, n) = (j.e.positions[i]?, twin.normals.get(i).copied().flatten()?);
            let search = super::functions::twin_search(twin, p, n, taps[i][FIND_BLOCKER].max_offset_uv)?;
            (search.blocked >= 0.95 && search.z_receiver - search.z_blocker > GAP)
                .then(|| lossless.returned[i][FIND_BLOCKER] - search.z_blocker)
        })
        .filter(|d| d.abs() < 0.05)
        .collect();
    if shifts.len() < 40 {
        return None;
    }
    let shift = median(shifts.clone())?;
    if shift.abs() <= UNPACK_SHIFT {
        return None;
    }
    let mut sizes: Vec<f32> = shifts.iter().map(|d| d.abs()).collect();
    let largest = percentile(&mut sizes, 0.9)?;
    let mut figures = BTreeMap::from([
        ("blocker_depth_shift_median", f64::from(shift)),
        ("blocker_depth_error_p90", f64::from(largest)),
        ("points", shifts.len() as f64),
    ]);
    let place = super::source_lines::unpack_function(j.e.fragment_source);
    if let Some((_, line)) = &place {
        figures.insert("unpack_line", *line as f64);
    }
    let name = place.as_ref().map_or("unpack", |(n, _)| n.as_str());
    let at = place.as_ref().map_or(String::new(), |(_, l)| fill(lang, " (line {})", &[l]));
    let direction =
        if shift < 0.0 { crate::i18n::tr(lang, "too near") } else { crate::i18n::tr(lang, "too far") };
    let explanation = fill(
        lang,
        "Your `{}`{} does not give back the depth your pack stored: from a map that keeps every bit, findBlocker returns the blockers' depth {:.4} {} (the median, in [0, 1] depth; up to {:.4}) where the whole disk it searched is blocked. Unpack every channel with the weights your pack used (dot(rgbaDepth, vec4(1.0, 1.0 / 256.0, 1.0 / 65536.0, 1.0 / 16777216.0)) for the framework's pack). A receiver reads its own depth off by as much: with a smaller bias it shadows itself.",
        &[&name, &at, &shift.abs(), &direction, &largest],
    );
    // Today's picture shows it where a receiver already finds itself.
    let shows = has(earlier, ids::SELF_SHADOWING) || has(earlier, ids::RECEIVER_COUNTS_AS_BLOCKER);
    let explanation = if shows {
        explanation
    } else {
        format!(
            "{} {explanation}",
            crate::i18n::tr(lang, "Hidden today by your bias (it shows as soon as the bias is smaller):")
        )
    };
    Some(Found { latent: !shows, ..Found::new(Some("findBlocker"), figures, explanation) })
}

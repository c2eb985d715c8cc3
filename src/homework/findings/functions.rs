//! Findings that name the student's function that parts from the reference first: where
//! `findBlocker` searched (its taps), what it returned against the twin's average blocker depth
//! over the same disk of shadowlab's map, and where the filter read.

use super::ids;
use super::{FindingKind, Found, Judged, median};
use crate::i18n::{Lang, fill};
use crate::shadow::{DepthImage, ShadowViewGpu, project_to_light, receiver_plane_gradient};
use glam::{Vec2, Vec3};
use std::collections::BTreeMap;

/// The recorded functions' channels (`RECORDED_FUNCTIONS` order).
pub(crate) const PCF: usize = 1;
pub(crate) const PCSS: usize = 2;
pub(crate) const FIND_BLOCKER: usize = 3;

/// `search_radius_wrong`: the search radius is NaN or infinite at more than this share of the
/// pixels findBlocker ran at...
const NOT_FINITE_SHARE: f64 = 0.01;
/// ...or under half a texel (every tap on the receiver's own texel) at more than this share (but
/// not nearly everywhere: a search as small as its tiny light is that light's, `no_penumbra`)...
const COLLAPSED_SHARE: f64 = 0.2;
const COLLAPSED_EVERYWHERE: f64 = 0.95;
/// ...or varies more than this (the 90th percentile over the 10th) over the scene's receivers: a
/// radius that similar triangles make nearly constant on an orthographic map (a near plane at
/// -100, as one student has it, moves it by 13% here; a perspective formula, near / z, by 50%).
const RADIUS_SPREAD: f32 = 1.4;
/// `samples_not_around_receiver`: the filter's taps' mean offset from the receiver, over their
/// root mean square offset (median over the pixels it filtered with 8 taps or more, over a
/// texel): a disk around the receiver keeps it near 0 (the framework's spiral 0.03; n random
/// taps about 1 / sqrt(n)).
const OFF_CENTRE: f32 = 0.6;
/// The twin's blocker search is evaluated at most at this many pixels.
const TWIN_PIXELS: usize = 4000;
/// `samples_not_around_receiver`: the filter's taps stretch the same way at every pixel (the
/// mean of their stretch over the pixels, 0 where each pixel's lies another way or none does, 1
/// where all lie on lines of one direction) more than this. One pixel's taps on a line whose angle
/// changes from pixel to pixel (the template's 20-sample, 10-ring spiral, turned by the pixel's
/// random angle) make noise, not a penumbra soft one way and hard the other.
const STRETCH: f32 = 0.5;
/// `depth_round_trip_wrong`: a lit surface's depth read back from the lossless map is off by more
/// than this (0.4 world units with far 400; a texel spans a fifth of it)...
const ROUND_TRIP_ERROR: f32 = 1e-3;
/// ...at more than this share of lit surfaces (at least `ROUND_TRIP_POINTS` of them, at most
/// `ROUND_TRIP_POINTS_MAX` looked at).
const ROUND_TRIP_SHARE: f64 = 0.25;
const ROUND_TRIP_POINTS: usize = 200;
const ROUND_TRIP_POINTS_MAX: usize = 20_000;

/// What the twin needs to search shadowlab's map where the student's findBlocker searched.
pub struct TwinInputs<'a> {
    pub map: &'a DepthImage,
    pub view: &'a ShadowViewGpu,
    pub normals: &'a [Option<Vec3>],
}

/// Where the lookups never meet the blockers, or the light puts the objects elsewhere, what a
/// function reads says nothing of the function.
pub(super) fn lookups_broken(earlier: &[super::Finding]) -> bool {
    super::has(earlier, ids::SHADOWS_MISSING) || super::has(earlier, ids::LIGHT_MODEL_MATRIX)
}

pub(crate) fn texel_uv(j: &Judged<'_>) -> f32 {
    1.0 / j.e.light.map_size.max(1) as f32
}

/// The search radius was NaN, infinite, zero, or swings with the receiver's depth.
pub const SEARCH_RADIUS_WRONG: FindingKind =
    FindingKind { id: ids::SEARCH_RADIUS_WRONG, lesson: "pcss", step: 2, judge: search_radius_wrong };

fn search_radius_wrong(j: &Judged<'_>, earlier: &[super::Finding], lang: Lang) -> Option<Found> {
    if !j.pcss() || lookups_broken(earlier) {
        return None;
    }
    let taps = &j.e.taps.taps;
    let searched: Vec<f32> = j
        .shaded
        .iter()
        .filter(|&&i| j.e.student.ran(i, FIND_BLOCKER) && taps[i][FIND_BLOCKER].reads >= 2.0)
        .map(|&i| taps[i][FIND_BLOCKER].max_offset_uv)
        .collect();
    if searched.len() < 100 {
        return None;
    }
    let n = searched.len() as f64;
    let texel = texel_uv(j);
    let not_finite = searched.iter().filter(|r| !r.is_finite()).count() as f64 / n;
    let collapsed = searched.iter().filter(|r| r.is_finite() && **r < 0.5 * texel).count() as f64 / n;
    let mut finite: Vec<f32> =
        searched.iter().copied().filter(|r| r.is_finite() && *r >= 0.5 * texel).collect();
    finite.sort_by(f32::total_cmp);
    let percentile =
        |p: f64| finite.get(((finite.len() as f64 - 1.0) * p) as usize).copied().unwrap_or(f32::NAN);
    let (low, mid, high) = (percentile(0.1), percentile(0.5), percentile(0.9));
    let spread = if finite.is_empty() { 1.0 } else { high / low.max(1e-9) };
    let broken =
        not_finite > NOT_FINITE_SHARE || (collapsed > COLLAPSED_SHARE && collapsed < COLLAPSED_EVERYWHERE);
    if !broken && spread <= RADIUS_SPREAD {
        return None;
    }
    let figures = BTreeMap::from([
        ("not_finite_share", not_finite),
        ("under_half_a_texel_share", collapsed),
        ("radius_texels_p10", f64::from(low / texel)),
        ("radius_texels_median", f64::from(mid / texel)),
        ("radius_texels_p90", f64::from(high / texel)),
    ]);
    let explanation = if broken {
        fill(
            lang,
            "findBlocker's search radius is wrong: it is not a finite number at {:.1}% of the receivers and under half a texel at {:.1}%. On an orthographic map similar triangles make it nearly the same for every receiver, w_light (z_r - z_near) / z_r: a near plane in world units mixed with a depth in [0, 1], or a clip-space depth taken for a distance, makes it negative, zero or infinite, and the search reads anywhere.",
            &[&(100.0 * not_finite), &(100.0 * collapsed)],
        )
    } else {
        fill(
            lang,
            "findBlocker's search radius swings with the receiver's depth, from {:.1} to {:.1} texels over this scene (10th to 90th percentile), where similar triangles on an orthographic map keep it nearly the same, w_light (z_r - z_near) / z_r with z_near the near plane's depth, 0. A near plane in world units mixed with a depth in [0, 1], or a perspective formula (near / z), does this.",
            &[&(low / texel), &(high / texel)],
        )
    };
    let mut figures = figures;
    let mut explanation = explanation;
    if let Some((line, code)) = super::formula_lines::receiver_division(j.e.fragment_source, "findBlocker") {
        figures.insert("line", line as f64);
        explanation += " ";
        explanation += &fill(lang, "Line {} divides by the receiver's depth: `{}`.", &[&line, &code]);
    }
    // A radius that swings leaves the picture right where the penumbrae still follow similar
    // triangles: it does not show today.
    let shows = broken || j.e.light.width.is_some_and(|w| w.law_holds == Some(false));
    let explanation = if shows {
        explanation
    } else {
        format!(
            "{} {explanation}",
            crate::i18n::tr(
                lang,
                "Hidden today by this scene: the search still reaches the blockers that shape each penumbra, and the penumbrae follow similar triangles; another scene or light shows it:"
            )
        )
    };
    Some(Found { latent: !shows, ..Found::new(Some("findBlocker"), figures, explanation) })
}

/// PCSS's filter reads at a uv that is not a number: its radius, the penumbra estimate, is
/// infinite or NaN (a blocker depth of 0, returned where no blocker was found, divided by).
pub const FILTER_RADIUS_NOT_FINITE: FindingKind = FindingKind {
    id: ids::FILTER_RADIUS_NOT_FINITE,
    lesson: "pcss",
    step: 3,
    judge: filter_radius_not_finite,
};

fn filter_radius_not_finite(j: &Judged<'_>, earlier: &[super::Finding], lang: Lang) -> Option<Found> {
    if !j.pcss() || lookups_broken(earlier) {
        return None;
    }
    let taps = &j.e.taps.taps;
    let filtered: Vec<f32> = j
        .shaded
        .iter()
        .filter(|&&i| taps[i][PCF].reads >= 1.0)
        .map(|&i| taps[i][PCF].max_offset_uv)
        .collect();
    if filtered.len() < 100 {
        return None;
    }
    let share = filtered.iter().filter(|r| !r.is_finite()).count() as f64 / filtered.len() as f64;
    (share > NOT_FINITE_SHARE).then(|| {
        Found::new(
            Some("PCSS"),
            BTreeMap::from([("not_finite_share", share), ("pixels", filtered.len() as f64)]),
            fill(
                lang,
                "PCSS filters over a radius that is not a number at {:.1}% of the pixels it filters: the penumbra estimate (z_r - z_blocker) / z_blocker is infinite where the blocker depth is 0, and the taps read texels nobody chose. Where findBlocker finds no blocker, return a value PCSS recognises (-1, or 1 with a test) and return full light before estimating.",
                &[&(100.0 * share)],
            ),
        )
    })
}

/// A search found reading anywhere (not finite, or on the receiver's own texel) leaves nothing
/// to judge downstream; one whose radius only swings still searches a disk.
pub(crate) fn search_broken(earlier: &[super::Finding]) -> bool {
    earlier.iter().any(|f| {
        f.id == ids::SEARCH_RADIUS_WRONG
            && (f.figures.get("not_finite_share").is_some_and(|s| *s > NOT_FINITE_SHARE)
                || f.figures
                    .get("under_half_a_texel_share")
                    .is_some_and(|s| *s > COLLAPSED_SHARE && *s < COLLAPSED_EVERYWHERE)
                || f.figures.contains_key("reads_at_receiver_share"))
    })
}

/// The twin's search at one pixel.
pub(crate) struct TwinSearch {
    /// The share of the disk that blocks, and the blockers' average depth (NDC).
    pub blocked: f32,
    pub z_blocker: f32,
    /// The receiver's depth, and how far its own plane's depth moves across the disk.
    pub z_receiver: f32,
    pub receiver_spread: f32,
}

/// The twin's search at one pixel, over a disk of `radius_uv` around the receiver.
pub(crate) fn twin_search(twin: &TwinInputs<'_>, p: Vec3, n: Vec3, radius_uv: f32) -> Option<TwinSearch> {
    let s = project_to_light(twin.view, p);
    let size = twin.map.size as i32;
    let texel = 1.0 / size as f32;
    let gradient = receiver_plane_gradient(twin.view, p, n, s);
    // A texel blocks where it lies in front of the receiver's own plane by more than the plane
    // moves over one and a half texels.
    let tolerance = (gradient.length() * 1.5 * texel).max(1e-4);
    let radius_texels = radius_uv * size as f32;
    let step = (radius_texels / 24.0).max(1.0);
    let centre = Vec2::new(s.x, s.y) * size as f32;
    let (mut count, mut blocked, mut sum) = (0u32, 0u32, 0.0f32);
    let steps = (radius_texels / step).ceil() as i32;
    for dy in -steps..=steps {
        for dx in -steps..=steps {
            let offset = Vec2::new(dx as f32, dy as f32) * step;
            if offset.length() > radius_texels {
                continue;
            }
            let t = (centre + offset).floor();
            let (x, y) = (t.x as i32, t.y as i32);
            if x < 0 || y < 0 || x >= size || y >= size {
                continue;
            }
            let depth = twin.map.depth_ndc[(y * size + x) as usize];
            let uv = (t + Vec2::splat(0.5)) * texel;
            let plane = s.z + gradient.dot(uv - Vec2::new(s.x, s.y));
            count += 1;
            if depth < plane - tolerance {
                blocked += 1;
                sum += depth;
            }
        }
    }
    (count > 0).then(|| TwinSearch {
        blocked: blocked as f32 / count as f32,
        z_blocker: if blocked > 0 { sum / blocked as f32 } else { f32::NAN },
        z_receiver: s.z,
        receiver_spread: gradient.length() * radius_uv,
    })
}

/// The twin's search where the student's findBlocker searched, at up to `TWIN_PIXELS` pixels
/// (evenly spread over those it ran at, facing the light, inside the map): (pixel, search).
pub(crate) fn twin_searches(j: &Judged<'_>) -> Vec<(usize, TwinSearch)> {
    let Some(twin) = j.e.twin else { return Vec::new() };
    let taps = &j.e.taps.taps;
    let texel = texel_uv(j);
    let candidates: Vec<usize> = j
        .shaded
        .iter()
        .copied()
        .filter(|&i| {
            let t = taps[i][FIND_BLOCKER];
            j.e.student.ran(i, FIND_BLOCKER)
                && t.reads >= 2.0
                && t.max_offset_uv.is_finite()
                && t.max_offset_uv >= texel
                && j.faces_light(i)
                && j.sound(i)
                && j.receivers[i].is_some_and(|r| r.inside())
        })
        .collect();
    let step = candidates.len().div_ceil(TWIN_PIXELS).max(1);
    candidates
        .iter()
        .step_by(step)
        .filter_map(|&i| {
            let (p, n) = (j.e.positions[i]?, twin.normals.get(i).copied().flatten()?);
            twin_search(twin, p, n, taps[i][FIND_BLOCKER].max_offset_uv).map(|s| (i, s))
        })
        .collect()
}

/// The lossless map, read back and unpacked, does not hold the depths the light pass was given:
/// `pack` loses them (a carry not taken out, another base in each channel). Where a surface is
/// fully lit, the texel its lookup reads holds its own depth; read with a 256-step unpack or a
/// 255-step one (whichever the student's pack uses), a sound pack gives it back to within the
/// depth a texel spans.
pub const DEPTH_ROUND_TRIP_WRONG: FindingKind = FindingKind {
    id: ids::DEPTH_ROUND_TRIP_WRONG,
    lesson: "hard-shadows",
    step: 3,
    judge: depth_round_trip_wrong,
};

fn depth_round_trip_wrong(j: &Judged<'_>, earlier: &[super::Finding], lang: Lang) -> Option<Found> {
    if lookups_broken(earlier) {
        return None;
    }
    let map = j.e.lossless_map?;
    let unpack =
        |c: [f32; 4], base: f32| c[0] + c[1] / base + c[2] / (base * base) + c[3] / (base * base * base);
    let lit: Vec<usize> = j
        .finite
        .iter()
        .map(|&(i, _)| i)
        .filter(|&i| {
            j.truth(i) >= super::LIT && j.faces_light(i) && j.receivers[i].is_some_and(|r| r.inside())
        })
        .collect();
    let step = lit.len().div_ceil(ROUND_TRIP_POINTS_MAX).max(1);
    // (point, its texel unpacked in base 256 and in base 255)
    let read: Vec<(usize, [f32; 2])> = lit
        .iter()
        .step_by(step)
        .filter_map(|&i| {
            let c = map.at(j.receivers[i]?.uv);
            Some((i, [unpack(c, 256.0), unpack(c, 255.0)]))
        })
        .collect();
    let errors: Vec<f32> = read
        .iter()
        .filter_map(|&(i, [d256, d255])| {
            let depth = j.receivers[i]?.depth;
            Some((d256 - depth).abs().min((d255 - depth).abs()))
        })
        .filter(|e| e.is_finite())
        .collect();
    if errors.len() < ROUND_TRIP_POINTS {
        return None;
    }
    let off = errors.iter().filter(|e| **e > ROUND_TRIP_ERROR).count() as f64 / errors.len() as f64;
    if off > ROUND_TRIP_SHARE && holds_distance_to_light(j, &read) {
        return None;
    }
    let mut sizes = errors.clone();
    sizes.sort_by(f32::total_cmp);
    let (typical, large) = (sizes[sizes.len() / 2], sizes[sizes.len() * 9 / 10]);
    (off > ROUND_TRIP_SHARE).then(|| {
        Found::new(
            Some("pack"),
            BTreeMap::from([
                ("off_share", off),
                ("depth_error_median", f64::from(typical)),
                ("depth_error_p90", f64::from(large)),
                ("points", errors.len() as f64),
            ]),
            fill(
                lang,
                "Depth does not come back from the map as it went in: even with every bit kept, the depth unpacked where a lit surface looks itself up differs from its own by {:.4} (typical) to {:.4} in [0, 1] depth, at {:.0}% of them. Your pack (shadowFragment.glsl) must take each channel's carry out of the one before (rgbaDepth -= rgbaDepth.gbaa * bitMask), in the same base as your unpack.",
                &[&typical, &large, &(100.0 * off)],
            ),
        )
    })
}

/// A lamp's map may hold each surface's distance to the light, scaled (`length(p - uLightPos) /
/// far`, a cube map's habit), instead of its projected depth: then the unpacked texels are
/// a + b * distance, with b > 0, to within the round trip's error at all but the usual share.
/// An orthographic light has no point to measure from: false.
fn holds_distance_to_light(j: &Judged<'_>, read: &[(usize, [f32; 2])]) -> bool {
    // The eye: what the light's projection sends to x = y = w = 0.
    let eye = j.e.light.clip_from_world.inverse() * glam::Vec4::Z;
    if eye.w.abs() < 1e-9 || !eye.is_finite() {
        return false;
    }
    let eye = eye.truncate() / eye.w;
    (0..2).any(|base| {
        let pairs: Vec<(f64, f64)> = read
            .iter()
            .filter_map(|&(i, d)| {
                let p = j.e.positions.get(i).copied().flatten()?;
                Some((f64::from(p.distance(eye)), f64::from(d[base])))
            })
            .filter(|(x, y)| x.is_finite() && y.is_finite())
            .collect();
        let n = pairs.len() as f64;
        if pairs.len() < ROUND_TRIP_POINTS {
            return false;
        }
        let (mx, my) =
            (pairs.iter().map(|p| p.0).sum::<f64>() / n, pairs.iter().map(|p| p.1).sum::<f64>() / n);
        let sxx: f64 = pairs.iter().map(|p| (p.0 - mx).powi(2)).sum();
        let sxy: f64 = pairs.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
        if sxx <= 0.0 {
            return false;
        }
        let b = sxy / sxx;
        let a = my - b * mx;
        let off = pairs.iter().filter(|(x, y)| (y - (a + b * x)).abs() > f64::from(ROUND_TRIP_ERROR)).count();
        b > 0.0 && (off as f64 / n) <= ROUND_TRIP_SHARE
    })
}

/// The filter's taps do not lie around the receiver: their mean is off it, or they lie on a line
/// (offsets that accumulate: a random walk).
pub const SAMPLES_NOT_AROUND_RECEIVER: FindingKind = FindingKind {
    id: ids::SAMPLES_NOT_AROUND_RECEIVER,
    lesson: "pcf",
    step: 3,
    judge: samples_not_around_receiver,
};

fn samples_not_around_receiver(j: &Judged<'_>, earlier: &[super::Finding], lang: Lang) -> Option<Found> {
    if lookups_broken(earlier) {
        return None;
    }
    let taps = &j.e.taps.taps;
    let texel = texel_uv(j);
    let (function, name) = if j.pcss() && !j.shaded.iter().any(|&i| taps[i][PCF].reads > 0.0) {
        (PCSS, "PCSS")
    } else {
        (PCF, "PCF")
    };
    let filtered: Vec<_> = j
        .shaded
        .iter()
        .map(|&i| taps[i][function])
        .filter(|t| t.reads >= 8.0 && t.rms_offset_uv.is_finite() && t.rms_offset_uv > texel)
        .collect();
    if filtered.len() < 100 {
        return None;
    }
    let off = median(filtered.iter().map(|t| t.mean_offset_uv / t.rms_offset_uv).collect())?;
    let stretch = (filtered.iter().map(|t| t.stretch).sum::<Vec2>() / filtered.len() as f32).length();
    (off > OFF_CENTRE || stretch > STRETCH).then(|| {
        Found::new(
            Some(name),
            BTreeMap::from([
                ("mean_offset_over_rms_median", f64::from(off)),
                ("common_stretch", f64::from(stretch)),
                ("pixels", filtered.len() as f64),
            ]),
            fill(
                lang,
                "{}'s taps are not spread over a disk around the receiver: their mean lies {:.0}% of their spread away from it, and they stretch along one line, the same at every pixel, {:.0}% of the way from a disk to a line. Offsets added to the previous tap's position walk away from the receiver or back and forth along a line, and a fixed seed turns every pixel's pattern the same way (the template's 20 samples in 10 rings lie on one line): offset the receiver's own uv by each sample, with a seed that changes from pixel to pixel.",
                &[&name, &(100.0 * off), &(100.0 * stretch)],
            ),
        )
    })
}

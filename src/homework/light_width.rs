//! The light width a student's shader behaves as, measured. The check scene's slabs float at
//! several heights over the floor; the penumbra of each one's shadow is fitted, and the widths
//! against similar triangles, w = w_light (d_r - d_b) / d_b [Fernando-2005], give the light
//! the shader behaves as, and whether it follows the law at all (contact hardening).
//!
//! A penumbra's width is fitted in the plane across the light, where a light's disk is round:
//! the student's visibility on the floor around the shadow against the shadow a disk of diameter
//! w makes of the slab's outline (the fraction of the disk the outline covers), least squares
//! over w. The ground truth's own light is such a disk, so the width found is the one whose
//! ground truth looks most like the student's shadow.

use crate::reference::disk_point;
use crate::scene::{Light, Scene};
use glam::{Vec2, Vec3};
use serde::Serialize;

/// Points a disk is sampled with, spread evenly over its area.
const DISK_SAMPLES: usize = 48;
/// At most this many floor pixels per slab enter the fit (evenly spaced).
const PIXELS_PER_SLAB: usize = 3000;
/// Widths tried before refining, from 0 to the largest a slab's surroundings can show.
const GRID_STEPS: usize = 40;
/// A slab is a probe of the light where its bottom is this far above the floor, world units.
const MIN_HEIGHT_WORLD: f32 = 1.0;
/// A fit is believed where, in every band of the disk model's visibility (tenths), the student's
/// mean differs from the model's by less than this: what is left is noise (a filter of a few
/// random taps), not a shadow of another shape.
const FIT_BIAS: f32 = 0.1;
/// `law_holds`: the widths follow similar triangles, combined in quadrature with a floor (what a
/// hard edge measures at this resolution), this well (R^2 of the widths)...
const LAW_R2: f32 = 0.9;
/// ...and the light's part of the widest penumbra is more than the resolution. Where it is not and
/// the floor is within this many resolutions, the light is too narrow to measure with this map
/// (nothing is said of the law); a floor above that is a filter of one width (no contact
/// hardening).
const FLOOR_OF_RESOLUTION: f32 = 2.0;

/// One slab's shadow: where it floats and the penumbra the student's shader gives it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SlabShadow {
    /// The object's name in the scene.
    pub name: String,
    /// Height of the slab's middle over the floor, world units.
    pub height_world: f32,
    /// The gap between the slab and the floor along the light, and the slab's distance from the
    /// light along its axis, world units; `ratio` = gap / distance, the similar triangles' factor.
    pub gap_world: f32,
    pub blocker_distance_world: f32,
    pub ratio: f32,
    /// The penumbra's fitted width across the light, world units (None: too few floor pixels
    /// around the shadow, or a visibility the disk's shadow does not explain).
    pub width_world: Option<f32>,
    /// Root mean square of the student's visibility against the fitted shadow, and the largest
    /// mean difference over a band of it (the fit's systematic part).
    pub fit_rms: f32,
    pub fit_bias: f32,
    /// The student's mean visibility in the shadow's core (where no point of a light of the
    /// fitted width reaches), None where the core has too few pixels: near 0 where the shadow is
    /// there, near 1 where a bias has taken it away.
    pub core_visibility: Option<f32>,
    pub pixels: usize,
}

/// What the slabs say of the light a shader behaves as.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LightWidthFit {
    pub slabs: Vec<SlabShadow>,
    /// Least squares of w = w_light * ratio over the slabs with a width, world units.
    pub implied_light_width_world: Option<f32>,
    /// R^2 of that fit (through the origin).
    pub r_squared: Option<f32>,
    /// The widest penumbra too narrow to tell from a hard edge here (a pixel's or a texel's
    /// footprint, whichever is larger), world units.
    pub resolution_world: f32,
    /// The widths grow with the gap as similar triangles say (None: too few widths to tell).
    pub law_holds: Option<bool>,
    /// Where the slabs cast shadows but fewer than two penumbrae are wider than the resolution:
    /// the light is narrower than this, world units (the resolution over the largest ratio, the
    /// widest penumbra such a light would cast), and no narrower width can be told with this
    /// map. `implied_light_width_world` is then below what can be measured.
    pub narrower_than_world: Option<f32>,
}

impl LightWidthFit {
    /// The light width to tell a student: a number where it can be measured, and where the
    /// widths follow similar triangles (where they do not, no light casts them: a fit through
    /// them is no light's width).
    pub fn measured_width_world(&self) -> Option<f32> {
        self.implied_light_width_world
            .filter(|_| self.narrower_than_world.is_none() && self.law_holds != Some(false))
    }
}

/// A probe of the light width: a box floating over the floor (the built-in cube, not rotated).
struct Slab {
    name: String,
    corners: [Vec3; 8],
    centre: Vec3,
}

fn slabs(scene: &Scene, t_s: f32) -> Vec<Slab> {
    scene
        .objects
        .iter()
        .filter(|o| o.mesh.name == "cube" && o.rotate_deg == Vec3::ZERO && o.is_still())
        .filter_map(|o| {
            let (lo, hi) = o.world_bounds(t_s);
            (lo.y > MIN_HEIGHT_WORLD).then(|| Slab {
                name: o.name.clone(),
                corners: std::array::from_fn(|k| {
                    Vec3::new(
                        if k & 1 == 0 { lo.x } else { hi.x },
                        if k & 2 == 0 { lo.y } else { hi.y },
                        if k & 4 == 0 { lo.z } else { hi.z },
                    )
                }),
                centre: 0.5 * (lo + hi),
            })
        })
        .collect()
}

/// A convex polygon's corners, counter-clockwise (Andrew's monotone chain).
fn convex_hull(mut points: Vec<Vec2>) -> Vec<Vec2> {
    points.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    let cross = |o: Vec2, a: Vec2, b: Vec2| (a - o).perp_dot(b - o);
    let mut hull: Vec<Vec2> = Vec::new();
    for pass in 0..2 {
        let start = hull.len();
        let ordered: Box<dyn Iterator<Item = &Vec2>> =
            if pass == 0 { Box::new(points.iter()) } else { Box::new(points.iter().rev()) };
        for &p in ordered {
            while hull.len() >= start + 2 && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0 {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    hull
}

fn inside(polygon: &[Vec2], p: Vec2) -> bool {
    (0..polygon.len())
        .all(|i| (polygon[(i + 1) % polygon.len()] - polygon[i]).perp_dot(p - polygon[i]) >= 0.0)
}

/// How deep inside a convex polygon `p` lies (0 outside).
fn depth_inside(polygon: &[Vec2], p: Vec2) -> f32 {
    if !inside(polygon, p) {
        return 0.0;
    }
    (0..polygon.len())
        .map(|i| {
            let (a, b) = (polygon[i], polygon[(i + 1) % polygon.len()]);
            (b - a).perp_dot(p - a) / (b - a).length().max(1e-12)
        })
        .fold(f32::INFINITY, f32::min)
}

/// Distance from `p` to a convex polygon (0 inside).
fn distance_to(polygon: &[Vec2], p: Vec2) -> f32 {
    if inside(polygon, p) {
        return 0.0;
    }
    (0..polygon.len())
        .map(|i| {
            let (a, b) = (polygon[i], polygon[(i + 1) % polygon.len()]);
            let t = ((p - a).dot(b - a) / (b - a).length_squared().max(1e-12)).clamp(0.0, 1.0);
            p.distance(a + (b - a) * t)
        })
        .fold(f32::INFINITY, f32::min)
}

/// The visibility a disk of diameter `width` around `q` gives past `outline`: the share of the
/// disk the outline does not cover.
fn disk_visibility(outline: &[Vec2], q: Vec2, width: f32, disk: &[Vec2]) -> f32 {
    if width <= 0.0 {
        return if inside(outline, q) { 0.0 } else { 1.0 };
    }
    let covered = disk.iter().filter(|d| inside(outline, q + **d * (0.5 * width))).count();
    1.0 - covered as f32 / disk.len() as f32
}

/// Sum of squared differences between the visibilities and the disk's shadow at `width`.
fn misfit(outline: &[Vec2], points: &[(Vec2, f32)], width: f32, disk: &[Vec2]) -> f32 {
    points.iter().map(|&(q, v)| (v - disk_visibility(outline, q, width, disk)).powi(2)).sum()
}

/// The width in 0..=`max` that fits best: a grid (finer near 0), then golden-section search
/// between the best point's neighbours.
fn best_width(outline: &[Vec2], points: &[(Vec2, f32)], max: f32, disk: &[Vec2]) -> (f32, f32) {
    let at = |j: usize| max * (j as f32 / (GRID_STEPS - 1) as f32).powi(2);
    let costs: Vec<f32> = (0..GRID_STEPS).map(|j| misfit(outline, points, at(j), disk)).collect();
    let best = (0..GRID_STEPS).min_by(|&a, &b| costs[a].total_cmp(&costs[b])).unwrap_or(0);
    let (mut lo, mut hi) = (at(best.saturating_sub(1)), at((best + 1).min(GRID_STEPS - 1)));
    let phi = 0.618_034_f32;
    for _ in 0..12 {
        let (a, b) = (hi - phi * (hi - lo), lo + phi * (hi - lo));
        if misfit(outline, points, a, disk) < misfit(outline, points, b, disk) {
            hi = b;
        } else {
            lo = a;
        }
    }
    let width = 0.5 * (lo + hi);
    let (width, cost) = [(width, misfit(outline, points, width, disk)), (at(best), costs[best])]
        .into_iter()
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap_or((width, f32::INFINITY));
    (width, (cost / points.len().max(1) as f32).sqrt())
}

/// The largest mean difference between the student's visibility and the disk model's over a
/// band of the model's value (tenths, from 0.1 to 0.9: at the ends noise that cannot go past 0
/// or 1 shifts a band's mean; bands of 30 points or more).
fn systematic_misfit(outline: &[Vec2], points: &[(Vec2, f32)], width: f32, disk: &[Vec2]) -> f32 {
    let mut bands = [(0.0f32, 0u32); 10];
    for &(q, v) in points {
        let model = disk_visibility(outline, q, width, disk);
        let band = &mut bands[((model * 10.0) as usize).min(9)];
        band.0 += v - model;
        band.1 += 1;
    }
    bands[1..9].iter().filter(|b| b.1 >= 30).map(|b| (b.0 / b.1 as f32).abs()).fold(0.0, f32::max)
}

/// The per-pixel inputs of a fit, all of one view's size, rows top first.
pub struct WidthInputs<'a> {
    pub width: u32,
    /// The student's visibility (None: no surface, or no visibility returned).
    pub visibility: &'a dyn Fn(usize) -> Option<f32>,
    /// World position and shading normal of the surface under each pixel.
    pub positions: &'a [Option<Vec3>],
    pub normals: &'a [Option<Vec3>],
}

/// Two unit vectors across the light's direction.
fn across(direction: Vec3) -> (Vec3, Vec3) {
    let e1 = direction.any_orthonormal_vector();
    (e1, direction.cross(e1))
}

/// Fit the penumbra of every slab of `scene` on the student's visibility, and the light width
/// the widths say, for `light` (the light the student's map was drawn with; its position is
/// where the homework's formula measures distances from).
pub fn fit(scene: &Scene, light: &Light, t_s: f32, inputs: &WidthInputs<'_>) -> LightWidthFit {
    let direction = light.direction_at(t_s);
    let origin = light.position_at(t_s);
    let (e1, e2) = across(direction);
    let onto = |p: Vec3| Vec2::new(p.dot(e1), p.dot(e2));
    let disk: Vec<Vec2> = (0..DISK_SAMPLES).map(|k| disk_point(k, DISK_SAMPLES)).collect();
    let probes = slabs(scene, t_s);
    let outlines: Vec<Vec<Vec2>> =
        probes.iter().map(|s| convex_hull(s.corners.iter().map(|&c| onto(c)).collect())).collect();
    // Floor pixels (facing up at height 0), in the plane across the light.
    let floor: Vec<(usize, Vec2)> = (0..inputs.positions.len())
        .filter_map(|i| {
            let (p, n) = (inputs.positions[i]?, inputs.normals[i]?);
            (p.y.abs() < 0.05 && n.normalize_or_zero().y > 0.95).then(|| (i, onto(p)))
        })
        .collect();
    let resolution_world = resolution(light, inputs, direction);
    let mut shadows = Vec::new();
    for (k, slab) in probes.iter().enumerate() {
        let outline = &outlines[k];
        let (lo, hi) = outline
            .iter()
            .fold((Vec2::splat(f32::INFINITY), Vec2::splat(f32::NEG_INFINITY)), |(lo, hi), p| {
                (lo.min(*p), hi.max(*p))
            });
        // Around the shadow as far as half its smaller side, at least 2 world units: wide
        // penumbrae of the high slabs stay inside, the neighbours' shadows outside.
        let margin = (0.5 * (hi - lo).min_element()).max(2.0);
        let others = |q: Vec2| outlines.iter().enumerate().any(|(j, o)| j != k && distance_to(o, q) < margin);
        let near: Vec<(Vec2, f32)> = floor
            .iter()
            .filter(|(_, q)| distance_to(outline, *q) < margin && !others(*q))
            .filter_map(|&(i, q)| {
                (inputs.visibility)(i).filter(|v| v.is_finite()).map(|v| (q, v.clamp(0.0, 1.0)))
            })
            .collect();
        let step = near.len().div_ceil(PIXELS_PER_SLAB).max(1);
        let points: Vec<(Vec2, f32)> = near.iter().step_by(step).copied().collect();
        let gap_world = slab.centre.y / (-direction.y).max(1e-3);
        let blocker_distance_world = (slab.centre - origin).dot(direction);
        let ratio = gap_world / blocker_distance_world.max(1e-3);
        let (width, rms) = if points.len() >= 50 {
            best_width(outline, &points, 2.0 * margin, &disk)
        } else {
            (0.0, f32::INFINITY)
        };
        let bias =
            if rms.is_finite() { systematic_misfit(outline, &points, width, &disk) } else { f32::INFINITY };
        let fitted = bias < FIT_BIAS;
        // The core: deeper inside the outline than half the penumbra (a light of the fitted
        // width cannot reach it), and than a little margin.
        let core_depth = if fitted { 0.5 * width + 0.3 } else { 0.75 };
        let core: Vec<f32> =
            near.iter().filter(|(q, _)| depth_inside(outline, *q) > core_depth).map(|(_, v)| *v).collect();
        let core_visibility = (core.len() >= 20).then(|| core.iter().sum::<f32>() / core.len() as f32);
        shadows.push(SlabShadow {
            name: slab.name.clone(),
            height_world: slab.centre.y,
            gap_world,
            blocker_distance_world,
            ratio,
            width_world: fitted.then_some(width),
            fit_rms: if rms.is_finite() { rms } else { -1.0 },
            fit_bias: if bias.is_finite() { bias } else { -1.0 },
            core_visibility,
            pixels: near.len(),
        });
    }
    law(shadows, resolution_world)
}

/// A penumbra narrower than a pixel's footprint on the floor or a texel of the map cannot be told
/// from a hard edge: the larger of the two, world units (median over the floor's pixels).
fn resolution(light: &Light, inputs: &WidthInputs<'_>, _direction: Vec3) -> f32 {
    let w = inputs.width as usize;
    let mut steps: Vec<f32> = (0..inputs.positions.len())
        .step_by(97)
        .filter_map(|i| {
            let (a, b) = (inputs.positions[i]?, inputs.positions.get(i + 1).copied().flatten()?);
            (i % w + 1 < w && a.y.abs() < 0.05 && b.y.abs() < 0.05).then(|| a.distance(b))
        })
        .collect();
    steps.sort_by(f32::total_cmp);
    let pixel = steps.get(steps.len() / 2).copied().unwrap_or(0.0);
    let texel = light.frustum_width_world() / light.shadow_map_size as f32;
    1.5 * pixel.max(texel)
}

/// w^2 = a g^2 + b over (g, w) by least squares, with b >= 0 (the floor's square): (a, b). None
/// with fewer than two points or no spread in g.
fn quadrature_fit(measured: &[(f32, f32)]) -> Option<(f32, f32)> {
    let n = measured.len() as f32;
    if measured.len() < 2 {
        return None;
    }
    let (mx, my) = measured.iter().fold((0.0, 0.0), |(x, y), (g, w)| (x + g * g / n, y + w * w / n));
    let (sxy, sxx) = measured.iter().fold((0.0, 0.0), |(xy, xx), (g, w)| {
        let dx = g * g - mx;
        (xy + dx * (w * w - my), xx + dx * dx)
    });
    if sxx <= 0.0 {
        return None;
    }
    let a = sxy / sxx;
    let b = my - a * mx;
    if b >= 0.0 {
        return Some((a, b));
    }
    // A floor below 0 says nothing: through the origin instead.
    let (gw, gg) = measured.iter().fold((0.0, 0.0), |(gw, gg), (g, w)| (gw + g * g * w * w, gg + g.powi(4)));
    (gg > 0.0).then(|| (gw / gg, 0.0))
}

/// A light width and a floor fitted to the widths, and how well they explain them.
#[derive(Clone, Copy, Debug)]
struct FloorFit {
    light: f32,
    floor: f32,
    r_squared: f32,
}

/// R^2 of `predicted` widths against the measured ones (0 where the widths do not vary).
fn r_squared_of(measured: &[(f32, f32)], predicted: impl Fn(f32) -> f32) -> f32 {
    let mean = measured.iter().map(|(_, w)| w).sum::<f32>() / measured.len().max(1) as f32;
    let spread: f32 = measured.iter().map(|(_, w)| (w - mean).powi(2)).sum();
    let residual: f32 = measured.iter().map(|(g, w)| (w - predicted(*g)).powi(2)).sum();
    if spread > 0.0 { 1.0 - residual / spread } else { 0.0 }
}

/// The light and the floor under the widths, two ways, the better kept: the light's penumbra and
/// a blur of the resolution combined in quadrature (w^2 = L^2 g^2 + F^2), or a filter that never
/// goes under a floor (w = max(L g, F): PCSS with a least filter radius, as many solutions write).
fn floor_fit(measured: &[(f32, f32)]) -> Option<FloorFit> {
    let quadrature = quadrature_fit(measured).map(|(a, b)| {
        let (light, floor) = (a.max(0.0).sqrt(), b.max(0.0).sqrt());
        let r_squared = r_squared_of(measured, |g| (a * g * g + b).max(0.0).sqrt());
        FloorFit { light, floor, r_squared }
    });
    // The floor: the least width; the light: through the origin over the widths clearly above it.
    let least = measured.iter().map(|(_, w)| *w).fold(f32::INFINITY, f32::min);
    let above: Vec<&(f32, f32)> = measured.iter().filter(|(_, w)| *w > 1.2 * least).collect();
    let (gw, gg) = above.iter().fold((0.0, 0.0), |(gw, gg), (g, w)| (gw + g * w, gg + g * g));
    let clamped = (gg > 0.0).then(|| {
        let light = gw / gg;
        let r_squared = r_squared_of(measured, |g| (light * g).max(least));
        FloorFit { light, floor: least, r_squared }
    });
    match (quadrature, clamped) {
        (Some(q), Some(c)) => Some(if c.r_squared > q.r_squared { c } else { q }),
        (q, c) => q.or(c),
    }
}

/// The light width the slabs' penumbrae say, and whether they follow similar triangles: each
/// width is the light's penumbra (w_light * ratio) and the resolution's floor combined in
/// quadrature, so that a narrow light's penumbrae, held up by the floor, are not read as widths
/// that do not grow.
fn law(slabs: Vec<SlabShadow>, resolution_world: f32) -> LightWidthFit {
    let measured: Vec<(f32, f32)> =
        slabs.iter().filter_map(|s| s.width_world.map(|w| (s.ratio, w))).collect();
    let fit = floor_fit(&measured);
    let implied = fit.map(|f| f.light);
    let r_squared = fit.map(|f| f.r_squared);
    // Widths under the resolution say nothing of the law: at least two must be over it. Shadows
    // that are there but not shaped as any light's (two or more) break it too.
    let resolved = measured.iter().filter(|(_, w)| *w > resolution_world).count();
    let misshapen = slabs
        .iter()
        .filter(|s| s.width_world.is_none() && s.core_visibility.is_some_and(|v| v < 0.5))
        .count();
    let widest_ratio = measured.iter().map(|(g, _)| *g).fold(0.0, f32::max);
    let light_part = implied.unwrap_or(0.0) * widest_ratio;
    let floor = fit.map_or(0.0, |f| f.floor);
    let resolution_bound = light_part <= resolution_world && floor <= FLOOR_OF_RESOLUTION * resolution_world;
    let law_holds = if misshapen >= 2 {
        Some(false)
    } else if resolved < 2 || resolution_bound {
        None
    } else {
        Some(r_squared.is_some_and(|r| r >= LAW_R2) && light_part > resolution_world)
    };
    // Shadows there, their penumbrae too narrow to tell the light from the floor: only a bound
    // can be said.
    let shadowed: Vec<&SlabShadow> = slabs
        .iter()
        .filter(|s| s.width_world.is_some() || s.core_visibility.is_some_and(|v| v < 0.5))
        .collect();
    let shadowed_ratio = shadowed.iter().map(|s| s.ratio).fold(0.0, f32::max);
    // (Not where the shadows are misshapen: those are no light's.)
    let unmeasured = law_holds.is_none() && (resolved < 2 || resolution_bound);
    let narrower_than_world = (unmeasured && shadowed_ratio > 0.0).then(|| resolution_world / shadowed_ratio);
    LightWidthFit {
        slabs,
        implied_light_width_world: implied,
        r_squared,
        resolution_world,
        law_holds,
        narrower_than_world,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_square_seen_through_a_disk_is_dark_inside_lit_outside_and_half_at_its_edge() {
        let square = [Vec2::new(0.0, 0.0), Vec2::new(4.0, 0.0), Vec2::new(4.0, 4.0), Vec2::new(0.0, 4.0)];
        let hull = convex_hull(vec![square[2], square[0], Vec2::new(2.0, 2.0), square[1], square[3]]);
        assert_eq!(hull.len(), 4, "{hull:?}");
        let disk: Vec<Vec2> = (0..256).map(|k| disk_point(k, 256)).collect();
        assert_eq!(disk_visibility(&hull, Vec2::new(2.0, 2.0), 1.0, &disk), 0.0);
        assert_eq!(disk_visibility(&hull, Vec2::new(6.0, 2.0), 1.0, &disk), 1.0);
        let edge = disk_visibility(&hull, Vec2::new(4.0, 2.0), 1.0, &disk);
        assert!((edge - 0.5).abs() < 0.03, "{edge}");
        assert!((distance_to(&hull, Vec2::new(7.0, 2.0)) - 3.0).abs() < 1e-6);
    }

    /// A visibility made by the disk model itself (with noise) is fitted back to its width.
    #[test]
    fn a_penumbra_is_fitted_back_to_its_width() {
        let square =
            convex_hull(vec![Vec2::ZERO, Vec2::new(6.0, 0.0), Vec2::new(6.0, 5.0), Vec2::new(0.0, 5.0)]);
        let disk: Vec<Vec2> = (0..DISK_SAMPLES).map(|k| disk_point(k, DISK_SAMPLES)).collect();
        let fine: Vec<Vec2> = (0..1024).map(|k| disk_point(k, 1024)).collect();
        for width in [0.4f32, 1.3, 3.0] {
            let mut seed = 7u32;
            let points: Vec<(Vec2, f32)> = (0..60)
                .flat_map(|y| (0..60).map(move |x| Vec2::new(-3.0 + 0.2 * x as f32, -3.0 + 0.18 * y as f32)))
                .map(|q| {
                    seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
                    let noise = (seed >> 8) as f32 / (1u32 << 24) as f32 - 0.5;
                    (q, (disk_visibility(&square, q, width, &fine) + 0.05 * noise).clamp(0.0, 1.0))
                })
                .collect();
            let (fitted, rms) = best_width(&square, &points, 6.0, &disk);
            assert!((fitted - width).abs() < 0.08 * width + 0.05, "{width}: {fitted}");
            assert!(rms < 0.05, "{rms}");
        }
    }

    fn slab(ratio: f32, width: Option<f32>) -> SlabShadow {
        SlabShadow {
            name: String::new(),
            height_world: 0.0,
            gap_world: 0.0,
            blocker_distance_world: 0.0,
            ratio,
            width_world: width,
            fit_rms: 0.0,
            fit_bias: 0.0,
            core_visibility: None,
            pixels: 100,
        }
    }

    #[test]
    fn similar_triangles_give_the_light_and_constant_or_shrinking_widths_break_the_law() {
        let ratios = [0.04, 0.11, 0.23, 0.45];
        let law_of =
            |widths: [f32; 4]| law(ratios.iter().zip(widths).map(|(&g, w)| slab(g, Some(w))).collect(), 0.2);
        let right = law_of(ratios.map(|g| 8.0 * g));
        assert!((right.implied_light_width_world.expect("a width") - 8.0).abs() < 1e-4);
        assert_eq!(right.law_holds, Some(true));
        assert_eq!(law_of([1.0, 1.0, 1.0, 1.0]).law_holds, Some(false));
        assert_eq!(law_of([2.0, 1.5, 1.0, 0.5]).law_holds, Some(false));
        // A constant filter with a little noise: its floor is far above the resolution.
        assert_eq!(law_of([2.0, 2.1, 1.9, 2.2]).law_holds, Some(false));
        // A light of 3 over a floor of 0.3 (one and a half resolutions): the widths combine in
        // quadrature, grow with the gap, and give the light back.
        let floored = law_of(ratios.map(|g| ((3.0 * g).powi(2) + 0.09f32).sqrt()));
        assert_eq!(floored.law_holds, Some(true), "{floored:?}");
        assert!((floored.implied_light_width_world.expect("a width") - 3.0).abs() < 0.05, "{floored:?}");
        assert_eq!(floored.narrower_than_world, None);
        // A least filter radius: w = max(3 g, 0.7), the light given back too.
        let least_filter = law_of(ratios.map(|g| (3.0 * g).max(0.7)));
        assert_eq!(least_filter.law_holds, Some(true), "{least_filter:?}");
        assert!(
            (least_filter.implied_light_width_world.expect("a width") - 3.0).abs() < 0.05,
            "{least_filter:?}"
        );
        // A light of 0.3 over that floor: its part of the widest penumbra is under the resolution,
        // the widths are the floor's; not a filter of one width but a light this map cannot
        // measure: nothing said of the law, and a bound on the light.
        let narrow = law_of(ratios.map(|g| ((0.3 * g).powi(2) + 0.09f32).sqrt()));
        assert_eq!(narrow.law_holds, None, "{narrow:?}");
        assert!(narrow.narrower_than_world.is_some_and(|b| (b - 0.2 / 0.45).abs() < 1e-6), "{narrow:?}");
        assert_eq!(right.narrower_than_world, None);
        assert_eq!(right.measured_width_world(), right.implied_light_width_world);
        // All under the resolution: nothing to tell of the law, and of the light only a bound:
        // the resolution (0.2) over the largest ratio (0.45), the widest penumbra it would cast.
        let unresolved = law_of([0.05, 0.08, 0.1, 0.15]);
        assert_eq!(unresolved.law_holds, None);
        let bound = unresolved.narrower_than_world.expect("a bound");
        assert!((bound - 0.2 / 0.45).abs() < 1e-6, "{bound}");
        assert_eq!(unresolved.measured_width_world(), None);
        // Shadows of no light's shape: the law is broken, and no bound is said of a light.
        let misshapen: Vec<SlabShadow> =
            ratios.iter().map(|&g| SlabShadow { core_visibility: Some(0.1), ..slab(g, None) }).collect();
        let broken = law(misshapen, 0.2);
        assert_eq!((broken.law_holds, broken.narrower_than_world), (Some(false), None));
        assert_eq!(broken.measured_width_world(), None);
        // No shadows at all: not even a bound.
        assert_eq!(law(ratios.iter().map(|&g| slab(g, None)).collect(), 0.2).narrower_than_world, None);
    }
}

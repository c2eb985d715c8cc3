//! The texel-density view: how many of a light's shadow-map texels fall across one screen pixel,
//! the measure of perspective aliasing. Under 1, one texel spreads over several pixels and the
//! shadow's edges show its blocks; over 1, texels are spent where no pixel reads them.

use super::{Legend, NO_SURFACE};
use crate::render::Analysis;
use crate::shadow::view_covering;
use crate::shadow::{LightGpu, ShadowViewGpu, outside_depth, outside_map, project_to_light};
use glam::{Vec2, Vec3};
use image::{Rgba, RgbaImage};

/// The densities the colours span, texels per pixel: four octaves either side of 1, fixed so
/// that pictures of two scenes or two map sizes compare. Densities beyond take the end colours.
pub const DENSITY_MIN: f32 = 1.0 / 16.0;
pub const DENSITY_MAX: f32 = 16.0;

/// Surfaces off the light's map (or past its depth range): there are no texels to count.
const OFF_THE_MAP: Rgba<u8> = Rgba([120, 120, 120, 255]);

/// What the view shows at one pixel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TexelDensity {
    /// No surface, or a surface one pixel across (no neighbour on it to measure against).
    NotMeasured,
    /// The surface lies outside the frustum of the light's view that covers it.
    OffTheMap,
    /// sqrt(|det J|), J = d(uv * map size) / d(screen pixel).
    TexelsPerPixel(f32),
}

/// The world position one pixel from (x, y) on the same object (the analysis normal's w is the
/// object index), with the step's sign: the right (lower) neighbour, else the left (upper) one,
/// so a surface's last column and row are measured too.
fn neighbour_on_surface(a: &Analysis, x: u32, y: u32, along_x: bool) -> Option<(Vec3, f32)> {
    let object = a.normal[a.index(x, y)][3];
    let at = |dx: i64, dy: i64| {
        let (nx, ny) = (i64::from(x) + dx, i64::from(y) + dy);
        let inside = (0..i64::from(a.width)).contains(&nx) && (0..i64::from(a.height)).contains(&ny);
        let j = inside.then(|| a.index(nx as u32, ny as u32))?;
        (a.hit(j) && a.normal[j][3] == object).then(|| Vec3::from_slice(&a.position[j][..3]))
    };
    let (forward, back) = if along_x { ((1, 0), (-1, 0)) } else { ((0, 1), (0, -1)) };
    at(forward.0, forward.1).map(|p| (p, 1.0)).or_else(|| at(back.0, back.1).map(|p| (p, -1.0)))
}

/// Shadow-map texels per screen pixel at pixel (x, y) for `light`: the Jacobian of the map's
/// texel coordinates over the screen, by differences with the pixel's neighbours on the same
/// surface, all three projected into the view that covers the centre pixel (a neighbour in
/// another view would measure the jump between the views, not the texels).
pub fn texel_density_at(
    a: &Analysis,
    x: u32,
    y: u32,
    light: &LightGpu,
    views: &[ShadowViewGpu],
) -> TexelDensity {
    let i = a.index(x, y);
    if !a.hit(i) {
        return TexelDensity::NotMeasured;
    }
    let centre = Vec3::from_slice(&a.position[i][..3]);
    let Some(view) = views.get(view_covering(light, views, centre)) else {
        return TexelDensity::OffTheMap;
    };
    let projected = project_to_light(view, centre);
    if outside_map(projected.truncate()) || outside_depth(projected.z) {
        return TexelDensity::OffTheMap;
    }
    let texels = |p: Vec3| project_to_light(view, p).truncate() * view.map_size_texels;
    let per_pixel = |(p, sign): (Vec3, f32)| -> Vec2 { (texels(p) - texels(centre)) * sign };
    let (Some(across), Some(down)) =
        (neighbour_on_surface(a, x, y, true), neighbour_on_surface(a, x, y, false))
    else {
        return TexelDensity::NotMeasured;
    };
    // |det J| is the texel area one pixel covers; its root counts texels along a pixel's side.
    let density = per_pixel(across).perp_dot(per_pixel(down)).abs().sqrt();
    if density.is_finite() { TexelDensity::TexelsPerPixel(density) } else { TexelDensity::NotMeasured }
}

/// A density's colour: log2 of it over DENSITY_MIN..DENSITY_MAX, clamped, through a diverging
/// ramp (ColorBrewer's RdBu, one stop per octave). Diverging because both ways off 1 are
/// failures of a different kind: red where texels are too few (blocky edges), blue where they
/// are too many (wasted), near-white where one texel meets one pixel. RdBu stays apart for the
/// common colour-vision deficiencies.
pub fn density_color(texels_per_pixel: f32) -> Rgba<u8> {
    const STOPS: [[u8; 3]; 9] = [
        [178, 24, 43],
        [214, 96, 77],
        [244, 165, 130],
        [253, 219, 199],
        [247, 247, 247],
        [209, 229, 240],
        [146, 197, 222],
        [67, 147, 195],
        [33, 102, 172],
    ];
    let (lo, hi) = (DENSITY_MIN.log2(), DENSITY_MAX.log2());
    let octaves = texels_per_pixel.log2();
    let t = if octaves.is_finite() { ((octaves - lo) / (hi - lo)).clamp(0.0, 1.0) } else { 0.0 };
    let x = t * (STOPS.len() - 1) as f32;
    let k = (x.floor() as usize).min(STOPS.len() - 2);
    let f = x - k as f32;
    let channel =
        |c: usize| (f32::from(STOPS[k][c]) * (1.0 - f) + f32::from(STOPS[k + 1][c]) * f).round() as u8;
    Rgba([channel(0), channel(1), channel(2), 255])
}

/// The densities measured over the picture, texels per pixel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DensityOnScreen {
    pub min: f32,
    pub median: f32,
    pub max: f32,
}

/// The texel-density view of the selected light: the picture, its legend (the fixed range of
/// the colours) and the densities measured (None where no surface on the map was seen).
pub fn texel_density_image(
    a: &Analysis,
    light: &LightGpu,
    views: &[ShadowViewGpu],
) -> (RgbaImage, Legend, Option<DensityOnScreen>) {
    let mut measured = Vec::new();
    let image = RgbaImage::from_fn(a.width, a.height, |x, y| match texel_density_at(a, x, y, light, views) {
        TexelDensity::TexelsPerPixel(d) => {
            measured.push(d);
            density_color(d)
        }
        TexelDensity::OffTheMap => OFF_THE_MAP,
        TexelDensity::NotMeasured => NO_SURFACE,
    });
    measured.sort_by(f32::total_cmp);
    let on_screen = (!measured.is_empty()).then(|| DensityOnScreen {
        min: measured[0],
        median: measured[measured.len() / 2],
        max: measured[measured.len() - 1],
    });
    let legend =
        Legend { label: "texel density", min: DENSITY_MIN, max: DENSITY_MAX, unit: "map texels per pixel" };
    (image, legend, on_screen)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Light, LightKind, LightSize};
    use crate::shadow::LightViewGpu;

    const MAP_TEXELS: u32 = 1024;

    fn light(kind: LightKind, position: Vec3, target: Vec3) -> Light {
        Light {
            kind,
            position,
            target,
            up: Vec3::Z,
            color: Vec3::ONE,
            intensity: 1.0,
            shadow_map_size: MAP_TEXELS,
            near: 0.5,
            far: 200.0,
            size: LightSize::Width { width_world: 1.0 },
            orbit_deg_per_s: 0.0,
            cascades: Default::default(),
        }
    }

    /// What an orthographic camera looking straight down sees: the ground y = 0 (object 0), each
    /// pixel `pixel_world` wide, centred on the origin; `surface` gives a pixel's height and
    /// object, None for no surface.
    fn from_above(
        (width, height): (u32, u32),
        pixel_world: f32,
        surface: impl Fn(u32, u32) -> Option<(f32, f32)>,
    ) -> Analysis {
        let mut position = Vec::new();
        let mut normal = Vec::new();
        for y in 0..height {
            for x in 0..width {
                let world_x = (x as f32 + 0.5 - width as f32 * 0.5) * pixel_world;
                let world_z = (y as f32 + 0.5 - height as f32 * 0.5) * pixel_world;
                match surface(x, y) {
                    Some((world_y, object)) => {
                        position.push([world_x, world_y, world_z, 1.0]);
                        normal.push([0.0, 1.0, 0.0, object]);
                    }
                    None => {
                        position.push([0.0; 4]);
                        normal.push([0.0; 4]);
                    }
                }
            }
        }
        let shadow = vec![[1.0, 0.0, 0.0, 0.0]; position.len()];
        Analysis { width, height, shadow, position, normal, moments: None, bleeding: None }
    }

    fn measured(a: &Analysis, x: u32, y: u32, l: &LightViewGpu) -> f32 {
        match texel_density_at(a, x, y, &l.light, &[l.view]) {
            TexelDensity::TexelsPerPixel(d) => d,
            other => panic!("pixel {x},{y}: {other:?}"),
        }
    }

    /// An orthographic light and camera both looking straight down at the ground: a texel is
    /// 2 * extent / map size world units wide and a pixel `pixel_world`, so the density is
    /// map size / (2 * extent) * pixel_world everywhere, the edges of the picture too.
    #[test]
    fn under_a_directional_light_seen_head_on_the_density_is_map_texels_per_pixel_width() {
        let extent_world = 20.0;
        let sun = light(LightKind::Directional { extent_world }, Vec3::new(0.0, 50.0, 0.0), Vec3::ZERO);
        let l = LightViewGpu::single(&sun, 0.0, MAP_TEXELS);
        for pixel_world in [0.01, 0.039_062_5, 0.25] {
            let a = from_above((16, 9), pixel_world, |_, _| Some((0.0, 0.0)));
            let expected = MAP_TEXELS as f32 / (2.0 * extent_world) * pixel_world;
            for (x, y) in [(0, 0), (7, 4), (15, 8), (15, 0)] {
                let d = measured(&a, x, y, &l);
                assert!(
                    (d / expected - 1.0).abs() < 1e-3,
                    "{pixel_world}: {d} at {x},{y}, expected {expected}"
                );
            }
        }
    }

    /// A spot light looking straight down over two floors, the left one at height 0 and the
    /// right one at 10 (another object): a texel at distance d is 2 d tan(fov / 2) / map size
    /// wide, so the density falls as 1 / d, and the floors' border pixels measure their own
    /// floor (the neighbour on the other object is passed over).
    #[test]
    fn under_a_spot_light_the_density_falls_as_one_over_the_distance() {
        let (fov_deg, light_height) = (60.0f32, 30.0);
        let spot = light(LightKind::Spot { fov_deg }, Vec3::new(0.0, light_height, 0.0), Vec3::ZERO);
        let l = LightViewGpu::single(&spot, 0.0, MAP_TEXELS);
        let pixel_world = 0.05;
        let a = from_above((16, 9), pixel_world, |x, _| Some(if x < 8 { (0.0, 0.0) } else { (10.0, 1.0) }));
        let expected =
            |d: f32| pixel_world * MAP_TEXELS as f32 / (2.0 * d * (0.5 * fov_deg.to_radians()).tan());
        for x in [0, 3, 7] {
            let d = measured(&a, x, 4, &l);
            assert!((d / expected(30.0) - 1.0).abs() < 1e-3, "floor at 0, pixel {x}: {d}");
        }
        for x in [8, 12, 15] {
            let d = measured(&a, x, 4, &l);
            assert!((d / expected(20.0) - 1.0).abs() < 1e-3, "floor at 10, pixel {x}: {d}");
        }
        assert!(measured(&a, 8, 4, &l) > measured(&a, 7, 4, &l), "nearer the light, more texels");
    }

    /// A spot light low over the ground, off to one side: along the ground away from it the
    /// texels stretch (farther, and more slanted to the light), so the density falls pixel by
    /// pixel; beyond the light's cone there are no texels.
    #[test]
    fn away_from_an_oblique_spot_light_the_density_falls_smoothly_and_stops_at_its_cone() {
        let spot =
            light(LightKind::Spot { fov_deg: 50.0 }, Vec3::new(-12.0, 6.0, 0.0), Vec3::new(4.0, 0.0, 0.0));
        let l = LightViewGpu::single(&spot, 0.0, MAP_TEXELS);
        let a = from_above((64, 9), 0.5, |_, _| Some((0.0, 0.0)));
        let row: Vec<TexelDensity> =
            (0..64).map(|x| texel_density_at(&a, x, 4, &l.light, &[l.view])).collect();
        let densities: Vec<f32> = row
            .iter()
            .filter_map(|d| match d {
                TexelDensity::TexelsPerPixel(d) => Some(*d),
                _ => None,
            })
            .collect();
        assert!(densities.len() > 20, "{row:?}");
        assert!(densities.windows(2).all(|w| w[1] < w[0]), "falls away from the light: {densities:?}");
        assert!(row.contains(&TexelDensity::OffTheMap), "past the cone: {row:?}");
    }

    /// A pixel whose right and lower neighbours are off the surface measures against its left
    /// and upper ones; a surface one pixel across has nothing to measure against.
    #[test]
    fn a_pixel_without_a_right_or_lower_neighbour_measures_against_the_left_and_upper_ones() {
        let sun = light(LightKind::Directional { extent_world: 20.0 }, Vec3::new(0.0, 50.0, 0.0), Vec3::ZERO);
        let l = LightViewGpu::single(&sun, 0.0, MAP_TEXELS);
        let a = from_above((8, 8), 0.1, |x, y| ((x < 5 && y < 5) || x == 7).then_some((0.0, 0.0)));
        let expected = measured(&a, 2, 2, &l);
        assert!((measured(&a, 4, 4, &l) / expected - 1.0).abs() < 1e-4);
        let alone = from_above((8, 8), 0.1, |x, y| (x == 3 && y == 3).then_some((0.0, 0.0)));
        assert_eq!(texel_density_at(&alone, 3, 3, &l.light, &[l.view]), TexelDensity::NotMeasured);
        assert_eq!(texel_density_at(&alone, 0, 0, &l.light, &[l.view]), TexelDensity::NotMeasured);
    }

    /// The colours: near-white at 1, red below, blue above, the ends held past the range.
    #[test]
    fn the_colours_diverge_from_white_at_one_texel_per_pixel() {
        let [r, g, b, _] = density_color(1.0).0;
        assert!(r > 240 && g > 240 && b > 240, "{r} {g} {b}");
        let [r, _, b, _] = density_color(0.25).0;
        assert!(r > b + 60, "too few texels read red: {r} {b}");
        let [r, _, b, _] = density_color(4.0).0;
        assert!(b > r + 60, "too many texels read blue: {r} {b}");
        assert_eq!(density_color(1e-3), density_color(DENSITY_MIN));
        assert_eq!(density_color(1e3), density_color(DENSITY_MAX));
    }
}

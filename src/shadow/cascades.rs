//! Cascaded shadow maps for a directional light: the camera's frustum cut into slices along its
//! view axis, each slice covered by an orthographic map of its own, so that the map near the
//! camera is sharp and the far one still reaches the horizon [Zhang-2006] [Engel-2006].
//!
//! Units: distances along the camera's view axis and widths in world units.

use crate::scene::{Camera, Light, Projection};
use glam::{Mat4, Vec3};

/// The distances (world units along the camera's view axis) where `count` cascades begin and
/// end over `near..far`: `count + 1` values, the practical split scheme of [Zhang-2006], weighted
/// as [Zhang-2007] states it: d_i = lambda n (f / n)^(i / N) + (1 - lambda) (n + (f - n) i / N).
/// lambda = 0 splits uniformly, 1 logarithmically (equal ratios: the same texels per pixel in each).
pub fn split_distances(near: f32, far: f32, count: u32, lambda: f32) -> Vec<f32> {
    let n = near.max(1e-4);
    let f = far.max(n * (1.0 + 1e-4));
    (0..=count)
        .map(|i| {
            let s = i as f32 / count as f32;
            let logarithmic = n * (f / n).powf(s);
            let uniform = n + (f - n) * s;
            lambda * logarithmic + (1.0 - lambda) * uniform
        })
        .collect()
}

/// The eight corners (world) of the camera's frustum between view distances `d0` and `d1`.
pub fn slice_corners(camera: &Camera, aspect: f32, d0: f32, d1: f32) -> [Vec3; 8] {
    let world_from_view = camera.view_from_world().inverse();
    let mut corners = [Vec3::ZERO; 8];
    for (i, d) in [d0, d1].into_iter().enumerate() {
        let half_height = match camera.projection {
            Projection::Perspective { fov_deg } => d * (0.5 * fov_deg.to_radians()).tan(),
            Projection::Orthographic { height_world } => 0.5 * height_world,
        };
        let half_width = half_height * aspect;
        for (j, (sx, sy)) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].into_iter().enumerate() {
            corners[4 * i + j] =
                world_from_view.transform_point3(Vec3::new(sx * half_width, sy * half_height, -d));
        }
    }
    corners
}

/// One cascade: its orthographic projection and the width it covers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CascadeFit {
    pub clip_from_world: Mat4,
    /// The square's side, world units: the bounding sphere's diameter.
    pub width_world: f32,
    /// Where the slice it covers begins and ends along the camera's view axis, world units.
    pub split_world: (f32, f32),
}

/// The light's `count` cascades over the camera's frustum (`Light::cascades`), sharpest first.
/// Each covers the bounding sphere of its slice: a sphere does not change size when the camera
/// turns, and its centre is snapped to whole texels of the light's view, so a still world casts
/// the same texels as the camera moves (no shimmering edges) [Valient-2008].
pub fn fit_cascades(light: &Light, camera: &Camera, aspect: f32, t_s: f32) -> Vec<CascadeFit> {
    let cascades = light.cascades;
    let far = camera.far.min(cascades.distance_world);
    let splits = split_distances(camera.near, far, cascades.count, cascades.lambda);
    let light_from_world = light.view_from_world(t_s);
    let map_texels = light.shadow_map_size as f32;
    splits
        .windows(2)
        .map(|d| {
            let corners = slice_corners(camera, aspect, d[0], d[1]);
            let centre = corners.iter().copied().sum::<Vec3>() / 8.0;
            let radius = corners.iter().map(|c| c.distance(centre)).fold(0.0, f32::max);
            // Rounded up to 1/64 world unit: the same sphere whatever the rounding of the turn.
            let radius = ((radius * 64.0).ceil() / 64.0).max(1.0 / 64.0);
            let texel_world = 2.0 * radius / map_texels;
            let c = light_from_world.transform_point3(centre);
            let (cx, cy) =
                ((c.x / texel_world).floor() * texel_world, (c.y / texel_world).floor() * texel_world);
            let projection = Mat4::orthographic_rh(
                cx - radius,
                cx + radius,
                cy - radius,
                cy + radius,
                light.near,
                light.far,
            );
            CascadeFit {
                clip_from_world: projection * light_from_world,
                width_world: 2.0 * radius,
                split_world: (d[0], d[1]),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Cascades, LightKind};

    fn camera() -> Camera {
        Camera {
            projection: Projection::Perspective { fov_deg: 60.0 },
            position: Vec3::new(0.0, 2.0, 10.0),
            target: Vec3::new(0.0, 1.0, 0.0),
            up: Vec3::Y,
            near: 0.5,
            far: 120.0,
        }
    }

    fn sun(count: u32, lambda: f32) -> Light {
        let scene = crate::scene::load_scene(&crate::shipped_path("assets/scenes/games202.toml"), &[])
            .expect("scene");
        let mut light = scene.lights[0];
        light.kind = LightKind::Directional { extent_world: 10.0 };
        light.position = Vec3::new(90.0, 180.0, 60.0);
        light.target = Vec3::ZERO;
        light.near = 1.0;
        light.far = 600.0;
        light.orbit_deg_per_s = 0.0;
        light.cascades = Cascades { count, lambda, ..Cascades::default() };
        light
    }

    #[test]
    fn splits_run_from_near_to_far_uniform_to_logarithmic() {
        let uniform = split_distances(1.0, 100.0, 4, 0.0);
        assert_eq!(uniform, vec![1.0, 25.75, 50.5, 75.25, 100.0]);
        let log = split_distances(1.0, 100.0, 4, 1.0);
        for (got, want) in log.iter().zip([1.0, 3.1623, 10.0, 31.623, 100.0]) {
            assert!((got - want).abs() < 1e-3 * want, "{log:?}");
        }
        // Equal ratios: every cascade spans the same depth range in log space.
        let half = split_distances(1.0, 100.0, 4, 0.5);
        assert!(half.windows(2).all(|w| w[1] > w[0]));
        assert!((half[1] - 0.5 * (25.75 + 3.1623)).abs() < 1e-3);
    }

    /// Every point of a slice lies inside its cascade's map: uv in 0..1 and depth in 0..1 (the
    /// light's near and far bound the scene).
    #[test]
    fn each_cascade_holds_its_slice() {
        let light = sun(4, 0.6);
        let fits = fit_cascades(&light, &camera(), 16.0 / 9.0, 0.0);
        assert_eq!(fits.len(), 4);
        for fit in &fits {
            for c in slice_corners(&camera(), 16.0 / 9.0, fit.split_world.0, fit.split_world.1) {
                let ndc = fit.clip_from_world.project_point3(c);
                assert!(ndc.x.abs() <= 1.0 && ndc.y.abs() <= 1.0, "{ndc}");
                assert!((0.0..=1.0).contains(&ndc.z), "{ndc}");
            }
        }
        // Sharpest first: each cascade's texels are smaller than the next one's.
        assert!(fits.windows(2).all(|w| w[0].width_world < w[1].width_world));
    }

    /// Turning the camera on the spot keeps every cascade's size, and moving it keeps the
    /// map's texel grid fixed in the world: the cascade moves by whole texels.
    #[test]
    fn cascades_are_stable_as_the_camera_turns_and_moves() {
        let light = sun(3, 0.5);
        let base = fit_cascades(&light, &camera(), 1.5, 0.0);
        let mut turned = camera();
        turned.orbit(0.7, 0.2);
        let mut moved = camera();
        moved.position += Vec3::new(0.37, 0.0, -0.61);
        moved.target += Vec3::new(0.37, 0.0, -0.61);
        for other in [fit_cascades(&light, &turned, 1.5, 0.0), fit_cascades(&light, &moved, 1.5, 0.0)] {
            for (a, b) in base.iter().zip(&other) {
                assert_eq!(a.width_world, b.width_world);
                // A world point lands at the same place within its texel in both.
                let texel_ndc = 2.0 / light.shadow_map_size as f32;
                let p = Vec3::new(1.3, 0.2, -2.7);
                let (pa, pb) = (a.clip_from_world.project_point3(p), b.clip_from_world.project_point3(p));
                let shift = (pa.truncate() - pb.truncate()) / texel_ndc;
                assert!((shift - shift.round()).abs().max_element() < 1e-2, "shift {shift}");
            }
        }
    }
}

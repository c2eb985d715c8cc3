//! Where along the camera's view axis each of a sun's cascades is read, picked as the renderer
//! picks them (`shadow::view_covering`): by map, from where the sharper cascade's map stops
//! holding the point to where its own does; by interval, its slice. The shadow-views diagram
//! draws these ranges, so it shows what the cascade-index view colours.

use crate::scene::Camera;
use crate::shadow::{LightGpu, ShadowViewGpu, view_covering};
use glam::Vec3;

/// Depths tried along the axis before each change of cascade is refined.
const SAMPLES: usize = 512;
/// Halvings of the step at each change: the boundary to within (range / SAMPLES) / 2^24.
const BISECTIONS: usize = 24;

/// For each of `light`'s views, sharpest first, the depths along `camera`'s view axis (world
/// units, within `from..to`) over which a lookup on the axis reads it, or None where it is never
/// read there. Depths that are not finite, or `to` not beyond `from`, read nothing.
pub fn read_along_view_axis(
    light: &LightGpu,
    views: &[ShadowViewGpu],
    camera: &Camera,
    from: f32,
    to: f32,
) -> Vec<Option<[f32; 2]>> {
    let count = light.view_count.max(1) as usize;
    let mut reads: Vec<Option<[f32; 2]>> = vec![None; count];
    if !(from.is_finite() && to.is_finite() && to > from) {
        return reads;
    }
    let pick = |d: f32| {
        let index = view_covering(light, views, on_view_axis(camera, d));
        index.saturating_sub(light.first_view as usize).min(count - 1)
    };
    let step = (to - from) / SAMPLES as f32;
    let (mut start, mut current) = (from, pick(from));
    for k in 1..=SAMPLES {
        let d = if k == SAMPLES { to } else { from + step * k as f32 };
        let next = pick(d);
        if next == current {
            continue;
        }
        // Bisect between the last depth that read `current` and `d`.
        let (mut near, mut far) = (d - step, d);
        for _ in 0..BISECTIONS {
            let mid = 0.5 * (near + far);
            if pick(mid) == current {
                near = mid;
            } else {
                far = mid;
            }
        }
        widen(&mut reads[current], start, far);
        (start, current) = (far, next);
    }
    widen(&mut reads[current], start, to);
    reads
}

/// `range` grown to hold `a..b`.
fn widen(range: &mut Option<[f32; 2]>, a: f32, b: f32) {
    *range = Some(match *range {
        Some([lo, hi]) => [lo.min(a), hi.max(b)],
        None => [a, b],
    });
}

/// A point on `camera`'s view axis at depth `depth_world` (what the ranges above are measured
/// on). The camera looks down its view space's -z: that row of the matrix, negated, is the axis.
pub fn on_view_axis(camera: &Camera, depth_world: f32) -> Vec3 {
    camera.position - camera.view_from_world().row(2).truncate() * depth_world
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shadow::frame_lights;

    fn avenue(selection: &str) -> crate::scene::Scene {
        let overrides = [("light.0.cascade_selection".to_string(), selection.to_string())];
        let path = crate::shipped_path("assets/scenes/sun_avenue.toml");
        crate::scene::load_scene(&path, &overrides).expect("sun_avenue")
    }

    /// Along the view axis, at every centimetre from the near plane to the last split, the range
    /// that holds a depth belongs to the cascade the twin reads there, for both selections; by
    /// interval the ranges are the slices, by map each runs well past its slice.
    #[test]
    fn the_ranges_drawn_are_the_cascades_the_twin_reads_along_the_view_axis() {
        for selection in ["interval", "map"] {
            let scene = avenue(selection);
            let (lights, views) = frame_lights(&scene, 16.0 / 9.0, 0.0, 1024);
            let sun = &lights[0];
            let cascades = &views[sun.first_view as usize..][..sun.view_count as usize];
            let (from, to) = (cascades[0].split_near_world, cascades[3].split_far_world);
            let reads = read_along_view_axis(sun, &views, &scene.camera, from, to);
            assert!(reads.iter().all(Option::is_some), "{selection}: {reads:?}");
            let mut d = from;
            while d < to {
                let twin =
                    view_covering(sun, &views, on_view_axis(&scene.camera, d)) - sun.first_view as usize;
                let holding: Vec<usize> = (0..4)
                    .filter(|&i| reads[i].is_some_and(|[a, b]| a - 1e-3 <= d && d <= b + 1e-3))
                    .collect();
                assert!(holding.contains(&twin), "{selection} at {d}: twin {twin}, drawn {holding:?}");
                d += 0.01;
            }
            for (i, view) in cascades.iter().enumerate() {
                let [a, b] = reads[i].expect("read");
                let slice = [view.split_near_world, view.split_far_world];
                if selection == "interval" {
                    assert!((a - slice[0]).abs() < 1e-3 && (b - slice[1]).abs() < 1e-3, "{i}: {a}..{b}");
                } else if i < 3 {
                    assert!(
                        b > 1.5 * slice[1],
                        "by map cascade {i} read to {b}, its slice ends at {}",
                        slice[1]
                    );
                }
            }
        }
    }

    /// Bad input reads nothing and does not panic.
    #[test]
    fn no_range_without_a_span_to_read() {
        let scene = avenue("map");
        let (lights, views) = frame_lights(&scene, 1.0, 0.0, 1024);
        for (from, to) in [(5.0, 5.0), (f32::NAN, 10.0), (0.0, f32::INFINITY), (10.0, 1.0)] {
            let reads = read_along_view_axis(&lights[0], &views, &scene.camera, from, to);
            assert!(reads.iter().all(Option::is_none), "{from}..{to}");
        }
        assert!(read_along_view_axis(&lights[0], &[], &scene.camera, 0.0, 1.0).len() == 4);
    }
}

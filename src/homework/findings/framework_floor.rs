//! The student's light over the framework's own floor, as the framework's engine.js lays it out
//! by default: `floorTransform = setTransform(0, 0, -30, 4, 4, 4)` on `assets/floor/floor.obj`,
//! a square of ±27.93 model units in x and z at y = 0, so the floor spans x -111.72..111.72 and
//! z -141.72..81.72 world units. The check's own scene is smaller: a light that leaves part of
//! this floor out of its frustum shows nothing wrong there, and a black band in the student's
//! own view.
//!
//! The map is the floor's alone (the framework's map is never cleared: a texel the floor does
//! not cover reads depth 0), read as the framework reads it (REPEAT: a lookup outside [0, 1]
//! wraps). A floor point is dark by the frustum where its lookup finds a depth in front of its
//! own, or where its own depth lies beyond the far plane (over 1: every texel is in front).
//! Blockers are left out: what is dark here is dark for the frustum alone.

use glam::{Mat4, Vec2, Vec3, Vec3Swizzles, Vec4Swizzles};

/// The framework's floor, world units (its model's half width 27.93, scaled by 4, moved -30 in z).
pub const FLOOR_MIN: Vec3 = Vec3::new(-111.72, 0.0, -141.72);
pub const FLOOR_MAX: Vec3 = Vec3::new(111.72, 0.0, 81.72);
/// The floor's own map, texels a side (its depth varies smoothly: coarse is exact enough).
const MAP_SIZE: usize = 256;
/// Floor points looked at, a side.
const SAMPLES: usize = 128;
/// A texel this much nearer than the point ([0, 1] depth) darkens it: the floor's own texels
/// differ from the point's depth by its slope over a texel of this map, well under this.
const DARKER_BY: f32 = 0.01;

/// What the student's light leaves dark on the framework's floor.
#[derive(Clone, Debug, PartialEq)]
pub struct FloorCoverage {
    /// Share of the floor's points dark by the frustum alone.
    pub dark_share: f64,
    /// Of those, the share whose own depth lies beyond the far plane.
    pub beyond_far_share: f64,
    /// The dark points' extent in world z and x (the band), world units.
    pub z_range: (f32, f32),
    pub x_range: (f32, f32),
    /// Share of the floor's points outside the frustum (their lookup outside [0, 1], or their
    /// depth past the far plane), and their extent in world z and x.
    pub outside_share: f64,
    pub outside_z_range: (f32, f32),
    pub outside_x_range: (f32, f32),
}

/// The floor point at a map texel: where the light's ray through it meets y = 0, inside the
/// floor and the depth range; its [0, 1] depth.
fn floor_depth_at(clip_from_world: Mat4, world_from_clip: Mat4, ndc: Vec2) -> Option<f32> {
    let near = world_from_clip * ndc.extend(-1.0).extend(1.0);
    let far = world_from_clip * ndc.extend(1.0).extend(1.0);
    let (near, far) = (near.xyz() / near.w, far.xyz() / far.w);
    let dy = far.y - near.y;
    if dy.abs() < 1e-6 {
        return None;
    }
    let t = -near.y / dy;
    if !(0.0..=1.0).contains(&t) {
        return None;
    }
    let p = near + t * (far - near);
    let inside = p.x >= FLOOR_MIN.x && p.x <= FLOOR_MAX.x && p.z >= FLOOR_MIN.z && p.z <= FLOOR_MAX.z;
    // Depth along the segment is linear in NDC z only for an orthographic light; project again.
    inside.then_some(p).and_then(|p| depth_of(clip_from_world, p).map(|(_, z)| z))
}

/// A world point's map uv and [0, 1] depth under `clip_from_world` (None: behind the eye).
fn depth_of(clip_from_world: Mat4, p: Vec3) -> Option<(Vec2, f32)> {
    let clip = clip_from_world * p.extend(1.0);
    (clip.w > 1e-6).then(|| {
        let ndc = clip.xyz() / clip.w;
        (ndc.xy() * 0.5 + 0.5, ndc.z * 0.5 + 0.5)
    })
}

/// The framework's floor under the student's light (`clip_from_world`, GL clip conventions, the
/// matrix an object at the origin gets: the floor's own is that times its model matrix).
/// `unwritten_lit`: their lookup reads a texel never written (depth 0) as lit (a guard such as
/// `if (d < EPS) return 1.0;`), so only texels the floor wrote can darken it.
pub fn coverage(clip_from_world: Mat4, unwritten_lit: bool) -> Option<FloorCoverage> {
    let world_from_clip = clip_from_world.inverse();
    if !world_from_clip.is_finite() {
        return None;
    }
    // The floor's depth in each texel; 0 where it does not cover the texel (never written).
    let map: Vec<f32> = (0..MAP_SIZE * MAP_SIZE)
        .map(|k| {
            let uv = (Vec2::new((k % MAP_SIZE) as f32, (k / MAP_SIZE) as f32) + 0.5) / MAP_SIZE as f32;
            floor_depth_at(clip_from_world, world_from_clip, uv * 2.0 - 1.0).unwrap_or(0.0)
        })
        .collect();
    let (mut dark, mut beyond, mut seen, mut outside) = (0usize, 0usize, 0usize, 0usize);
    let empty = (f32::INFINITY, f32::NEG_INFINITY);
    let (mut z_range, mut x_range, mut outside_z, mut outside_x) = (empty, empty, empty, empty);
    let widen = |range: &mut (f32, f32), v: f32| *range = (range.0.min(v), range.1.max(v));
    for j in 0..SAMPLES {
        for i in 0..SAMPLES {
            let f = (Vec2::new(i as f32, j as f32) + 0.5) / SAMPLES as f32;
            let p = Vec3::new(
                FLOOR_MIN.x + f.x * (FLOOR_MAX.x - FLOOR_MIN.x),
                0.0,
                FLOOR_MIN.z + f.y * (FLOOR_MAX.z - FLOOR_MIN.z),
            );
            let Some((uv, depth)) = depth_of(clip_from_world, p) else { continue };
            seen += 1;
            if uv.cmplt(Vec2::ZERO).any() || uv.cmpgt(Vec2::ONE).any() || depth > 1.0 {
                outside += 1;
                widen(&mut outside_z, p.z);
                widen(&mut outside_x, p.x);
            }
            // REPEAT: the texel a lookup outside [0, 1] wraps to.
            let wrapped = uv - uv.floor();
            let texel = (wrapped * MAP_SIZE as f32).as_uvec2().min(glam::UVec2::splat(MAP_SIZE as u32 - 1));
            let stored = map[texel.y as usize * MAP_SIZE + texel.x as usize];
            if unwritten_lit && stored == 0.0 {
                continue;
            }
            let past_far = depth > 1.0;
            if past_far || stored + DARKER_BY < depth {
                dark += 1;
                beyond += usize::from(past_far);
                widen(&mut z_range, p.z);
                widen(&mut x_range, p.x);
            }
        }
    }
    (seen > 0).then(|| FloorCoverage {
        dark_share: dark as f64 / seen as f64,
        beyond_far_share: beyond as f64 / dark.max(1) as f64,
        z_range,
        x_range,
        outside_share: outside as f64 / seen as f64,
        outside_z_range: outside_z,
        outside_x_range: outside_x,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The framework's light: from (0, 80, 80) at the origin, an orthographic box `half` wide
    /// each way, from 0.01 to `far`.
    fn light(half: f32, far: f32) -> Mat4 {
        Mat4::orthographic_rh_gl(-half, half, -half, half, 0.01, far)
            * Mat4::look_at_rh(Vec3::new(0.0, 80.0, 80.0), Vec3::ZERO, Vec3::Y)
    }

    #[test]
    fn the_framework_floor_is_covered_by_the_frameworks_light_and_not_by_short_or_narrow_ones() {
        // ±100 and far 400: the floor's x edges (±111.7) wrap onto floor texels of the same depth
        // (the light lies in the yz plane): nothing is dark.
        let framework = coverage(light(100.0, 400.0), false).expect("a coverage");
        assert!(framework.dark_share < 0.005, "{framework:?}");
        // Far 200: the far end of the floor lies 213 world units from the light; the band beyond
        // about 200 (z < -123) is dark, all of it past the far plane.
        let short = coverage(light(100.0, 200.0), false).expect("a coverage");
        assert!((0.05..0.15).contains(&short.dark_share), "{short:?}");
        assert!(short.beyond_far_share > 0.99, "{short:?}");
        assert!((short.z_range.0 + 141.7).abs() < 2.0 && (short.z_range.1 + 123.0).abs() < 3.0, "{short:?}");
        // ±80: the far floor (v up to 100.2) wraps to rows nothing covers: a band dark at the far
        // end, not past the far plane.
        let narrow = coverage(light(80.0, 400.0), false).expect("a coverage");
        assert!(narrow.dark_share > 0.05, "{narrow:?}");
        assert!(narrow.beyond_far_share < 0.01, "{narrow:?}");
        assert!(narrow.z_range.0 < -140.0, "{narrow:?}");
        // A lookup that reads a texel never written as lit leaves both bands lit: the floor past
        // the far plane is clipped, so its own texels are never written either.
        for (half, far) in [(80.0, 400.0), (100.0, 200.0)] {
            let guarded = coverage(light(half, far), true).expect("a coverage");
            assert!(guarded.dark_share < 0.005, "±{half}, far {far}: {guarded:?}");
        }
    }
}

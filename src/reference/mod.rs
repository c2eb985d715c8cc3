//! Ground truth for soft shadows: the average of many hard shadows from sample points over the
//! light's area (spot lights: point lights on a disk of diameter `width`, perspective maps) or
//! from directions over its angular disk (directional lights: orthographic maps; a width is
//! turned into the angle it subtends at the light's target; point lights: point lights inside a
//! sphere of diameter `width`, spread so that every receiver sees them evenly over the sphere's
//! disk, each with its six cube faces).
//! A published comparison averages 1024 hard shadows [Guennebaud-2006].

use crate::scene::{BiasMode, DepthStorage, Light, LightKind, LightSize, ShadowSettings, Technique};
use crate::shadow::{LightGpu, LightViewGpu, ShadowViewGpu};
use glam::{Mat4, Vec2, Vec3};

const GOLDEN_ANGLE: f32 = 2.399_963_2;

/// Point `k` of `n` on the unit disk, spread evenly over its area: a golden-angle spiral
/// [Vogel-1979].
pub fn disk_point(k: usize, n: usize) -> Vec2 {
    let r = ((k as f32 + 0.5) / n as f32).sqrt();
    let a = k as f32 * GOLDEN_ANGLE;
    Vec2::new(a.cos(), a.sin()) * r
}

/// The light's own axis at time `t`: forward, and two unit vectors spanning its area.
fn light_basis(light: &Light, t_s: f32) -> (Vec3, Vec3, Vec3) {
    let forward = light.direction_at(t_s);
    let up = crate::scene::safe_up_for(forward, light.up);
    let right = forward.cross(up).normalize();
    (forward, right, right.cross(forward))
}

/// The hard-shadow lights whose average is the ground truth, each with its one view as the GPU
/// reads it (layer 0 of a map of the light's own size). A light of size 0 gives itself.
pub fn sample_lights(light: &Light, t_s: f32, count: usize) -> Vec<LightViewGpu> {
    let size = light.shadow_map_size;
    let (forward, right, up) = light_basis(light, t_s);
    let position = light.position_at(t_s);
    let distance = (light.target - position).length().max(1e-3);
    // A directional light given a width is an area light seen from its target: the width
    // subtends 2*atan(w / 2d) there. Its ground truth tilts the orthographic map over that angle,
    // so that a width of 0 gives back exactly the orthographic hard shadow PCSS starts from.
    let angle_deg = match (light.size, light.kind) {
        (LightSize::AngularDiameter { angular_diameter_deg }, _) => Some(angular_diameter_deg),
        (LightSize::Width { width_world }, LightKind::Directional { .. }) => {
            Some((2.0 * (0.5 * width_world / distance).atan()).to_degrees())
        }
        (LightSize::Width { .. }, LightKind::Spot { .. } | LightKind::Point) => None,
    };
    match (light.size, angle_deg) {
        (LightSize::Width { width_world }, None)
            if light.stores_distance() && width_world > 0.0 && count > 1 =>
        {
            (0..count)
                .map(|k| {
                    let eye = position + sphere_point(k, count) * (0.5 * width_world);
                    LightViewGpu {
                        light: LightGpu::new(light, eye, forward, 0, 6),
                        view: cube_face_view_at(light, eye, 0, size),
                    }
                })
                .collect()
        }
        (LightSize::Width { width_world }, None) if width_world > 0.0 && count > 1 => (0..count)
            .map(|k| {
                // Point lights over the spot light's disk, each with the light's own frustum.
                let p = disk_point(k, count) * (0.5 * width_world);
                let eye = position + right * p.x + up * p.y;
                let clip = light.clip_from_view() * Mat4::look_to_rh(eye, forward, up);
                LightViewGpu {
                    light: LightGpu::new(light, eye, forward, 0, 1),
                    view: ShadowViewGpu::new(light, clip, 0, size),
                }
            })
            .collect(),
        (_, Some(angular_diameter_deg)) if angular_diameter_deg > 0.0 && count > 1 => {
            let tan_half = (0.5 * angular_diameter_deg.to_radians()).tan();
            (0..count)
                .map(|k| {
                    let p = disk_point(k, count) * tan_half;
                    let direction = (forward + right * p.x + up * p.y).normalize();
                    let eye = light.target - direction * distance;
                    let sample_up = crate::scene::safe_up_for(direction, up);
                    let clip = light.clip_from_view() * Mat4::look_to_rh(eye, direction, sample_up);
                    LightViewGpu {
                        light: LightGpu::new(light, eye, direction, 0, 1),
                        view: ShadowViewGpu::new(light, clip, 0, size),
                    }
                })
                .collect()
        }
        _ => vec![LightViewGpu::single(light, t_s, size)],
    }
}

/// A point light's cube face `face` seen from `eye`, in layer `face` of an array `atlas_size`
/// wide.
fn cube_face_view_at(light: &Light, eye: Vec3, face: usize, atlas_size: u32) -> ShadowViewGpu {
    let (forward, up) = crate::scene::CUBE_FACES[face];
    let clip = light.clip_from_view() * Mat4::look_to_rh(eye, forward, up);
    ShadowViewGpu::new(light, clip, 0, atlas_size).on_face(face as u32)
}

/// The shadow views one sample renders: a point light's six faces (layers 0..6), else its one.
pub fn sample_views(light: &Light, sample: &LightViewGpu) -> Vec<ShadowViewGpu> {
    if sample.view.cube == 0 {
        return vec![sample.view];
    }
    let eye = glam::Vec4::from(sample.view.origin).truncate();
    let atlas = (sample.view.map_size_texels / sample.view.atlas_scale).round() as u32;
    (0..6).map(|face| cube_face_view_at(light, eye, face, atlas)).collect()
}

/// Point `k` of `n` in the unit ball, spread so that its projection on every plane through the
/// centre is even over the unit disk: a spherical light of uniform radiance looks like an evenly
/// bright disk from anywhere, and averaging hard shadows from these points weighs each part of
/// that disk alike. The radial density that does it is 1 / sqrt(1 - s²) (the inverse Abel
/// transform of a uniform disk), whose share within radius s is
/// F(s) = (2/pi) (asin s - s sqrt(1 - s²)). Directions on a Fibonacci sphere, radii at the
/// van der Corput points of F, so the two are not in step.
pub fn sphere_point(k: usize, n: usize) -> Vec3 {
    let z = 1.0 - 2.0 * (k as f32 + 0.5) / n as f32;
    let ring = (1.0 - z * z).max(0.0).sqrt();
    let a = k as f32 * GOLDEN_ANGLE;
    let direction = Vec3::new(ring * a.cos(), z, ring * a.sin());
    direction * sphere_radius_at_share(van_der_corput(k as u32))
}

/// The radical inverse of k in base 2, offset half a step from 0: in (0, 1).
fn van_der_corput(k: u32) -> f32 {
    ((f64::from(k.reverse_bits()) + 0.5) / 2f64.powi(32)) as f32
}

/// The radius s at which F(s) = u (see `sphere_point`), by bisection: F rises from 0 to 1.
fn sphere_radius_at_share(u: f32) -> f32 {
    let share = |s: f64| (2.0 / std::f64::consts::PI) * (s.asin() - s * (1.0 - s * s).sqrt());
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        if share(mid) < f64::from(u) { lo = mid } else { hi = mid }
    }
    (0.5 * (lo + hi)) as f32
}

/// Settings the ground truth's hard shadows use: the user's bias is replaced by a robust one
/// (half a texel plus a one-texel normal offset), so acne or peter panning in the technique
/// shows up as error instead of being copied into the reference; and the depths are kept as
/// floats, so an RGBA8 map's rounding does too.
pub fn reference_settings(user: &ShadowSettings) -> ShadowSettings {
    ShadowSettings {
        technique: Technique::Hard,
        bias_mode: BiasMode::Adaptive,
        adaptive_c: 1.0,
        normal_offset_texels: 1.0,
        clamp_outside: true,
        depth_storage: DepthStorage::Float32,
        ..*user
    }
}

/// The shadow settings a ground truth depends on: [`reference_settings`] with the fields its
/// hard, adaptively biased lookup never reads (the filters, the blocker search, VSM, the other
/// bias modes' numbers, and the rasteriser's bias and culling, which its own shadow pass leaves
/// off) put back to their defaults. Two scenes whose settings give the same value here have the
/// same ground truth, whatever technique each shows (`tests/physics.rs` holds the GPU to it).
pub fn settings_read(user: &ShadowSettings) -> ShadowSettings {
    let d = ShadowSettings::default();
    ShadowSettings {
        bias: d.bias,
        slope_bias: d.slope_bias,
        depth_bias_constant: d.depth_bias_constant,
        depth_bias_slope: d.depth_bias_slope,
        cull_front_faces: d.cull_front_faces,
        pcf_kernel: d.pcf_kernel,
        samples: d.samples,
        radius_texels: d.radius_texels,
        rotate_per_pixel: d.rotate_per_pixel,
        noise_seed: d.noise_seed,
        blocker_samples: d.blocker_samples,
        min_filter_radius_texels: d.min_filter_radius_texels,
        search_radius_scale: d.search_radius_scale,
        ortho_near_factor: d.ortho_near_factor,
        vsm_min_variance: d.vsm_min_variance,
        vsm_bleed_reduction: d.vsm_bleed_reduction,
        ..reference_settings(user)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The lamp's samples seen from any direction cover its disk evenly: on planes through the
    /// centre at several tilts, the share within radius r of the disk is r² (a uniform disk's),
    /// and no point leaves the ball.
    #[test]
    fn sphere_points_project_evenly_onto_the_disk_from_every_direction() {
        let n = 4096;
        let points: Vec<Vec3> = (0..n).map(|k| sphere_point(k, n)).collect();
        assert!(points.iter().all(|p| p.length() <= 1.0 + 1e-5));
        for axis in
            [Vec3::Y, Vec3::X, Vec3::new(1.0, 2.0, 3.0).normalize(), Vec3::new(-2.0, 0.5, 1.0).normalize()]
        {
            for r in [0.3f32, 0.5, 0.7, 0.9] {
                let inside = points.iter().filter(|p| (**p - axis * p.dot(axis)).length() < r).count();
                let share = inside as f32 / n as f32;
                assert!(
                    (share - r * r).abs() < 0.02,
                    "axis {axis}: share within {r} is {share}, want {}",
                    r * r
                );
            }
        }
    }
}

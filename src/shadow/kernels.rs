//! Sample patterns and noise: the twin of the "sample patterns" part of
//! shaders/shadow_filter.wgsl and the hash in shaders/common.wgsl (same names, same bits).

use crate::scene::Kernel;
pub use crate::scene::{MAX_TAPS, filter_taps, grid_side};
use glam::Vec2;

pub const TAU: f32 = std::f32::consts::TAU;
pub const GOLDEN_ANGLE: f32 = 2.399_963_2;
pub const NUM_RINGS: f32 = 10.0;

/// PCG hash [Jarzynski-2020], wrapping u32 maths exactly as in WGSL.
pub fn pcg_hash(v: u32) -> u32 {
    let state = v.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277_803_737);
    (word >> 22) ^ word
}

pub fn unit_float(h: u32) -> f32 {
    (h >> 8) as f32 * (1.0 / 16_777_216.0)
}

pub fn pixel_seed(pixel: (u32, u32), noise_seed: u32, rotate_per_pixel: bool) -> u32 {
    if rotate_per_pixel {
        pcg_hash(pixel.0 ^ pcg_hash(pixel.1 ^ pcg_hash(noise_seed)))
    } else {
        pcg_hash(noise_seed)
    }
}

/// An angle brought into [-pi, pi] (the shader does the same before sin and cos).
fn wrap_angle(a: f32) -> f32 {
    a - TAU * (a / TAU + 0.5).floor()
}

/// Tap `i` of `n` before the pixel's rotation: what the renderer writes into the GPU's
/// `kernel_table`, and what the twin turns the same way. The uniform kernel has no table
/// (its points are new random ones per pixel): zero.
pub fn kernel_base(kernel: Kernel, i: u32, n: u32) -> Vec2 {
    match kernel {
        Kernel::Poisson => {
            // poissonDiskSamples [GAMES202-HW1]: a spiral, radius ((i+1)/n)^0.75, NUM_RINGS
            // turns.
            let angle = wrap_angle(i as f32 * TAU * NUM_RINGS / n as f32);
            let r = ((i + 1) as f32 / n as f32).powf(0.75);
            Vec2::new(angle.cos(), angle.sin()) * r
        }
        Kernel::Uniform => Vec2::ZERO,
        Kernel::Grid => {
            let side = grid_side(n);
            if side == 1 {
                return Vec2::ZERO;
            }
            let g = Vec2::new((i % side) as f32, (i / side) as f32);
            g / (side - 1) as f32 * 2.0 - Vec2::ONE
        }
        Kernel::Vogel | Kernel::Hardware => {
            // Golden-angle spiral [Vogel-1979], radius sqrt((i + 0.5) / n).
            let angle = wrap_angle(i as f32 * GOLDEN_ANGLE);
            Vec2::new(angle.cos(), angle.sin()) * ((i as f32 + 0.5) / n as f32).sqrt()
        }
    }
}

/// The `n` taps of a kernel before rotation (n <= MAX_TAPS), as the GPU table holds them.
pub fn kernel_table(kernel: Kernel, n: u32) -> Vec<Vec2> {
    (0..n.min(MAX_TAPS)).map(|i| kernel_base(kernel, i, n)).collect()
}

/// The pixel's rotation of the pattern: (cos, sin) of TAU * unit_float(seed).
pub fn pixel_rotation(seed: u32) -> Vec2 {
    let angle = wrap_angle(TAU * unit_float(seed));
    Vec2::new(angle.cos(), angle.sin())
}

fn rotate_by(p: Vec2, rotation: Vec2) -> Vec2 {
    Vec2::new(rotation.x * p.x - rotation.y * p.y, rotation.y * p.x + rotation.x * p.y)
}

/// Tap `i` of `n` in the unit disk for a pixel with noise `seed`.
pub fn kernel_offset(kernel: Kernel, i: u32, n: u32, seed: u32) -> Vec2 {
    match kernel {
        Kernel::Uniform => {
            // uniformDiskSamples [GAMES202-HW1]: (cos 2 pi x, sin 2 pi x) * sqrt(y), uniform
            // over the area.
            let h = pcg_hash(seed ^ pcg_hash(i + 1));
            let x = unit_float(h);
            let y = unit_float(pcg_hash(h));
            Vec2::new((TAU * x).cos(), (TAU * x).sin()) * y.sqrt()
        }
        // The regular grid [LearnOpenGL-ShadowMapping]: axis-aligned texel offsets, never turned.
        Kernel::Grid => kernel_base(kernel, i, n),
        _ => rotate_by(kernel_base(kernel, i, n), pixel_rotation(seed)),
    }
}

/// The whole pattern, as the sample-pattern plot and the diagrams draw it.
pub fn kernel_points(kernel: Kernel, samples: u32, seed: u32) -> Vec<Vec2> {
    let n = filter_taps(kernel, samples);
    (0..n).map(|i| kernel_offset(kernel, i, n, seed)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_side_is_the_exact_integer_square_root() {
        for (n, side) in
            [(1, 1), (3, 1), (4, 2), (8, 2), (9, 3), (15, 3), (16, 4), (24, 4), (25, 5), (128, 11)]
        {
            assert_eq!(grid_side(n), side, "n = {n}");
        }
        assert_eq!(filter_taps(Kernel::Grid, 9), 9);
        assert_eq!(filter_taps(Kernel::Vogel, 9), 9);
    }

    /// The 3x3 grid of [LearnOpenGL-ShadowMapping]: offsets -1, 0, 1 on both axes, whatever the
    /// pixel's rotation.
    #[test]
    fn the_grid_is_axis_aligned_and_never_turned() {
        let expected: Vec<Vec2> =
            (0..9).map(|i| Vec2::new((i % 3) as f32 - 1.0, (i / 3) as f32 - 1.0)).collect();
        for seed in [0, 1, 12345, pcg_hash(7)] {
            assert_eq!(kernel_points(Kernel::Grid, 9, seed), expected, "seed {seed}");
        }
        // The disks do turn with the seed.
        assert_ne!(kernel_points(Kernel::Vogel, 9, 1), kernel_points(Kernel::Vogel, 9, 12345));
    }

    #[test]
    fn wrapped_angles_stay_in_range_and_keep_their_direction() {
        for a in [0.0f32, 3.0, 7.0, -7.0, 69.0, 311.0] {
            let w = wrap_angle(a);
            assert!((-std::f32::consts::PI..=std::f32::consts::PI).contains(&w), "{a} -> {w}");
            assert!((w.cos() - a.cos()).abs() < 1e-3 && (w.sin() - a.sin()).abs() < 1e-3, "{a}");
        }
    }
}

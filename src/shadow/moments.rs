//! The twin of the VSM moments (shaders/moments.wgsl) and of `filtered_moments` in
//! shaders/shadow_filter.wgsl: the same chain, built the same way from the read-back map.

use super::{DepthImage, ShadowViewGpu};
use glam::Vec2;

/// Texel (x, y) of the array layer holding `map` in its top-left corner, as the moments pass
/// reads it: coordinates past the array's edge repeat its last row or column, and texels
/// beyond the map hold the clear value 1.
pub fn atlas_depth(map: &DepthImage, atlas: u32, x: u32, y: u32) -> f32 {
    let (x, y) = (x.min(atlas - 1), y.min(atlas - 1));
    if x >= map.size || y >= map.size { 1.0 } else { map.depth_ndc[(y * map.size + x) as usize] }
}

/// The fractional level of a chain of `level_count` levels that a filter of `radius_texels`
/// map texels reads: the level whose texels span the radius (`filtered_moments` in
/// shaders/shadow_filter.wgsl). Its floor and the level above are blended.
pub fn level_for_radius(radius_texels: f32, block: u32, level_count: u32) -> f32 {
    let widest = level_count.saturating_sub(1) as f32;
    (radius_texels / block as f32).max(1.0).log2().clamp(0.0, widest)
}

/// (mean depth, mean squared depth) per texel, level 0 first; each level `side` x `side`.
pub struct MomentsChain {
    pub levels: Vec<(u32, Vec<Vec2>)>,
}

impl MomentsChain {
    /// The chain of one light's map inside an array `atlas` texels wide: texels of the array
    /// beyond the light's map hold the clear value 1, as on the GPU.
    pub fn new(map: &DepthImage, atlas: u32, block: u32) -> Self {
        let depth = |x: u32, y: u32| atlas_depth(map, atlas, x, y);
        let side = atlas.div_ceil(block);
        let mut level0 = Vec::with_capacity((side * side) as usize);
        for y in 0..side {
            for x in 0..side {
                let mut sum = Vec2::ZERO;
                for by in 0..block {
                    for bx in 0..block {
                        let z = depth(x * block + bx, y * block + by);
                        sum += Vec2::new(z, z * z);
                    }
                }
                level0.push(sum / (block * block) as f32);
            }
        }
        let mut levels = vec![(side, level0)];
        while levels.last().is_some_and(|(s, _)| *s > 1) {
            let (finer_side, finer) = levels.last().expect("a level");
            let side = finer_side / 2;
            let at =
                |x: u32, y: u32| finer[(y.min(finer_side - 1) * finer_side + x.min(finer_side - 1)) as usize];
            let mut level = Vec::with_capacity((side * side) as usize);
            for y in 0..side {
                for x in 0..side {
                    let (a, b) = (at(2 * x, 2 * y), at(2 * x + 1, 2 * y));
                    let (c, d) = (at(2 * x, 2 * y + 1), at(2 * x + 1, 2 * y + 1));
                    level.push((((a + b) + c) + d) * 0.25);
                }
            }
            levels.push((side, level));
        }
        Self { levels }
    }

    /// The lookup of `filtered_moments`: the fractional level for a filter radius in map texels,
    /// and the two levels it blends with their weights.
    pub fn levels_for(&self, view: &ShadowViewGpu, radius_texels: f32) -> [(usize, f32); 2] {
        let widest = (self.levels.len() - 1) as f32;
        let level = level_for_radius(radius_texels, view.moments_block, self.levels.len() as u32);
        let finer = level.floor();
        let coarser = (finer + 1.0).min(widest);
        [(finer as usize, 1.0 - (level - finer)), (coarser as usize, level - finer)]
    }

    /// Which texels a lookup reads at one level: its span in map texels per side, and the four
    /// texels with their bilinear weights (00, 10, 01, 11).
    pub fn footprint(&self, view: &ShadowViewGpu, uv: Vec2, level: usize) -> Footprint {
        let span = view.moments_block << level;
        let p = uv * view.map_size_texels / (view.moments_block as f32 * (level as f32).exp2())
            - Vec2::splat(0.5);
        let i0 = p.floor();
        let f = p - i0;
        let last = self.levels[level].0 as i32 - 1;
        let at = |dx: i32, dy: i32| {
            [(i0.x as i32 + dx).clamp(0, last) as u32, (i0.y as i32 + dy).clamp(0, last) as u32]
        };
        Footprint {
            level,
            span,
            texels: [at(0, 0), at(1, 0), at(0, 1), at(1, 1)],
            weights: [(1.0 - f.x, 1.0 - f.y), (f.x, 1.0 - f.y), (1.0 - f.x, f.y), (f.x, f.y)],
        }
    }

    fn at_level(&self, view: &ShadowViewGpu, uv: Vec2, level: usize) -> Vec2 {
        let fp = self.footprint(view, uv, level);
        let (side, texels) = &self.levels[level];
        let m = |i: usize| texels[(fp.texels[i][1] * side + fp.texels[i][0]) as usize];
        // In the shader's order: across, then down.
        let (fx, fy) = (fp.weights[1].0, fp.weights[2].1);
        let top = m(0) * (1.0 - fx) + m(1) * fx;
        let bottom = m(2) * (1.0 - fx) + m(3) * fx;
        top * (1.0 - fy) + bottom * fy
    }

    /// What `filtered_moments` reads at `uv` for a filter radius in map texels.
    pub fn filtered(&self, view: &ShadowViewGpu, uv: Vec2, radius_texels: f32) -> Vec2 {
        let [(finer, _), (coarser, t)] = self.levels_for(view, radius_texels);
        // WGSL mix(a, b, t) = a * (1 - t) + b * t.
        self.at_level(view, uv, finer) * (1.0 - t) + self.at_level(view, uv, coarser) * t
    }
}

/// The texels of one VSM lookup (see `MomentsChain::footprint`).
pub struct Footprint {
    pub level: usize,
    /// Map texels per side of one texel of `level`.
    pub span: u32,
    /// Texel coordinates at `level`: 00, 10, 01, 11.
    pub texels: [[u32; 2]; 4],
    /// Bilinear weights (across, down) of each: the texel's weight is their product.
    pub weights: [(f32, f32); 4],
}

//! VSM and VSSM in the twin (the moments part of shaders/shadow_filter.wgsl).

use super::*;

impl Twin<'_> {
    /// The VSM moments of the map, built on first use.
    pub fn moments(&self) -> &moments::MomentsChain {
        let (atlas, map, block) = (self.atlas_size(), self.map, self.view.moments_block);
        self.moments.get_or_init(|| moments::MomentsChain::new(map, atlas, block))
    }

    /// VSM: Chebyshev's one-sided bound on the filtered moments (the shader's `visibility_vsm`)
    /// [Donnelly-2006].
    pub fn visibility_vsm(&mut self, coord: &ShadowCoord, radius_texels: f32) -> f32 {
        if self.params.clamp_outside == 1 && no_map_data(self.view, coord) {
            return 1.0;
        }
        let (_, _, bound) = self.vsm_filter(coord, radius_texels);
        let v = self.reduce_light_bleeding(bound);
        self.record(TapKind::Filter, coord.uv, v);
        v
    }

    /// One VSM filter: the filtered moments, the depth tested (the receiver's less the bias) and
    /// Chebyshev's bound (before any bleed reduction).
    fn vsm_filter(&self, coord: &ShadowCoord, radius_texels: f32) -> (Vec2, f32, f32) {
        let m = self.moments().filtered(self.view, coord.uv, radius_texels);
        let t = coord.depth_ndc - self.receiver_bias_ndc(coord, radius_texels);
        (m, t, self.chebyshev_upper_bound(m, t))
    }

    /// The shader's `reduce_light_bleeding`: bounds up to a are shadow, the rest stretched
    /// back over 0..1.
    pub fn reduce_light_bleeding(&self, p: f32) -> f32 {
        let a = self.params.vsm_bleed_reduction;
        ((p - a) / (1.0 - a)).clamp(0.0, 1.0)
    }

    /// What a VSM lookup of `radius_texels` at the coord sees: the filtered moments, the
    /// depth t it tests, Chebyshev's bound, and the true lit fraction of the same footprint (the
    /// map texels at or behind t, weighted as the lookup weights them).
    pub fn vsm_lookup(&self, coord: &ShadowCoord, radius_texels: f32) -> VsmLookup {
        let (moments, t, bound) = self.vsm_filter(coord, radius_texels);
        let depths = self.vsm_footprint_depths(coord, radius_texels);
        // Folded from +0.0: an empty f64 sum would be -0.0.
        let lit = depths.iter().filter(|(z, _)| *z >= t).fold(0.0f64, |sum, (_, w)| sum + f64::from(*w));
        VsmLookup {
            moments,
            t,
            bound,
            visibility: self.reduce_light_bleeding(bound),
            true_lit_fraction: lit as f32,
            depths,
        }
    }

    /// The share of a VSM lookup's footprint that is not nearer than the receiver's own plane
    /// (less `bias_ndc`) at each texel's centre: what an exact filter of the same window gives
    /// without shadowing a tilted receiver with itself. VSM's visibility above it is light
    /// bleeding.
    pub fn vsm_plane_lit_fraction(
        &self,
        world_pos: Vec3,
        normal: Vec3,
        radius_texels: f32,
        bias_ndc: f32,
    ) -> f32 {
        let plane_params = ShadowParamsGpu { bias_mode: BIAS_RECEIVER_PLANE, ..*self.params };
        let coord = light_space_lookup(self.light, self.view, &plane_params, world_pos, normal);
        let size = self.view.map_size_texels;
        let mut lit = 0.0f64;
        self.for_each_footprint_depth(&coord, radius_texels, |[x, y], z, w| {
            let centre = Vec2::new(x as f32 + 0.5, y as f32 + 0.5) / size;
            if z >= coord.depth_ndc + coord.depth_gradient.dot(centre - coord.uv) - bias_ndc {
                lit += f64::from(w);
            }
        });
        lit as f32
    }

    /// Every map depth a VSM lookup of `radius_texels` averages, with its weight in the
    /// lookup (NDC, weights summing to 1): the distribution whose mean and variance the
    /// filtered moments hold.
    pub fn vsm_footprint_depths(&self, coord: &ShadowCoord, radius_texels: f32) -> Vec<(f32, f32)> {
        let mut depths = Vec::new();
        self.for_each_footprint_depth(coord, radius_texels, |_, z, w| depths.push((z, w)));
        depths
    }

    /// Calls `visit(texel, depth, weight)` for every map texel a VSM lookup averages (texels
    /// of the light's map, depths NDC, weights summing to 1).
    pub fn for_each_footprint_depth(
        &self,
        coord: &ShadowCoord,
        radius_texels: f32,
        mut visit: impl FnMut([u32; 2], f32, f32),
    ) {
        let (view, chain, atlas) = (self.view, self.moments(), self.atlas_size());
        for (level, level_weight) in chain.levels_for(view, radius_texels) {
            if level_weight == 0.0 {
                continue;
            }
            let fp = chain.footprint(view, coord.uv, level);
            let per_texel = 1.0 / (fp.span * fp.span) as f32;
            for (texel, (wx, wy)) in fp.texels.iter().zip(fp.weights) {
                let w = level_weight * wx * wy * per_texel;
                if w == 0.0 {
                    continue;
                }
                let (x0, y0) = (texel[0] * fp.span, texel[1] * fp.span);
                for y in y0..y0 + fp.span {
                    for x in x0..x0 + fp.span {
                        visit([x, y], moments::atlas_depth(self.map, atlas, x, y), w);
                    }
                }
            }
        }
    }

    /// Light bleeding at one surface point: VSM's (or VSSM's) visibility minus the lit share
    /// of the window its filter read, each texel tested against the receiver's plane
    /// (`vsm_plane_lit_fraction`); 0 where the technique is neither, or the point is outside
    /// the frustum and lit anyway.
    pub fn vsm_light_bleeding_at(&mut self, pixel: (u32, u32), world_pos: Vec3, normal: Vec3) -> f32 {
        let (coord, result) = self.analysis_at(pixel, world_pos, normal);
        let radius = match self.params.technique {
            TECHNIQUE_VSM => self.params.radius_texels,
            TECHNIQUE_VSSM if result.search.found > 0 => result.penumbra.filter_radius_texels,
            _ => return 0.0,
        };
        if self.params.clamp_outside == 1 && no_map_data(self.view, &coord) {
            return 0.0;
        }
        let bias = self.receiver_bias_ndc(&coord, radius);
        result.visibility - self.vsm_plane_lit_fraction(world_pos, normal, radius, bias)
    }

    /// P(depth >= t) <= sigma² / (sigma² + (t - mu)²) for t > mu; 1 for t <= mu.
    pub fn chebyshev_upper_bound(&self, m: Vec2, t: f32) -> f32 {
        if t <= m.x {
            return 1.0;
        }
        let variance = (m.y - m.x * m.x).max(self.params.vsm_min_variance);
        let d = t - m.x;
        variance / (variance + d * d)
    }

    /// VSSM (the shader's `visibility_vssm`): the average blocker depth from the moments over
    /// the search region, PCSS's similar triangles, a VSM filter of half the penumbra.
    pub fn visibility_vssm(&mut self, coord: &ShadowCoord) -> ShadowVisibility {
        let mut out = ShadowVisibility { visibility: 1.0, ..Default::default() };
        if self.params.clamp_outside == 1 && no_map_data(self.view, coord) {
            return out;
        }
        let view = self.view;
        out.search.radius_texels = self.blocker_search_radius_uv(coord) * view.map_size_texels;
        let m = self.moments().filtered(view, coord.uv, out.search.radius_texels);
        let t = coord.depth_ndc - self.receiver_bias_ndc(coord, 0.0);
        let unoccluded = self.chebyshev_upper_bound(m, t);
        self.record(TapKind::BlockerSearch, coord.uv, 1.0 - unoccluded);
        if unoccluded >= 1.0 {
            return out;
        }
        let z_occ = (m.x - unoccluded * t) / (1.0 - unoccluded);
        out.search.found = 1;
        out.search.avg_depth_linear = depth_linear_from_ndc(view, z_occ.clamp(0.0, 1.0));
        out.penumbra = self.estimate_penumbra(coord, out.search.avg_depth_linear);
        out.visibility = self.visibility_vsm(coord, out.penumbra.filter_radius_texels);
        out
    }
}

//! The CPU twin of shaders/shadow_sampling.wgsl: the same functions with the same names and
//! units, run on a read-back shadow map. It powers the pixel probe and the tests that hold the
//! GPU to the maths. A formula is fixed in both places or in neither.

pub mod gpu;
pub mod kernels;
pub mod moments;

use crate::scene::Kernel;
use glam::{Vec2, Vec3, Vec4};
pub use gpu::{
    BIAS_ADAPTIVE, BIAS_CONSTANT, BIAS_RECEIVER_PLANE, BIAS_SLOPE, DEPTH_RGBA8, LightGpu, SIZE_MODEL_ANGULAR,
    ShadowParamsGpu, TECHNIQUE_HARD, TECHNIQUE_NONE, TECHNIQUE_PCF, TECHNIQUE_PCSS, TECHNIQUE_VSM,
    TECHNIQUE_VSSM, kernel_from_id,
};
use kernels::{filter_taps, kernel_offset};

/// One light's shadow map read back: NDC depth per texel, row-major, top row first (uv.y = 0).
#[derive(Clone, Debug)]
pub struct DepthImage {
    pub size: u32,
    pub depth_ndc: Vec<f32>,
}

#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ShadowCoord {
    pub uv: Vec2,
    pub depth_ndc: f32,
    pub depth_linear: f32,
    pub n_dot_l: f32,
    /// Receiver-plane bias only (else 0): the receiver's plane as NDC depth per uv of the map.
    pub depth_gradient: Vec2,
}

#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BlockerSearch {
    pub radius_texels: f32,
    pub found: u32,
    pub avg_depth_linear: f32,
}

#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Penumbra {
    pub width_world: f32,
    pub filter_radius_texels: f32,
}

#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PcssResult {
    pub visibility: f32,
    pub search: BlockerSearch,
    pub penumbra: Penumbra,
}

/// A VSM lookup seen in full (`Twin::vsm_lookup`).
#[derive(Clone, Debug, PartialEq)]
pub struct VsmLookup {
    /// (mean depth, mean squared depth), NDC.
    pub moments: Vec2,
    /// The depth tested: the receiver's less the bias, NDC.
    pub t: f32,
    /// Chebyshev's one-sided bound.
    pub bound: f32,
    /// What VSM returns: the bound after the bleed reduction (the bound itself when it is off).
    pub visibility: f32,
    /// The share of the same footprint's depths at or behind t.
    pub true_lit_fraction: f32,
    /// The footprint's depths with their weights (`Twin::vsm_footprint_depths`).
    pub depths: Vec<(f32, f32)>,
}

/// Which loop a traced tap came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TapKind {
    BlockerSearch,
    Filter,
}

/// One shadow-map lookup, for the probe's picture of the samples.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tap {
    pub kind: TapKind,
    pub uv: Vec2,
    /// Blocker search: 1 = a blocker. Filter: the lit fraction of the tap (0 or 1, bilinear for hardware).
    pub value: f32,
}

/// One light's shadow map and parameters, as the GPU had them.
pub struct Twin<'a> {
    pub light: &'a LightGpu,
    pub params: &'a ShadowParamsGpu,
    pub map: &'a DepthImage,
    /// When Some, every lookup is recorded.
    pub trace: Option<Vec<Tap>>,
    /// The VSM moments of `map`, built on first use.
    moments: std::cell::OnceCell<moments::MomentsChain>,
}

fn orthographic(light: &LightGpu) -> bool {
    light.orthographic == 1
}

pub fn depth_linear_from_ndc(light: &LightGpu, z: f32) -> f32 {
    if orthographic(light) {
        return light.near + z * (light.far - light.near);
    }
    light.near * light.far / (light.far - z * (light.far - light.near))
}

pub fn ndc_per_world(light: &LightGpu, depth_linear: f32) -> f32 {
    if orthographic(light) {
        return 1.0 / (light.far - light.near);
    }
    light.far * light.near / (depth_linear * depth_linear * (light.far - light.near))
}

pub fn texel_world_at(light: &LightGpu, depth_linear: f32) -> f32 {
    if orthographic(light) {
        return light.frustum_width_world / light.map_size_texels;
    }
    2.0 * depth_linear * light.tan_half_fov / light.map_size_texels
}

pub fn light_dir_to(light: &LightGpu, world_pos: Vec3) -> Vec3 {
    if orthographic(light) {
        return -Vec4::from(light.direction).truncate();
    }
    (Vec4::from(light.position).truncate() - world_pos).normalize()
}

pub fn project_to_light(light: &LightGpu, world_pos: Vec3) -> Vec3 {
    let clip = glam::Mat4::from_cols_array_2d(&light.clip_from_world) * world_pos.extend(1.0);
    let ndc = clip.truncate() / clip.w;
    Vec3::new(ndc.x * 0.5 + 0.5, ndc.y * -0.5 + 0.5, ndc.z)
}

/// The uv lies off the shadow map. Written as "not inside", like the shader, so NaN counts as
/// outside.
pub fn outside_map(uv: Vec2) -> bool {
    !(uv.x >= 0.0 && uv.y >= 0.0 && uv.x <= 1.0 && uv.y <= 1.0)
}

/// The NDC depth lies outside the map's range, 0..1.
pub fn outside_depth(z: f32) -> bool {
    !(0.0..=1.0).contains(&z)
}

/// The receiver has no shadow-map data: outside the map or past its depth range.
pub fn outside_frustum(coord: &ShadowCoord) -> bool {
    outside_map(coord.uv) || outside_depth(coord.depth_ndc)
}

/// Two unit vectors that span the plane with unit normal n (Duff et al. 2017).
fn tangents_of(n: Vec3) -> [Vec3; 2] {
    let sign = if n.z >= 0.0 { 1.0 } else { -1.0 };
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    [Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x), Vec3::new(b, sign + n.y * n.y * a, -n.y)]
}

/// The receiver's plane (through p, normal n, projected at s) as NDC depth per uv of the map,
/// from two points of the plane a texel from p; 0 edge-on to the light.
pub fn receiver_plane_gradient(light: &LightGpu, p: Vec3, n: Vec3, s: Vec3) -> Vec2 {
    let step = texel_world_at(light, depth_linear_from_ndc(light, s.z));
    let t = tangents_of(n);
    let a = project_to_light(light, p + t[0] * step) - s;
    let b = project_to_light(light, p + t[1] * step) - s;
    let det = a.x * b.y - a.y * b.x;
    let (a_uv, b_uv) = (Vec2::new(a.x, a.y), Vec2::new(b.x, b.y));
    // Also false for NaN, as in the shader.
    let spans_the_map = det.abs() > 1e-3 * a_uv.length() * b_uv.length();
    if !spans_the_map {
        return Vec2::ZERO;
    }
    Vec2::new(a.z * b.y - a.y * b.z, a.x * b.z - a.z * b.x) / det
}

/// The GAMES202 framework's RGBA8 depth round trip (`pack`, 8-bit storage, `unpack`); see the
/// shader's `rgba8_round_trip`.
pub fn rgba8_round_trip(depth_ndc: f32) -> f32 {
    let unpack_shift = Vec4::new(1.0, 1.0 / 256.0, 1.0 / 65_536.0, 1.0 / 16_777_216.0);
    if depth_ndc >= 1.0 {
        return ((unpack_shift.x + unpack_shift.y) + unpack_shift.z) + unpack_shift.w;
    }
    let scaled = depth_ndc * Vec4::new(1.0, 256.0, 65_536.0, 16_777_216.0);
    let mut rgba = scaled - scaled.floor();
    rgba -= Vec4::new(rgba.y, rgba.z, rgba.w, rgba.w) * Vec4::new(1.0 / 256.0, 1.0 / 256.0, 1.0 / 256.0, 0.0);
    let quantised = (rgba.clamp(Vec4::ZERO, Vec4::ONE) * 255.0).to_array().map(f32::round_ties_even);
    let parts = Vec4::from_array(quantised) * (1.0 / 255.0) * unpack_shift;
    ((parts.x + parts.y) + parts.z) + parts.w
}

/// The light-space lookup of a surface point (the shader's `light_space_lookup`): it needs the
/// light and the parameters, not the map.
pub fn light_space_lookup(
    light: &LightGpu,
    params: &ShadowParamsGpu,
    world_pos: Vec3,
    normal: Vec3,
) -> ShadowCoord {
    let mut out = ShadowCoord { n_dot_l: normal.dot(light_dir_to(light, world_pos)), ..Default::default() };
    let mut p = world_pos;
    if params.normal_offset_texels > 0.0 {
        let d = depth_linear_from_ndc(light, project_to_light(light, world_pos).z);
        p = world_pos + normal * (params.normal_offset_texels * texel_world_at(light, d));
    }
    let s = project_to_light(light, p);
    out.uv = Vec2::new(s.x, s.y);
    out.depth_ndc = s.z;
    out.depth_linear = depth_linear_from_ndc(light, s.z);
    if params.bias_mode == BIAS_RECEIVER_PLANE {
        out.depth_gradient = receiver_plane_gradient(light, p, normal, s);
    }
    out
}

/// WGSL `fract`: x - floor(x) (Rust's `f32::fract` truncates towards zero instead).
fn wgsl_fract(v: Vec2) -> Vec2 {
    v - v.floor()
}

impl<'a> Twin<'a> {
    pub fn new(light: &'a LightGpu, params: &'a ShadowParamsGpu, map: &'a DepthImage) -> Self {
        Self { light, params, map, trace: None, moments: std::cell::OnceCell::new() }
    }

    fn record(&mut self, kind: TapKind, uv: Vec2, value: f32) {
        if let Some(trace) = &mut self.trace {
            trace.push(Tap { kind, uv, value });
        }
    }

    pub fn light_space_lookup(&self, world_pos: Vec3, normal: Vec3) -> ShadowCoord {
        light_space_lookup(self.light, self.params, world_pos, normal)
    }

    /// Texels per side of the array the light's map shares (its map is the top-left corner).
    fn atlas_size(&self) -> u32 {
        (self.light.map_size_texels / self.light.atlas_scale).round() as u32
    }

    pub fn receiver_bias_ndc(&self, coord: &ShadowCoord, filter_radius_texels: f32) -> f32 {
        let p = self.params;
        match p.bias_mode {
            BIAS_CONSTANT => p.bias,
            BIAS_SLOPE => (p.slope_bias * (1.0 - coord.n_dot_l)).max(p.bias),
            BIAS_RECEIVER_PLANE => p.bias,
            BIAS_ADAPTIVE => {
                let a = (1.0 + filter_radius_texels.ceil())
                    * 0.5
                    * texel_world_at(self.light, coord.depth_linear);
                let b = 1.0 - coord.n_dot_l;
                let bias_world = p.adaptive_c * a.max(a * b);
                bias_world * ndc_per_world(self.light, coord.depth_linear)
            }
            _ => 0.0,
        }
    }

    /// Texel (x, y) of the light's map; texels of the array layer beyond the light's map size
    /// hold the clear value 1.
    fn texel(&self, x: i32, y: i32) -> f32 {
        let size = self.map.size as i32;
        if x < 0 || y < 0 || x >= size || y >= size {
            return 1.0;
        }
        self.map.depth_ndc[(y * size + x) as usize]
    }

    pub fn stored_depth_ndc(&self, uv: Vec2) -> f32 {
        let depth = self.stored_depth_float_ndc(uv);
        if self.params.depth_storage == DEPTH_RGBA8 { rgba8_round_trip(depth) } else { depth }
    }

    /// The depth the shadow pass wrote at a uv, before any RGBA8 round trip.
    pub fn stored_depth_float_ndc(&self, uv: Vec2) -> f32 {
        let lookup = if self.params.clamp_outside == 0 { wgsl_fract(uv) } else { uv };
        let size = self.light.map_size_texels as i32;
        let t = (lookup * self.light.map_size_texels).floor();
        self.texel((t.x as i32).clamp(0, size - 1), (t.y as i32).clamp(0, size - 1))
    }

    /// The comparison sampler's bilinear 2x2 test (clamp to edge over the whole array layer).
    fn hardware_compare(&self, uv: Vec2, reference: f32) -> f32 {
        let atlas = self.atlas_size() as f32;
        let p = uv * self.light.atlas_scale * atlas - Vec2::splat(0.5);
        let i0 = p.floor();
        let f = p - i0;
        let max = atlas as i32 - 1;
        let test = |dx: i32, dy: i32| {
            let x = (i0.x as i32 + dx).clamp(0, max);
            let y = (i0.y as i32 + dy).clamp(0, max);
            if reference <= self.texel(x, y) { 1.0 } else { 0.0 }
        };
        let top = test(0, 0) * (1.0 - f.x) + test(1, 0) * f.x;
        let bottom = test(0, 1) * (1.0 - f.x) + test(1, 1) * f.x;
        top * (1.0 - f.y) + bottom * f.y
    }

    /// The depth a tap at `uv` compares the map's with (see the shader's `tap_reference_ndc`).
    pub fn tap_reference_ndc(
        &self,
        coord: &ShadowCoord,
        uv: Vec2,
        bias_ndc: f32,
        point_sampled: bool,
    ) -> f32 {
        if self.params.bias_mode == BIAS_RECEIVER_PLANE {
            let size = self.light.map_size_texels;
            let at = if point_sampled { ((uv * size).floor() + Vec2::splat(0.5)) / size } else { uv };
            return coord.depth_ndc + coord.depth_gradient.dot(at - coord.uv) - bias_ndc;
        }
        coord.depth_ndc - bias_ndc
    }

    pub fn depth_test(&self, coord: &ShadowCoord, uv: Vec2, bias_ndc: f32) -> f32 {
        let p = self.params;
        if p.clamp_outside == 1 && (outside_map(uv) || outside_depth(coord.depth_ndc)) {
            return 1.0;
        }
        let bilinear = kernel_from_id(p.kernel) == Kernel::Hardware && p.technique != TECHNIQUE_HARD;
        let reference = self.tap_reference_ndc(coord, uv, bias_ndc, !bilinear);
        if bilinear {
            let lookup = if p.clamp_outside == 0 { wgsl_fract(uv) } else { uv };
            return self.hardware_compare(lookup, reference);
        }
        if reference <= self.stored_depth_ndc(uv) { 1.0 } else { 0.0 }
    }

    pub fn visibility_hard(&mut self, coord: &ShadowCoord) -> f32 {
        let bias = self.receiver_bias_ndc(coord, 0.0);
        let p = self.params;
        let outside = p.clamp_outside == 1 && outside_frustum(coord);
        let lit =
            outside || self.tap_reference_ndc(coord, coord.uv, bias, true) <= self.stored_depth_ndc(coord.uv);
        let v = if lit { 1.0 } else { 0.0 };
        self.record(TapKind::Filter, coord.uv, v);
        v
    }

    pub fn visibility_pcf(&mut self, coord: &ShadowCoord, radius_texels: f32, seed: u32) -> f32 {
        let kernel = kernel_from_id(self.params.kernel);
        let n = filter_taps(kernel, self.params.samples);
        let radius_uv = radius_texels / self.light.map_size_texels;
        let bias = self.receiver_bias_ndc(coord, radius_texels);
        let mut lit = 0.0;
        for i in 0..n {
            let uv = coord.uv + kernel_offset(kernel, i, n, seed) * radius_uv;
            let v = self.depth_test(coord, uv, bias);
            self.record(TapKind::Filter, uv, v);
            lit += v;
        }
        lit / n as f32
    }

    /// The blocker search's radius in uv (the shader's `blocker_search_radius_uv`).
    pub fn blocker_search_radius_uv(&self, coord: &ShadowCoord) -> f32 {
        let light = self.light;
        let d_r = coord.depth_linear;
        let radius_world = if light.size_model == SIZE_MODEL_ANGULAR {
            (d_r - light.near) * light.tan_half_angle
        } else {
            0.5 * light.light_width_world * (d_r - light.near) / d_r
        };
        radius_world.max(0.0) * self.params.search_radius_scale / light.frustum_width_world
    }

    pub fn search_blockers(&mut self, coord: &ShadowCoord, seed: u32) -> BlockerSearch {
        let light = self.light;
        let mut out = BlockerSearch::default();
        if self.params.clamp_outside == 1 && outside_frustum(coord) {
            return out;
        }
        let radius_uv = self.blocker_search_radius_uv(coord);
        out.radius_texels = radius_uv * light.map_size_texels;
        let mut kernel = kernel_from_id(self.params.kernel);
        if kernel == Kernel::Hardware {
            kernel = Kernel::Vogel;
        }
        let n = filter_taps(kernel, self.params.blocker_samples);
        let bias = self.receiver_bias_ndc(coord, 0.0);
        let mut sum = 0.0;
        for i in 0..n {
            let uv = coord.uv + kernel_offset(kernel, i, n, seed) * radius_uv;
            if self.params.clamp_outside == 1 && outside_map(uv) {
                self.record(TapKind::BlockerSearch, uv, 0.0);
                continue;
            }
            let z = self.stored_depth_ndc(uv);
            let blocker = z < self.tap_reference_ndc(coord, uv, bias, true);
            self.record(TapKind::BlockerSearch, uv, if blocker { 1.0 } else { 0.0 });
            if blocker {
                out.found += 1;
                sum += depth_linear_from_ndc(light, z);
            }
        }
        if out.found > 0 {
            out.avg_depth_linear = sum / out.found as f32;
        }
        out
    }

    pub fn estimate_penumbra(&self, coord: &ShadowCoord, d_blocker: f32) -> Penumbra {
        let light = self.light;
        let d_r = coord.depth_linear;
        let gap = (d_r - d_blocker).max(0.0);
        let width_world = if light.size_model == SIZE_MODEL_ANGULAR {
            gap * 2.0 * light.tan_half_angle
        } else {
            light.light_width_world * gap / d_blocker.max(1e-6)
        };
        let mut radius_uv = 0.5 * width_world / light.frustum_width_world;
        if !orthographic(light) || self.params.ortho_near_factor == 1 {
            radius_uv = radius_uv * light.near / d_r;
        }
        Penumbra {
            width_world,
            filter_radius_texels: (radius_uv * light.map_size_texels)
                .max(self.params.min_filter_radius_texels),
        }
    }

    pub fn visibility_pcss(&mut self, coord: &ShadowCoord, seed: u32) -> PcssResult {
        let mut out = PcssResult { search: self.search_blockers(coord, seed), ..Default::default() };
        if out.search.found == 0 {
            out.visibility = 1.0;
            return out;
        }
        out.penumbra = self.estimate_penumbra(coord, out.search.avg_depth_linear);
        out.visibility = self.visibility_pcf(coord, out.penumbra.filter_radius_texels, seed);
        out
    }

    /// The VSM moments of the map, built on first use.
    pub fn moments(&self) -> &moments::MomentsChain {
        let (atlas, map, block) = (self.atlas_size(), self.map, self.light.moments_block);
        self.moments.get_or_init(|| moments::MomentsChain::new(map, atlas, block))
    }

    /// VSM: Chebyshev's one-sided bound on the filtered moments (the shader's `visibility_vsm`).
    pub fn visibility_vsm(&mut self, coord: &ShadowCoord, radius_texels: f32) -> f32 {
        if self.params.clamp_outside == 1 && outside_frustum(coord) {
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
        let m = self.moments().filtered(self.light, coord.uv, radius_texels);
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
        let coord = light_space_lookup(self.light, &plane_params, world_pos, normal);
        let size = self.light.map_size_texels;
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
        let (light, chain, atlas) = (self.light, self.moments(), self.atlas_size());
        for (level, level_weight) in chain.levels_for(light, radius_texels) {
            if level_weight == 0.0 {
                continue;
            }
            let fp = chain.footprint(light, coord.uv, level);
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
        if self.params.clamp_outside == 1 && outside_frustum(&coord) {
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
    pub fn visibility_vssm(&mut self, coord: &ShadowCoord) -> PcssResult {
        let mut out = PcssResult { visibility: 1.0, ..Default::default() };
        if self.params.clamp_outside == 1 && outside_frustum(coord) {
            return out;
        }
        let light = self.light;
        out.search.radius_texels = self.blocker_search_radius_uv(coord) * light.map_size_texels;
        let m = self.moments().filtered(light, coord.uv, out.search.radius_texels);
        let t = coord.depth_ndc - self.receiver_bias_ndc(coord, 0.0);
        let unoccluded = self.chebyshev_upper_bound(m, t);
        self.record(TapKind::BlockerSearch, coord.uv, 1.0 - unoccluded);
        if unoccluded >= 1.0 {
            return out;
        }
        let z_occ = (m.x - unoccluded * t) / (1.0 - unoccluded);
        out.search.found = 1;
        out.search.avg_depth_linear = depth_linear_from_ndc(light, z_occ.clamp(0.0, 1.0));
        out.penumbra = self.estimate_penumbra(coord, out.search.avg_depth_linear);
        out.visibility = self.visibility_vsm(coord, out.penumbra.filter_radius_texels);
        out
    }

    pub fn shadow_visibility(&mut self, coord: &ShadowCoord, seed: u32) -> PcssResult {
        match self.params.technique {
            TECHNIQUE_PCF => PcssResult {
                visibility: self.visibility_pcf(coord, self.params.radius_texels, seed),
                ..Default::default()
            },
            TECHNIQUE_PCSS => self.visibility_pcss(coord, seed),
            TECHNIQUE_NONE => PcssResult { visibility: 1.0, ..Default::default() },
            TECHNIQUE_VSM => PcssResult {
                visibility: self.visibility_vsm(coord, self.params.radius_texels),
                ..Default::default()
            },
            TECHNIQUE_VSSM => self.visibility_vssm(coord),
            _ => PcssResult { visibility: self.visibility_hard(coord), ..Default::default() },
        }
    }

    /// What the analysis pass writes for a pixel: the twin of `fs_analysis`.
    pub fn analysis_at(
        &mut self,
        pixel: (u32, u32),
        world_pos: Vec3,
        normal: Vec3,
    ) -> (ShadowCoord, PcssResult) {
        let seed = kernels::pixel_seed(pixel, self.params.noise_seed, self.params.rotate_per_pixel == 1);
        let coord = self.light_space_lookup(world_pos, normal);
        let result = self.shadow_visibility(&coord, seed);
        (coord, result)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The homework's pack / RGBA8 / unpack round trip: channels in 1/256 steps kept in 1/255
    /// steps give +z/255 below the middle of the depth range and -(1 - z)/255 above it; the
    /// clear colour, white, reads back just past 1.
    #[test]
    fn the_rgba8_round_trip_is_off_by_about_a_255th_with_a_sign_change_at_half_depth() {
        for z in [0.05f32, 0.2, 0.3, 0.45, 0.5] {
            let error = rgba8_round_trip(z) - z;
            assert!((error - z / 255.0).abs() < 2e-5, "z {z}: error {error}");
        }
        for z in [0.51f32, 0.6, 0.8, 0.99] {
            let error = rgba8_round_trip(z) - z;
            assert!((error + (1.0 - z) / 255.0).abs() < 2e-5, "z {z}: error {error}");
        }
        let white = 1.0 + 1.0 / 256.0 + 1.0 / 65_536.0 + 1.0 / 16_777_216.0;
        assert_eq!(rgba8_round_trip(1.0), white);
        // Monotone within each half: a nearer depth never reads back farther.
        let samples: Vec<f32> = (0..2000).map(|i| i as f32 / 4000.0).collect();
        for w in samples.windows(2) {
            assert!(rgba8_round_trip(w[0]) <= rgba8_round_trip(w[1]), "{w:?}");
        }
    }

    #[test]
    fn nan_counts_as_outside_the_map_as_in_the_shader() {
        assert!(outside_map(Vec2::new(f32::NAN, 0.5)));
        assert!(outside_depth(f32::NAN));
        assert!(!outside_map(Vec2::new(0.0, 1.0)));
        assert!(outside_map(Vec2::new(-1e-6, 0.5)));
    }
}

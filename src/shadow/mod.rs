//! The CPU twin of shaders/shadow_lookup.wgsl (light_space.rs) and shaders/shadow_filter.wgsl
//! (this file, kernels.rs and vsm.rs): the same functions with the same names and units, run on
//! a read-back shadow map. It powers the pixel probe and the tests that hold the
//! GPU to the maths. A formula is fixed in both places or in neither.

pub mod cascades;
pub mod gpu;
pub mod kernels;
mod light_space;
pub mod moments;
mod vsm;

use crate::scene::Kernel;
use glam::{Vec2, Vec3};
pub use gpu::{
    BIAS_ADAPTIVE, BIAS_CONSTANT, BIAS_RECEIVER_PLANE, BIAS_SLOPE, CASCADE_BORDER_TEXELS,
    CASCADE_BY_INTERVAL, CASCADE_BY_MAP, DEPTH_RGBA8, LightGpu, LightViewGpu, SIZE_MODEL_ANGULAR,
    ShadowParamsGpu, ShadowViewGpu, TECHNIQUE_HARD, TECHNIQUE_NONE, TECHNIQUE_PCF, TECHNIQUE_PCSS,
    TECHNIQUE_VSM, TECHNIQUE_VSSM, frame_lights, kernel_from_id, views_needed,
};
use kernels::{filter_taps, kernel_offset};
pub use light_space::{
    blocker_search_radius_uv, cascade_holds, cube_face_axes, cube_face_uv, cube_face_view,
    depth_linear_from_ndc, depth_ndc_from_linear, face_covering, in_cascade_slice, light_dir_to,
    light_space_lookup, map_tap, ndc_per_world, no_map_data, off_axis_sec, outside_depth, outside_frustum,
    outside_map, project_to_light, read_texel_centre_uv, receiver_bias_ndc, receiver_plane_gradient,
    rgba8_round_trip, texel_world_at, view_axis_depth, view_covering,
};

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

/// What [`Twin::shadow_visibility`] returns for a technique id it does not know: no visibility is
/// negative, so a missing case shows (the shader's `VISIBILITY_UNKNOWN_TECHNIQUE`).
pub const VISIBILITY_UNKNOWN_TECHNIQUE: f32 = -1.0;

/// A lookup's visibility (0 shadowed .. 1 lit), with the blocker search and penumbra behind it
/// where the technique has them (PCSS, VSSM; zeros otherwise).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ShadowVisibility {
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

/// One light, the shadow view a lookup reads, its map and the parameters, as the GPU had them.
pub struct Twin<'a> {
    pub light: &'a LightGpu,
    pub view: &'a ShadowViewGpu,
    pub params: &'a ShadowParamsGpu,
    pub map: &'a DepthImage,
    /// A cube face's view: the light's six maps, by face (a filter's taps cross onto the others).
    pub cube_maps: Option<&'a [DepthImage]>,
    /// When Some, every lookup is recorded.
    pub trace: Option<Vec<Tap>>,
    /// The VSM moments of `map`, built on first use.
    moments: std::cell::OnceCell<moments::MomentsChain>,
}

/// WGSL `fract`: x - floor(x) (Rust's `f32::fract` truncates towards zero instead).
fn wgsl_fract(v: Vec2) -> Vec2 {
    v - v.floor()
}

/// PCSS step 2 (the shader's `estimate_penumbra`): the penumbra's width on a receiver at
/// `d_receiver` (world units from the light, landing at `receiver_uv`) behind blockers averaging
/// `d_blocker`, by similar triangles [Fernando-2005], and the filter radius in map texels that
/// covers it (on a cube face off its axis, times sec^1.5(theta): [`off_axis_sec`]).
pub fn estimate_penumbra(
    light: &LightGpu,
    view: &ShadowViewGpu,
    params: &ShadowParamsGpu,
    d_receiver: f32,
    receiver_uv: Vec2,
    d_blocker: f32,
) -> Penumbra {
    let gap = (d_receiver - d_blocker).max(0.0);
    let width_world = if light.size_model == SIZE_MODEL_ANGULAR {
        gap * 2.0 * light.tan_half_angle
    } else {
        light.light_width_world * gap / d_blocker.max(1e-6)
    };
    let mut radius_uv = 0.5 * width_world / view.frustum_width_world;
    if view.orthographic == 0 || params.ortho_near_factor == 1 {
        radius_uv = radius_uv * view.near / d_receiver;
    }
    let sec = off_axis_sec(view, receiver_uv);
    radius_uv *= sec * sec.sqrt();
    Penumbra {
        width_world,
        filter_radius_texels: (radius_uv * view.map_size_texels).max(params.min_filter_radius_texels),
    }
}

/// [`estimate_penumbra`] the other way round: the average blocker depth (world units from the
/// light) that gives a penumbra `width_world` wide on a receiver at `d_receiver`,
/// d_blocker = w_light d_r / (w_p + w_light) for a width, d_r - w_p / (2 tan(theta / 2)) for an
/// angle. None where the light has no size (every blocker depth then gives no penumbra).
pub fn blocker_depth_from_penumbra(light: &LightGpu, d_receiver: f32, width_world: f32) -> Option<f32> {
    let d_blocker = if light.size_model == SIZE_MODEL_ANGULAR {
        (light.tan_half_angle > 0.0).then(|| d_receiver - width_world / (2.0 * light.tan_half_angle))
    } else {
        (light.light_width_world > 0.0)
            .then(|| light.light_width_world * d_receiver / (width_world + light.light_width_world))
    };
    d_blocker.filter(|d| d.is_finite())
}

/// The radius (map texels) a technique's filter uses: fixed for PCF and VSM, the penumbra's for
/// PCSS and VSSM (`penumbra`: where the blocker search found something), none for hard shadows.
pub fn filter_radius_texels(params: &ShadowParamsGpu, penumbra: Option<&Penumbra>) -> f32 {
    match params.technique {
        TECHNIQUE_PCF | TECHNIQUE_VSM => params.radius_texels,
        TECHNIQUE_PCSS | TECHNIQUE_VSSM => penumbra.map_or(0.0, |p| p.filter_radius_texels),
        _ => 0.0,
    }
}

/// The pattern the blocker search takes: the filter's, except that the hardware kernel (2x2
/// bilinear comparisons) has no depths to average and searches with Vogel's positions.
pub fn search_kernel(filter_kernel: Kernel) -> Kernel {
    if filter_kernel == Kernel::Hardware { Kernel::Vogel } else { filter_kernel }
}

impl<'a> Twin<'a> {
    pub fn new(
        light: &'a LightGpu,
        view: &'a ShadowViewGpu,
        params: &'a ShadowParamsGpu,
        map: &'a DepthImage,
    ) -> Self {
        Self { light, view, params, map, cube_maps: None, trace: None, moments: std::cell::OnceCell::new() }
    }

    /// A point light's twin on cube face `view.face`, with all six of its maps (`maps[face]`).
    pub fn cube(
        light: &'a LightGpu,
        view: &'a ShadowViewGpu,
        params: &'a ShadowParamsGpu,
        maps: &'a [DepthImage],
    ) -> Self {
        assert_eq!(maps.len(), 6, "a point light has six maps");
        Self { cube_maps: Some(maps), ..Self::new(light, view, params, &maps[view.face as usize]) }
    }

    /// A twin for each of a light's `views` over its `maps` (the same order): one for a spot or
    /// directional light, six for a point light's faces (each reading all six). Pick the one
    /// that covers a point with `view_covering` (less the light's `first_view`).
    pub fn for_views(
        light: &'a LightGpu,
        views: &'a [ShadowViewGpu],
        params: &'a ShadowParamsGpu,
        maps: &'a [DepthImage],
    ) -> Vec<Self> {
        assert_eq!(views.len(), maps.len(), "one map per view");
        views
            .iter()
            .zip(maps)
            .map(|(view, map)| {
                if view.cube == 1 {
                    Self::cube(light, view, params, maps)
                } else {
                    Self::new(light, view, params, map)
                }
            })
            .collect()
    }

    /// The map a tap on `view` reads: a cube face's own, else the twin's one map.
    fn map_of(&self, view: &ShadowViewGpu) -> &'a DepthImage {
        match self.cube_maps {
            Some(maps) => &maps[view.face as usize],
            None => self.map,
        }
    }

    fn record(&mut self, kind: TapKind, uv: Vec2, value: f32) {
        if let Some(trace) = &mut self.trace {
            trace.push(Tap { kind, uv, value });
        }
    }

    pub fn light_space_lookup(&self, world_pos: Vec3, normal: Vec3) -> ShadowCoord {
        light_space_lookup(self.light, self.view, self.params, world_pos, normal)
    }

    /// Texels per side of the array the view's map shares (its map is the top-left corner).
    fn atlas_size(&self) -> u32 {
        (self.view.map_size_texels / self.view.atlas_scale).round() as u32
    }

    pub fn receiver_bias_ndc(&self, coord: &ShadowCoord, filter_radius_texels: f32) -> f32 {
        receiver_bias_ndc(self.view, self.params, coord, filter_radius_texels)
    }

    /// Texel (x, y) of a map; texels of the array layer beyond the view's map size hold the
    /// clear value 1.
    fn texel(map: &DepthImage, x: i32, y: i32) -> f32 {
        let size = map.size as i32;
        if x < 0 || y < 0 || x >= size || y >= size {
            return 1.0;
        }
        map.depth_ndc[(y * size + x) as usize]
    }

    /// The stored depth a tap at `uv` of the lookup's view reads (on a cube, past the face's edge:
    /// on the face the tap's direction falls in, `map_tap`).
    pub fn stored_depth_ndc(&self, uv: Vec2) -> f32 {
        let (view, uv) = map_tap(self.view, uv);
        self.stored_depth_on(&view, uv)
    }

    /// The stored depth at `uv` of `view`'s own map.
    fn stored_depth_on(&self, view: &ShadowViewGpu, uv: Vec2) -> f32 {
        let depth = self.stored_depth_float_on(view, uv);
        if self.params.depth_storage == DEPTH_RGBA8 { rgba8_round_trip(depth) } else { depth }
    }

    /// The depth the shadow pass wrote at a uv of the lookup's view, before any RGBA8 round trip.
    pub fn stored_depth_float_ndc(&self, uv: Vec2) -> f32 {
        self.stored_depth_float_on(self.view, uv)
    }

    fn stored_depth_float_on(&self, view: &ShadowViewGpu, uv: Vec2) -> f32 {
        let lookup = if self.params.clamp_outside == 0 { wgsl_fract(uv) } else { uv };
        let size = view.map_size_texels as i32;
        let t = (lookup * view.map_size_texels).floor();
        Self::texel(self.map_of(view), (t.x as i32).clamp(0, size - 1), (t.y as i32).clamp(0, size - 1))
    }

    /// The comparison sampler's bilinear 2x2 test on `map` (clamp to edge over the whole array
    /// layer).
    fn hardware_compare(&self, map: &DepthImage, uv: Vec2, reference: f32) -> f32 {
        let atlas = self.atlas_size() as f32;
        let p = uv * self.view.atlas_scale * atlas - Vec2::splat(0.5);
        let i0 = p.floor();
        let f = p - i0;
        let max = atlas as i32 - 1;
        let test = |dx: i32, dy: i32| {
            let x = (i0.x as i32 + dx).clamp(0, max);
            let y = (i0.y as i32 + dy).clamp(0, max);
            if reference <= Self::texel(map, x, y) { 1.0 } else { 0.0 }
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
            let at = if point_sampled { read_texel_centre_uv(self.view, self.params, uv) } else { uv };
            return coord.depth_ndc + coord.depth_gradient.dot(at - coord.uv) - bias_ndc;
        }
        coord.depth_ndc - bias_ndc
    }

    pub fn depth_test(&self, coord: &ShadowCoord, uv: Vec2, bias_ndc: f32) -> f32 {
        let p = self.params;
        let (tap_view, tap_uv) = map_tap(self.view, uv);
        if p.clamp_outside == 1 && (outside_map(tap_uv) || outside_depth(coord.depth_ndc)) {
            return 1.0;
        }
        let bilinear = kernel_from_id(p.kernel) == Kernel::Hardware && p.technique != TECHNIQUE_HARD;
        let reference = self.tap_reference_ndc(coord, uv, bias_ndc, !bilinear);
        if bilinear {
            let lookup = if p.clamp_outside == 0 { wgsl_fract(tap_uv) } else { tap_uv };
            return self.hardware_compare(self.map_of(&tap_view), lookup, reference);
        }
        if reference <= self.stored_depth_on(&tap_view, tap_uv) { 1.0 } else { 0.0 }
    }

    pub fn visibility_hard(&mut self, coord: &ShadowCoord) -> f32 {
        let bias = self.receiver_bias_ndc(coord, 0.0);
        let p = self.params;
        let (tap_view, tap_uv) = map_tap(self.view, coord.uv);
        let outside = p.clamp_outside == 1 && (no_map_data(self.view, coord) || outside_map(tap_uv));
        let lit = outside
            || self.tap_reference_ndc(coord, coord.uv, bias, true) <= self.stored_depth_on(&tap_view, tap_uv);
        let v = if lit { 1.0 } else { 0.0 };
        self.record(TapKind::Filter, coord.uv, v);
        v
    }

    pub fn visibility_pcf(&mut self, coord: &ShadowCoord, radius_texels: f32, seed: u32) -> f32 {
        let kernel = kernel_from_id(self.params.kernel);
        let n = filter_taps(kernel, self.params.samples);
        let radius_uv = radius_texels / self.view.map_size_texels;
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
        blocker_search_radius_uv(self.light, self.view, self.params, coord.depth_linear, coord.uv)
    }

    pub fn search_blockers(&mut self, coord: &ShadowCoord, seed: u32) -> BlockerSearch {
        let view = self.view;
        let mut out = BlockerSearch::default();
        if self.params.clamp_outside == 1 && no_map_data(view, coord) {
            return out;
        }
        let radius_uv = self.blocker_search_radius_uv(coord);
        out.radius_texels = radius_uv * view.map_size_texels;
        let kernel = search_kernel(kernel_from_id(self.params.kernel));
        let n = filter_taps(kernel, self.params.blocker_samples);
        let bias = self.receiver_bias_ndc(coord, 0.0);
        let mut sum = 0.0;
        for i in 0..n {
            let uv = coord.uv + kernel_offset(kernel, i, n, seed) * radius_uv;
            let (tap_view, tap_uv) = map_tap(view, uv);
            if self.params.clamp_outside == 1 && outside_map(tap_uv) {
                self.record(TapKind::BlockerSearch, uv, 0.0);
                continue;
            }
            let z = self.stored_depth_on(&tap_view, tap_uv);
            let blocker = z < self.tap_reference_ndc(coord, uv, bias, true);
            self.record(TapKind::BlockerSearch, uv, if blocker { 1.0 } else { 0.0 });
            if blocker {
                out.found += 1;
                sum += depth_linear_from_ndc(view, z);
            }
        }
        if out.found > 0 {
            out.avg_depth_linear = sum / out.found as f32;
        }
        out
    }

    pub fn estimate_penumbra(&self, coord: &ShadowCoord, d_blocker: f32) -> Penumbra {
        estimate_penumbra(self.light, self.view, self.params, coord.depth_linear, coord.uv, d_blocker)
    }

    pub fn visibility_pcss(&mut self, coord: &ShadowCoord, seed: u32) -> ShadowVisibility {
        let mut out = ShadowVisibility { search: self.search_blockers(coord, seed), ..Default::default() };
        if out.search.found == 0 {
            out.visibility = 1.0;
            return out;
        }
        out.penumbra = self.estimate_penumbra(coord, out.search.avg_depth_linear);
        out.visibility = self.visibility_pcf(coord, out.penumbra.filter_radius_texels, seed);
        out
    }

    pub fn shadow_visibility(&mut self, coord: &ShadowCoord, seed: u32) -> ShadowVisibility {
        match self.params.technique {
            TECHNIQUE_PCF => ShadowVisibility {
                visibility: self.visibility_pcf(coord, self.params.radius_texels, seed),
                ..Default::default()
            },
            TECHNIQUE_PCSS => self.visibility_pcss(coord, seed),
            TECHNIQUE_NONE => ShadowVisibility { visibility: 1.0, ..Default::default() },
            TECHNIQUE_VSM => ShadowVisibility {
                visibility: self.visibility_vsm(coord, self.params.radius_texels),
                ..Default::default()
            },
            TECHNIQUE_VSSM => self.visibility_vssm(coord),
            TECHNIQUE_HARD => {
                ShadowVisibility { visibility: self.visibility_hard(coord), ..Default::default() }
            }
            // As the shader: an id no arm knows is an impossible visibility a test sees.
            _ => ShadowVisibility { visibility: VISIBILITY_UNKNOWN_TECHNIQUE, ..Default::default() },
        }
    }

    /// What the analysis pass writes for a pixel: the twin of `fs_analysis`.
    pub fn analysis_at(
        &mut self,
        pixel: (u32, u32),
        world_pos: Vec3,
        normal: Vec3,
    ) -> (ShadowCoord, ShadowVisibility) {
        let seed = kernels::pixel_seed(pixel, self.params.noise_seed, self.params.rotate_per_pixel == 1);
        let coord = self.light_space_lookup(world_pos, normal);
        let result = self.shadow_visibility(&coord, seed);
        (coord, result)
    }
}

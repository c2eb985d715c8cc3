//! The pixel probe: everything about the surface under one camera pixel, per light — from the
//! GPU's analysis pass, the CPU twin (every intermediate value and tap) and the ground truth.

use crate::render::{AnalysisPixel, Frame, FrameRequest, GpuWait, Readback, RenderError, Renderer};
use crate::scene::{BiasMode, DepthStorage, Scene, Technique};
use crate::shadow::DepthImage;
use crate::shadow::{TapKind, Twin, kernels};

mod view_read;
use glam::Vec3;
use serde::{Deserialize, Serialize};
use view_read::cascade_probe;
pub use view_read::{CUBE_FACE_NAMES, CascadeProbe};

#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct TapReport {
    /// "blocker-search" or "filter".
    pub kind: String,
    pub uv: [f32; 2],
    /// Blocker search: 1 = blocker. Filter: lit fraction of the tap.
    pub value: f32,
}

#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct LightProbe {
    pub light: usize,
    /// The shadow view (of the frame's views) the pixel was looked up in: the light's own map,
    /// or a point light's cube face towards the pixel.
    pub shadow_view: usize,
    /// A point light only: which face of its cube ("+X", "-X", "+Y", "-Y", "+Z", "-Z").
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cube_face: Option<String>,
    /// A sun with cascades only: which one was read and why not a sharper one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cascade: Option<CascadeProbe>,
    pub shadow_map_uv: [f32; 2],
    pub shadow_map_texel: [i32; 2],
    pub inside_light_frustum: bool,
    pub n_dot_l: f32,
    pub receiver_depth_ndc: f32,
    pub receiver_depth_linear: f32,
    pub stored_depth_ndc: f32,
    pub stored_depth_linear: f32,
    pub bias_ndc: f32,
    /// Receiver-plane bias only: how much the receiver's plane recedes from the light per texel
    /// of the map, along its steepest direction, world units (what the per-tap plane adds).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub receiver_plane_depth_per_texel_world: Option<f32>,
    /// RGBA8 depth storage only: the stored depth after the pack / 8-bit / unpack round trip
    /// minus the float depth the shadow pass wrote, NDC.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stored_depth_rgba8_error_ndc: Option<f32>,
    /// VSM and VSSM only: the filter's moments lookup, Chebyshev's bound and the true lit
    /// fraction of the same footprint.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub vsm: Option<VsmProbe>,
    /// VSSM only: its blocker-depth estimate beside the true average of the same search
    /// footprint and PCSS's sampled average.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub vssm: Option<VssmProbe>,
    pub blocker_search_radius_uv: f32,
    pub blocker_search_radius_texels: f32,
    pub blockers_found: u32,
    pub blocker_samples: u32,
    /// d_blocker, world units; None where no blocker was found (or the technique has no search).
    pub avg_blocker_depth_linear: Option<f32>,
    pub penumbra_width_world: f32,
    pub filter_radius_uv: f32,
    pub filter_radius_texels: f32,
    pub filter_samples: u32,
    pub visibility_gpu: f32,
    pub visibility_twin: f32,
    pub visibility_reference: Option<f32>,
    pub taps: Vec<TapReport>,
}

#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct VsmProbe {
    pub mean_depth_ndc: f32,
    /// sigma² = E[z²] - E[z]², NDC² (before the minimum variance).
    pub variance_ndc2: f32,
    /// The depth tested (the receiver's less the bias), NDC.
    pub tested_depth_ndc: f32,
    /// Chebyshev's one-sided bound.
    pub chebyshev_bound: f32,
    /// The visibility VSM gives: the bound after the bleed reduction (the bound when it is off).
    pub visibility: f32,
    /// The settings the bound was taken with: the least variance (NDC²) and the bleed reduction.
    pub min_variance_ndc2: f32,
    pub bleed_reduction: f32,
    /// The share of the same footprint's depths at or behind the tested depth; the bound is
    /// never below it.
    pub true_lit_fraction: f32,
    /// The share of the same footprint not nearer than the receiver's own plane at each texel
    /// (less the bias): an exact filter of the window that does not shadow a tilted receiver
    /// with itself. The visibility above it is light bleeding.
    pub plane_lit_fraction: f32,
    /// The footprint's depth distribution: `HISTOGRAM_BINS` weights (summing to 1) over
    /// `histogram_range_ndc`, which also spans the tested depth.
    pub histogram_range_ndc: [f32; 2],
    pub histogram: Vec<f32>,
}

/// Bins of [`VsmProbe::histogram`].
pub const HISTOGRAM_BINS: usize = 48;

#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct VssmProbe {
    /// Chebyshev's bound on the unoccluded share over the search region.
    pub unoccluded_bound: f32,
    /// z_occ = (z_avg - P t) / (1 - P), as a linear depth: VSSM's average blocker depth, world units.
    pub estimated_blocker_depth_linear: f32,
    /// The true average depth of the texels nearer than t in the same footprint, world units:
    /// their mean NDC depth taken to a linear depth, as VSSM's own estimate is (so the two differ
    /// only by the estimate's assumptions); None where there are none.
    pub footprint_blocker_depth_linear: Option<f32>,
    /// PCSS's sampled blocker average at this pixel with the same settings, world units; None
    /// where its search finds nothing.
    pub pcss_blocker_depth_linear: Option<f32>,
}

#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct ProbeReport {
    pub pixel: [u32; 2],
    pub size: [u32; 2],
    pub time_s: f32,
    pub technique: Technique,
    pub hit: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub object: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub world_position: Option<[f32; 3]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub normal: Option<[f32; 3]>,
    pub lights: Vec<LightProbe>,
}

/// Probe `pixel` of the frame described by `request` (which is rendered here, once per light);
/// with `with_reference`, each light's ground truth at the pixel too.
pub fn probe(
    renderer: &mut Renderer,
    scene: &Scene,
    request: &FrameRequest,
    pixel: (u32, u32),
    with_reference: bool,
) -> Result<ProbeReport, RenderError> {
    let mut probing = Probing::start(renderer, scene, request, pixel)?;
    probing.with_reference = with_reference;
    loop {
        probing = match probing.advance(renderer, scene, GpuWait::Block)? {
            Probed::Waiting(probing) => *probing,
            Probed::Done(report) => return Ok(report),
        };
    }
}

/// A probe on its way, a light at a time: each light's frame (the analysis pass at the one pixel)
/// is rendered and its read-backs submitted, and the twin works on them once they are there, so
/// that a caller which cannot wait for the GPU returns between lights.
pub struct Probing {
    request: FrameRequest,
    pixel: (u32, u32),
    /// Work out each light's ground truth at the pixel too (waiting for the GPU).
    with_reference: bool,
    report: ProbeReport,
    /// The light rendered last, its frame, and the pixel's analysis and its map on their way.
    light: usize,
    frame: Frame,
    coming: LightReadbacks,
}

/// The pixel's analysis and every map of the light (a point light's six faces; none without a light).
type LightReadbacks = Readback<(AnalysisPixel, Vec<DepthImage>)>;

/// Where a probe is after `Probing::advance`.
pub enum Probed {
    /// Read-backs are on their way: advance again later.
    Waiting(Box<Probing>),
    Done(ProbeReport),
}

impl Probing {
    /// Check the pixel, render the first light's frame and submit its read-backs.
    pub fn start(
        renderer: &mut Renderer,
        scene: &Scene,
        request: &FrameRequest,
        pixel: (u32, u32),
    ) -> Result<Self, RenderError> {
        let (w, h) = request.size;
        if pixel.0 >= w || pixel.1 >= h {
            return Err(RenderError::Usage(format!(
                "pixel {},{} is outside the {w}x{h} image",
                pixel.0, pixel.1
            )));
        }
        let report = ProbeReport {
            pixel: [pixel.0, pixel.1],
            size: [w, h],
            time_s: request.time_s,
            technique: scene.shadow.technique,
            hit: false,
            object: None,
            world_position: None,
            normal: None,
            lights: Vec::new(),
        };
        let (frame, coming) = submit_light(renderer, scene, request, pixel, 0)?;
        Ok(Self { request: *request, pixel, with_reference: false, report, light: 0, frame, coming })
    }

    /// Once the read-backs of the light rendered last are there (asking as `wait` says): its
    /// numbers, then the next light's frame is rendered and its read-backs submitted.
    pub fn advance(
        self,
        renderer: &mut Renderer,
        scene: &Scene,
        wait: GpuWait,
    ) -> Result<Probed, RenderError> {
        if !self.coming.arrived(renderer.device(), wait)? {
            return Ok(Probed::Waiting(Box::new(self)));
        }
        let Self { request, pixel, with_reference, mut report, light, frame, coming } = self;
        let (here, maps) = coming.finish()?;
        if here.position[3] <= 0.5 {
            return Ok(Probed::Done(report));
        }
        report.hit = true;
        report.world_position = Some([here.position[0], here.position[1], here.position[2]]);
        report.normal = Some([here.normal[0], here.normal[1], here.normal[2]]);
        report.object = scene.objects.get(here.normal[3] as usize).map(|o| o.name.clone());
        // Without lights there is only the surface to report.
        if maps.is_empty() {
            return Ok(Probed::Done(report));
        }
        // The ground truth starts from the light's own frame, the last one rendered.
        let reference = if with_reference {
            let i = (pixel.1 * request.size.0 + pixel.0) as usize;
            Some(renderer.render_reference(scene, light)?[i])
        } else {
            None
        };
        report.lights.push(light_probe(scene, pixel, (light, &frame), &here, &maps, reference));
        let next = light + 1;
        if next >= scene.lights.len() {
            return Ok(Probed::Done(report));
        }
        let (frame, coming) = submit_light(renderer, scene, &request, pixel, next)?;
        Ok(Probed::Waiting(Box::new(Self {
            request,
            pixel,
            with_reference,
            report,
            light: next,
            frame,
            coming,
        })))
    }
}

/// Render light `light`'s frame of the probe (the analysis pass at `pixel`, nothing else shaded)
/// and submit the read-backs of the pixel's analysis and of the light's map.
fn submit_light(
    renderer: &mut Renderer,
    scene: &Scene,
    request: &FrameRequest,
    pixel: (u32, u32),
    light: usize,
) -> Result<(Frame, LightReadbacks), RenderError> {
    let frame = FrameRequest {
        selected_light: light,
        final_color: false,
        analysis: true,
        only_pixel: Some(pixel),
        ..*request
    };
    let rendered = renderer.render(scene, &frame)?;
    let here = renderer.analysis_pixel_readback(pixel.0, pixel.1)?;
    // Every map of the light: which one the pixel reads is known once its position is back.
    let mut maps = Readback::ready(Vec::new());
    if let Some((first, views)) = rendered.views_of(light) {
        for index in first..first + views.len() {
            maps = maps.zip(renderer.shadow_map_readback(index)?).map(|(mut maps, map)| {
                maps.push(map);
                Ok(maps)
            });
        }
    }
    Ok((rendered, here.zip(maps)))
}

/// Everything about light `light` at the probed pixel, from its frame's lights and parameters,
/// the pixel's analysis and the light's map.
fn light_probe(
    scene: &Scene,
    pixel: (u32, u32),
    (light_index, rendered): (usize, &Frame),
    here: &AnalysisPixel,
    maps: &[DepthImage],
    reference: Option<f32>,
) -> LightProbe {
    let position = Vec3::from_slice(&here.position[..3]);
    let normal = Vec3::from_slice(&here.normal[..3]);
    let light_gpu = rendered.lights[light_index];
    // The view the pixel's lookup read (a point light: the cube face towards it).
    let view_index = crate::shadow::view_covering(&light_gpu, &rendered.views, position);
    let view = rendered.views[view_index];
    let params = rendered.params;
    let own = view_index - light_gpu.first_view as usize;
    let mut twin = if view.cube == 1 {
        Twin::cube(&light_gpu, &view, &params, maps)
    } else {
        Twin::new(&light_gpu, &view, &params, &maps[own])
    };
    twin.trace = Some(Vec::new());
    let (coord, result) = twin.analysis_at(pixel, position, normal);
    let penumbra = (result.search.found > 0).then_some(&result.penumbra);
    let filter_radius_texels = crate::shadow::filter_radius_texels(&params, penumbra);
    let map_size = view.map_size_texels;
    let stored = twin.stored_depth_ndc(coord.uv);
    let taps = twin.trace.take().unwrap_or_default();
    let vssm = (scene.shadow.technique == Technique::Vssm && result.search.found > 0)
        .then(|| vssm_probe(&mut twin, &coord, &result, pixel));
    LightProbe {
        light: light_index,
        shadow_view: view_index,
        cube_face: (view.cube == 1).then(|| CUBE_FACE_NAMES[view.face as usize].to_string()),
        cascade: cascade_probe(&light_gpu, &rendered.views, view_index, position),
        shadow_map_uv: coord.uv.to_array(),
        shadow_map_texel: [(coord.uv.x * map_size).floor() as i32, (coord.uv.y * map_size).floor() as i32],
        inside_light_frustum: !crate::shadow::no_map_data(&view, &coord),
        n_dot_l: coord.n_dot_l,
        receiver_depth_ndc: coord.depth_ndc,
        receiver_depth_linear: coord.depth_linear,
        stored_depth_ndc: stored,
        stored_depth_linear: crate::shadow::depth_linear_from_ndc(&view, stored),
        bias_ndc: twin.receiver_bias_ndc(&coord, filter_radius_texels),
        vsm: match scene.shadow.technique {
            Technique::Vsm => Some(vsm_probe(&twin, &coord, (position, normal), scene.shadow.radius_texels)),
            Technique::Vssm if result.search.found > 0 => {
                Some(vsm_probe(&twin, &coord, (position, normal), result.penumbra.filter_radius_texels))
            }
            _ => None,
        },
        vssm,
        stored_depth_rgba8_error_ndc: (scene.shadow.depth_storage == DepthStorage::Rgba8)
            .then(|| stored - twin.stored_depth_float_ndc(coord.uv)),
        receiver_plane_depth_per_texel_world: (scene.shadow.bias_mode == BiasMode::ReceiverPlane).then(
            || {
                coord.depth_gradient.length()
                    / map_size
                    / crate::shadow::ndc_per_world(&view, coord.depth_linear)
            },
        ),
        blocker_search_radius_uv: result.search.radius_texels / map_size,
        blocker_search_radius_texels: result.search.radius_texels,
        blockers_found: result.search.found,
        // Only PCSS searches, with the search's own pattern.
        blocker_samples: match scene.shadow.technique {
            Technique::Pcss => kernels::filter_taps(
                crate::shadow::search_kernel(scene.shadow.pcf_kernel),
                scene.shadow.blocker_samples,
            ),
            _ => 0,
        },
        avg_blocker_depth_linear: (result.search.found > 0).then_some(result.search.avg_depth_linear),
        penumbra_width_world: result.penumbra.width_world,
        filter_radius_uv: filter_radius_texels / map_size,
        filter_radius_texels,
        // Taps the filter really took: PCSS skips it where no blocker was found.
        filter_samples: match scene.shadow.technique {
            Technique::None => 0,
            Technique::Hard => 1,
            // Four moments texels on each of two levels, interpolated.
            Technique::Vsm => 8,
            Technique::Vssm if result.search.found == 0 => 0,
            Technique::Vssm => 8,
            Technique::Pcss if result.search.found == 0 => 0,
            _ => scene.shadow.effective_samples(),
        },
        visibility_gpu: here.shadow[0],
        visibility_twin: result.visibility,
        visibility_reference: reference,
        taps: taps
            .iter()
            .map(|t| TapReport {
                kind: match t.kind {
                    TapKind::BlockerSearch => "blocker-search",
                    TapKind::Filter => "filter",
                }
                .into(),
                uv: t.uv.to_array(),
                value: t.value,
            })
            .collect(),
    }
}

fn vsm_probe(
    twin: &Twin<'_>,
    coord: &crate::shadow::ShadowCoord,
    (position, normal): (Vec3, Vec3),
    radius_texels: f32,
) -> VsmProbe {
    let lookup = twin.vsm_lookup(coord, radius_texels);
    let bias = twin.receiver_bias_ndc(coord, radius_texels);
    let (histogram_range_ndc, histogram) = histogram(&lookup.depths, lookup.t);
    VsmProbe {
        mean_depth_ndc: lookup.moments.x,
        variance_ndc2: lookup.moments.y - lookup.moments.x * lookup.moments.x,
        tested_depth_ndc: lookup.t,
        chebyshev_bound: lookup.bound,
        visibility: lookup.visibility,
        min_variance_ndc2: twin.params.vsm_min_variance,
        bleed_reduction: twin.params.vsm_bleed_reduction,
        true_lit_fraction: lookup.true_lit_fraction,
        plane_lit_fraction: twin.vsm_plane_lit_fraction(position, normal, radius_texels, bias),
        histogram_range_ndc,
        histogram,
    }
}

/// Weighted depths binned over their range widened to take in `t` (at least 1e-4 NDC wide).
fn histogram(depths: &[(f32, f32)], t: f32) -> ([f32; 2], Vec<f32>) {
    let (mut lo, mut hi) = (t, t);
    for (z, _) in depths {
        lo = lo.min(*z);
        hi = hi.max(*z);
    }
    let pad = ((hi - lo) * 0.05).max(5e-5);
    let (lo, hi) = (lo - pad, hi + pad);
    let mut bins = vec![0.0f32; HISTOGRAM_BINS];
    for (z, w) in depths {
        let i = ((z - lo) / (hi - lo) * HISTOGRAM_BINS as f32) as usize;
        bins[i.min(HISTOGRAM_BINS - 1)] += w;
    }
    ([lo, hi], bins)
}

/// VSSM's blocker estimate at the pixel beside the truth of its footprint and PCSS's search.
fn vssm_probe(
    twin: &mut Twin<'_>,
    coord: &crate::shadow::ShadowCoord,
    result: &crate::shadow::ShadowVisibility,
    pixel: (u32, u32),
) -> VssmProbe {
    let (view, params) = (*twin.view, *twin.params);
    // As the shader's search: the bias of a zero radius.
    let radius = result.search.radius_texels;
    let t = coord.depth_ndc - twin.receiver_bias_ndc(coord, 0.0);
    let unoccluded_bound = twin.chebyshev_upper_bound(twin.moments().filtered(&view, coord.uv, radius), t);
    let (mut sum, mut weight) = (0.0f64, 0.0f64);
    twin.for_each_footprint_depth(coord, radius, |_, z, w| {
        if z < t {
            sum += f64::from(z * w);
            weight += f64::from(w);
        }
    });
    let footprint_blocker_depth_linear =
        (weight > 0.0).then(|| crate::shadow::depth_linear_from_ndc(&view, (sum / weight) as f32));
    let seed = kernels::pixel_seed(pixel, params.noise_seed, params.rotate_per_pixel == 1);
    let pcss = twin.search_blockers(coord, seed);
    VssmProbe {
        unoccluded_bound,
        estimated_blocker_depth_linear: result.search.avg_depth_linear,
        footprint_blocker_depth_linear,
        pcss_blocker_depth_linear: (pcss.found > 0).then_some(pcss.avg_depth_linear),
    }
}

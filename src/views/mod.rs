//! Debug views as images: the camera view, the shadow term, the shadow map, PCSS heatmaps,
//! the shadow map's texels per screen pixel, the map each pixel reads, the ground truth and the
//! error against it.
//! Heatmaps come with the value range they map.

pub mod cascade_index;
pub mod overlays;
mod shadow_map;
pub mod texel_density;

pub use shadow_map::{CUBE_CROSS_CELLS, MapsLayout, light_maps_image, shadow_map_image};

use crate::i18n::Lang;
use crate::render::Analysis;
use crate::shadow::depth_linear_from_ndc;
use crate::shadow::{LightViewGpu, ShadowParamsGpu, ShadowViewGpu};
use image::{Rgba, RgbaImage};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum View {
    Final,
    Visibility,
    ShadowMap,
    BlockerRadius,
    Penumbra,
    Blockers,
    /// PCSS step 1's result: the average depth of the blockers found, world units.
    BlockerDepth,
    /// The VSM moments the filter reads: mean depth and standard deviation per texel.
    Moments,
    /// Shadow-map texels per screen pixel (perspective aliasing), on a log scale.
    TexelDensity,
    /// Which of the light's shadow maps (cascade, cube face) each pixel reads, one colour each.
    CascadeIndex,
    Reference,
    Error,
}

impl View {
    pub const ALL: [View; 12] = [
        View::Final,
        View::Visibility,
        View::ShadowMap,
        View::BlockerRadius,
        View::Penumbra,
        View::Blockers,
        View::BlockerDepth,
        View::Moments,
        View::TexelDensity,
        View::CascadeIndex,
        View::Reference,
        View::Error,
    ];

    pub fn name(self) -> &'static str {
        match self {
            View::Final => "final",
            View::Visibility => "visibility",
            View::ShadowMap => "shadow-map",
            View::BlockerRadius => "blocker-radius",
            View::Penumbra => "penumbra",
            View::Blockers => "blockers",
            View::BlockerDepth => "blocker-depth",
            View::Moments => "moments",
            View::TexelDensity => "texel-density",
            View::CascadeIndex => "cascade-index",
            View::Reference => "reference",
            View::Error => "error",
        }
    }

    /// The view's name as the panels show it in `lang`: the `--view` name in English, a
    /// translation in Chinese (lesson texts name views by it).
    pub fn label(self, lang: Lang) -> &'static str {
        crate::i18n::tr(lang, self.name())
    }

    pub fn from_name(name: &str) -> Option<View> {
        View::ALL.into_iter().find(|v| v.name() == name)
    }

    pub fn needs_reference(self) -> bool {
        matches!(self, View::Reference | View::Error)
    }
}

/// A heatmap's legend: the values at the two ends of the colour ramp and their unit.
#[derive(Clone, Debug, PartialEq)]
pub struct Legend {
    pub label: &'static str,
    pub min: f32,
    pub max: f32,
    pub unit: &'static str,
}

impl std::fmt::Display for Legend {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {:.4} .. {:.4} {} (dark blue .. yellow)", self.label, self.min, self.max, self.unit)
    }
}

/// Background of pixels with no surface in the float views.
const NO_SURFACE: Rgba<u8> = Rgba([40, 43, 51, 255]);

/// A perceptual ramp (dark blue, teal, green, yellow), t in 0..1.
pub fn heat_color(t: f32) -> Rgba<u8> {
    const STOPS: [[f32; 3]; 5] = [
        [0.267, 0.005, 0.329],
        [0.230, 0.322, 0.546],
        [0.128, 0.567, 0.551],
        [0.369, 0.789, 0.383],
        [0.993, 0.906, 0.144],
    ];
    let t = if t.is_finite() { t.clamp(0.0, 1.0) } else { 0.0 };
    let x = t * (STOPS.len() - 1) as f32;
    let i = (x.floor() as usize).min(STOPS.len() - 2);
    let f = x - i as f32;
    let channel = |k: usize| ((STOPS[i][k] * (1.0 - f) + STOPS[i + 1][k] * f) * 255.0).round() as u8;
    Rgba([channel(0), channel(1), channel(2), 255])
}

pub fn gray(v: f32) -> Rgba<u8> {
    let g = (v.clamp(0.0, 1.0) * 255.0).round() as u8;
    Rgba([g, g, g, 255])
}

/// Greyscale image of a per-pixel value in 0..1 (white = 1), surfaces only.
pub fn gray_image(analysis: &Analysis, value: impl Fn(usize) -> f32) -> RgbaImage {
    RgbaImage::from_fn(analysis.width, analysis.height, |x, y| {
        let i = analysis.index(x, y);
        if analysis.hit(i) { gray(value(i)) } else { NO_SURFACE }
    })
}

/// Heatmap of a per-pixel value over the surfaces, scaled to its own range (from 0).
pub fn heat_image(
    analysis: &Analysis,
    label: &'static str,
    unit: &'static str,
    value: impl Fn(usize) -> f32,
) -> (RgbaImage, Legend) {
    let max = (0..analysis.shadow.len())
        .filter(|&i| analysis.hit(i))
        .map(&value)
        .filter(|v| v.is_finite())
        .fold(0.0f32, f32::max);
    let legend = Legend { label, min: 0.0, max, unit };
    let scale = if max > 0.0 { 1.0 / max } else { 0.0 };
    let image = RgbaImage::from_fn(analysis.width, analysis.height, |x, y| {
        let i = analysis.index(x, y);
        if analysis.hit(i) { heat_color(value(i) * scale) } else { NO_SURFACE }
    });
    (image, legend)
}

/// Pixels where the blocker search found nothing (or there was none) in the blocker-depth view.
const NO_BLOCKER: Rgba<u8> = Rgba([120, 120, 120, 255]);

/// d_blocker per pixel, world units from the light, recovered from what the analysis pass
/// wrote: the penumbra width w_p (texels on the receiver, times the texel's world size at the
/// receiver's depth d_r) through the twin's inverse of the similar-triangle step
/// (`shadow::blocker_depth_from_penumbra`). None where nothing was found, or where the light has
/// no size (w_p is then 0 whatever d_blocker is). Where the blockers average
/// at or behind the receiver (the receiver-plane bias on a curved surface) there is no gap and
/// no penumbra, and this gives d_r.
pub fn blocker_depth_at(
    analysis: &Analysis,
    i: usize,
    light: &LightViewGpu,
    params: &ShadowParamsGpu,
) -> Option<f32> {
    if !analysis.hit(i) || analysis.shadow[i][3] < 0.5 {
        return None;
    }
    let position = glam::Vec3::from_slice(&analysis.position[i][..3]);
    let normal = glam::Vec3::from_slice(&analysis.normal[i][..3]);
    // The view that covers the point (a cube's face towards it), as the analysis pass read it.
    let view = crate::shadow::face_covering(&light.view, position);
    let coord = crate::shadow::light_space_lookup(&light.light, &view, params, position, normal);
    let w_p = analysis.shadow[i][2] * crate::shadow::texel_world_at(&view, coord.depth_linear, coord.uv);
    let d_r = coord.depth_linear;
    crate::shadow::blocker_depth_from_penumbra(&light.light, d_r, w_p)
}

/// The blocker-depth view: d_blocker as a heatmap over its own range, grey where none was found.
pub fn blocker_depth_image(
    analysis: &Analysis,
    light: &LightViewGpu,
    params: &ShadowParamsGpu,
) -> (RgbaImage, Legend) {
    let depths: Vec<Option<f32>> =
        (0..analysis.shadow.len()).map(|i| blocker_depth_at(analysis, i, light, params)).collect();
    let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
    for d in depths.iter().flatten() {
        lo = lo.min(*d);
        hi = hi.max(*d);
    }
    if !lo.is_finite() {
        (lo, hi) = (0.0, 0.0);
    }
    let span = (hi - lo).max(1e-6);
    let image = RgbaImage::from_fn(analysis.width, analysis.height, |x, y| {
        let i = analysis.index(x, y);
        match depths[i] {
            Some(d) => heat_color((d - lo) / span),
            None if analysis.hit(i) => NO_BLOCKER,
            None => NO_SURFACE,
        }
    });
    let unit = "world units from the light (grey: no blocker)";
    (image, Legend { label: "average blocker depth", min: lo, max: hi, unit })
}

/// The moments view: one level of a light's VSM moments as two panels side by side, the mean
/// depth (left) and the standard deviation of the depths each texel averages (right), both as
/// world units along the light (sigma through the depth curve's slope at the mean, exact for an
/// orthographic light). Panels are enlarged to at least 256 px a side, texels kept square.
pub fn moments_image(
    moments: &crate::render::MomentsLevel,
    view: &ShadowViewGpu,
) -> (RgbaImage, Legend, Legend) {
    let side = moments.side.max(1);
    let stats: Vec<(f32, f32)> = moments
        .texels
        .iter()
        .map(|&[m1, m2]| {
            let mean = depth_linear_from_ndc(view, m1.clamp(0.0, 1.0));
            let sigma_ndc = (m2 - m1 * m1).max(0.0).sqrt();
            (mean, sigma_ndc / crate::shadow::ndc_per_world(view, mean))
        })
        .collect();
    let (mut lo, mut hi, mut sigma_max) = (f32::INFINITY, f32::NEG_INFINITY, 0.0f32);
    for (mean, sigma) in &stats {
        lo = lo.min(*mean);
        hi = hi.max(*mean);
        sigma_max = sigma_max.max(*sigma);
    }
    if !lo.is_finite() {
        (lo, hi) = (view.near, view.far);
    }
    let span = (hi - lo).max(1e-6);
    let scale = 256u32.div_ceil(side).max(1);
    let (panel, gap) = (side * scale, 8);
    let image = RgbaImage::from_fn(2 * panel + gap, panel, |x, y| {
        let (column, x) = match x {
            x if x < panel => (0, x),
            x if x < panel + gap => return NO_SURFACE,
            x => (1, x - panel - gap),
        };
        let (mean, sigma) = stats.get(((y / scale) * side + x / scale) as usize).copied().unwrap_or_default();
        match column {
            0 => heat_color((mean - lo) / span),
            _ if sigma_max > 0.0 => heat_color(sigma / sigma_max),
            _ => heat_color(0.0),
        }
    });
    let unit = "world units from the light";
    (
        image,
        Legend { label: "mean depth (left)", min: lo, max: hi, unit },
        Legend { label: "standard deviation (right)", min: 0.0, max: sigma_max, unit: "world units" },
    )
}

/// Mean |visibility - ground truth| over the pixels with a surface (0 where there are none): the
/// number the error view's and the error overlay's legends give, and `{frame.mean_abs_error}`.
pub fn mean_abs_error(analysis: &Analysis, reference: &[f32]) -> f32 {
    let mut sum = 0.0f64;
    let mut count = 0usize;
    for (i, (shadow, truth)) in analysis.shadow.iter().zip(reference).enumerate() {
        if analysis.hit(i) {
            sum += f64::from((shadow[0] - truth).abs());
            count += 1;
        }
    }
    if count > 0 { (sum / count as f64) as f32 } else { 0.0 }
}

/// |technique - reference| over the surfaces, and its mean.
pub fn error_image(analysis: &Analysis, reference: &[f32]) -> (RgbaImage, Legend, f32) {
    let mae = mean_abs_error(analysis, reference);
    let image = RgbaImage::from_fn(analysis.width, analysis.height, |x, y| {
        let i = analysis.index(x, y);
        if analysis.hit(i) { heat_color((analysis.shadow[i][0] - reference[i]).abs()) } else { NO_SURFACE }
    });
    (image, Legend { label: "|visibility - reference|", min: 0.0, max: 1.0, unit: "" }, mae)
}

/// Render `view` of `scene` for light `light` at time `t`: the image, and a summary line for the
/// legend (value range, mean error) where the view has one.
pub fn render_view(
    renderer: &mut crate::render::Renderer,
    scene: &crate::scene::Scene,
    view: View,
    light: usize,
    time_s: f32,
    size: (u32, u32),
    lang: Lang,
) -> Result<(RgbaImage, Option<String>), crate::render::RenderError> {
    let rendered = render_view_measured(renderer, scene, view, light, time_s, size, lang)?;
    Ok((rendered.image, rendered.summary))
}

/// A view as [`render_view`] makes it, with the numbers its legend gives.
pub struct RenderedView {
    pub image: RgbaImage,
    pub summary: Option<String>,
    /// The error view's mean absolute error against the ground truth (None for other views).
    pub mean_abs_error: Option<f32>,
}

/// [`render_view`], keeping the numbers of the legend.
pub fn render_view_measured(
    renderer: &mut crate::render::Renderer,
    scene: &crate::scene::Scene,
    view: View,
    light: usize,
    time_s: f32,
    size: (u32, u32),
    lang: Lang,
) -> Result<RenderedView, crate::render::RenderError> {
    let request = crate::render::FrameRequest {
        time_s,
        size,
        selected_light: light,
        final_color: view == View::Final,
        analysis: view != View::Final,
        ..Default::default()
    };
    let frame = renderer.render(scene, &request)?;
    let no_light = || {
        let count = frame.lights.len();
        crate::render::RenderError::Usage(format!("light {light} does not exist (the scene has {count})"))
    };
    let plain = |image, summary| RenderedView { image, summary, mean_abs_error: None };
    Ok(match view {
        View::Final => plain(renderer.read_color()?, None),
        View::ShadowMap => {
            let (_, views) = frame.views_of(light).ok_or_else(no_light)?;
            let maps = renderer.read_light_maps(light)?;
            let (image, legend) = light_maps_image(&maps, views);
            plain(image, Some(legend.to_string()))
        }
        _ => {
            let mut a = renderer.read_analysis()?;
            if view == View::Moments {
                let (index, _) = frame.first_view_of(light).ok_or_else(no_light)?;
                a.moments = Some(renderer.read_moments_for_radius(index, frame.params.radius_texels)?);
            }
            let reference =
                if view.needs_reference() { Some(renderer.render_reference(scene, light)?) } else { None };
            let samples = scene.shadow.reference_samples;
            let light_view = frame.light_view(light);
            let light_and_params = light_view.as_ref().map(|l| (l, &frame.params));
            let (image, legend) =
                analysis_view(view, &a, reference.as_deref(), samples, light_and_params, &frame.views, lang)
                    .ok_or_else(|| {
                        crate::render::RenderError::Usage(format!("view {} has no image", view.name()))
                    })?;
            let mean_abs_error =
                reference.as_deref().filter(|_| view == View::Error).map(|r| mean_abs_error(&a, r));
            RenderedView { image, summary: Some(legend), mean_abs_error }
        }
    })
}

/// A view made from the analysis pass (and the ground truth for `reference` and `error`), with
/// its legend. None for the views that are not (final, shadow map), and for reference and error
/// without a ground truth. `views` are the frame's shadow views, of every light (a lookup reads
/// the one of its light that covers the point).
pub fn analysis_view(
    view: View,
    a: &Analysis,
    reference: Option<&[f32]>,
    reference_samples: u32,
    light: Option<(&LightViewGpu, &ShadowParamsGpu)>,
    views: &[ShadowViewGpu],
    lang: Lang,
) -> Option<(RgbaImage, String)> {
    use crate::i18n::{fill, tr};
    match view {
        View::Final | View::ShadowMap => None,
        View::Moments => {
            let (light, _) = light?;
            let moments = a.moments.as_ref()?;
            let (image, mean, sigma) = moments_image(moments, &light.view);
            let text = fill(
                lang,
                "VSM moments, level {} (each texel averages {}x{} map texels), read by a filter of {} texels, dark blue .. yellow\nleft: mean depth {} .. {} world units from the light; right: standard deviation 0 .. {} world units",
                &[
                    &moments.level,
                    &moments.span_texels,
                    &moments.span_texels,
                    &format!("{:.1}", moments.radius_texels),
                    &format!("{:.2}", mean.min),
                    &format!("{:.2}", mean.max),
                    &format!("{:.3}", sigma.max),
                ],
            );
            Some((image, text))
        }
        View::BlockerDepth => {
            let (light, params) = light?;
            let (image, legend) = blocker_depth_image(a, light, params);
            // The languages round differently: the template gives the decimals.
            let text = fill(
                lang,
                "average blocker depth: {:.4} .. {:.4} world units from the light (grey: no blocker) (dark blue .. yellow)",
                &[&legend.min, &legend.max],
            );
            Some((image, text))
        }
        View::TexelDensity => {
            let (light, _) = light?;
            let (image, legend, on_screen) = texel_density::texel_density_image(a, &light.light, views);
            let range = fill(
                lang,
                "{}: {} .. {} {}, log: red < 1 blocky, blue > 1 wasted",
                &[&tr(lang, legend.label), &legend.min, &legend.max, &tr(lang, legend.unit)],
            );
            let measured = match on_screen {
                Some(d) => fill(
                    lang,
                    "on screen: {} .. {}, median {}",
                    &[&format!("{:.3}", d.min), &format!("{:.3}", d.max), &format!("{:.3}", d.median)],
                ),
                None => tr(lang, "on screen: no surface on the light's map").into(),
            };
            Some((image, format!("{range}\n{measured}")))
        }
        View::CascadeIndex => Some(cascade_index::cascade_index_image(a, &light?.0.light, views, lang)),
        View::Visibility => {
            let legend = tr(lang, "visibility: black = shadowed, white = lit");
            Some((gray_image(a, |i| a.shadow[i][0]), legend.into()))
        }
        View::BlockerRadius | View::Penumbra | View::Blockers => {
            let (label, unit, channel) = match view {
                View::BlockerRadius => ("blocker-search radius", "texels", 1),
                View::Penumbra => ("penumbra width", "texels", 2),
                _ => ("blockers found", "taps", 3),
            };
            let (image, legend) = heat_image(a, label, unit, |i| a.shadow[i][channel]);
            // Blockers found are a count of taps: whole numbers.
            let decimals = if channel == 3 { 0 } else { 4 };
            let legend = fill(
                lang,
                "{}: {} .. {} {} (dark blue .. yellow)",
                &[
                    &tr(lang, label),
                    &format!("{:.decimals$}", legend.min),
                    &format!("{:.decimals$}", legend.max),
                    &tr(lang, unit),
                ],
            );
            Some((image, legend))
        }
        View::Reference => {
            let reference = reference?;
            let note = fill(lang, "reference: {} hard shadows averaged", &[&reference_samples]);
            Some((gray_image(a, |i| reference[i]), note))
        }
        View::Error => {
            let (image, legend, mae) = error_image(a, reference?);
            let text = fill(
                lang,
                "|visibility - reference|: {} .. {}  (dark blue .. yellow)\nmean absolute error: {}",
                &[&format!("{:.4}", legend.min), &format!("{:.4}", legend.max), &format!("{mae:.5}")],
            );
            Some((image, text))
        }
    }
}

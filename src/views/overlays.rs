//! Overlays on the camera view, computed from the analysis pass: PCSS heatmaps, the shadow-map
//! texel grid projected on surfaces, the outside-the-frustum tint, and the error against the
//! ground truth. Each comes with a legend line. The app and the slides draw the same ones.

use crate::i18n::{Lang, fill, tr};
use crate::render::{Analysis, Readback, RenderError, Renderer};
use crate::shadow::project_to_light;
use crate::shadow::{DepthImage, LightViewGpu, ShadowParamsGpu, ShadowViewGpu};
use crate::views::heat_color;
use glam::Vec3;
use image::{Rgba, RgbaImage};

/// Overlays on the camera view.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Overlay {
    BlockerRadius,
    Penumbra,
    Blockers,
    TexelGrid,
    OutsideFrustum,
    Error,
    /// Where VSM's bound lets through light that the same filter window blocks (light bleeding).
    Bleeding,
    LightFrustum,
}

impl Overlay {
    pub const ALL: [Overlay; 8] = [
        Overlay::BlockerRadius,
        Overlay::Penumbra,
        Overlay::Blockers,
        Overlay::TexelGrid,
        Overlay::OutsideFrustum,
        Overlay::Error,
        Overlay::Bleeding,
        Overlay::LightFrustum,
    ];
    pub fn name(self) -> &'static str {
        match self {
            Overlay::BlockerRadius => "blocker-search radius",
            Overlay::Penumbra => "penumbra width",
            Overlay::Blockers => "blockers found",
            Overlay::TexelGrid => "shadow-map texel grid",
            Overlay::OutsideFrustum => "outside the light frustum",
            Overlay::Error => "error vs ground truth",
            Overlay::Bleeding => "light bleeding",
            Overlay::LightFrustum => "light frustum wireframe",
        }
    }

    /// Drawn against the ground truth.
    pub fn needs_reference(self) -> bool {
        self == Overlay::Error
    }
}

/// The overlays combined into one translucent image, and their legends.
pub fn compose(
    lang: Lang,
    overlays: &[Overlay],
    analysis: &Analysis,
    shadow_view: Option<&ShadowViewGpu>,
    reference: Option<&[f32]>,
) -> (RgbaImage, Vec<String>) {
    let mut image = RgbaImage::new(analysis.width, analysis.height);
    let mut legends = Vec::new();
    for &overlay in overlays {
        match overlay {
            Overlay::BlockerRadius | Overlay::Penumbra | Overlay::Blockers => {
                let (channel, label, unit) = match overlay {
                    Overlay::BlockerRadius => (1, "blocker-search radius", "texels"),
                    Overlay::Penumbra => (2, "penumbra width", "texels"),
                    _ => (3, "blockers found", "taps"),
                };
                let max = (0..analysis.shadow.len())
                    .filter(|&i| analysis.hit(i))
                    .map(|i| analysis.shadow[i][channel])
                    .fold(0.0f32, f32::max);
                legends.push(fill(
                    lang,
                    "{}: 0 .. {} {} (dark blue .. yellow)",
                    &[&tr(lang, label), &format!("{max:.2}"), &tr(lang, unit)],
                ));
                let scale = if max > 0.0 { 1.0 / max } else { 0.0 };
                paint(&mut image, analysis, |i| {
                    let v = analysis.shadow[i][channel];
                    (v > 0.0).then(|| with_alpha(heat_color(v * scale), 170))
                });
            }
            Overlay::TexelGrid => {
                let Some(view) = shadow_view else { continue };
                let size = view.map_size_texels;
                legends.push(fill(
                    lang,
                    "texel grid: lines where the shadow-map texel changes ({}² map)",
                    &[&size],
                ));
                let texel = |i: usize| {
                    let p = Vec3::from_slice(&analysis.position[i][..3]);
                    let s = project_to_light(view, p);
                    ((s.x * view.map_size_texels).floor() as i64, (s.y * view.map_size_texels).floor() as i64)
                };
                let w = analysis.width as usize;
                paint(&mut image, analysis, |i| {
                    let right = i + 1;
                    let down = i + w;
                    let here = texel(i);
                    let edge = (right % w != 0
                        && right < analysis.shadow.len()
                        && analysis.hit(right)
                        && texel(right) != here)
                        || (down < analysis.shadow.len() && analysis.hit(down) && texel(down) != here);
                    edge.then_some(Rgba([255, 255, 255, 150]))
                });
            }
            Overlay::OutsideFrustum => {
                let Some(view) = shadow_view else { continue };
                legends.push(tr(lang, "orange: outside the light's frustum (no map data)").into());
                paint(&mut image, analysis, |i| {
                    let s = project_to_light(view, Vec3::from_slice(&analysis.position[i][..3]));
                    // The twin's rule: NaN (a point in a spot light's own plane) is outside too.
                    let outside = crate::shadow::outside_map(glam::Vec2::new(s.x, s.y))
                        || crate::shadow::outside_depth(s.z);
                    outside.then_some(Rgba([255, 140, 0, 110]))
                });
            }
            Overlay::Error => {
                let Some(reference) = reference else {
                    legends.push(tr(lang, "error: computing the ground truth...").into());
                    continue;
                };
                let (_, _, mae) = crate::views::error_image(analysis, reference);
                legends.push(fill(
                    lang,
                    "|visibility − ground truth|: 0 .. 1, mean {}",
                    &[&format!("{mae:.4}")],
                ));
                paint(&mut image, analysis, |i| {
                    let e = (analysis.shadow[i][0] - reference[i]).abs();
                    (e > 0.02).then(|| with_alpha(heat_color(e), 200))
                });
            }
            Overlay::Bleeding => {
                let Some(bleeding) = analysis.bleeding.as_deref() else {
                    legends.push(tr(lang, "light bleeding: only VSM and VSSM bound their lit share").into());
                    continue;
                };
                let summary = light_bleeding(analysis, bleeding);
                legends.push(fill(
                    lang,
                    "magenta stripes: light bleeding ≥ {}, up to {}; {} % of the surface",
                    &[
                        &BLEED_THRESHOLD,
                        &format!("{:.2}", summary.max),
                        &format!("{:.1}", 100.0 * summary.share),
                    ],
                ));
                // Hatched, so the light that bleeds stays visible between the stripes; the
                // stripes' opacity grows with the amount.
                let width = analysis.width as usize;
                paint(&mut image, analysis, |i| {
                    let excess = bleeding.get(i).copied().unwrap_or(0.0);
                    let stripe = (i % width + i / width) % 8 < 4;
                    (stripe && excess >= BLEED_THRESHOLD)
                        .then(|| Rgba([255, 0, 200, (110.0 + 145.0 * excess.min(1.0)).round() as u8]))
                });
            }
            Overlay::LightFrustum => {}
        }
    }
    (image, legends)
}

/// Light bleeding of at least this much is painted (below it, the bound's small excess over a
/// receiver's own depths spread around t).
pub const BLEED_THRESHOLD: f32 = 0.05;

/// How much light VSM lets through that the same window blocks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bleeding {
    /// The largest light bleeding over the surfaces.
    pub max: f32,
    /// The share of surface pixels with `BLEED_THRESHOLD` or more.
    pub share: f32,
}

pub fn light_bleeding(analysis: &Analysis, bleeding: &[f32]) -> Bleeding {
    let (mut max, mut count, mut surface) = (0.0f32, 0usize, 0usize);
    for (i, excess) in bleeding.iter().enumerate().take(analysis.shadow.len()) {
        if analysis.hit(i) {
            max = max.max(*excess);
            surface += 1;
            count += usize::from(*excess >= BLEED_THRESHOLD);
        }
    }
    Bleeding { max, share: if surface > 0 { count as f32 / surface as f32 } else { 0.0 } }
}

/// The light bleeding of the renderer's last frame, for its analysis `analysis` of light
/// `light`: None unless that frame used VSM or VSSM.
pub fn bleeding_of_last_frame(
    renderer: &Renderer,
    analysis: &Analysis,
    light: usize,
) -> Result<Option<Vec<f32>>, RenderError> {
    let inputs = bleeding_inputs_readback(renderer, light)?.wait(renderer.device())?;
    Ok(inputs.map(|inputs| inputs.bleeding(analysis)))
}

/// What the light bleeding of a frame needs beside its analysis: the light's map and the light
/// and the shadow parameters as the GPU had them.
pub struct BleedingInputs {
    pub map: DepthImage,
    pub light: LightViewGpu,
    pub params: ShadowParamsGpu,
}

impl BleedingInputs {
    /// The bleeding per pixel of `analysis` (`vsm_light_bleeding`).
    pub fn bleeding(&self, analysis: &Analysis) -> Vec<f32> {
        vsm_light_bleeding(analysis, &self.map, &self.light, &self.params)
    }
}

/// The inputs of light `light`'s bleeding in the renderer's last frame, its map on its way
/// back: None unless that frame used VSM or VSSM.
pub fn bleeding_inputs_readback(
    renderer: &Renderer,
    light: usize,
) -> Result<Readback<Option<BleedingInputs>>, RenderError> {
    let Some(frame) = renderer.last_frame() else { return Ok(Readback::ready(None)) };
    let first = crate::shadow::gpu::first_view_of(&frame.lights, &frame.views, light);
    let Some((view_index, light_gpu)) = first.filter(|_| frame.params.uses_moments()) else {
        return Ok(Readback::ready(None));
    };
    let params = frame.params;
    Ok(renderer
        .shadow_map_readback(view_index)?
        .map(move |map| Ok(Some(BleedingInputs { map, light: light_gpu, params }))))
}

/// Light bleeding per pixel of `analysis` (`Twin::vsm_light_bleeding_at`): VSM's or VSSM's
/// visibility minus the lit share of the window its filter read (each texel against the
/// receiver's plane), worked out by the CPU twin on `map`. Only pixels that are neither fully lit nor dark can bleed; the rest are 0.
pub fn vsm_light_bleeding(
    analysis: &Analysis,
    map: &DepthImage,
    light: &LightViewGpu,
    params: &ShadowParamsGpu,
) -> Vec<f32> {
    let mut twin = crate::shadow::Twin::new(&light.light, &light.view, params, map);
    (0..analysis.shadow.len())
        .map(|i| {
            let v = analysis.shadow[i][0];
            if !analysis.hit(i) || !(BLEED_THRESHOLD..1.0).contains(&v) {
                return 0.0;
            }
            let pixel = ((i % analysis.width as usize) as u32, (i / analysis.width as usize) as u32);
            let position = Vec3::from_slice(&analysis.position[i][..3]);
            let normal = Vec3::from_slice(&analysis.normal[i][..3]);
            twin.vsm_light_bleeding_at(pixel, position, normal)
        })
        .collect()
}

fn with_alpha(c: Rgba<u8>, a: u8) -> Rgba<u8> {
    Rgba([c[0], c[1], c[2], a])
}

/// Alpha-blend `color(i)` over the surfaces.
fn paint(image: &mut RgbaImage, analysis: &Analysis, color: impl Fn(usize) -> Option<Rgba<u8>>) {
    for (i, pixel) in image.pixels_mut().enumerate() {
        if !analysis.hit(i) {
            continue;
        }
        if let Some(c) = color(i) {
            let a = f32::from(c[3]) / 255.0;
            let under = f32::from(pixel[3]) / 255.0;
            let out_a = a + under * (1.0 - a);
            for k in 0..3 {
                let mixed = f32::from(c[k]) * a + f32::from(pixel[k]) * under * (1.0 - a);
                pixel[k] = if out_a > 0.0 { (mixed / out_a).round() as u8 } else { 0 };
            }
            pixel[3] = (out_a * 255.0).round() as u8;
        }
    }
}

/// The edges of every shadow view's frustum as seen by a camera (`clip_from_world` of the
/// camera), in fractions of the camera's view (0..1 across, 0..1 down), with whether the view's
/// light is `selected`. Edges behind the camera are left out.
pub fn light_frustum_edges(
    clip_from_world: &glam::Mat4,
    views: &[ShadowViewGpu],
    selected: usize,
) -> Vec<([f32; 2], [f32; 2], bool)> {
    let to_view = |p: Vec3| {
        let clip = *clip_from_world * p.extend(1.0);
        (clip.w > 1e-4).then(|| {
            let ndc = clip.truncate() / clip.w;
            [ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5]
        })
    };
    let mut edges = Vec::new();
    for view in views {
        let world_from_clip = glam::Mat4::from_cols_array_2d(&view.clip_from_world).inverse();
        let corner = |x: f32, y: f32, z: f32| {
            let w = world_from_clip * glam::Vec4::new(x, y, z, 1.0);
            w.truncate() / w.w
        };
        let c: Vec<Vec3> = [
            (-1., -1., 0.),
            (1., -1., 0.),
            (1., 1., 0.),
            (-1., 1., 0.),
            (-1., -1., 1.),
            (1., -1., 1.),
            (1., 1., 1.),
            (-1., 1., 1.),
        ]
        .iter()
        .map(|&(x, y, z)| corner(x, y, z))
        .collect();
        for (a, b) in
            [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]
        {
            if let (Some(pa), Some(pb)) = (to_view(c[a]), to_view(c[b])) {
                edges.push((pa, pb, view.light as usize == selected));
            }
        }
    }
    edges
}

/// The frustum colours: the selected light's and the others'.
pub const FRUSTUM_SELECTED: [u8; 3] = [255, 200, 60];
pub const FRUSTUM_OTHER: [u8; 3] = [120, 170, 255];

/// Whether `view` leaves `overlay` out: the view shows it already; a heatmap view takes no
/// second heatmap (the same colours, two legends); a view of the light's map takes nothing drawn
/// in the camera's picture.
pub fn hidden_by_view(view: crate::views::View, overlay: Overlay) -> bool {
    use crate::views::View;
    let heat_overlay =
        matches!(overlay, Overlay::BlockerRadius | Overlay::Penumbra | Overlay::Blockers | Overlay::Error);
    match view {
        View::ShadowMap | View::Moments => true,
        View::BlockerRadius
        | View::Penumbra
        | View::Blockers
        | View::BlockerDepth
        | View::TexelDensity
        | View::CascadeIndex
        | View::Error => heat_overlay,
        View::Final | View::Visibility | View::Reference => false,
    }
}

/// Alpha-blend a translucent `overlay` (from [`compose`]) over an opaque picture of its size.
pub fn blend_onto(picture: &mut RgbaImage, overlay: &RgbaImage) {
    if picture.dimensions() != overlay.dimensions() {
        return;
    }
    for (under, over) in picture.pixels_mut().zip(overlay.pixels()) {
        let a = f32::from(over[3]) / 255.0;
        for k in 0..3 {
            under[k] = (f32::from(over[k]) * a + f32::from(under[k]) * (1.0 - a)).round() as u8;
        }
    }
}

/// Draw the shadow views' frustum edges onto a picture of the camera view (slides, screenshots).
pub fn draw_light_frusta(
    picture: &mut RgbaImage,
    clip_from_world: &glam::Mat4,
    views: &[ShadowViewGpu],
    selected: usize,
) {
    let (w, h) = picture.dimensions();
    let Some(mut pixmap) = tiny_skia::Pixmap::from_vec(
        picture.as_raw().clone(),
        tiny_skia::IntSize::from_wh(w, h).unwrap_or_else(|| tiny_skia::IntSize::from_wh(1, 1).expect("1x1")),
    ) else {
        return;
    };
    let width = (w.max(h) as f32 / 640.0).max(1.5);
    let stroke = tiny_skia::Stroke { width, ..Default::default() };
    for (a, b, is_selected) in light_frustum_edges(clip_from_world, views, selected) {
        let mut path = tiny_skia::PathBuilder::new();
        path.move_to(a[0] * w as f32, a[1] * h as f32);
        path.line_to(b[0] * w as f32, b[1] * h as f32);
        let Some(path) = path.finish() else { continue };
        let [r, g, bl] = if is_selected { FRUSTUM_SELECTED } else { FRUSTUM_OTHER };
        let mut paint = tiny_skia::Paint::default();
        paint.set_color_rgba8(r, g, bl, 255);
        paint.anti_alias = true;
        pixmap.stroke_path(&path, &paint, &stroke, tiny_skia::Transform::identity(), None);
    }
    // The picture is opaque, so premultiplied and straight alpha are the same bytes.
    if let Some(drawn) = RgbaImage::from_raw(w, h, pixmap.take()) {
        *picture = drawn;
    }
}

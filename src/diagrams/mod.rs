//! Explanatory 2D diagrams of shadow techniques, drawn with tiny-skia from live numbers.
//!
//! Every diagram is drawn in a logical space of at least 960x540 units scaled uniformly onto the
//! requested pixmap, so labels keep their proportions at any size (19 px labels at 960x540).

mod acne_bias;
mod canvas;
pub mod cascade_reads;
mod chebyshev;
mod cjk_font;
pub mod live;
mod multi_light;
mod pcf_kernel;
mod pcss;
mod shadow_views;
mod style;
mod text;
mod two_pass;
mod widgets;

#[cfg(test)]
mod tests;

use crate::i18n::Lang;
use crate::scene::Technique;
pub use canvas::{Canvas, MAX_TEXT_GROWTH};
#[cfg(not(target_arch = "wasm32"))]
pub use cjk_font::BUILT_IN_CJK_FONT;
#[cfg(target_arch = "wasm32")]
pub use cjk_font::set_served_cjk_font;
pub use cjk_font::{CJK_FONT_PATHS, CjkFont, FontBytes, built_in_cjk_font, cjk_font, system_cjk_font};
pub use shadow_views::VIEW_COLORS;
pub use text::{TextMetrics, TextRenderer, TextStyle, is_cjk};

/// Largest accepted width or height, in pixels.
pub const MAX_SIDE_PX: u32 = 8192;

/// Errors from [`draw`] and [`encode_png`].
#[derive(Debug, thiserror::Error)]
pub enum DiagramError {
    #[error("invalid diagram size {width_px}x{height_px}: each side must be 1..={MAX_SIDE_PX} px")]
    InvalidSize { width_px: u32, height_px: u32 },
    #[error("PNG encoding failed: {0}")]
    Encode(String),
    #[error("invalid font data: {0}")]
    Font(String),
}

/// The available diagrams.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DiagramKind {
    TwoPass,
    AcneBias,
    PcfKernel,
    PcssTriangles,
    MultiLight,
    Chebyshev,
    ShadowViews,
}

impl DiagramKind {
    pub const ALL: [DiagramKind; 7] = [
        DiagramKind::TwoPass,
        DiagramKind::AcneBias,
        DiagramKind::PcfKernel,
        DiagramKind::PcssTriangles,
        DiagramKind::MultiLight,
        DiagramKind::Chebyshev,
        DiagramKind::ShadowViews,
    ];

    /// Stable identifier (file names, command line).
    pub fn id(&self) -> &'static str {
        match self {
            DiagramKind::TwoPass => "two-pass",
            DiagramKind::AcneBias => "acne-bias",
            DiagramKind::PcfKernel => "pcf-kernel",
            DiagramKind::PcssTriangles => "pcss",
            DiagramKind::MultiLight => "multi-light",
            DiagramKind::Chebyshev => "chebyshev",
            DiagramKind::ShadowViews => "shadow-views",
        }
    }

    /// The diagram's tab in `lang`: the id in English, a translation in Chinese.
    pub fn label(&self, lang: Lang) -> &'static str {
        crate::i18n::tr(lang, self.id())
    }

    pub fn from_id(id: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|k| k.id() == id)
    }

    /// English title shown in the diagram's title bar (translated by `crate::i18n`).
    pub fn title(&self) -> &'static str {
        match self {
            DiagramKind::TwoPass => "Shadow mapping in two passes",
            DiagramKind::AcneBias => "Shadow acne, depth bias and peter panning",
            DiagramKind::PcfKernel => "PCF: the filter kernel on the shadow map",
            DiagramKind::PcssTriangles => "PCSS: penumbra width from similar triangles",
            DiagramKind::MultiLight => "Several lights: one shadow map each (top view)",
            DiagramKind::Chebyshev => "VSM: Chebyshev's bound on the depths in the filter window",
            DiagramKind::ShadowViews => "A light's shadow maps: a sun's cascades, a lamp's cube",
        }
    }
}

impl DiagramInputs {
    /// The probed point has no shadow-map data: the CPU twin's rule
    /// (`crate::shadow::outside_frustum`), off the map or outside its depth range.
    pub fn outside_frustum(&self) -> bool {
        self.outside_map || self.outside_depth
    }
}

/// One light seen from above (XZ plane), for [`DiagramKind::MultiLight`].
#[derive(Clone, Debug, PartialEq)]
pub struct LightTopView {
    pub position_xz: [f32; 2],
    pub target_xz: [f32; 2],
    /// Orthographic half extent, or tan(fov/2) * distance-to-target for a spot light (world).
    pub half_width_world: f32,
    pub spot: bool,
    pub color_rgb: [f32; 3],
}

/// Live numbers the diagrams are drawn from. Units are in the field names; depths are linear
/// distances from the light along its axis.
#[derive(Clone, Debug, PartialEq)]
pub struct DiagramInputs {
    /// The shadow technique the numbers come from.
    pub technique: Technique,
    /// Angle between the light direction and the receiver's normal (0 = overhead), degrees.
    pub light_angle_deg: f32,
    pub shadow_map_size_texels: u32,
    /// W: orthographic width, or near-plane width for a perspective light (world).
    pub frustum_width_world: f32,
    pub light_near: f32,
    pub light_far: f32,
    pub orthographic: bool,
    /// Depth bias currently applied, NDC depth units.
    pub bias_ndc: f32,
    pub normal_offset_texels: f32,
    pub receiver_depth_linear: f32,
    pub stored_depth_linear: f32,
    /// Average blocker depth; `None` = the blocker search found nothing.
    pub blocker_depth_linear: Option<f32>,
    /// Area-light model: light width (world). Exactly one of this and the angular diameter is set.
    pub light_width_world: Option<f32>,
    /// Directional model: angular diameter of the light (degrees).
    pub light_angular_diameter_deg: Option<f32>,
    pub penumbra_width_world: f32,
    pub search_radius_texels: f32,
    pub filter_radius_texels: f32,
    /// Where the probe's lookup lies inside its texel, 0..1 on each axis (0.5 = the centre).
    pub probe_in_texel: [f32; 2],
    /// PCF sample offsets in the unit disk.
    pub pcf_samples: Vec<[f32; 2]>,
    /// Per sample: true = blocked (same length as `pcf_samples`).
    pub sample_blocked: Vec<bool>,
    pub blockers_found: u32,
    pub blocker_samples: u32,
    pub visibility: f32,
    /// The probed point's uv lies off the shadow map (`crate::shadow::outside_map`).
    pub outside_map: bool,
    /// The probed point's depth lies outside the map's 0..1 NDC range
    /// (`crate::shadow::outside_depth`).
    pub outside_depth: bool,
    /// RGBA8 depth storage: the stored depth after the pack / 8-bit / unpack round trip minus
    /// the depth the shadow pass wrote, NDC; `None` for float storage.
    pub stored_depth_rgba8_error_ndc: Option<f32>,
    /// Points outside the frustum count as lit (`clamp_outside`); otherwise the lookup wraps.
    pub clamp_outside: bool,
    /// The shadow pass culls front faces: closed objects store their back faces, so a lit
    /// surface is never compared with itself (`cull_front_faces`).
    pub cull_front_faces: bool,
    /// Receiver-plane bias: each tap is compared with the receiver's plane at the centre of
    /// the texel it reads, less the constant bias.
    pub receiver_plane: bool,
    pub lights: Vec<LightTopView>,
    /// VSM and VSSM: what the probe's filter lookup read. None draws an example, marked so.
    pub vsm: Option<VsmPlot>,
    /// Object centre and radius in the XZ plane (world).
    pub objects_xz: Vec<([f32; 2], f32)>,
    pub camera_xz: [f32; 2],
    /// The light's shadow views, for [`DiagramKind::ShadowViews`].
    pub shadow_views: ShadowViewsPlot,
}

/// A light's shadow views for [`DiagramKind::ShadowViews`]. Distances and widths in world units.
#[derive(Clone, Debug, PartialEq)]
pub enum ShadowViewsPlot {
    /// A sun's cascades (one for a light with one map): where each slice of the camera's view
    /// begins and ends along its axis (`count + 1` values), each cascade's map width, the width
    /// of one map over the scene, the split's lambda, and the cascade the probe read. How a pixel
    /// picks its cascade, and the depths along the axis over which each is read under that
    /// selection (`cascade_reads`; None: never read on the axis).
    Cascades {
        splits_world: Vec<f32>,
        widths_world: Vec<f32>,
        one_map_width_world: f32,
        lambda: f32,
        probe_cascade: Option<usize>,
        selection: crate::scene::CascadeSelection,
        read_world: Vec<Option<[f32; 2]>>,
    },
    /// A point light's cube from above, and the face the probe read (`CUBE_FACES` order).
    Cube { lamp_xz: [f32; 2], probe_face: Option<usize> },
}

/// One VSM lookup for [`DiagramKind::Chebyshev`] (see `crate::probe::VsmProbe`). Depths are NDC.
#[derive(Clone, Debug, PartialEq)]
pub struct VsmPlot {
    pub histogram_range_ndc: [f32; 2],
    /// Shares of the window's depths in equal bins over the range (summing to 1).
    pub histogram: Vec<f32>,
    pub mean_ndc: f32,
    pub variance_ndc2: f32,
    pub min_variance_ndc2: f32,
    pub tested_ndc: f32,
    pub chebyshev_bound: f32,
    /// After the bleed reduction.
    pub visibility: f32,
    pub true_lit_fraction: f32,
    /// The window's share not nearer than the receiver's own plane: what the visibility is
    /// measured against for light bleeding.
    pub plane_lit_fraction: f32,
    /// 0 = off.
    pub bleed_reduction: f32,
    pub filter_radius_texels: f32,
}

impl VsmPlot {
    /// Two slabs' depths in one window, the receiver behind both: the true lit share is 0, the
    /// bound is not (the light-bleeding case).
    pub fn example() -> Self {
        let (lo, hi, bins) = (0.28f32, 0.62f32, 48usize);
        let mut histogram = vec![0.0; bins];
        let bin = |z: f32| (((z - lo) / (hi - lo)) * bins as f32) as usize;
        for (z, share) in [(0.30, 0.35), (0.305, 0.15), (0.55, 0.3), (0.555, 0.2)] {
            histogram[bin(z).min(bins - 1)] += share;
        }
        let depths = [(0.30f32, 0.35f32), (0.305, 0.15), (0.55, 0.3), (0.555, 0.2)];
        let mean: f32 = depths.iter().map(|(z, w)| z * w).sum();
        let square: f32 = depths.iter().map(|(z, w)| z * z * w).sum();
        let variance = square - mean * mean;
        let t = 0.60;
        let d = t - mean;
        let bound = variance / (variance + d * d);
        Self {
            histogram_range_ndc: [lo, hi],
            histogram,
            mean_ndc: mean,
            variance_ndc2: variance,
            min_variance_ndc2: 1e-6,
            tested_ndc: t,
            chebyshev_bound: bound,
            visibility: bound,
            true_lit_fraction: 0.0,
            plane_lit_fraction: 0.0,
            bleed_reduction: 0.0,
            filter_radius_texels: 8.0,
        }
    }
}

/// `n` points of a golden-angle disk in the unit disk [Vogel-1979].
pub fn vogel_disk(n: usize) -> Vec<[f32; 2]> {
    let golden = std::f32::consts::PI * (3.0 - 5f32.sqrt());
    (0..n)
        .map(|i| {
            let r = ((i as f32 + 0.5) / n as f32).sqrt();
            let a = i as f32 * golden;
            [r * a.cos(), r * a.sin()]
        })
        .collect()
}

impl Default for DiagramInputs {
    fn default() -> Self {
        let pcf_samples = vogel_disk(16);
        // A straight shadow edge across the kernel: the half of the samples on one side is blocked.
        let proj: Vec<f32> = pcf_samples.iter().map(|s| s[0] * 0.8 + s[1] * 0.6).collect();
        let sample_blocked =
            proj.iter().map(|p| proj.iter().filter(|q| *q < p).count() < pcf_samples.len() / 2).collect();
        let spot_dist = (80f32 * 80.0 + 20.0 * 20.0).sqrt();
        Self {
            technique: Technique::Pcss,
            light_angle_deg: 45.0,
            shadow_map_size_texels: 2048,
            frustum_width_world: 200.0,
            light_near: 0.01,
            light_far: 400.0,
            orthographic: true,
            bias_ndc: 0.002,
            normal_offset_texels: 0.0,
            receiver_depth_linear: 113.0,
            stored_depth_linear: 113.0,
            blocker_depth_linear: Some(100.0),
            light_width_world: Some(2.0),
            light_angular_diameter_deg: None,
            penumbra_width_world: 0.26,
            search_radius_texels: 10.0,
            filter_radius_texels: 5.0,
            probe_in_texel: [0.5, 0.5],
            pcf_samples,
            sample_blocked,
            blockers_found: 8,
            blocker_samples: 16,
            visibility: 0.5,
            outside_map: false,
            outside_depth: false,
            stored_depth_rgba8_error_ndc: None,
            clamp_outside: true,
            cull_front_faces: false,
            receiver_plane: false,
            lights: vec![
                LightTopView {
                    position_xz: [0.0, 80.0],
                    target_xz: [0.0, 0.0],
                    half_width_world: 100.0,
                    spot: false,
                    color_rgb: [1.0, 1.0, 1.0],
                },
                LightTopView {
                    position_xz: [-70.0, -20.0],
                    target_xz: [10.0, 0.0],
                    half_width_world: (30f32).to_radians().tan() * spot_dist,
                    spot: true,
                    color_rgb: [1.0, 0.55, 0.2],
                },
            ],
            vsm: Some(VsmPlot::example()),
            objects_xz: vec![([0.0, 0.0], 10.0), ([40.0, 0.0], 10.0), ([-30.0, 25.0], 6.0)],
            camera_xz: [30.0, 30.0],
            // Four cascades over 0.3..160 with lambda 0.7 (the avenue's), each a sphere's width.
            shadow_views: ShadowViewsPlot::Cascades {
                splits_world: crate::shadow::cascades::split_distances(0.3, 160.0, 4, 0.7),
                widths_world: vec![33.4, 40.0, 72.0, 143.0],
                one_map_width_world: 220.0,
                lambda: 0.7,
                probe_cascade: Some(1),
                selection: crate::scene::CascadeSelection::ByMap,
                read_world: vec![
                    Some([0.3, 26.0]),
                    Some([26.0, 61.0]),
                    Some([61.0, 120.0]),
                    Some([120.0, 160.0]),
                ],
            },
        }
    }
}

/// Sanitised near/far planes: finite, near > 0, far > near.
fn planes(inputs: &DiagramInputs) -> (f32, f32) {
    let near = style::fin(inputs.light_near, 0.01).clamp(1e-6, 1e8);
    let far = style::fin(inputs.light_far, 400.0).clamp(near * 1.0001 + 1e-6, 1e9);
    (near, far)
}

/// The light and its view as the twin's formulas take them, from the diagram's numbers made safe
/// to draw (finite, near > 0, far > near, a map at least one texel wide).
pub(crate) fn light_gpu(inputs: &DiagramInputs) -> crate::shadow::LightViewGpu {
    let (near, far) = planes(inputs);
    let width = style::fin(inputs.frustum_width_world, 200.0).abs().max(1e-6);
    let (size_model, light_width_world, tan_half_angle) = match inputs.light_angular_diameter_deg {
        Some(deg) => {
            let theta = style::fin(deg, 0.53).abs().min(170.0).to_radians();
            (crate::shadow::SIZE_MODEL_ANGULAR, 0.0, (0.5 * theta).tan())
        }
        None => (0, style::fin(inputs.light_width_world.unwrap_or(0.0), 0.0).abs().min(1e9), 0.0),
    };
    let light = crate::shadow::LightGpu {
        directional: u32::from(inputs.orthographic),
        size_model,
        light_width_world,
        tan_half_angle,
        view_count: 1,
        ..bytemuck::Zeroable::zeroed()
    };
    let view = crate::shadow::ShadowViewGpu {
        near,
        far,
        frustum_width_world: width,
        // W is the near plane's width for a perspective light.
        tan_half_fov: 0.5 * width / near,
        orthographic: u32::from(inputs.orthographic),
        map_size_texels: inputs.shadow_map_size_texels.max(1) as f32,
        atlas_scale: 1.0,
        moments_block: 1,
        ..bytemuck::Zeroable::zeroed()
    };
    crate::shadow::LightViewGpu { light, view }
}

/// NDC depth in [0, 1] (wgpu range) of linear depth `d` for the light described by `inputs`.
fn ndc_from_linear(inputs: &DiagramInputs, d: f32) -> f32 {
    let (near, far) = planes(inputs);
    let d = style::fin(d, far).clamp(near * 1e-3, 1e12);
    style::fin(crate::shadow::depth_ndc_from_linear(&light_gpu(inputs).view, d), 1.0)
}

/// World length of the NDC bias at linear depth `d` (exact for orthographic; the local slope of
/// the depth curve for perspective).
fn bias_world(inputs: &DiagramInputs, d: f32) -> f32 {
    style::fin(style::fin(inputs.bias_ndc, 0.0) / ndc_per_world(inputs, d), 0.0)
}

/// World width of one shadow-map texel at linear depth `d` on the light's axis (the twin's
/// `texel_world_at` at the map's centre).
fn texel_world(inputs: &DiagramInputs, d: f32) -> f32 {
    let (near, _) = planes(inputs);
    let axis_uv = glam::Vec2::splat(0.5);
    crate::shadow::texel_world_at(&light_gpu(inputs).view, style::fin(d, near).abs(), axis_uv)
}

/// NDC depth per world unit at linear depth `d` (constant for orthographic), within the planes.
fn ndc_per_world(inputs: &DiagramInputs, d: f32) -> f32 {
    let (near, far) = planes(inputs);
    crate::shadow::ndc_per_world(&light_gpu(inputs).view, style::fin(d, near).clamp(near, far))
}

/// Draws `kind` from `inputs` with labels in `lang` onto a new `width_px` x `height_px`
/// premultiplied RGBA pixmap. Fails only for a zero or oversized (> [`MAX_SIDE_PX`]) size.
pub fn draw(
    kind: DiagramKind,
    inputs: &DiagramInputs,
    lang: Lang,
    width_px: u32,
    height_px: u32,
) -> Result<tiny_skia::Pixmap, DiagramError> {
    draw_traced(kind, inputs, lang, [width_px, height_px], 0.0).map(|(pixmap, _)| pixmap)
}

/// [`draw`] for a panel on screen, also returning every string drawn (as translated) with its
/// size in pixels: text smaller than `min_text_px` grows towards it (at most
/// [`MAX_TEXT_GROWTH`] times), and a panel wider than 16:9 gives the text columns and the
/// legend the extra width.
pub fn draw_traced(
    kind: DiagramKind,
    inputs: &DiagramInputs,
    lang: Lang,
    [width_px, height_px]: [u32; 2],
    min_text_px: f32,
) -> Result<(tiny_skia::Pixmap, Vec<(String, f32)>), DiagramError> {
    let c = draw_canvas(kind, inputs, lang, [width_px, height_px], min_text_px)?;
    Ok((c.pixmap, c.drawn))
}

/// [`draw_traced`], returning the whole canvas (where every text and frame was drawn).
pub(crate) fn draw_canvas(
    kind: DiagramKind,
    inputs: &DiagramInputs,
    lang: Lang,
    [width_px, height_px]: [u32; 2],
    min_text_px: f32,
) -> Result<Canvas, DiagramError> {
    let bad = DiagramError::InvalidSize { width_px, height_px };
    if width_px == 0 || height_px == 0 || width_px > MAX_SIDE_PX || height_px > MAX_SIDE_PX {
        return Err(bad);
    }
    // Text grows towards `min_text_px` only as far as the canvas holds it: where a text column
    // is squeezed into a strip or texts meet, the diagram is drawn again with smaller text, down
    // to its design size. While a value is dragged the same panel is drawn again and again:
    // start from the size that fitted it last time rather than try the larger ones again.
    let key = (kind, [width_px, height_px], lang, min_text_px.to_bits());
    let fitted = LAST_FIT.with(|last| last.get().filter(|(k, _)| *k == key).map(|(_, t)| t));
    let mut min_text = fitted.unwrap_or(min_text_px);
    for _ in 0..MAX_SHRINKS {
        let c = draw_once(kind, inputs, lang, [width_px, height_px], min_text)?;
        if !c.cramped && c.overlapping_text().is_empty() {
            LAST_FIT.with(|last| last.set(Some((key, min_text))));
            return Ok(c);
        }
        min_text *= SHRINK;
    }
    draw_once(kind, inputs, lang, [width_px, height_px], 0.0)
}

/// The text size that last fitted a panel: (kind, size, language, asked text size) and the
/// text size drawn; per thread, so that what one thread draws never depends on another's.
type FitKey = (DiagramKind, [u32; 2], Lang, u32);
thread_local! {
    static LAST_FIT: std::cell::Cell<Option<(FitKey, f32)>> = const { std::cell::Cell::new(None) };
}

/// Tries at a smaller text size before the design size, and the factor of each.
const MAX_SHRINKS: usize = 4;
const SHRINK: f32 = 0.85;

fn draw_once(
    kind: DiagramKind,
    inputs: &DiagramInputs,
    lang: Lang,
    [width_px, height_px]: [u32; 2],
    min_text_px: f32,
) -> Result<Canvas, DiagramError> {
    let bad = DiagramError::InvalidSize { width_px, height_px };
    let pixmap = tiny_skia::Pixmap::new(width_px, height_px).ok_or(bad)?;
    let mut c = canvas::Canvas::new(pixmap, lang, min_text_px);
    c.title_bar(kind.title());
    match kind {
        DiagramKind::TwoPass => two_pass::draw(&mut c, inputs),
        DiagramKind::AcneBias => acne_bias::draw(&mut c, inputs),
        DiagramKind::PcfKernel => pcf_kernel::draw(&mut c, inputs),
        DiagramKind::PcssTriangles => pcss::draw(&mut c, inputs),
        DiagramKind::MultiLight => multi_light::draw(&mut c, inputs),
        DiagramKind::Chebyshev => chebyshev::draw(&mut c, inputs),
        DiagramKind::ShadowViews => shadow_views::draw(&mut c, inputs),
    }
    Ok(c)
}

/// Encodes a pixmap as PNG (straight alpha, as PNG requires).
pub fn encode_png(pixmap: &tiny_skia::Pixmap) -> Result<Vec<u8>, DiagramError> {
    pixmap.encode_png().map_err(|e| DiagramError::Encode(e.to_string()))
}

//! Text labels for the diagrams: glyphs rasterised with `ab_glyph` and alpha-blended onto a
//! `tiny_skia::Pixmap`, with per-glyph fallback to further fonts (symbols, CJK).

use std::sync::OnceLock;

use ab_glyph::{Font, FontArc, FontRef, FontVec, GlyphId, PxScale, ScaleFont, point};
use tiny_skia::{Color, Pixmap, PremultipliedColorU8};

use super::DiagramError;

/// Usual Debian/Ubuntu locations of CJK fonts (fonts-noto-cjk, fonts-wqy-*, fonts-arphic-*, ...).
pub const CJK_FONT_PATHS: [&str; 12] = [
    "/usr/share/fonts/opentype/noto/NotoSansCJK-Regular.ttc",
    "/usr/share/fonts/opentype/noto/NotoSansCJKsc-Regular.otf",
    "/usr/share/fonts/opentype/noto/NotoSerifCJK-Regular.ttc",
    "/usr/share/fonts/truetype/noto/NotoSansCJK-Regular.ttc",
    "/usr/share/fonts/noto-cjk/NotoSansCJK-Regular.ttc",
    "/usr/share/fonts/google-noto-cjk/NotoSansCJK-Regular.ttc",
    "/usr/share/fonts/truetype/wqy/wqy-microhei.ttc",
    "/usr/share/fonts/truetype/wqy/wqy-zenhei.ttc",
    "/usr/share/fonts/wqy-microhei/wqy-microhei.ttc",
    "/usr/share/fonts/truetype/arphic/uming.ttc",
    "/usr/share/fonts/truetype/arphic/ukai.ttc",
    "/usr/share/fonts/truetype/droid/DroidSansFallbackFull.ttf",
];

/// Reads the first CJK font found in [`CJK_FONT_PATHS`]; `None` when none is installed
/// (on Debian: `apt-get install fonts-noto-cjk`).
pub fn load_system_cjk_font() -> Option<Vec<u8>> {
    CJK_FONT_PATHS.iter().find_map(|path| {
        let bytes = std::fs::read(path).ok()?;
        // Only accept files that parse as a font (index 0 of a collection).
        FontRef::try_from_slice_and_index(&bytes, 0).ok()?;
        Some(bytes)
    })
}

/// Horizontal extent and vertical metrics of a line of text, in pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TextMetrics {
    pub width_px: f32,
    pub ascent_px: f32,
    pub descent_px: f32,
}

impl TextMetrics {
    pub fn height_px(&self) -> f32 {
        self.ascent_px + self.descent_px
    }
}

/// Size (pixels), colour and weight of drawn text.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TextStyle {
    pub px: f32,
    pub color: Color,
    pub bold: bool,
}

/// Draws single-line labels. The first font is the primary one; each character the primary
/// font lacks is taken from the first fallback font that has it.
pub struct TextRenderer {
    fonts: Vec<FontArc>,
}

impl std::fmt::Debug for TextRenderer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("TextRenderer").field("fonts", &self.fonts.len()).finish()
    }
}

impl Default for TextRenderer {
    fn default() -> Self {
        Self::new()
    }
}

impl TextRenderer {
    /// Ubuntu Light, then Hack (maths symbols), then a system CJK font when one is installed.
    pub fn new() -> Self {
        let mut fonts: Vec<FontArc> =
            [epaint_default_fonts::UBUNTU_LIGHT, epaint_default_fonts::HACK_REGULAR]
                .into_iter()
                .filter_map(|bytes| FontArc::try_from_slice(bytes).ok())
                .collect();
        if let Some(font) = load_system_cjk_font().and_then(|b| FontVec::try_from_vec_and_index(b, 0).ok()) {
            fonts.push(FontArc::new(font));
        }
        Self { fonts }
    }

    /// A renderer from font files (`.ttf`, `.otf`, or index 0 of a `.ttc`).
    pub fn from_font_data(primary: Vec<u8>, fallbacks: Vec<Vec<u8>>) -> Result<Self, DiagramError> {
        let fonts = std::iter::once(primary)
            .chain(fallbacks)
            .map(|bytes| {
                FontVec::try_from_vec_and_index(bytes, 0)
                    .map(FontArc::new)
                    .map_err(|e| DiagramError::Font(e.to_string()))
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self { fonts })
    }

    /// The process-wide renderer used by the diagrams (fonts are parsed once).
    pub fn shared() -> &'static TextRenderer {
        static SHARED: OnceLock<TextRenderer> = OnceLock::new();
        SHARED.get_or_init(TextRenderer::new)
    }

    /// Number of loaded fonts (primary plus fallbacks).
    pub fn font_count(&self) -> usize {
        self.fonts.len()
    }

    /// Whether any loaded font has a glyph for `ch`.
    pub fn covers(&self, ch: char) -> bool {
        self.fonts.iter().any(|f| f.glyph_id(ch).0 != 0)
    }

    /// Index of the font used for `ch`, and its glyph.
    fn pick(&self, ch: char) -> Option<(usize, GlyphId)> {
        let found = self.fonts.iter().enumerate().find_map(|(i, f)| {
            let id = f.glyph_id(ch);
            (id.0 != 0).then_some((i, id))
        });
        found.or_else(|| self.fonts.first().map(|f| (0, f.glyph_id(ch))))
    }

    /// Pixel scale for font `fi` such that its em square matches the primary font's at `px`.
    fn scale_for(&self, fi: usize, px: f32) -> PxScale {
        let em_ratio = |f: &FontArc| {
            let upem = f.units_per_em().unwrap_or(1000.0).max(1.0);
            (f.height_unscaled() / upem).clamp(0.5, 3.0)
        };
        match (self.fonts.first(), self.fonts.get(fi)) {
            (Some(p), Some(f)) if fi > 0 => PxScale::from(px * em_ratio(f) / em_ratio(p)),
            _ => PxScale::from(px),
        }
    }

    /// Glyph positions (font index, glyph, x offset) and total advance of `text` at `px`.
    fn layout(&self, text: &str, px: f32) -> (Vec<(usize, GlyphId, f32)>, f32) {
        let mut x = 0.0;
        let mut prev: Option<(usize, GlyphId)> = None;
        let mut out = Vec::with_capacity(text.len());
        for ch in text.chars().filter(|c| !c.is_control()) {
            let Some((fi, id)) = self.pick(ch) else {
                continue;
            };
            let font = self.fonts[fi].as_scaled(self.scale_for(fi, px));
            if let Some((pfi, pid)) = prev
                && pfi == fi
            {
                x += font.kern(pid, id);
            }
            out.push((fi, id, x));
            x += font.h_advance(id);
            prev = Some((fi, id));
        }
        (out, x)
    }

    /// Size of `text` at `px` pixels (ascent and descent from the primary font).
    pub fn measure(&self, text: &str, px: f32) -> TextMetrics {
        let px = sane_px(px);
        let (_, width_px) = self.layout(text, px);
        let (ascent_px, descent_px) = self.fonts.first().map_or((px * 0.8, px * 0.2), |f| {
            let s = f.as_scaled(PxScale::from(px));
            (s.ascent(), -s.descent())
        });
        TextMetrics { width_px, ascent_px, descent_px }
    }

    /// Draws `text` with its left end at `x` and its baseline at `baseline_y` (pixels).
    /// `style.bold` thickens strokes by drawing each glyph twice with a small horizontal offset.
    pub fn draw(&self, pixmap: &mut Pixmap, text: &str, x: f32, baseline_y: f32, style: TextStyle) {
        let TextStyle { px, color, bold } = style;
        if !(x.is_finite() && baseline_y.is_finite()) {
            return;
        }
        let px = sane_px(px);
        let (glyphs, _) = self.layout(text, px);
        let offsets: &[f32] = if bold { &[0.0, 0.045] } else { &[0.0, 0.018] };
        let outlined: Vec<_> = glyphs
            .iter()
            .flat_map(|&(fi, id, gx)| {
                offsets.iter().filter_map(move |&dx| {
                    let pos = point(x + gx + dx * px, baseline_y);
                    let scale = self.scale_for(fi, px);
                    self.fonts[fi].outline_glyph(id.with_scale_and_position(scale, pos))
                })
            })
            .collect();
        // Coverage buffer over the union of glyph boxes, clipped to the pixmap.
        let (pw, ph) = (pixmap.width() as i32, pixmap.height() as i32);
        let (mut x0, mut y0, mut x1, mut y1) = (pw, ph, 0, 0);
        for g in &outlined {
            let b = g.px_bounds();
            x0 = x0.min((b.min.x as i32).max(0));
            y0 = y0.min((b.min.y as i32).max(0));
            x1 = x1.max((b.max.x.ceil() as i32).min(pw));
            y1 = y1.max((b.max.y.ceil() as i32).min(ph));
        }
        if x1 <= x0 || y1 <= y0 {
            return;
        }
        let bw = (x1 - x0) as usize;
        let mut cover = vec![0.0_f32; bw * (y1 - y0) as usize];
        for g in &outlined {
            let b = g.px_bounds();
            g.draw(|gx, gy, c| {
                let (cx, cy) = (b.min.x as i32 + gx as i32, b.min.y as i32 + gy as i32);
                if cx >= x0 && cy >= y0 && cx < x1 && cy < y1 {
                    let cell = &mut cover[(cy - y0) as usize * bw + (cx - x0) as usize];
                    *cell = cell.max(c.clamp(0.0, 1.0));
                }
            });
        }
        blend_coverage(pixmap, &cover, (x0, y0, bw), color);
    }
}

fn sane_px(px: f32) -> f32 {
    if px.is_finite() { px.clamp(1.0, 512.0) } else { 16.0 }
}

/// Source-over blend of `color` with per-pixel coverage onto a premultiplied pixmap.
fn blend_coverage(pixmap: &mut Pixmap, cover: &[f32], origin: (i32, i32, usize), color: Color) {
    let (x0, y0, bw) = origin;
    let pw = pixmap.width() as usize;
    let src = [color.red(), color.green(), color.blue()];
    let pixels = pixmap.pixels_mut();
    for (i, &c) in cover.iter().enumerate() {
        let idx = (y0 as usize + i / bw) * pw + x0 as usize + i % bw;
        let Some(dst) = pixels.get_mut(idx) else {
            continue;
        };
        if c <= 0.0 {
            continue;
        }
        let a = c * color.alpha();
        let keep = 1.0 - a;
        let mix = |s: f32, d: u8| (s * a * 255.0 + d as f32 * keep).round().clamp(0.0, 255.0) as u8;
        let out_a = mix(1.0, dst.alpha());
        let (r, g, b) = (
            mix(src[0], dst.red()).min(out_a),
            mix(src[1], dst.green()).min(out_a),
            mix(src[2], dst.blue()).min(out_a),
        );
        if let Some(p) = PremultipliedColorU8::from_rgba(r, g, b, out_a) {
            *dst = p;
        }
    }
}

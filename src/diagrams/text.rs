//! Text for the diagrams and the slides. cosmic-text shapes each string (harfrust), takes every
//! character the UI font lacks from the next font that has it (maths symbols, CJK) and breaks
//! lines by the Unicode rules (UAX #14). Glyphs are rasterised once and cached; a line's
//! coverage is blended onto the `tiny_skia::Pixmap` by tiny-skia like every other layer.

use std::collections::HashMap;
use std::sync::{Arc, Mutex, MutexGuard, OnceLock};

use cosmic_text::{
    Attrs, Buffer, CacheKey, CacheKeyFlags, Fallback, Family, FontSystem, Metrics, Shaping, SwashCache,
    SwashContent, Wrap, fontdb,
};
use tiny_skia::{Color, Pixmap, PixmapPaint, PremultipliedColorU8, Transform};

use super::DiagramError;
use super::cjk_font::{FontBytes, cjk_font};

/// Han ideographs, kana, CJK punctuation and full-width forms: written without spaces between
/// them (lines of a Chinese paragraph join without one).
pub fn is_cjk(c: char) -> bool {
    matches!(c as u32,
        0x2E80..=0x2FDF | 0x3000..=0x303F | 0x3040..=0x30FF | 0x3400..=0x4DBF | 0x4E00..=0x9FFF
        | 0xF900..=0xFAFF | 0xFE30..=0xFE4F | 0xFF00..=0xFFEF)
}

/// Characters that end a paragraph. cosmic-text starts a line at `\r` and `\n` and refuses a
/// line holding several bidi paragraphs, which the others would start.
fn is_paragraph_break(c: char) -> bool {
    matches!(c, '\n' | '\r' | '\u{0B}' | '\u{0C}' | '\u{1C}'..='\u{1E}' | '\u{85}' | '\u{2028}' | '\u{2029}')
}

/// `text` without paragraph breaks (each becomes a space), tabs as spaces and no other control
/// characters: one line, as shaped for labels.
fn single_line(text: &str) -> String {
    text.chars()
        .map(|c| if is_paragraph_break(c) || c == '\t' { ' ' } else { c })
        .filter(|c| !c.is_control())
        .collect()
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

/// How far right each glyph is drawn a second time, as a fraction of the text size: Ubuntu
/// Light is thin at slide sizes, and there is no bold face to switch to.
const REGULAR_OFFSET_EM: f32 = 0.018;
const BOLD_OFFSET_EM: f32 = 0.045;

/// The fonts after the primary one, tried in order for characters it lacks. cosmic-text asks
/// for `'static` names; the few family names are leaked once per renderer.
struct FallbackFamilies(Vec<&'static str>);

impl Fallback for FallbackFamilies {
    fn common_fallback(&self) -> &[&'static str] {
        &self.0
    }
    fn forbidden_fallback(&self) -> &[&'static str] {
        &[]
    }
    fn script_fallback(&self, _script: unicode_script::Script, _locale: &str) -> &[&'static str] {
        &[]
    }
}

/// The shaping state cosmic-text mutates on every call.
struct Engine {
    fonts: FontSystem,
    /// Rasterised glyphs, by font, glyph, size and quarter-pixel position.
    glyphs: SwashCache,
    /// Shaped single lines, by text and size (bits of the f32 pixel size).
    lines: HashMap<(String, u32), Arc<ShapedLine>>,
}

/// More distinct lines than a session of diagrams and slides draws; past it the cache restarts.
const MAX_CACHED_LINES: usize = 4096;
/// Glyph images kept (each size and quarter-pixel position is one; resizing a panel makes new
/// sizes): past it the image cache restarts.
const MAX_CACHED_GLYPHS: usize = 16384;

/// A glyph of a shaped line: its font and pen position, pixels from the line's start on its
/// baseline.
struct ShapedGlyph {
    font_id: fontdb::ID,
    glyph_id: u16,
    weight: fontdb::Weight,
    flags: CacheKeyFlags,
    x: f32,
    y: f32,
}

/// A shaped line and its advance.
struct ShapedLine {
    glyphs: Vec<ShapedGlyph>,
    width_px: f32,
}

/// Shapes, measures, breaks and draws text in a primary font with fallbacks.
pub struct TextRenderer {
    engine: Mutex<Engine>,
    primary: String,
    /// Weight of the primary face (Ubuntu Light is 300): asking for another would match no face.
    primary_weight: fontdb::Weight,
    /// Ascent and descent of the primary font, in ems.
    ascent_em: f32,
    descent_em: f32,
}

impl std::fmt::Debug for TextRenderer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("TextRenderer").field("primary", &self.primary).finish_non_exhaustive()
    }
}

impl Default for TextRenderer {
    fn default() -> Self {
        Self::new()
    }
}

impl TextRenderer {
    /// Ubuntu Light, then Hack (maths symbols), then the CJK font ([`cjk_font`]).
    pub fn new() -> Self {
        let builtin = [epaint_default_fonts::UBUNTU_LIGHT, epaint_default_fonts::HACK_REGULAR]
            .map(|bytes| (Arc::new(bytes) as FontBytes, 0));
        let cjk = cjk_font();
        // A page whose served copy did not arrive has none: its Chinese has no glyphs.
        let cjk = cjk.is_present().then(|| (Arc::clone(&cjk.bytes), cjk.face_index));
        match Self::from_faces(builtin.into_iter().chain(cjk).collect()) {
            Ok(renderer) => renderer,
            // The built-in fonts ship inside egui and always parse.
            Err(e) => panic!("the built-in UI fonts must load: {e}"),
        }
    }

    /// A renderer from font files (`.ttf`, `.otf`, or index 0 of a `.ttc`).
    pub fn from_font_data(primary: Vec<u8>, fallbacks: Vec<Vec<u8>>) -> Result<Self, DiagramError> {
        let faces = std::iter::once(primary).chain(fallbacks).map(|bytes| (Arc::new(bytes) as FontBytes, 0));
        Self::from_faces(faces.collect())
    }

    /// A renderer from `(font data, face index)` pairs, the primary face first.
    pub fn from_faces(faces: Vec<(FontBytes, u32)>) -> Result<Self, DiagramError> {
        let mut db = fontdb::Database::new();
        let mut families = Vec::new();
        let mut primary_metrics = None;
        for (i, (bytes, index)) in faces.into_iter().enumerate() {
            let source = fontdb::Source::Binary(bytes);
            let ids = db.load_font_source(source);
            let face = ids
                .iter()
                .filter_map(|id| db.face(*id))
                .find(|f| f.index == index)
                .ok_or_else(|| DiagramError::Font(format!("font {} has no face {index}", i + 1)))?;
            let family = face.families.first().map(|(name, _)| name.clone()).unwrap_or_default();
            if i == 0 {
                primary_metrics = Some((face.id, face.weight));
            }
            // Faces of a collection other than the chosen one would be fallbacks too.
            let unwanted: Vec<_> = ids.iter().copied().filter(|id| *id != face.id).collect();
            for id in unwanted {
                db.remove_face(id);
            }
            families.push(family);
        }
        let Some((primary_id, primary_weight)) = primary_metrics else {
            return Err(DiagramError::Font("no font given".into()));
        };
        let fallback: Vec<&'static str> =
            families.iter().skip(1).map(|f| &*Box::leak(f.clone().into_boxed_str())).collect();
        let mut fonts =
            FontSystem::new_with_locale_and_db_and_fallback("en-US".into(), db, FallbackFamilies(fallback));
        let primary_font = fonts
            .get_font(primary_id, primary_weight)
            .ok_or_else(|| DiagramError::Font("the primary font does not load".into()))?;
        let m = primary_font.metrics();
        let upem = f32::from(m.units_per_em.max(1));
        let (ascent_em, descent_em) = (m.ascent / upem, -m.descent / upem);
        Ok(Self {
            engine: Mutex::new(Engine { fonts, glyphs: SwashCache::new(), lines: HashMap::new() }),
            primary: families.swap_remove(0),
            primary_weight,
            ascent_em,
            descent_em,
        })
    }

    /// The process-wide renderer used by the diagrams and slides (fonts are parsed once).
    pub fn shared() -> &'static TextRenderer {
        static SHARED: OnceLock<TextRenderer> = OnceLock::new();
        SHARED.get_or_init(TextRenderer::new)
    }

    fn engine(&self) -> MutexGuard<'_, Engine> {
        // A panic while shaping leaves no half-updated state worth refusing.
        self.engine.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
    }

    /// Whether any loaded font has a glyph for `ch`.
    pub fn covers(&self, ch: char) -> bool {
        let mut engine = self.engine();
        let ids: Vec<_> = engine.fonts.db().faces().map(|f| f.id).collect();
        ids.into_iter().any(|id| {
            engine
                .fonts
                .get_font(id, fontdb::Weight::NORMAL)
                .is_some_and(|font| font.as_swash().charmap().map(ch) != 0)
        })
    }

    /// A buffer holding `text` at `px`, broken to `width_px` when given, shaped.
    fn shape(&self, engine: &mut Engine, text: &str, px: f32, width_px: Option<f32>) -> Buffer {
        let mut buffer = Buffer::new(&mut engine.fonts, Metrics::new(px, px * 1.25));
        buffer.set_wrap(if width_px.is_some() { Wrap::WordOrGlyph } else { Wrap::None });
        buffer.set_size(width_px, None);
        let attrs = Attrs::new().family(Family::Name(&self.primary)).weight(self.primary_weight);
        buffer.set_text(text, &attrs, Shaping::Advanced, None);
        buffer.shape_until_scroll(&mut engine.fonts, false);
        buffer
    }

    /// `text` as one line (see [`single_line`]), shaped at `px`. Labels are measured, then
    /// drawn, then redrawn on every frame of a drag: shaped lines are kept by text and size.
    fn line(&self, text: &str, px: f32) -> Arc<ShapedLine> {
        let key = (text.to_string(), px.to_bits());
        let mut engine = self.engine();
        if let Some(line) = engine.lines.get(&key) {
            return Arc::clone(line);
        }
        if engine.lines.len() >= MAX_CACHED_LINES {
            engine.lines.clear();
        }
        let buffer = self.shape(&mut engine, &single_line(text), px, None);
        let mut line = ShapedLine { glyphs: Vec::new(), width_px: 0.0 };
        for run in buffer.layout_runs() {
            line.width_px = line.width_px.max(run.line_w);
            for g in run.glyphs {
                line.glyphs.push(ShapedGlyph {
                    font_id: g.font_id,
                    glyph_id: g.glyph_id,
                    weight: g.font_weight,
                    // Unhinted, as the advances are: glyphs keep their shapes at every size.
                    flags: g.cache_key_flags | CacheKeyFlags::DISABLE_HINTING,
                    x: g.x + g.font_size * g.x_offset,
                    y: g.y - g.font_size * g.y_offset,
                });
            }
        }
        let line = Arc::new(line);
        engine.lines.insert(key, Arc::clone(&line));
        line
    }

    /// Size of `text` at `px` pixels (ascent and descent from the primary font).
    pub fn measure(&self, text: &str, px: f32) -> TextMetrics {
        let px = sane_px(px);
        let width_px = if text.is_empty() { 0.0 } else { self.line(text, px).width_px };
        TextMetrics { width_px, ascent_px: self.ascent_em * px, descent_px: self.descent_em * px }
    }

    /// `text` broken into lines no wider than `max_width_px` at `px`, by the Unicode line
    /// breaking rules (between words, between Chinese characters but not before a closing or
    /// after an opening mark); a word wider than the line is cut between characters. Newlines
    /// start new paragraphs.
    pub fn wrap(&self, text: &str, px: f32, max_width_px: f32) -> Vec<String> {
        let px = sane_px(px);
        let width = if max_width_px.is_finite() { max_width_px.max(px) } else { f32::MAX };
        let mut lines = Vec::new();
        for paragraph in text.replace("\r\n", "\n").split(is_paragraph_break) {
            let mut engine = self.engine();
            let buffer = self.shape(&mut engine, &single_line(paragraph), px, Some(width));
            let before = lines.len();
            for run in buffer.layout_runs() {
                let start = run.glyphs.iter().map(|g| g.start).min().unwrap_or(0);
                let end = run.glyphs.iter().map(|g| g.end).max().unwrap_or(0);
                lines.push(run.text.get(start..end).unwrap_or_default().trim().to_string());
            }
            // One line at least per paragraph, whatever the shaper makes of an empty one.
            if lines.len() == before {
                lines.push(String::new());
            }
        }
        lines
    }

    /// Draws `text` with its left end at `x` and its baseline at `baseline_y` (pixels). Glyph
    /// coverage comes from cosmic-text's cache (a label redrawn at the same size and
    /// quarter-pixel position is not rasterised again); the line's coverage is blended onto the
    /// pixmap in one source-over pass by tiny-skia, as every other shape.
    pub fn draw(&self, pixmap: &mut Pixmap, text: &str, x: f32, baseline_y: f32, style: TextStyle) {
        if !(x.is_finite() && baseline_y.is_finite()) || text.is_empty() {
            return;
        }
        let px = sane_px(style.px);
        let line = self.line(text, px);
        let thicken = if style.bold { BOLD_OFFSET_EM } else { REGULAR_OFFSET_EM } * px;
        let mut engine = self.engine();
        let Engine { fonts, glyphs, .. } = &mut *engine;
        if glyphs.image_cache.len() >= MAX_CACHED_GLYPHS {
            glyphs.image_cache.clear();
        }
        // Where each glyph's image lands: each glyph twice, the second a little to the right.
        let mut stamps = Vec::with_capacity(line.glyphs.len() * 2);
        let (pw, ph) = (pixmap.width() as i32, pixmap.height() as i32);
        let (mut x0, mut y0, mut x1, mut y1) = (pw, ph, 0, 0);
        for g in &line.glyphs {
            for dx in [0.0, thicken] {
                // Whole pixels down: swash would move a glyph up by a fractional y offset, and
                // quarter-pixel steps across suffice.
                let pos = (x + g.x + dx, (baseline_y + g.y).round());
                if !(pos.0.abs() < 1e6 && pos.1.abs() < 1e6) {
                    continue;
                }
                let (key, ix, iy) = CacheKey::new(g.font_id, g.glyph_id, px, pos, g.weight, g.flags);
                let Some(image) = glyphs.get_image(fonts, key) else {
                    continue;
                };
                let (left, top) = (ix + image.placement.left, iy - image.placement.top);
                let (w, h) = (image.placement.width as i32, image.placement.height as i32);
                x0 = x0.min(left.max(0));
                y0 = y0.min(top.max(0));
                x1 = x1.max((left + w).min(pw));
                y1 = y1.max((top + h).min(ph));
                stamps.push((key, left, top));
            }
        }
        if x1 <= x0 || y1 <= y0 {
            return;
        }
        // The line's coverage over the union of its glyph boxes, clipped to the pixmap.
        let (bw, bh) = ((x1 - x0) as usize, (y1 - y0) as usize);
        let mut cover = vec![0u8; bw * bh];
        for (key, left, top) in stamps {
            let Some(image) = glyphs.get_image(fonts, key) else {
                continue;
            };
            let (w, h) = (image.placement.width as i32, image.placement.height as i32);
            // A mask byte per pixel, or RGBA for a colour glyph (emoji).
            let stride = if image.content == SwashContent::Mask { 1 } else { 4 };
            for row in 0..h {
                let cy = top + row;
                if cy < y0 || cy >= y1 {
                    continue;
                }
                for col in 0..w {
                    let cx = left + col;
                    if cx < x0 || cx >= x1 {
                        continue;
                    }
                    // The alpha channel of a colour glyph, the mask itself otherwise.
                    let i = (row * w + col) as usize * stride + stride - 1;
                    let cell = &mut cover[(cy - y0) as usize * bw + (cx - x0) as usize];
                    *cell = (*cell).max(image.data.get(i).copied().unwrap_or(0));
                }
            }
        }
        let Some(mut ink) = Pixmap::new(bw as u32, bh as u32) else {
            return;
        };
        let c = style.color;
        for (dst, &coverage) in ink.pixels_mut().iter_mut().zip(&cover) {
            let a = f32::from(coverage) / 255.0 * c.alpha();
            let channel = |v: f32| (v * a * 255.0).round() as u8;
            let alpha = (a * 255.0).round() as u8;
            if let Some(p) = PremultipliedColorU8::from_rgba(
                channel(c.red()).min(alpha),
                channel(c.green()).min(alpha),
                channel(c.blue()).min(alpha),
                alpha,
            ) {
                *dst = p;
            }
        }
        pixmap.draw_pixmap(x0, y0, ink.as_ref(), &PixmapPaint::default(), Transform::identity(), None);
    }
}

fn sane_px(px: f32) -> f32 {
    if px.is_finite() { px.clamp(1.0, 512.0) } else { 16.0 }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A drag puts new numbers in the labels on every frame, and a resized panel new sizes: the
    /// shaped lines and glyph images those key stay within their bounds however long it goes on.
    #[test]
    fn the_caches_keyed_on_live_values_stay_bounded() {
        let text = TextRenderer::new();
        let mut pixmap = Pixmap::new(64, 16).expect("pixmap");
        let style = |px| TextStyle { px, color: Color::BLACK, bold: false };
        for k in 0..(2 * MAX_CACHED_LINES + 100) {
            let label = format!("d_blocker = {:.3}", k as f32 * 0.001);
            text.measure(&label, 12.0);
            if k % 8 == 0 {
                // Sizes as a panel being resized makes them, each with new glyph images.
                text.draw(&mut pixmap, &label, 0.0, 12.0, style(8.0 + (k % 2048) as f32 * 0.01));
            }
            let engine = text.engine();
            assert!(engine.lines.len() <= MAX_CACHED_LINES, "{} lines kept", engine.lines.len());
            // A line's glyphs (each stamped twice) may pass the bound before the next restart.
            let glyphs = engine.glyphs.image_cache.len();
            assert!(glyphs <= MAX_CACHED_GLYPHS + 2 * label.len(), "{glyphs} glyph images kept");
        }
    }
}

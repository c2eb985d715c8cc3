//! Text for the diagrams and the slides. cosmic-text shapes each string (harfrust), takes every
//! character the UI font lacks from the next font that has it (maths symbols, CJK) and breaks
//! lines by the Unicode rules (UAX #14); each glyph's outline becomes a `tiny_skia::Path`,
//! filled like every other shape, so text and drawing share one painter and one anti-aliasing.

use std::sync::{Mutex, MutexGuard, OnceLock};

use cosmic_text::{
    Attrs, Buffer, CacheKey, CacheKeyFlags, Command, Fallback, Family, FontSystem, Metrics, Shaping,
    SwashCache, Wrap, fontdb,
};
use tiny_skia::{Color, FillRule, LineJoin, Mask, Paint, Path, PathBuilder, Pixmap, Stroke, Transform};

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

/// A CJK font file and the face in it meant for Simplified Chinese (a `.ttc` such as Noto Sans
/// CJK holds the Japanese, Korean and Chinese forms of the same characters as separate faces).
#[derive(Clone)]
pub struct CjkFont {
    pub bytes: Vec<u8>,
    pub face_index: u32,
}

impl std::fmt::Debug for CjkFont {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("CjkFont")
            .field("bytes", &self.bytes.len())
            .field("face_index", &self.face_index)
            .finish()
    }
}

/// Reads the first CJK font found in [`CJK_FONT_PATHS`] and picks its Simplified Chinese face;
/// `None` when none is installed (on Debian: `apt-get install fonts-noto-cjk`).
pub fn load_system_cjk_font() -> Option<CjkFont> {
    CJK_FONT_PATHS.iter().find_map(|path| {
        let bytes = std::fs::read(path).ok()?;
        let face_index = simplified_chinese_face(&bytes)?;
        Some(CjkFont { bytes, face_index })
    })
}

/// Index of the face named "... SC" (Simplified Chinese), else of the first face; `None` when
/// the data holds no font.
fn simplified_chinese_face(bytes: &[u8]) -> Option<u32> {
    let mut db = fontdb::Database::new();
    db.load_font_source(fontdb::Source::Binary(std::sync::Arc::new(bytes.to_vec())));
    let faces: Vec<_> =
        db.faces().map(|f| (f.index, f.families.iter().any(|(n, _)| n.ends_with(" SC")))).collect();
    faces.iter().find(|(_, sc)| *sc).or(faces.first()).map(|(i, _)| *i)
}

/// Han ideographs, kana, CJK punctuation and full-width forms: written without spaces between
/// them (lines of a Chinese paragraph join without one).
pub fn is_cjk(c: char) -> bool {
    matches!(c as u32,
        0x2E80..=0x2FDF | 0x3000..=0x303F | 0x3040..=0x30FF | 0x3400..=0x4DBF | 0x4E00..=0x9FFF
        | 0xF900..=0xFAFF | 0xFE30..=0xFE4F | 0xFF00..=0xFFEF)
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

/// Extra stroke around each glyph's outline, as a fraction of the text size: Ubuntu Light is
/// thin for light-on-dark text at slide sizes, and there is no bold face to switch to.
const REGULAR_STROKE_EM: f32 = 0.018;
const BOLD_STROKE_EM: f32 = 0.045;

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
    outlines: SwashCache,
}

/// A shaped line: each glyph's outline key and pen position (pixels from the line's start on
/// its baseline), and the advance of the whole line.
struct ShapedLine {
    glyphs: Vec<(CacheKey, f32, f32)>,
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
    font_count: usize,
}

impl std::fmt::Debug for TextRenderer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("TextRenderer")
            .field("primary", &self.primary)
            .field("fonts", &self.font_count)
            .finish()
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
        let builtin = [epaint_default_fonts::UBUNTU_LIGHT, epaint_default_fonts::HACK_REGULAR]
            .map(|bytes| (bytes.to_vec(), 0));
        let cjk = load_system_cjk_font().map(|f| (f.bytes, f.face_index));
        match Self::from_faces(builtin.into_iter().chain(cjk).collect()) {
            Ok(renderer) => renderer,
            // The built-in fonts ship inside egui and always parse.
            Err(e) => panic!("the built-in UI fonts must load: {e}"),
        }
    }

    /// A renderer from font files (`.ttf`, `.otf`, or index 0 of a `.ttc`).
    pub fn from_font_data(primary: Vec<u8>, fallbacks: Vec<Vec<u8>>) -> Result<Self, DiagramError> {
        Self::from_faces(std::iter::once(primary).chain(fallbacks).map(|bytes| (bytes, 0)).collect())
    }

    /// A renderer from `(font data, face index)` pairs, the primary face first.
    pub fn from_faces(faces: Vec<(Vec<u8>, u32)>) -> Result<Self, DiagramError> {
        let mut db = fontdb::Database::new();
        let mut families = Vec::new();
        let mut primary_metrics = None;
        for (i, (bytes, index)) in faces.into_iter().enumerate() {
            let source = fontdb::Source::Binary(std::sync::Arc::new(bytes));
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
        let font_count = families.len();
        let mut fonts =
            FontSystem::new_with_locale_and_db_and_fallback("en-US".into(), db, FallbackFamilies(fallback));
        let primary_font = fonts
            .get_font(primary_id, primary_weight)
            .ok_or_else(|| DiagramError::Font("the primary font does not load".into()))?;
        let m = primary_font.metrics();
        let upem = f32::from(m.units_per_em.max(1));
        let (ascent_em, descent_em) = (m.ascent / upem, -m.descent / upem);
        Ok(Self {
            engine: Mutex::new(Engine { fonts, outlines: SwashCache::new() }),
            primary: families.swap_remove(0),
            primary_weight,
            ascent_em,
            descent_em,
            font_count,
        })
    }

    /// The process-wide renderer used by the diagrams and slides (fonts are parsed once).
    pub fn shared() -> &'static TextRenderer {
        static SHARED: OnceLock<TextRenderer> = OnceLock::new();
        SHARED.get_or_init(TextRenderer::new)
    }

    /// Number of loaded fonts (primary plus fallbacks).
    pub fn font_count(&self) -> usize {
        self.font_count
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

    /// `text` as one line (control characters dropped), shaped at `px`.
    fn line(&self, text: &str, px: f32) -> ShapedLine {
        let one_line: String = text.chars().filter(|c| !c.is_control()).collect();
        let mut engine = self.engine();
        let buffer = self.shape(&mut engine, &one_line, px, None);
        let mut line = ShapedLine { glyphs: Vec::new(), width_px: 0.0 };
        for run in buffer.layout_runs() {
            line.width_px = line.width_px.max(run.line_w);
            for g in run.glyphs {
                let (key, _, _) = CacheKey::new(
                    g.font_id,
                    g.glyph_id,
                    g.font_size,
                    (0.0, 0.0),
                    g.font_weight,
                    g.cache_key_flags | CacheKeyFlags::DISABLE_HINTING,
                );
                let x = g.x + g.font_size * g.x_offset;
                let y = g.y - g.font_size * g.y_offset;
                line.glyphs.push((key, x, y));
            }
        }
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
        for paragraph in text.split('\n') {
            let mut engine = self.engine();
            let buffer = self.shape(&mut engine, paragraph, px, Some(width));
            let before = lines.len();
            for run in buffer.layout_runs() {
                let start = run.glyphs.iter().map(|g| g.start).min().unwrap_or(0);
                let end = run.glyphs.iter().map(|g| g.end).max().unwrap_or(0);
                lines.push(run.text.get(start..end).unwrap_or_default().trim().to_string());
            }
            if lines.len() == before {
                lines.push(String::new());
            }
        }
        lines
    }

    /// Glyph outlines of `text` at `px`, placed with the line's start at `x` and its baseline
    /// at `baseline_y` (pixels).
    pub fn outlines(&self, text: &str, x: f32, baseline_y: f32, px: f32) -> Vec<Path> {
        if !(x.is_finite() && baseline_y.is_finite()) || text.is_empty() {
            return Vec::new();
        }
        let line = self.line(text, sane_px(px));
        let mut engine = self.engine();
        let Engine { fonts, outlines } = &mut *engine;
        line.glyphs
            .iter()
            .filter_map(|&(key, gx, gy)| {
                let commands = outlines.get_outline_commands(fonts, key)?;
                glyph_path(commands, x + gx, baseline_y + gy)
            })
            .collect()
    }

    /// Draws `text` with its left end at `x` and its baseline at `baseline_y` (pixels), through
    /// `transform` and inside `clip`.
    pub fn draw_with(
        &self,
        pixmap: &mut Pixmap,
        text: &str,
        [x, baseline_y]: [f32; 2],
        style: TextStyle,
        transform: Transform,
        clip: Option<&Mask>,
    ) {
        let px = sane_px(style.px);
        let mut paint = Paint::default();
        paint.set_color(style.color);
        paint.anti_alias = true;
        let em = if style.bold { BOLD_STROKE_EM } else { REGULAR_STROKE_EM };
        let stroke = Stroke { width: em * px, line_join: LineJoin::Round, ..Stroke::default() };
        for path in self.outlines(text, x, baseline_y, px) {
            pixmap.fill_path(&path, &paint, FillRule::Winding, transform, clip);
            pixmap.stroke_path(&path, &paint, &stroke, transform, clip);
        }
    }

    /// Draws `text` with its left end at `x` and its baseline at `baseline_y` (pixels).
    pub fn draw(&self, pixmap: &mut Pixmap, text: &str, x: f32, baseline_y: f32, style: TextStyle) {
        self.draw_with(pixmap, text, [x, baseline_y], style, Transform::identity(), None);
    }
}

/// A glyph outline (y up, pixels from the pen position) as a path in pixmap space (y down).
fn glyph_path(commands: &[Command], x: f32, y: f32) -> Option<Path> {
    let mut pb = PathBuilder::new();
    for c in commands {
        match *c {
            Command::MoveTo(p) => pb.move_to(x + p.x, y - p.y),
            Command::LineTo(p) => pb.line_to(x + p.x, y - p.y),
            Command::QuadTo(c, p) => pb.quad_to(x + c.x, y - c.y, x + p.x, y - p.y),
            Command::CurveTo(a, b, p) => pb.cubic_to(x + a.x, y - a.y, x + b.x, y - b.y, x + p.x, y - p.y),
            Command::Close => pb.close(),
        }
    }
    pb.finish()
}

fn sane_px(px: f32) -> f32 {
    if px.is_finite() { px.clamp(1.0, 512.0) } else { 16.0 }
}

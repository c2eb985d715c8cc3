//! The one drawing surface for diagrams and slides: shape, clip, picture and text primitives in
//! canvas units. A diagram's canvas maps a 960x540 design box uniformly onto the pixmap, centred
//! vertically and at the left of a wider pixmap (so text columns on the right can run on); a
//! slide's canvas is in pixels, its layout its own.

use image::RgbaImage;
use tiny_skia::{
    Color, FillRule, GradientStop, LineCap, LineJoin, LinearGradient, Mask, Paint, Path, PathBuilder, Pixmap,
    PixmapPaint, Point, SpreadMode, Stroke, StrokeDash, Transform,
};

use super::style::{Anchor, Style, col, fin, pal};
use super::text::{TextRenderer, TextStyle};
use crate::i18n;
use crate::i18n::Lang;

/// A label laid out by [`Canvas::plan_label`]: its lines (translated) and their boxes.
pub struct Planned {
    pub lines: Vec<String>,
    pub boxes: Vec<[f32; 4]>,
    pub st: Style,
}

impl Planned {
    /// The box around all its lines, `[x, y, w, h]`.
    pub fn bounds(&self) -> [f32; 4] {
        let x0 = self.boxes.iter().map(|b| b[0]).fold(f32::INFINITY, f32::min);
        let y0 = self.boxes.iter().map(|b| b[1]).fold(f32::INFINITY, f32::min);
        let x1 = self.boxes.iter().map(|b| b[0] + b[2]).fold(f32::NEG_INFINITY, f32::max);
        let y1 = self.boxes.iter().map(|b| b[1] + b[3]).fold(f32::NEG_INFINITY, f32::max);
        if x0 > x1 { [0.0; 4] } else { [x0, y0, x1 - x0, y1 - y0] }
    }
}

/// Pixmap plus a uniform scale from canvas units to pixels (a diagram's design box is at least
/// 960x540 units; a slide's canvas is in pixels).
pub struct Canvas {
    pub pixmap: Pixmap,
    scale: f32,
    /// Offset of the design box inside the full logical canvas.
    off: [f32; 2],
    clip: Option<Mask>,
    text: &'static TextRenderer,
    /// Language of every label: [`Canvas::text`] and [`Canvas::measure`] translate exact
    /// matches of the string table, templates go through [`Canvas::fill`].
    pub lang: Lang,
    /// Every string drawn, as drawn, with its size in pixels (the tests look for English left
    /// in a Chinese diagram and for text too small to read).
    pub drawn: Vec<(String, f32)>,
    /// Smallest text size, design units: text drawn smaller than this on screen grows to it
    /// (up to [`MAX_TEXT_GROWTH`] times its design size).
    min_text: f32,
    /// Right edge of the rightmost text drawn so far, design units.
    pub text_right: f32,
    /// Every text drawn through [`Canvas::text`] (as drawn) with its box `[x, y, w, h]`,
    /// design units: grown labels move off the ones they would cover, labels laid out with
    /// [`Canvas::plan_label`] keep clear of all of them, and the tests check that none overlap.
    pub text_boxes: Vec<(String, [f32; 4])>,
    /// Boxes that hold text of their own (the title bar, legends): other text keeps out of them.
    pub frames: Vec<[f32; 4]>,
    /// Lines drawn as the continuation of a label broken over several lines (the count of
    /// labels is `drawn.len()` less this).
    pub continued: usize,
    /// Labels [`Canvas::fit_label`] had to cut, in full.
    pub shortened: Vec<String>,
    /// A text column had too little room left for its text (a strip a few letters wide): the
    /// text grew more than this canvas holds.
    pub cramped: bool,
}

/// How much a label may grow to reach the minimum text size: more would bury the drawing.
pub const MAX_TEXT_GROWTH: f32 = 1.75;

/// Margin of a text's plate around its box, and of any text from the pixmap's edges.
const TEXT_PAD: f32 = 3.0;
/// Least vertical gap between the boxes of two labels.
pub const LABEL_GAP: f32 = 2.0;

/// Whether boxes `a` and `b` (`[x, y, w, h]`) overlap, or come within `gap` of each other
/// vertically while overlapping horizontally.
pub fn boxes_meet(a: &[f32; 4], b: &[f32; 4], gap: f32) -> bool {
    a[0] < b[0] + b[2] && b[0] < a[0] + a[2] && a[1] < b[1] + b[3] + gap && b[1] < a[1] + a[3] + gap
}

/// Where the anchor lies on a box, as fractions of its width and height from the top left.
fn anchor_fractions(anchor: Anchor) -> (f32, f32) {
    use Anchor::*;
    let fx = match anchor {
        TopLeft | MidLeft | BottomLeft => 0.0,
        TopCenter | BottomCenter => 0.5,
        _ => 1.0,
    };
    let fy = match anchor {
        TopLeft | TopCenter | TopRight => 0.0,
        MidLeft | MidRight => 0.5,
        _ => 1.0,
    };
    (fx, fy)
}

mod labels;

impl Canvas {
    /// A canvas on `pixmap` with labels in `lang`, text at least `min_text_px` pixels high
    /// where growing it by at most [`MAX_TEXT_GROWTH`] reaches that.
    pub fn new(pixmap: Pixmap, lang: Lang, min_text_px: f32) -> Self {
        let (pw, ph) = (pixmap.width() as f32, pixmap.height() as f32);
        let scale = (pw / 960.0).min(ph / 540.0).max(1e-3);
        let off = [0.0, (ph / scale - 540.0) * 0.5];
        let min_text = fin(min_text_px, 0.0).max(0.0) / scale;
        Self::with_units(pixmap, lang, scale, off, min_text, col(pal::BG, 1.0))
    }

    /// A canvas in pixels, filled with `background`, for layouts of their own (the slides).
    pub fn in_pixels(pixmap: Pixmap, lang: Lang, background: Color) -> Self {
        Self::with_units(pixmap, lang, 1.0, [0.0, 0.0], 0.0, background)
    }

    fn with_units(pixmap: Pixmap, lang: Lang, scale: f32, off: [f32; 2], min_text: f32, bg: Color) -> Self {
        let mut c = Self {
            pixmap,
            scale,
            off,
            clip: None,
            text: TextRenderer::shared(),
            lang,
            drawn: Vec::new(),
            min_text,
            text_right: 0.0,
            text_boxes: Vec::new(),
            frames: Vec::new(),
            continued: 0,
            shortened: Vec::new(),
            cramped: false,
        };
        c.pixmap.fill(bg);
        c
    }

    fn ts(&self) -> Transform {
        let s = self.scale;
        Transform::from_row(s, 0.0, 0.0, s, self.off[0] * s, self.off[1] * s)
    }

    /// Clips later shapes (not text) to the rectangle; `None` removes the clip.
    pub fn set_clip(&mut self, rect: Option<[f32; 4]>) {
        self.clip = rect.and_then(|[x, y, w, h]| {
            let mut mask = Mask::new(self.pixmap.width(), self.pixmap.height())?;
            let path = Self::poly(&[[x, y], [x + w, y], [x + w, y + h], [x, y + h]], true)?;
            mask.fill_path(&path, FillRule::Winding, true, self.ts());
            Some(mask)
        });
    }

    fn paint(color: Color) -> Paint<'static> {
        let mut p = Paint::default();
        p.set_color(color);
        p.anti_alias = true;
        p
    }

    pub fn fill_path(&mut self, path: &Path, color: Color) {
        let t = self.ts();
        let paint = Self::paint(color);
        self.pixmap.fill_path(path, &paint, FillRule::Winding, t, self.clip.as_ref());
    }

    pub fn stroke_path(&mut self, path: &Path, color: Color, width: f32, dash: Option<f32>) {
        let mut stroke = Stroke {
            width: width.max(0.1),
            line_cap: LineCap::Round,
            line_join: LineJoin::Round,
            ..Stroke::default()
        };
        if let Some(d) = dash {
            stroke.line_cap = LineCap::Butt;
            stroke.dash = StrokeDash::new(vec![d, d * 0.7], 0.0);
        }
        let t = self.ts();
        let paint = Self::paint(color);
        self.pixmap.stroke_path(path, &paint, &stroke, t, self.clip.as_ref());
    }

    /// Fills the rectangle with a horizontal gradient from `c0` (left) to `c1` (right).
    pub fn gradient_rect(&mut self, r: [f32; 4], c0: Color, c1: Color) {
        let [x, y, w, h] = r.map(|v| fin(v, 0.0).clamp(-1e4, 1e4));
        let (p0, p1) = (Point::from_xy(x, y), Point::from_xy(x + w.max(0.01), y));
        let stops = vec![GradientStop::new(0.0, c0), GradientStop::new(1.0, c1)];
        let Some(shader) = LinearGradient::new(p0, p1, stops, SpreadMode::Pad, Transform::identity()) else {
            return;
        };
        let Some(path) = Self::poly(&[[x, y], [x + w, y], [x + w, y + h], [x, y + h]], true) else {
            return;
        };
        let paint = Paint { shader, anti_alias: true, ..Paint::default() };
        let t = self.ts();
        self.pixmap.fill_path(&path, &paint, FillRule::Winding, t, self.clip.as_ref());
    }

    /// Draws `src` with its top-left corner at `at`, through the canvas scale (nearest texel; on
    /// a canvas in pixels, the picture's pixels as they are).
    pub fn picture(&mut self, src: &Pixmap, at: [f32; 2]) {
        let t = self.ts().pre_translate(fin(at[0], 0.0), fin(at[1], 0.0));
        self.pixmap.draw_pixmap(0, 0, src.as_ref(), &PixmapPaint::default(), t, self.clip.as_ref());
    }

    /// Draws an opaque image with its top-left corner at `at`, as [`Canvas::picture`].
    pub fn image(&mut self, img: &RgbaImage, at: [f32; 2]) {
        let Some(size) = tiny_skia::IntSize::from_wh(img.width(), img.height()) else {
            return;
        };
        // Opaque pixels: straight and premultiplied alpha are the same bytes.
        let data: Vec<u8> = img.pixels().flat_map(|p| [p[0], p[1], p[2], 255]).collect();
        if let Some(src) = Pixmap::from_vec(data, size) {
            self.picture(&src, at);
        }
    }

    /// Polygon or polyline through `pts` (coordinates clamped to a sane range).
    pub fn poly(pts: &[[f32; 2]], close: bool) -> Option<Path> {
        let mut pb = PathBuilder::new();
        for (i, p) in pts.iter().enumerate() {
            let (x, y) = (fin(p[0], 0.0).clamp(-1e4, 1e4), fin(p[1], 0.0).clamp(-1e4, 1e4));
            if i == 0 { pb.move_to(x, y) } else { pb.line_to(x, y) }
        }
        if close {
            pb.close();
        }
        pb.finish()
    }

    pub fn line(&mut self, a: [f32; 2], b: [f32; 2], color: Color, width: f32) {
        self.polyline(&[a, b], color, width, None);
    }

    pub fn dashed(&mut self, a: [f32; 2], b: [f32; 2], color: Color, width: f32, dash: f32) {
        self.polyline(&[a, b], color, width, Some(dash));
    }

    pub fn polyline(&mut self, pts: &[[f32; 2]], color: Color, width: f32, dash: Option<f32>) {
        if let Some(p) = Self::poly(pts, false) {
            self.stroke_path(&p, color, width, dash);
        }
    }

    pub fn polygon(&mut self, pts: &[[f32; 2]], fill: Color) {
        if let Some(p) = Self::poly(pts, true) {
            self.fill_path(&p, fill);
        }
    }

    /// Rectangle `[x, y, w, h]`, filled and/or outlined.
    pub fn rect(&mut self, r: [f32; 4], fill: Option<Color>, line: Option<(Color, f32)>) {
        let [x, y, w, h] = r;
        let r = [[x, y], [x + w, y], [x + w, y + h], [x, y + h]];
        if let Some(p) = Self::poly(&r, true) {
            if let Some(f) = fill {
                self.fill_path(&p, f);
            }
            if let Some((c, lw)) = line {
                self.stroke_path(&p, c, lw, None);
            }
        }
    }

    pub fn circle(&mut self, c: [f32; 2], r: f32, fill: Option<Color>, line: Option<(Color, f32)>) {
        let (x, y) = (fin(c[0], 0.0).clamp(-1e4, 1e4), fin(c[1], 0.0).clamp(-1e4, 1e4));
        let Some(p) = PathBuilder::from_circle(x, y, fin(r, 1.0).clamp(0.1, 1e4)) else {
            return;
        };
        if let Some(f) = fill {
            self.fill_path(&p, f);
        }
        if let Some((c, lw)) = line {
            self.stroke_path(&p, c, lw, None);
        }
    }

    /// Line from `a` to `b` with an arrow head at `b` (and at `a` when `both`).
    pub fn arrow(&mut self, a: [f32; 2], b: [f32; 2], color: Color, width: f32, both: bool) {
        self.line(a, b, color, width);
        let heads: &[([f32; 2], [f32; 2])] = if both { &[(a, b), (b, a)] } else { &[(a, b)] };
        for &(from, to) in heads {
            let (dx, dy) = (to[0] - from[0], to[1] - from[1]);
            let len = (dx * dx + dy * dy).sqrt();
            if len.is_nan() || len <= 1e-3 {
                continue;
            }
            let (ux, uy) = (dx / len, dy / len);
            let s = (4.0 + width * 2.5).min(len * 0.6);
            let back = [to[0] - ux * s, to[1] - uy * s];
            let l = [back[0] - uy * s * 0.55, back[1] + ux * s * 0.55];
            let r = [back[0] + uy * s * 0.55, back[1] - ux * s * 0.55];
            self.polygon(&[to, l, r], color);
        }
    }
}

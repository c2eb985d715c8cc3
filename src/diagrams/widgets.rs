//! Title bar, legends, markers and text columns drawn on a [`Canvas`].

use tiny_skia::{Color, ColorU8};

use super::canvas::Canvas;
use super::style::{Anchor, FS_LABEL, FS_SMALL, FS_TITLE, Style, Swatch, TITLE_H, col, pal};

impl Canvas {
    /// Dark bar across the top of the whole pixmap with the title in white.
    pub fn title_bar(&mut self, title: &str) {
        let [x, y, w, _] = self.full_rect();
        self.rect([x, y, w, TITLE_H], Some(col(pal::TITLE_BG, 1.0)), None);
        self.frames.push([x, y, w, TITLE_H]);
        let st = Style::em(FS_TITLE, pal::TITLE_FG).no_plate();
        self.text(title, [x + 18.0, y + TITLE_H * 0.5], Anchor::MidLeft, st);
    }

    /// Legend box with its corner `anchor` at `p`. Returns its box `[x, y, w, h]`.
    pub fn legend(&mut self, items: &[(Swatch, &str)], p: [f32; 2], anchor: Anchor) -> [f32; 4] {
        let (row, sw) = (self.fs(FS_SMALL) * 1.45, 30.0);
        let [w, h] = self.legend_size(items);
        let x = match anchor {
            Anchor::TopRight | Anchor::BottomRight | Anchor::MidRight => p[0] - w,
            _ => p[0],
        };
        let y = match anchor {
            Anchor::BottomLeft | Anchor::BottomRight | Anchor::BottomCenter => p[1] - h,
            _ => p[1],
        };
        self.rect([x, y, w, h], Some(col(pal::BG, 0.94)), Some((col(pal::MUTED, 1.0), 1.5)));
        self.frames.push([x, y, w, h]);
        for (i, (swatch, s)) in items.iter().enumerate() {
            let cy = y + 6.0 + row * (i as f32 + 0.5);
            self.swatch(*swatch, x + 8.0, cy, sw);
            let st = Style::label(FS_SMALL).no_plate();
            self.text(s, [x + sw + 18.0, cy], Anchor::MidLeft, st);
        }
        [x, y, w, h]
    }

    /// Width and height of the box [`Canvas::legend`] draws.
    pub fn legend_size(&self, items: &[(Swatch, &str)]) -> [f32; 2] {
        let tw = items.iter().map(|(_, s)| self.measure(s, FS_SMALL).0).fold(0.0, f32::max);
        [60.0 + tw, self.fs(FS_SMALL) * 1.45 * items.len() as f32 + 12.0]
    }

    /// One-row legend centred on `center` (x centre, bottom y); on a panel wide enough, a
    /// legend box right of all the text instead, which leaves the bottom to grown text.
    pub fn legend_row(&mut self, items: &[(Swatch, &str)], center: [f32; 2]) -> [f32; 4] {
        if self.legend_fits_right(items, self.text_right) {
            return self.legend_right(items);
        }
        self.legend_bottom_row(items, center)
    }

    /// Legend box right of all the text drawn so far (of the design box at least).
    pub fn legend_right(&mut self, items: &[(Swatch, &str)]) -> [f32; 4] {
        let right_x = self.text_right.max(960.0) + 24.0;
        self.legend(items, [right_x, 64.0], Anchor::TopLeft)
    }

    /// One-row legend centred on `center` (x centre, bottom y).
    pub fn legend_bottom_row(&mut self, items: &[(Swatch, &str)], center: [f32; 2]) -> [f32; 4] {
        let (sw, gap) = (26.0, 22.0);
        let widths: Vec<f32> = items.iter().map(|(_, s)| self.measure(s, FS_SMALL).0 + sw + 8.0).collect();
        let total = widths.iter().sum::<f32>() + gap * (items.len().max(1) - 1) as f32 + 20.0;
        let [fx, _, fw, _] = self.full_rect();
        let x0 = (center[0] - total * 0.5).min(fx + fw - total - 4.0).max(fx + 4.0);
        let y = self.legend_row_top(center[1]);
        let h = center[1] - y;
        let frame = Some((col(pal::MUTED, 1.0), 1.5));
        self.rect([x0, y, total, h], Some(col(pal::BG, 0.94)), frame);
        self.frames.push([x0, y, total, h]);
        let (mut x, cy) = (x0 + 10.0, y + h * 0.5);
        for ((swatch, s), w) in items.iter().zip(&widths) {
            self.swatch(*swatch, x, cy, sw);
            let st = Style::label(FS_SMALL).no_plate();
            self.text(s, [x + sw + 8.0, cy], Anchor::MidLeft, st);
            x += w + gap;
        }
        [x0, y, total, h]
    }

    /// Whether [`Canvas::legend_row`] puts its box right of text reaching `text_right`, rather
    /// than a row at the bottom.
    pub fn legend_fits_right(&self, items: &[(Swatch, &str)], text_right: f32) -> bool {
        let [fx, _, fw, _] = self.full_rect();
        text_right.max(960.0) + 24.0 + self.legend_size(items)[0] + 8.0 <= fx + fw
    }

    /// Top of the bottom row [`Canvas::legend_row`] draws with its bottom at `bottom`.
    pub fn legend_row_top(&self, bottom: f32) -> f32 {
        bottom - self.fs(FS_SMALL) * 1.6
    }

    fn swatch(&mut self, swatch: Swatch, x0: f32, cy: f32, sw: f32) {
        let (x1, mid) = (x0 + sw, [x0 + sw / 2.0, cy]);
        match swatch {
            Swatch::Fill(c, a) => {
                self.rect([x0, cy - 7.0, sw, 14.0], Some(col(c, a)), Some((col(c, 1.0), 1.5)))
            }
            Swatch::Line(c) => self.line([x0, cy], [x1, cy], col(c, 1.0), 4.0),
            Swatch::Dashed(c) => self.dashed([x0, cy], [x1, cy], col(c, 1.0), 3.0, 6.0),
            Swatch::Dot(c) => self.circle(mid, 6.5, Some(col(c, 1.0)), None),
            Swatch::HollowCross(c) => self.cross_marker(mid, 7.0, c),
        }
    }

    /// Hollow ring with an X: the "blocked" marker.
    pub fn cross_marker(&mut self, c: [f32; 2], r: f32, color: ColorU8) {
        let k = col(color, 1.0);
        self.circle(c, r, Some(col(pal::BG, 1.0)), Some((k, 2.5)));
        let d = r * 0.62;
        self.line([c[0] - d, c[1] - d], [c[0] + d, c[1] + d], k, 2.5);
        self.line([c[0] - d, c[1] + d], [c[0] + d, c[1] - d], k, 2.5);
    }

    /// Light icon: a disc filled with `fill` and eight rays, outlined in `ray`.
    pub fn sun(&mut self, at: [f32; 2], fill: Color, ray: Color) {
        for i in 0..8 {
            let (s, c) = (i as f32 * std::f32::consts::FRAC_PI_4).sin_cos();
            let (r0, r1) = (16.0, 23.0);
            self.line([at[0] + c * r0, at[1] + s * r0], [at[0] + c * r1, at[1] + s * r1], ray, 3.0);
        }
        self.circle(at, 12.0, Some(fill), Some((ray, 3.5)));
    }

    /// Camera icon (body and lens) at `at` looking along `angle` (radians), scaled by `k`.
    pub fn camera_icon(&mut self, at: [f32; 2], angle: f32, k: f32) {
        let (sa, ca) = angle.sin_cos();
        let rot = |x: f32, y: f32| [at[0] + k * (x * ca - y * sa), at[1] + k * (x * sa + y * ca)];
        let body = [rot(-26.0, -13.0), rot(4.0, -13.0), rot(4.0, 13.0), rot(-26.0, 13.0)];
        self.polygon(&body, col(pal::CAMERA, 1.0));
        self.polygon(&[rot(4.0, 0.0), rot(18.0, -10.0), rot(18.0, 10.0)], col(pal::CAMERA, 1.0));
    }

    /// Horizontal bracket over the span `x0..x1` at `y`, its ticks pointing up.
    pub fn bracket(&mut self, x0: f32, x1: f32, y: f32, color: Color, width: f32) {
        let pts = [[x0, y - 9.0], [x0, y], [x1, y], [x1, y - 9.0]];
        self.polyline(&pts, color, width, None);
    }
}

/// A column of text lines with plates, top to bottom; a line that would pass [`COLUMN_BOTTOM`]
/// (grown text on a small panel) starts a new column to the right, and so does a block of
/// lines that would not fit whole (a formula and its continuation, a two-line verdict).
pub struct Column {
    pub x: f32,
    pub y: f32,
    top: f32,
    /// Lowest a line may reach before the column flows on.
    pub bottom: f32,
    /// Widest line of the current column, design units.
    width: f32,
    /// Right edge of the widest line of all columns so far, design units.
    right: f32,
    /// Only measures: draws nothing (to try a layout before drawing it).
    dry: bool,
    /// The box of every line so far, `[x, y, w, h]`.
    pub boxes: Vec<[f32; 4]>,
}

/// Least room a text column should have, in text heights: less is a strip of a few letters a
/// line (the canvas is then drawn again with smaller text).
const MIN_COLUMN_EMS: f32 = 8.0;

/// Lowest a column line may reach: the legend row sits below.
pub const COLUMN_BOTTOM: f32 = 494.0;

impl Column {
    pub fn new(x: f32, y: f32) -> Self {
        Self { x, y, top: y, bottom: COLUMN_BOTTOM, width: 0.0, right: x, dry: false, boxes: Vec::new() }
    }

    /// A column that measures its lines without drawing them: [`Column::right`] then tells
    /// how far the drawn column would reach.
    pub fn dry(self) -> Self {
        Self { dry: true, ..self }
    }

    /// Right edge of the widest line so far, design units.
    pub fn right(&self) -> f32 {
        self.right
    }

    fn advance(c: &Canvas, st: &Style) -> f32 {
        c.fs(st.size) * 1.5
    }

    /// One line (broken where wider than the room left of the pixmap's edge).
    pub fn styled(&mut self, c: &mut Canvas, s: &str, st: Style) {
        self.block(c, &[(s, st)]);
    }

    /// Draws the line at the current place (no flow) and moves down.
    fn put(&mut self, c: &mut Canvas, s: &str, st: Style) {
        let b = if self.dry {
            c.text_box(s, [self.x, self.y], Anchor::TopLeft, st.size)
        } else {
            c.text(s, [self.x, self.y], Anchor::TopLeft, st)
        };
        self.boxes.push(b);
        let w = b[2];
        self.width = self.width.max(w);
        self.right = self.right.max(self.x + w);
        self.y += Self::advance(c, &st);
    }

    /// Lines kept together: the block starts a new column when it would pass the bottom, and
    /// a line wider than the room left of the pixmap's edge is wrapped within the block.
    pub fn block<S: AsRef<str>>(&mut self, c: &mut Canvas, lines: &[(S, Style)]) {
        let [fx, _, fw, _] = c.full_rect();
        // Each line, broken where wider than the room: (text, style, continues the line before).
        let wrapped = |c: &Canvas, x: f32| -> Vec<(String, Style, bool)> {
            let room = (fx + fw - 4.0 - x).max(60.0);
            lines
                .iter()
                .flat_map(|(s, st)| {
                    let s = crate::i18n::tr(c.lang, s.as_ref());
                    let parts = match c.measure(s, st.size).0 > room {
                        true => c.wrap(s, c.fs(st.size), room),
                        false => vec![s.to_string()],
                    };
                    parts.into_iter().enumerate().map(move |(i, p)| (p, *st, i > 0))
                })
                .collect()
        };
        let height =
            |c: &Canvas, ls: &[(String, Style, bool)]| ls.iter().map(|(_, st, _)| Self::advance(c, st)).sum();
        let mut ls = wrapped(c, self.x);
        let x = self.x;
        self.reserve(height(c, &ls));
        if self.x != x {
            ls = wrapped(c, self.x);
        }
        let widest = lines.iter().map(|(_, st)| c.fs(st.size)).fold(0.0, f32::max);
        if !self.dry && fx + fw - 4.0 - self.x < MIN_COLUMN_EMS * widest {
            c.cramped = true;
        }
        for (s, st, continues) in &ls {
            self.put(c, s, *st);
            if *continues && !self.dry {
                c.continued += 1;
            }
        }
    }

    /// Starts a new column when `height` more would pass [`COLUMN_BOTTOM`].
    pub fn reserve(&mut self, height: f32) {
        if self.y + height > self.bottom && self.y > self.top {
            (self.x, self.y, self.width) = (self.x + self.width + 24.0, self.top, 0.0);
        }
    }

    /// Regular ink line at label size.
    pub fn line(&mut self, c: &mut Canvas, s: &str) {
        self.styled(c, s, Style::label(FS_LABEL));
    }

    /// Regular coloured line at label size.
    pub fn tint(&mut self, c: &mut Canvas, s: &str, color: ColorU8) {
        self.styled(c, s, Style::tint(FS_LABEL, color));
    }

    /// Bold coloured line at label size.
    pub fn em(&mut self, c: &mut Canvas, s: &str, color: ColorU8) {
        self.styled(c, s, Style::em(FS_LABEL, color));
    }
}

//! Text on the canvas: sizes, fitting and wrapping, and labels placed clear of each other and of
//! what is drawn (the checks the diagram tests make on every label).

use super::*;

impl Canvas {
    /// `template` in the canvas language with its `{}` holes filled in order.
    pub fn fill(&self, template: &'static str, args: &[&dyn std::fmt::Display]) -> String {
        i18n::fill(self.lang, template, args)
    }

    /// The size text of design size `size` is drawn at (grown towards the minimum size).
    pub fn fs(&self, size: f32) -> f32 {
        size.max(self.min_text).min(size * MAX_TEXT_GROWTH)
    }

    /// Width of `s` as given (not translated) at size `size`, canvas units.
    pub fn text_width(&self, s: &str, size: f32) -> f32 {
        self.text.measure(s, size * self.scale).width_px / self.scale
    }

    /// `s` cut to `max_width` at `size` with an ellipsis (as given, not translated).
    pub fn fit(&self, s: &str, size: f32, max_width: f32) -> String {
        if self.text_width(s, size) <= max_width {
            return s.to_string();
        }
        // The longest prefix that fits with the ellipsis, by bisection over character ends.
        let ends: Vec<usize> = s.char_indices().map(|(i, _)| i).skip(1).chain([s.len()]).collect();
        let cut = |n: usize| format!("{}…", s[..if n == 0 { 0 } else { ends[n - 1] }].trim_end());
        let (mut fits, mut too_long) = (0, ends.len());
        while too_long - fits > 1 {
            let mid = (fits + too_long) / 2;
            if self.text_width(&cut(mid), size) <= max_width { fits = mid } else { too_long = mid }
        }
        cut(fits)
    }

    /// [`Canvas::fit`] for a label that should fit: one that does not is listed in
    /// [`Canvas::shortened`].
    pub fn fit_label(&mut self, s: &str, size: f32, max_width: f32) -> String {
        let fitted = self.fit(s, size, max_width);
        if fitted != s {
            self.shortened.push(s.to_string());
        }
        fitted
    }

    /// `s` (as given) broken into lines no wider than `max_width` at `size` (Unicode line breaking).
    pub fn wrap(&self, s: &str, size: f32, max_width: f32) -> Vec<String> {
        self.text.wrap(s, size * self.scale, max_width * self.scale)
    }

    /// Draws `s` as given (not translated, not moved) with its left end at `x` and its baseline
    /// at `baseline`, at size `size`, canvas units.
    pub fn text_run(&mut self, s: &str, [x, baseline]: [f32; 2], size: f32, color: Color, bold: bool) {
        let (sc, [ox, oy]) = (self.scale, self.off);
        self.drawn.push((s.to_string(), size * sc));
        let style = TextStyle { px: size * sc, color, bold };
        self.text.draw(&mut self.pixmap, s, (x + ox) * sc, (baseline + oy) * sc, style);
    }

    pub fn measure(&self, text: &str, size: f32) -> (f32, f32) {
        let text = i18n::tr(self.lang, text);
        let m = self.text.measure(text, self.fs(size) * self.scale);
        (m.width_px / self.scale, m.height_px() / self.scale)
    }

    /// Every pair of drawn texts whose boxes overlap, and every text that reaches into a frame
    /// (title bar, legend) without lying inside it.
    pub fn overlapping_text(&self) -> Vec<String> {
        let meet = |a: &[f32; 4], b: &[f32; 4]| super::boxes_meet(a, b, -0.5);
        let inside = |a: &[f32; 4], f: &[f32; 4]| {
            a[0] >= f[0] - 0.5
                && a[1] >= f[1] - 0.5
                && a[0] + a[2] <= f[0] + f[2] + 0.5
                && a[1] + a[3] <= f[1] + f[3] + 0.5
        };
        let mut out = Vec::new();
        for (i, (s, a)) in self.text_boxes.iter().enumerate() {
            for (t, b) in &self.text_boxes[i + 1..] {
                if meet(a, b) {
                    out.push(format!("{s:?} {a:?} overlaps {t:?} {b:?}"));
                }
            }
            for f in &self.frames {
                if meet(a, f) && !inside(a, f) {
                    out.push(format!("{s:?} {a:?} reaches into the frame {f:?}"));
                }
            }
        }
        out
    }

    /// The whole pixmap in design units, `[x, y, w, h]` (wider or taller than the design box
    /// when the aspect ratio differs from 16:9).
    pub fn full_rect(&self) -> [f32; 4] {
        let [ox, oy] = self.off;
        let (pw, ph) = (self.pixmap.width() as f32, self.pixmap.height() as f32);
        [-ox, -oy, pw / self.scale, ph / self.scale]
    }

    /// The box `[x, y, w, h]` text `s` (translated) of design size `size` takes when anchored at
    /// `p`, kept inside the pixmap, and its ascent.
    fn layout(&self, s: &str, p: [f32; 2], anchor: Anchor, size: f32) -> ([f32; 4], f32) {
        let s = i18n::tr(self.lang, s);
        let sc = self.scale;
        let m = self.text.measure(s, self.fs(size) * sc);
        let (w, asc, h) = (m.width_px / sc, m.ascent_px / sc, m.height_px() / sc);
        let (fx, fy) = anchor_fractions(anchor);
        let pad = TEXT_PAD;
        let [fx0, fy0, fw, fh] = self.full_rect();
        let x = (fin(p[0], 0.0) - fx * w).clamp(fx0 + pad, (fx0 + fw - w - pad).max(fx0 + pad));
        let y = (fin(p[1], 0.0) - fy * h).clamp(fy0 + pad, (fy0 + fh - h - pad).max(fy0 + pad));
        ([x, y, w, h], asc)
    }

    /// The box [`Canvas::text`] would draw `s` in at `p` (before any move off earlier text).
    pub fn text_box(&self, s: &str, p: [f32; 2], anchor: Anchor, size: f32) -> [f32; 4] {
        self.layout(s, p, anchor, size).0
    }

    /// Whether the box `b` keeps at least `gap` from every text drawn so far, every frame and
    /// every box of `avoid`.
    pub fn is_clear(&self, b: [f32; 4], gap: f32, avoid: &[[f32; 4]]) -> bool {
        let drawn = self.text_boxes.iter().map(|(_, o)| o);
        !drawn.chain(&self.frames).chain(avoid).any(|o| boxes_meet(&b, o, gap))
    }

    /// Lays out a label of one or more `lines` (each translated; drawn one under another,
    /// aligned as `anchor` says) at the first of `spots` (point and anchor of the whole block)
    /// where the block stays inside the pixmap and keeps clear of the text drawn so far, the
    /// frames and every box of `avoid`; at the first spot when none does. Draw it with
    /// [`Canvas::draw_planned`].
    pub fn plan_label(
        &self,
        lines: &[&str],
        spots: &[([f32; 2], Anchor)],
        st: Style,
        avoid: &[[f32; 4]],
    ) -> Planned {
        self.find_label_spot(lines, spots, st, avoid)
            .unwrap_or_else(|| self.label_at(lines, spots.first().copied(), st))
    }

    /// [`Canvas::plan_label`] without the fallback: `None` when no spot is free.
    pub fn find_label_spot(
        &self,
        lines: &[&str],
        spots: &[([f32; 2], Anchor)],
        st: Style,
        avoid: &[[f32; 4]],
    ) -> Option<Planned> {
        let [fx0, fy0, fw, fh] = self.full_rect();
        let inside = |b: &[f32; 4]| {
            b[0] >= fx0 + TEXT_PAD
                && b[1] >= fy0 + TEXT_PAD
                && b[0] + b[2] <= fx0 + fw - TEXT_PAD
                && b[1] + b[3] <= fy0 + fh - TEXT_PAD
        };
        spots
            .iter()
            .map(|spot| self.label_at(lines, Some(*spot), st))
            .find(|p| p.boxes.iter().all(|b| inside(b) && self.is_clear(*b, LABEL_GAP, avoid)))
    }

    /// The place for `lines` nearest `target` (box centre to target) among the points of a grid
    /// over `region` (`[x, y, w, h]`) where the label, anchored at its top left, stays inside
    /// the region and the pixmap and keeps clear as in [`Canvas::find_label_spot`].
    pub fn find_label_near(
        &self,
        lines: &[&str],
        target: [f32; 2],
        region: [f32; 4],
        st: Style,
        avoid: &[[f32; 4]],
    ) -> Option<Planned> {
        let at_origin = self.label_at(lines, Some(([0.0, 0.0], Anchor::TopLeft)), st);
        let [_, _, w, h] = at_origin.bounds();
        let [fx0, fy0, fw, fh] = self.full_rect();
        let x0 = region[0].max(fx0 + TEXT_PAD);
        let y0 = region[1].max(fy0 + TEXT_PAD);
        let x1 = (region[0] + region[2]).min(fx0 + fw - TEXT_PAD) - w;
        let y1 = (region[1] + region[3]).min(fy0 + fh - TEXT_PAD) - h;
        let step = 8.0;
        let (nx, ny) = (((x1 - x0) / step).floor(), ((y1 - y0) / step).floor());
        if !(nx >= 0.0 && ny >= 0.0) || nx * ny > 1e5 {
            return None;
        }
        let mut best: Option<(f32, [f32; 2])> = None;
        for iy in 0..=ny as usize {
            for ix in 0..=nx as usize {
                let (x, y) = (x0 + ix as f32 * step, y0 + iy as f32 * step);
                let (dx, dy) = (x + w * 0.5 - target[0], y + h * 0.5 - target[1]);
                let d = dx * dx + dy * dy;
                if best.is_some_and(|(bd, _)| bd <= d) {
                    continue;
                }
                let free = at_origin
                    .boxes
                    .iter()
                    .all(|b| self.is_clear([b[0] + x, b[1] + y, b[2], b[3]], LABEL_GAP, avoid));
                if free {
                    best = Some((d, [x, y]));
                }
            }
        }
        best.map(|(_, [x, y])| Planned {
            boxes: at_origin.boxes.iter().map(|b| [b[0] + x, b[1] + y, b[2], b[3]]).collect(),
            ..at_origin
        })
    }

    /// The label's lines laid out at `spot`.
    fn label_at(&self, lines: &[&str], spot: Option<([f32; 2], Anchor)>, st: Style) -> Planned {
        let lines: Vec<String> = lines.iter().map(|l| i18n::tr(self.lang, l).to_string()).collect();
        let sizes: Vec<(f32, f32)> = lines.iter().map(|l| self.measure(l, st.size)).collect();
        let w = sizes.iter().map(|s| s.0).fold(0.0, f32::max);
        let h = sizes.iter().map(|s| s.1).fold(0.0, f32::max);
        let n = lines.len() as f32;
        let block_h = n * h + (n - 1.0).max(0.0) * LABEL_GAP;
        let Some((p, anchor)) = spot else {
            return Planned { lines: Vec::new(), boxes: Vec::new(), st };
        };
        let (ax, ay) = anchor_fractions(anchor);
        let (x0, y0) = (fin(p[0], 0.0) - ax * w, fin(p[1], 0.0) - ay * block_h);
        let step = h + LABEL_GAP;
        let boxes = sizes
            .iter()
            .enumerate()
            .map(|(i, (lw, _))| [x0 + ax * (w - lw), y0 + i as f32 * step, *lw, h])
            .collect();
        Planned { lines, boxes, st }
    }

    /// Draws a label laid out by [`Canvas::plan_label`].
    pub fn draw_planned(&mut self, p: &Planned) {
        for (line, b) in p.lines.iter().zip(&p.boxes) {
            self.text(line, [b[0], b[1]], Anchor::TopLeft, p.st);
        }
        self.continued += p.lines.len().saturating_sub(1);
    }

    /// Draws text anchored at `p`, kept inside the pixmap; with `st.plate`, a translucent plate
    /// behind it keeps it legible over lines. Returns the box `[x, y, w, h]`.
    pub fn text(&mut self, s: &str, p: [f32; 2], anchor: Anchor, st: Style) -> [f32; 4] {
        let ([x, mut y, w, h], asc) = self.layout(s, p, anchor, st.size);
        let s = i18n::tr(self.lang, s);
        let [_, fy0, _, fh] = self.full_rect();
        let pad = TEXT_PAD;
        if st.plate && self.min_text > 0.0 {
            y = self.clear_of_earlier_text([x, y, w, h], [fy0 + pad, fy0 + fh - h - pad]);
        }
        self.text_boxes.push((s.to_string(), [x, y, w, h]));
        if st.plate {
            let plate = [x - pad, y - pad * 0.5, w + 2.0 * pad, h + pad];
            self.rect(plate, Some(col(pal::BG, 0.88)), None);
        }
        self.text_right = self.text_right.max(x + w);
        self.text_run(s, [x, y + asc], self.fs(st.size), col(st.color, 1.0), st.bold);
        [x, y, w, h]
    }

    /// `y` for the box `b` moved up or down (whichever is the shorter move within `y_range`)
    /// until it covers no earlier text. Only text grown for a small panel needs this: the
    /// layouts are drawn for their design sizes.
    fn clear_of_earlier_text(&self, b: [f32; 4], y_range: [f32; 2]) -> f32 {
        let free = |y: f32| {
            let moved = [b[0], y, b[2], b[3]];
            !self.text_boxes.iter().any(|(_, o)| boxes_meet(&moved, o, LABEL_GAP))
        };
        let mut candidates = vec![b[1]];
        for (_, o) in &self.text_boxes {
            candidates.push(o[1] + o[3] + LABEL_GAP + 0.5);
            candidates.push(o[1] - b[3] - LABEL_GAP - 0.5);
        }
        candidates
            .into_iter()
            .filter(|y| (y_range[0]..=y_range[1].max(y_range[0])).contains(y) && free(*y))
            .min_by(|a, c| (a - b[1]).abs().total_cmp(&(c - b[1]).abs()))
            .unwrap_or(b[1])
    }

    /// Shorthand: ink-coloured label with a plate.
    pub fn label(&mut self, s: &str, p: [f32; 2], anchor: Anchor, size: f32) -> [f32; 4] {
        self.text(s, p, anchor, Style::label(size))
    }
}

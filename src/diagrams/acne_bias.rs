//! Shadow acne and peter panning: a tilted receiver under light from above, the depth "steps"
//! the shadow map stores (one per texel: the depth at the texel centre), and the bias that
//! moves the steps down.

use super::canvas::{Canvas, Planned};
use super::style::{Anchor, FS_LABEL, FS_SMALL, Style, Swatch, col, fin, ndc, num, pal};
use super::widgets::Column;
use super::{DiagramInputs, bias_world, ndc_per_world, texel_world};
use crate::i18n;

/// Plot box: x, y, w, h.
const PLOT: [f32; 4] = [30.0, 100.0, 540.0, 376.0];
/// Thickness of the object (a plate resting on the receiver), texels.
const PLATE: f32 = 0.6;

#[derive(Clone, Copy, PartialEq)]
enum Verdict {
    Lit,
    Acne,
    Shadow,
    Leak,
}

/// The zoomed window, in texel units: `n` texels wide, depth measured downwards.
struct View {
    n: usize,
    tpx: f32,
    x_left: f32,
    y_mid: f32,
    slope: f32,
    contact: f32,
}

impl View {
    fn sx(&self, x: f32) -> f32 {
        self.x_left + x * self.tpx
    }
    fn sy(&self, d: f32) -> f32 {
        self.y_mid + d * self.tpx
    }
    /// Receiver depth at `x` (texels, relative to the window's middle).
    fn surf(&self, x: f32) -> f32 {
        (x - self.n as f32 * 0.5) * self.slope
    }
    fn plate_top(&self) -> f32 {
        self.surf(self.contact) - PLATE
    }
    /// Depth stored by texel `i`: the plate where it covers the texel centre, else the surface.
    fn stored(&self, i: usize) -> f32 {
        let xc = i as f32 + 0.5;
        if xc >= self.contact { self.plate_top() } else { self.surf(xc) }
    }
    fn at(&self, x: f32) -> [f32; 2] {
        [self.sx(x), self.sy(self.surf(x))]
    }
}

pub fn draw(c: &mut Canvas, inp: &DiagramInputs) {
    let map = inp.shadow_map_size_texels.max(1) as f32;
    let w_frustum = fin(inp.frustum_width_world, 200.0).abs().max(1e-6);
    let recv = fin(inp.receiver_depth_linear, 113.0);
    // One texel's footprint at the receiver.
    let near = fin(inp.light_near, 1.0).abs().max(1e-6);
    let texel = texel_world(inp, recv);
    let angle = fin(inp.light_angle_deg, 45.0).abs().min(89.9);
    let slope = angle.to_radians().tan();
    let slope_draw = angle.min(85.0).to_radians().tan();
    let k_normal = fin(inp.normal_offset_texels, 0.0).max(0.0);
    // A normal offset of k texels acts as an extra depth bias of k * texel / cos(angle).
    let normal_world = k_normal * texel / angle.min(85.0).to_radians().cos();
    let bias_w = bias_world(inp, recv).max(0.0);
    let bias_eff = bias_w + normal_world;
    let needed = 0.5 * texel * slope;

    // A fixed world window (8 texels of a 2048 map), narrowed for steep slopes so it fits.
    let n = ((8.0 * map / 2048.0 / slope_draw.max(1.0)).round() as usize).clamp(3, 20);
    let nf = n as f32;
    let tpx = (PLOT[2] / nf).min(PLOT[3] / (nf * slope_draw + 3.0)).max(12.0);
    let v = View {
        n,
        tpx,
        x_left: PLOT[0] + (PLOT[2] - nf * tpx) * 0.5,
        y_mid: PLOT[1] + (1.2 + nf * 0.5 * slope_draw) * tpx,
        slope: slope_draw,
        contact: nf * 0.5 + 0.5,
    };
    let bias_tx = bias_eff / texel;

    c.set_clip(Some(PLOT));
    // Receiver body and the plate.
    let (x0, x1, bottom) = (-2.0, nf + 2.0, PLOT[1] + PLOT[3] + 10.0);
    let body = [v.at(x0), v.at(x1), [v.sx(x1), bottom], [v.sx(x0), bottom]];
    c.polygon(&body, col(pal::RECEIVER, 0.35));
    let (top, base) = (v.sy(v.plate_top()), v.sy(v.surf(v.contact)));
    let (pl, pr) = (v.sx(v.contact), v.sx(x1));
    c.polygon(&[[pl, top], [pr, top], [pr, base], [pl, base]], col(pal::BLOCKER, 1.0));
    // Light rays through the texel centres.
    for i in 0..n {
        let x = v.sx(i as f32 + 0.5);
        c.arrow([x, PLOT[1] - 4.0], [x, v.sy(v.stored(i)) - 4.0], col(pal::LIGHT, 0.75), 2.0, false);
    }
    // Surface, coloured by the shadow test at each point.
    let steps = 240;
    let mut prev: Option<([f32; 2], Verdict)> = None;
    let (mut acne_at, mut leak_end) = (None, v.contact);
    let inside =
        |p: [f32; 2]| p[0] > PLOT[0] + 40.0 && (PLOT[1] + 10.0..PLOT[1] + PLOT[3] - 40.0).contains(&p[1]);
    for j in 0..=steps {
        let x = j as f32 / steps as f32 * nf;
        let i = (x.floor() as usize).min(n - 1);
        // With front faces culled the map holds the object's far side: the lit surface (before
        // the contact) is never compared with itself, whatever the bias; the blocker still is.
        let self_test = x <= v.contact;
        // The receiver-plane bias compares every point of a texel at the texel's centre.
        let receiver = if inp.receiver_plane { v.surf(i as f32 + 0.5) } else { v.surf(x) };
        let shadowed = !(inp.cull_front_faces && self_test) && receiver - bias_tx > v.stored(i) + 1e-4;
        // With the plane, a point before the contact is shadowed only by a texel the object
        // covers: a real (if quantised) shadow, not acne.
        let before_contact = x <= v.contact && !(inp.receiver_plane && i as f32 + 0.5 >= v.contact);
        let verdict = match (!before_contact, shadowed) {
            (false, false) => Verdict::Lit,
            (false, true) => Verdict::Acne,
            (true, true) => Verdict::Shadow,
            (true, false) => Verdict::Leak,
        };
        if verdict == Verdict::Leak {
            leak_end = x;
        }
        let pt = v.at(x);
        if let Some((pp, pv)) = prev {
            let (color, width) = match pv {
                Verdict::Lit | Verdict::Leak => (pal::LIGHT, 8.0),
                Verdict::Acne => (pal::BLOCKED, 10.0),
                Verdict::Shadow => (pal::SHADOW, 8.0),
            };
            c.line(pp, pt, col(color, 1.0), width);
            if pv == Verdict::Acne && acne_at.is_none() && inside(pp) {
                acne_at = Some(pp);
            }
        }
        prev = Some((pt, verdict));
    }
    // Stored steps, and the same steps moved down by the bias; with the receiver plane, what
    // each texel's points are compared with: the plane at the centre, less the bias (on the step).
    let shift_px = (bias_tx * tpx).min(PLOT[3] * 2.0);
    for i in 0..n {
        let (a, b, y) = (v.sx(i as f32), v.sx(i as f32 + 1.0), v.sy(v.stored(i)));
        c.line([a, y], [b, y], col(pal::BLOCKER, 1.0), 3.5);
        if inp.receiver_plane && i as f32 + 0.5 < v.contact {
            let y = v.sy(v.surf(i as f32 + 0.5)) - shift_px - 4.0;
            c.dashed([a, y], [b, y], col(pal::SEARCH, 1.0), 3.0, 7.0);
        } else if !inp.receiver_plane && shift_px > 0.5 {
            c.dashed([a, y + shift_px], [b, y + shift_px], col(pal::SEARCH, 1.0), 3.0, 7.0);
        }
    }
    c.set_clip(None);

    // Shadow-map row at the top.
    let row = [v.sx(0.0), PLOT[1] - 26.0, nf * tpx, 18.0];
    for i in 0..n {
        let cell = [v.sx(i as f32), row[1], tpx, row[3]];
        c.rect(cell, Some(col(pal::BG, 1.0)), Some((col(pal::INK, 1.0), 1.5)));
    }
    // What the labels keep off: the texel row, the surface, the object and the arrows.
    let mut drawing = vec![row];
    for i in 0..n {
        let (a, b) = (v.at(i as f32), v.at(i as f32 + 1.0));
        drawing.push([
            a[0].min(b[0]) - 5.0,
            a[1].min(b[1]) - 5.0,
            (b[0] - a[0]).abs() + 10.0,
            (b[1] - a[1]).abs() + 10.0,
        ]);
    }
    let plate_right = pr.min(PLOT[0] + PLOT[2]);
    drawing.push([pl, top, (plate_right - pl).max(0.0), base - top]);
    // Bias arrow on the first visible texel.
    let first = (0..n).find(|&i| v.sy(v.stored(i)) > PLOT[1] + 6.0).unwrap_or(0);
    let mut bias_label = None;
    if shift_px > 0.5 && !inp.receiver_plane {
        let (x, y) = (v.sx(first as f32 + 0.75), v.sy(v.stored(first)));
        let y_end = (y + shift_px).min(PLOT[1] + PLOT[3] - 4.0);
        c.arrow([x, y], [x, y_end], col(pal::SEARCH, 1.0), 2.5, false);
        drawing.push([x - 4.0, y, 8.0, y_end - y]);
        let t = match y + shift_px > y_end {
            true => c.fill("bias = {} texels (steps below view)", &[&num(bias_tx)]),
            false => c.fill("bias = {} texels", &[&num(bias_tx)]),
        };
        bias_label = Some((t, [x + 8.0, (y + y_end) * 0.5]));
    }
    let mut gap_label = None;
    if leak_end > v.contact + 0.02 {
        let gap_w = if slope > 1e-6 { (bias_eff - PLATE * texel).max(0.0) / slope } else { f32::INFINITY };
        let end = leak_end.min(nf);
        // A dimension line across the light (the gap is measured across it, not along the
        // slope), under the surface's deeper end.
        let (a, b) = (v.at(v.contact), v.at(end));
        let y = (a[1].max(b[1]) + 26.0).min(PLOT[1] + PLOT[3] - 20.0);
        let (a, b) = ([a[0], y], [b[0], y]);
        c.arrow(a, b, col(pal::PENUMBRA, 1.0), 3.0, true);
        drawing.push([a[0].min(b[0]), y - 6.0, (b[0] - a[0]).abs(), 12.0]);
        let t = match leak_end >= nf - 0.01 {
            true => c.fill("peter panning gap = {} world, beyond view", &[&num(gap_w)]),
            false => c.fill("peter panning gap = {} world", &[&num(gap_w)]),
        };
        gap_label = Some((t, [a, b]));
    }
    let marks = Marks {
        texels: [v.sx(0.0), v.sx(nf), row[1], row[1] + row[3]],
        contact: [v.sx(v.contact), top, base],
        acne: acne_at,
        bias: bias_label,
        gap: gap_label,
    };

    // The numbers, in blocks that stay whole (a formula and its value, the verdict).
    let npw = ndc_per_world(inp, recv);
    let label = |s: String| (s, Style::label(FS_LABEL));
    let mut blocks: Vec<Vec<(String, Style)>> = Vec::new();
    if inp.orthographic {
        let t = c.fill("   = {} / {} = {} world", &[&num(w_frustum), &(map as u32), &num(texel)]);
        blocks.push(vec![label("texel = W / map size".into()), label(t)]);
    } else {
        let t = c.fill(
            "   = {} / {} · {} / {} = {} world",
            &[&num(w_frustum), &(map as u32), &num(recv), &num(near), &num(texel)],
        );
        blocks.push(vec![label("texel = W_near / map size · d / near".into()), label(t)]);
    }
    let (angle_txt, slope_txt) = angle_and_slope(angle);
    blocks.push(vec![label(c.fill("slope = tan({}°) = {}", &[&angle_txt, &slope_txt]))]);
    let t = c.fill("   = {} world = {} NDC", &[&num(needed), &ndc(needed * npw)]);
    blocks.push(vec![label("needed bias ≈ texel/2 · slope".into()), label(t)]);
    let b_ndc = ndc(fin(inp.bias_ndc, 0.0));
    blocks.push(vec![label(c.fill("bias = {} NDC = {} world", &[&b_ndc, &num(bias_w)]))]);
    let t = c.fill("normal offset = {} texels", &[&num(k_normal)]);
    let t2 = c.fill("   = {} world of extra bias", &[&num(normal_world)]);
    blocks.push(vec![label(t), label(t2)]);
    let (verdict, vc) = if inp.cull_front_faces {
        (["front faces culled: the map holds", "back faces, so no acne here"], pal::LIT)
    } else if inp.receiver_plane && bias_eff > 0.0 {
        (["receiver plane: each point is tested", "at its texel's centre: no acne"], pal::LIT)
    } else if bias_eff < needed * 0.999 {
        (["too little bias:", "acne (self-shadowing stripes)"], pal::BLOCKED)
    } else if bias_eff > needed * 3.0 {
        (["more bias than needed:", "shadow detaches (peter panning)"], pal::PENUMBRA)
    } else {
        (["bias about right:", "no acne, small gap"], pal::LIT)
    };
    let verdict = verdict.map(|l| (l.to_string(), Style::em(FS_LABEL, vc))).to_vec();

    let items = [
        (Swatch::Line(pal::LIGHT), "lit"),
        (Swatch::Line(pal::BLOCKED), "acne"),
        (Swatch::Line(pal::SHADOW), "shadow"),
        (Swatch::Line(pal::BLOCKER), "stored depth"),
        (
            Swatch::Dashed(pal::SEARCH),
            if inp.receiver_plane { "plane at texel centre" } else { "stored + bias" },
        ),
        (Swatch::Fill(pal::BLOCKER, 1.0), "object"),
    ];
    // The numbers first, at their place; the labels on the plot around the drawing and clear
    // of them. The legend goes right of all the text where the panel is wide enough, else under
    // the last column of numbers where that has room, else in a row at the bottom, which the
    // labels and the numbers then keep above.
    let [fx, fy, fw, fh] = c.full_rect();
    let legend_size = c.legend_size(&items);
    for place in [Legend::Right, Legend::UnderNumbers, Legend::Below] {
        let bottom = match place {
            Legend::Below => c.legend_row_top(LEGEND_BOTTOM),
            _ => fy + fh,
        } - 6.0;
        let column = |dry: bool| {
            let mut col = Column::new(COLUMN_X, PLOT[1] + 4.0);
            col.bottom = bottom;
            if dry { col.dry() } else { col }
        };
        let mut trial = column(true);
        lay_out(c, &mut trial, &blocks, &verdict);
        let mut avoid = drawing.clone();
        avoid.extend(trial.boxes.iter().copied());
        let last = trial.boxes.last().copied().unwrap_or([COLUMN_X, PLOT[1], 0.0, 0.0]);
        let under = [last[0], last[1] + last[3] + 12.0, legend_size[0], legend_size[1]];
        if place == Legend::UnderNumbers {
            if under[1] + under[3] > bottom || under[0] + under[2] > fx + fw - 4.0 {
                continue;
            }
            avoid.push(under);
        }
        let labels = plan_labels(c, &marks, &avoid, bottom);
        let labels_right = labels.iter().map(|l| l.bounds()).map(|b| b[0] + b[2]).fold(0.0, f32::max);
        let text_right = c.text_right.max(labels_right).max(trial.right());
        if place == Legend::Right && !c.legend_fits_right(&items, text_right) {
            continue;
        }
        lay_out(c, &mut column(false), &blocks, &verdict);
        for l in &labels {
            c.draw_planned(l);
        }
        match place {
            Legend::Right => c.legend_right(&items),
            Legend::UnderNumbers => c.legend(&items, [under[0], under[1]], Anchor::TopLeft),
            Legend::Below => c.legend_bottom_row(&items, [480.0, LEGEND_BOTTOM]),
        };
        break;
    }
}

#[derive(Clone, Copy, PartialEq)]
enum Legend {
    Right,
    UnderNumbers,
    Below,
}

/// Bottom of the legend row.
const LEGEND_BOTTOM: f32 = 530.0;
/// Left of the numbers' column.
const COLUMN_X: f32 = 600.0;

/// Where the plot's labels belong.
struct Marks {
    /// The texel row: left, right, top, bottom.
    texels: [f32; 4],
    /// The contact point (x, y) and the object's base.
    contact: [f32; 3],
    /// The first acne on the surface.
    acne: Option<[f32; 2]>,
    /// The bias label and the middle of its arrow.
    bias: Option<(String, [f32; 2])>,
    /// The gap label and the ends of its dimension line.
    gap: Option<(String, [[f32; 2]; 2])>,
}

/// The labels on the plot, each at the first of its places that covers no other label, none of
/// `drawing` (the picture and the numbers) and nothing below `bottom`: on one line or, where
/// that fits nowhere, on two or three, and left of the numbers' column unless they fit nowhere
/// else.
fn plan_labels(c: &Canvas, m: &Marks, drawing: &[[f32; 4]], bottom: f32) -> Vec<Planned> {
    let [fx, fy, fw, _] = c.full_rect();
    let mut avoid = drawing.to_vec();
    avoid.push([fx, bottom, fw, 1e4]);
    let numbers = [COLUMN_X - 10.0, fy, 1e5, 1e5];
    let mut out: Vec<Planned> = Vec::new();
    // Anywhere left of the numbers and above the bottom, as a last resort.
    let plot_side = [fx, PLOT[1] - 40.0, COLUMN_X - 10.0 - fx, bottom - (PLOT[1] - 40.0)];
    let mut place = |c: &Canvas, text: &str, spots: &[([f32; 2], Anchor)], st: Style| {
        let one = vec![i18n::tr(c.lang, text).to_string()];
        // Only long labels are broken: a short one would be cut after its "=".
        let width = c.measure(text, st.size).0;
        let long = width > 12.0 * c.fs(st.size);
        let wrapped =
            [0.6, 0.4].map(|k| if long { c.wrap(&one[0], c.fs(st.size), width * k) } else { Vec::new() });
        let variants: Vec<Vec<&str>> = [&one, &wrapped[0], &wrapped[1]]
            .into_iter()
            .filter(|v| !v.is_empty())
            .map(|v| v.iter().map(String::as_str).collect())
            .collect();
        let beside_numbers: Vec<[f32; 4]> = avoid.iter().copied().chain([numbers]).collect();
        let target = spots.first().map_or([0.0; 2], |s| s.0);
        let found = variants
            .iter()
            .find_map(|v| c.find_label_spot(v, spots, st, &beside_numbers))
            .or_else(|| variants.iter().find_map(|v| c.find_label_spot(v, spots, st, &avoid)))
            .or_else(|| variants.iter().find_map(|v| c.find_label_near(v, target, plot_side, st, &avoid)));
        let p = found.unwrap_or_else(|| c.plan_label(&[text], spots, st, &avoid));
        avoid.extend(p.boxes.iter().copied());
        out.push(p);
    };
    let [l, r, t, b] = m.texels;
    let small = Style::label(FS_SMALL);
    let spots = [
        ([l, t - 4.0], Anchor::BottomLeft),
        ([r + 10.0, (t + b) * 0.5], Anchor::MidLeft),
        ([l - 10.0, (t + b) * 0.5], Anchor::MidRight),
    ];
    place(c, "shadow-map texels", &spots, small);
    let [x, top, base] = m.contact;
    let step = c.fs(FS_SMALL) * 1.3;
    let spots = [
        ([x - 6.0, top - 6.0], Anchor::BottomRight),
        ([x + 6.0, top - 6.0], Anchor::BottomLeft),
        ([x - 10.0, (top + base) * 0.5], Anchor::MidRight),
        ([x - 6.0, base + 6.0], Anchor::TopRight),
        ([x - 6.0, top - 6.0 - step], Anchor::BottomRight),
        ([x - 6.0, base + 6.0 + step], Anchor::TopRight),
    ];
    place(c, "contact", &spots, small);
    if let Some([x, y]) = m.acne {
        let step = c.fs(FS_LABEL) * 1.3;
        let down = |k: usize| y + 16.0 + k as f32 * step;
        let mut spots: Vec<_> = (0..4).map(|k| ([x - 14.0, down(k)], Anchor::TopRight)).collect();
        spots.push(([x - 14.0, y - 10.0], Anchor::BottomRight));
        spots.extend((0..4).map(|k| ([x + 14.0, down(k)], Anchor::TopLeft)));
        place(c, "acne (surface below its own step)", &spots, Style::em(FS_LABEL, pal::BLOCKED));
    }
    if let Some((text, p)) = &m.bias {
        let [x, y] = *p;
        // Beside its arrow, else right of the surface, level with the arrow or near it.
        let ks = [0.0, 1.0, -1.0, 2.0, -2.0, 3.0, -3.0, 4.0];
        let mut spots: Vec<_> = ks.iter().map(|k| ([x, y + k * step], Anchor::MidLeft)).collect();
        spots.extend(ks.iter().map(|k| ([r + 10.0, y + k * step], Anchor::MidLeft)));
        place(c, text, &spots, small);
    }
    if let Some((text, [a, b])) = &m.gap {
        let (mid, y) = ((a[0] + b[0]) * 0.5, a[1]);
        let mut spots = vec![
            ([mid, y + 10.0], Anchor::TopCenter),
            ([PLOT[0] + 4.0, y + 10.0], Anchor::TopLeft),
            ([mid, y - 10.0], Anchor::BottomCenter),
            ([PLOT[0] + 4.0, y - 10.0], Anchor::BottomLeft),
        ];
        // Beside the line's far end, and up from there.
        let right = a[0].max(b[0]) + 10.0;
        spots.extend((0..6).map(|k| ([right, y - k as f32 * step], Anchor::MidLeft)));
        place(c, text, &spots, Style::em(FS_SMALL, pal::PENUMBRA));
    }
    out
}

/// The number blocks and, after a gap, the verdict, down `col` (which flows on as needed).
fn lay_out(c: &mut Canvas, col: &mut Column, blocks: &[Vec<(String, Style)>], verdict: &[(String, Style)]) {
    for b in blocks {
        col.block(c, b);
    }
    col.y += 10.0;
    col.block(c, verdict);
}

/// The light's angle and the slope as printed: the angle to the fewest decimals (one to three)
/// at which the tangent of the printed angle, printed, is the printed slope.
pub(super) fn angle_and_slope(angle_deg: f32) -> (String, String) {
    let angle = f64::from(angle_deg);
    let slope = format!("{:.2}", angle.to_radians().tan());
    let mut shown = (String::new(), String::new());
    for decimals in 1..=3 {
        let a = format!("{angle:.decimals$}");
        let tan_shown = format!("{:.2}", a.parse::<f64>().unwrap_or(angle).to_radians().tan());
        let matches = tan_shown == slope;
        shown = (a, tan_shown);
        if matches {
            break;
        }
    }
    shown
}

//! Shadow acne and peter panning: a tilted receiver under light from above, the depth "steps"
//! the shadow map stores (one per texel: the depth at the texel centre), and the bias that
//! moves the steps down.

use super::canvas::Canvas;
use super::style::{Anchor, FS_LABEL, FS_SMALL, Style, Swatch, col, fin, ndc, num, pal};
use super::widgets::Column;
use super::{DiagramInputs, bias_world, ndc_per_world};

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
    // One texel's footprint at the receiver: W / map for an orthographic map; a perspective
    // map's W is its near-plane width, so the footprint grows with depth, times d / near.
    let near = fin(inp.light_near, 1.0).abs().max(1e-6);
    let texel = if inp.orthographic { w_frustum / map } else { w_frustum / map * recv.abs() / near };
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
    for i in 0..n {
        let cell = [v.sx(i as f32), PLOT[1] - 26.0, tpx, 18.0];
        c.rect(cell, Some(col(pal::BG, 1.0)), Some((col(pal::INK, 1.0), 1.5)));
    }
    c.label("shadow-map texels", [v.sx(0.0), PLOT[1] - 30.0], Anchor::BottomLeft, FS_SMALL);
    // Bias arrow on the first visible texel.
    let first = (0..n).find(|&i| v.sy(v.stored(i)) > PLOT[1] + 6.0).unwrap_or(0);
    if shift_px > 0.5 && !inp.receiver_plane {
        let (x, y) = (v.sx(first as f32 + 0.75), v.sy(v.stored(first)));
        let y_end = (y + shift_px).min(PLOT[1] + PLOT[3] - 4.0);
        c.arrow([x, y], [x, y_end], col(pal::SEARCH, 1.0), 2.5, false);
        let t = match y + shift_px > y_end {
            true => c.fill("bias = {} texels (steps below view)", &[&num(bias_tx)]),
            false => c.fill("bias = {} texels", &[&num(bias_tx)]),
        };
        c.label(&t, [x + 8.0, (y + y_end) * 0.5], Anchor::MidLeft, FS_SMALL);
    }
    if let Some(p) = acne_at {
        let st = Style::em(FS_LABEL, pal::BLOCKED);
        c.text("acne (surface below its own step)", [p[0] - 14.0, p[1] + 16.0], Anchor::TopRight, st);
    }
    if leak_end > v.contact + 0.02 {
        let gap_w = if slope > 1e-6 { (bias_eff - PLATE * texel).max(0.0) / slope } else { f32::INFINITY };
        let end = leak_end.min(nf);
        // A dimension line across the light (the gap is measured across it, not along the
        // slope), under the surface's deeper end.
        let (a, b) = (v.at(v.contact), v.at(end));
        let y = a[1].max(b[1]) + 26.0;
        let (a, b) = ([a[0], y], [b[0], y]);
        c.arrow(a, b, col(pal::PENUMBRA, 1.0), 3.0, true);
        let t = match leak_end >= nf - 0.01 {
            true => c.fill("peter panning gap = {} world, beyond view", &[&num(gap_w)]),
            false => c.fill("peter panning gap = {} world", &[&num(gap_w)]),
        };
        // Centred under the arrow, but kept left of the number column.
        let half_w = c.measure(&t, FS_SMALL).0 * 0.5;
        let x = ((a[0] + b[0]) * 0.5).min(590.0 - half_w);
        let at = [x, ((a[1] + b[1]) * 0.5 + 16.0).min(PLOT[1] + PLOT[3] - 12.0)];
        c.text(&t, at, Anchor::TopCenter, Style::em(FS_SMALL, pal::PENUMBRA));
    }
    c.label("contact", [v.sx(v.contact) - 6.0, top - 6.0], Anchor::BottomRight, FS_SMALL);

    // Numbers, in a column on the right.
    let npw = ndc_per_world(inp, recv);
    let mut text = Column::new(600.0, PLOT[1] + 4.0);
    if inp.orthographic {
        text.line(c, "texel = W / map size");
        let t = c.fill("   = {} / {} = {} world", &[&num(w_frustum), &(map as u32), &num(texel)]);
        text.line(c, &t);
    } else {
        text.line(c, "texel = W_near / map size · d / near");
        let t = c.fill(
            "   = {} / {} · {} / {} = {} world",
            &[&num(w_frustum), &(map as u32), &num(recv), &num(near), &num(texel)],
        );
        text.line(c, &t);
    }
    let t = c.fill("slope = tan({}°) = {}", &[&format!("{angle:.0}"), &format!("{slope:.2}")]);
    text.line(c, &t);
    text.line(c, "needed bias ≈ texel/2 · slope");
    let t = c.fill("   = {} world = {} NDC", &[&num(needed), &ndc(needed * npw)]);
    text.line(c, &t);
    let b_ndc = ndc(fin(inp.bias_ndc, 0.0));
    let t = c.fill("bias = {} NDC = {} world", &[&b_ndc, &num(bias_w)]);
    text.line(c, &t);
    let t = c.fill("normal offset = {} texels", &[&num(k_normal)]);
    text.line(c, &t);
    let t = c.fill("   = {} world of extra bias", &[&num(normal_world)]);
    text.line(c, &t);
    text.y += 10.0;
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
    for l in verdict {
        text.em(c, l, vc);
    }

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
    c.legend_row(&items, [480.0, 530.0]);
}

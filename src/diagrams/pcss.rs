//! PCSS in side view: the similar triangles between the light, the blocker's edge and the
//! receiver that give the penumbra width, and the blocker-search cone cut by the near plane.

use super::canvas::Canvas;
use super::style::{Anchor, FS_LABEL, FS_SMALL, Style, Swatch, col, fin, nice_floor, num, pal};
use super::widgets::Column;
use super::{DiagramInputs, planes};
use crate::scene::Technique;
use crate::shadow::{self, ShadowParamsGpu};

/// Drawing area (x, y, w, h); depths run from `Y_LIGHT` down to `Y_RECV`.
const AREA: [f32; 4] = [20.0, 52.0, 580.0, 450.0];
const Y_LIGHT: f32 = 104.0;
const Y_RECV: f32 = 424.0;
const X_EDGE: f32 = 385.0;
const MAX_WIDTH_PX: f32 = 300.0;

/// Widths and depths of the picture, world units, sanitised.
struct Numbers {
    near: f32,
    d_r: f32,
    d_b: f32,
    has_blocker: bool,
    /// Angular diameter (radians) for the directional model.
    theta: Option<f32>,
    w_light: f32,
    w_pen: f32,
    w_search: f32,
    /// Width of the light (area model) or of the angular cone at the light (directional).
    top_w: f32,
}

fn numbers(inp: &DiagramInputs) -> Numbers {
    let (near, _) = planes(inp);
    let d_r = fin(inp.receiver_depth_linear, 113.0).clamp(1e-6, 1e12);
    let bd = inp.blocker_depth_linear;
    let blocker = bd.map(|d| fin(d, d_r).clamp(d_r.min(near) * 1e-3, 1e12));
    let d_b = blocker.unwrap_or(d_r * 0.88).max(1e-9);
    let ad = inp.light_angular_diameter_deg;
    let theta = ad.map(|t| fin(t, 0.53).abs().min(170.0).to_radians());
    let w_light = fin(inp.light_width_world.unwrap_or(0.0), 0.0);
    let w_light = w_light.abs().min(1e9);
    // The twin's similar triangles (search region and penumbra), unscaled and unclamped.
    let light = super::light_gpu(inp);
    let params = ShadowParamsGpu { search_radius_scale: 1.0, ..bytemuck::Zeroable::zeroed() };
    let (view, light) = (light.view, light.light);
    // Drawn along the light's axis: at the centre of its map.
    let axis_uv = glam::Vec2::splat(0.5);
    let w_pen = shadow::estimate_penumbra(&light, &view, &params, d_r, axis_uv, d_b).width_world;
    let w_search = 2.0
        * shadow::blocker_search_radius_uv(&light, &view, &params, d_r, axis_uv)
        * view.frustum_width_world;
    let top_w = match theta {
        Some(t) => d_b * 2.0 * (t * 0.5).tan(),
        None => w_light,
    };
    let has_blocker = blocker.is_some();
    let w_pen = if has_blocker { fin(w_pen, 0.0) } else { 0.0 };
    let (w_search, top_w) = (fin(w_search, 0.0), fin(top_w, 0.0));
    Numbers { near, d_r, d_b, has_blocker, theta, w_light, w_pen, w_search, top_w }
}

pub fn draw(c: &mut Canvas, inp: &DiagramInputs) {
    let n = numbers(inp);
    let searches = searches(inp.technique);
    // Depths normalised to the panel height; widths exaggerated by a nice factor.
    let vs = (Y_RECV - Y_LIGHT) / n.d_r.max(n.d_b).max(n.near);
    let max_w = n.w_pen.max(if searches { n.w_search } else { 0.0 }).max(n.top_w);
    let exag = Some(max_w * vs).filter(|v| *v > 1e-9);
    let exag = exag.map_or(1.0, |v| nice_floor(MAX_WIDTH_PX / v));
    let hs = vs * exag;
    let x = |w: f32| X_EDGE + w * hs;
    let (y_b, y_near) = (Y_LIGHT + n.d_b * vs, (Y_LIGHT + n.near * vs).max(Y_LIGHT + 8.0));
    let (p0, p1) = (x(-n.w_pen * 0.5), x(n.w_pen * 0.5));
    let pen = col(pal::PENUMBRA, 1.0);
    let search = col(pal::SEARCH, 1.0);

    c.set_clip(Some(AREA));
    // Receiver: umbra, penumbra gradient, lit part.
    c.rect([AREA[0], Y_RECV, AREA[2], 12.0], Some(col(pal::RECEIVER, 0.45)), None);
    if n.has_blocker {
        c.rect([AREA[0], Y_RECV, p0 - AREA[0], 12.0], Some(col(pal::SHADOW, 1.0)), None);
        let band = [p0, Y_RECV, p1 - p0, 12.0];
        c.gradient_rect(band, col(pal::SHADOW, 1.0), col(pal::RECEIVER, 0.45));
    }
    c.line([AREA[0], Y_RECV], [AREA[0] + AREA[2], Y_RECV], col(pal::RECEIVER, 1.0), 3.0);
    // Search cone from the shaded point: to the light's ends (area light) or on past the near
    // plane (directional light); its cut with the near plane is the search region. Only the
    // techniques that search for blockers have one.
    let recv_pt = [X_EDGE, Y_RECV];
    let y_near_true = Y_LIGHT + n.near * vs;
    let s_half = n.w_search * 0.5 * hs * (Y_RECV - y_near) / (Y_RECV - y_near_true).max(1e-3);
    let cut = [[X_EDGE - s_half, y_near], [X_EDGE + s_half, y_near]];
    let tips = match n.theta {
        None => [[x(-n.w_light * 0.5), Y_LIGHT], [x(n.w_light * 0.5), Y_LIGHT]],
        Some(_) => cut,
    };
    if searches {
        c.polygon(&[recv_pt, tips[0], tips[1]], col(pal::SEARCH, 0.16));
        for tip in tips {
            c.dashed(recv_pt, tip, col(pal::SEARCH, 0.9), 2.0, 8.0);
        }
        let muted = col(pal::MUTED, 1.0);
        c.dashed([AREA[0], y_near], [AREA[0] + AREA[2], y_near], muted, 1.5, 6.0);
        c.line(cut[0], cut[1], search, 6.0);
    }
    // Blocker and the penumbra lines past its edge.
    if n.has_blocker {
        let slab = [AREA[0] + 110.0, y_b - 6.0, X_EDGE - AREA[0] - 110.0, 12.0];
        c.rect(slab, Some(col(pal::BLOCKER, 1.0)), None);
        let edge = [X_EDGE, y_b];
        let half = n.top_w * 0.5;
        for (end, hit) in [[x(-half), Y_LIGHT], [x(half), Y_LIGHT]].into_iter().zip([p1, p0]) {
            c.line(end, edge, pen, 2.5);
            c.line(edge, [hit, Y_RECV], pen, 2.5);
        }
        c.circle(edge, 5.0, Some(col(pal::INK, 1.0)), None);
        if n.theta.is_some() {
            // The angular cone at the blocker's edge, opened up by the width exaggeration.
            let half_draw = (half * hs / (y_b - Y_LIGHT).max(1e-3)).atan();
            let arc: Vec<[f32; 2]> = (0..=16)
                .map(|i| {
                    let a = half_draw * (i as f32 / 8.0 - 1.0);
                    [X_EDGE + 46.0 * a.sin(), y_b - 46.0 * a.cos()]
                })
                .collect();
            c.polyline(&arc, pen, 2.5, None);
            let st = Style::em(FS_LABEL, pal::PENUMBRA);
            c.text("θ", [X_EDGE, y_b - 52.0], Anchor::BottomCenter, st);
        }
    }
    // The light: a bar of width w_light, or a sun for the directional model.
    let (light, light_edge) = (Some(col(pal::LIGHT, 1.0)), Some((col(pal::LIGHT_DARK, 1.0), 2.0)));
    if n.theta.is_none() {
        let (l, r) = (x(-n.w_light * 0.5), x(n.w_light * 0.5));
        let (l, r) = if r - l < 8.0 { (X_EDGE - 4.0, X_EDGE + 4.0) } else { (l, r) };
        c.rect([l, Y_LIGHT - 10.0, r - l, 10.0], light, light_edge);
    } else {
        c.circle([X_EDGE, Y_LIGHT - 22.0], 13.0, light, light_edge);
    }
    c.set_clip(None);

    // Labels on the drawing.
    let ink = col(pal::INK, 1.0);
    c.arrow([40.0, Y_LIGHT], [40.0, Y_RECV], ink, 2.5, true);
    let d_r_txt = format!("d_receiver = {}", num(n.d_r));
    let d_r_box = c.label(&d_r_txt, [50.0, Y_RECV + 16.0], Anchor::TopLeft, FS_LABEL);
    if n.has_blocker {
        c.arrow([62.0, Y_LIGHT], [62.0, y_b], col(pal::BLOCKER, 1.0), 2.5, true);
        let t = format!("d_blocker = {}", num(n.d_b));
        c.label(&t, [72.0, y_b - 10.0], Anchor::BottomLeft, FS_LABEL);
    }
    if searches {
        let near_txt = c.fill("near plane d = {}", &[&num(n.near)]);
        let near_box = c.label(&near_txt, [74.0, y_near + 4.0], Anchor::TopLeft, FS_SMALL);
        // Below the cut, and below the near-plane label where grown text would overlap it.
        let half_w = c.measure("search region", FS_SMALL).0 * 0.5;
        let overlaps = X_EDGE - half_w < near_box[0] + near_box[2] + 6.0;
        let y = if overlaps { near_box[1] + near_box[3] + 4.0 } else { y_near + 6.0 };
        c.text("search region", [X_EDGE, y], Anchor::TopCenter, Style::em(FS_SMALL, pal::SEARCH));
    }
    match n.theta {
        None => {
            let t = c.fill("w_light = {} world", &[&num(n.w_light)]);
            c.label(&t, [X_EDGE, Y_LIGHT - 16.0], Anchor::BottomCenter, FS_LABEL)
        }
        Some(t) => {
            let t = format!("θ = {}°", num(t.to_degrees()));
            c.label(&t, [X_EDGE + 20.0, Y_LIGHT - 22.0], Anchor::MidLeft, FS_LABEL)
        }
    };
    if n.has_blocker && p1 - p0 > 1.0 {
        let (b0, b1) = (p0.max(AREA[0]), p1.min(AREA[0] + AREA[2]));
        c.bracket(b0, b1, Y_RECV + 22.0, pen, 3.0);
        let t = c.fill("w_penumbra = {} world", &[&num(n.w_pen)]);
        // Under its bracket, clear of the d_receiver label.
        let half_w = c.measure(&t, FS_LABEL).0 * 0.5;
        let at = [((b0 + b1) * 0.5).max(d_r_box[0] + d_r_box[2] + 12.0 + half_w), Y_RECV + 30.0];
        let st = Style::em(FS_LABEL, pal::PENUMBRA);
        c.text(&t, at, Anchor::TopCenter, st);
    }
    let ex = if exag >= 1.0 { format!("{exag:.0}") } else { num(exag) };
    let scale_note = c.fill("widths ×{}, depths to scale", &[&ex]);
    formulas(c, inp, &n, &scale_note);

    let mut items = vec![
        (Swatch::Fill(pal::LIGHT, 1.0), "light"),
        (Swatch::Fill(pal::BLOCKER, 1.0), "blocker"),
        (Swatch::Fill(pal::SHADOW, 1.0), "umbra"),
        (Swatch::Line(pal::PENUMBRA), "penumbra edges"),
        (Swatch::Fill(pal::SEARCH, 0.2), "search cone"),
        (Swatch::Fill(pal::RECEIVER, 0.45), "receiver"),
    ];
    if !searches {
        items.retain(|(_, s)| *s != "search cone");
    }
    c.legend_row(&items, [480.0, 530.0]);
}

/// Whether `technique` searches for blockers and sizes its filter from the penumbra (PCSS,
/// VSSM); the others filter with a fixed radius (PCF, VSM) or not at all (hard, none).
fn searches(technique: Technique) -> bool {
    matches!(technique, Technique::Pcss | Technique::Vssm)
}

/// The formulas with the live numbers, in a column on the right: what the technique does, the
/// penumbra the light casts, and for PCSS and VSSM the blocker search and the filter it sizes.
fn formulas(c: &mut Canvas, inp: &DiagramInputs, n: &Numbers, scale_note: &str) {
    let mut col_ = Column::new(612.0, 64.0);
    let searches = searches(inp.technique);
    let r_f = num(fin(inp.filter_radius_texels, 0.0));
    match inp.technique {
        Technique::Pcf | Technique::Vsm => {
            let t = match inp.technique {
                Technique::Pcf => c.fill("PCF: fixed filter radius = {} texels", &[&r_f]),
                _ => c.fill("VSM: fixed filter radius = {} texels", &[&r_f]),
            };
            col_.em(c, &t, pal::SEARCH);
            col_.tint(c, "(no blocker search, no w_penumbra)", pal::MUTED);
        }
        Technique::Hard => {
            col_.em(c, "hard shadows: one depth test, no filter", pal::INK);
            col_.tint(c, "(no blocker search, no w_penumbra)", pal::MUTED);
        }
        Technique::None => col_.em(c, "no shadows: nothing is tested", pal::INK),
        Technique::Pcss | Technique::Vssm => {}
    }
    if !searches && n.has_blocker {
        col_.tint(c, "what PCSS would estimate here:", pal::MUTED);
    }
    let (d_r, d_b) = (num(n.d_r), num(n.d_b));
    match (n.has_blocker, n.theta) {
        (false, _) if !searches => {}
        (false, _) => {
            col_.line(c, "blocker search found nothing:");
            col_.em(c, "no blockers: fully lit", pal::LIT);
            col_.tint(c, "(the filter step is skipped)", pal::MUTED);
        }
        (true, None) => {
            col_.line(c, "w_penumbra = w_light · (d_r − d_b) / d_b");
            let w = num(n.w_light);
            col_.line(c, &format!("  = {w} · ({d_r} − {d_b}) / {d_b}"));
        }
        (true, Some(t)) => {
            col_.line(c, "w_penumbra = (d_r − d_b) · 2·tan(θ/2)");
            let t = num(t.to_degrees());
            col_.line(c, &format!("  = ({d_r} − {d_b}) · 2·tan({t}°/2)"));
        }
    }
    if n.has_blocker {
        let t = c.fill("  = {} world", &[&num(n.w_pen)]);
        col_.em(c, &t, pal::PENUMBRA);
        if n.d_b >= n.d_r {
            col_.tint(c, "blocker not in front of receiver", pal::MUTED);
        }
    }
    if searches {
        let search = match n.theta {
            None => "w_search = w_light · (d_r − near) / d_r",
            Some(_) => "w_search = (d_r − near) · 2·tan(θ/2)",
        };
        col_.line(c, search);
        let ws = num(n.w_search);
        let t = c.fill("  = {} world on the near plane", &[&ws]);
        col_.em(c, &t, pal::SEARCH);
        let r_s = num(fin(inp.search_radius_texels, 0.0));
        let t = c.fill("search radius = {} texels", &[&r_s]);
        col_.line(c, &t);
        let (found, total) = (inp.blockers_found, inp.blocker_samples);
        // VSSM takes no taps: its blockers come from the moments.
        let t = match total {
            0 if found > 0 => c.fill("blockers: estimated from the moments", &[]),
            _ => c.fill("blockers found: {} / {}", &[&found, &total]),
        };
        col_.line(c, &t);
        // Without blockers the filter is skipped: no radius to show.
        if n.has_blocker {
            let t = c.fill("filter radius = {} texels", &[&r_f]);
            col_.line(c, &t);
        }
        let reported = fin(inp.penumbra_width_world, n.w_pen);
        if n.has_blocker && (reported - n.w_pen).abs() > 0.01 * n.w_pen.abs().max(1e-6) {
            let t = c.fill("(shader's w_penumbra: {} world)", &[&num(reported)]);
            col_.tint(c, &t, pal::MUTED);
        }
    }
    col_.tint(c, scale_note, pal::MUTED);
}

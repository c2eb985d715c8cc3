//! Shadow mapping in two passes: light frustum and shadow map, camera, and the depth comparison
//! at one surface point P.

use super::canvas::Canvas;
use super::style::{Anchor, FS_LABEL, FS_SMALL, Style, Swatch, col, fin, ndc, num, pal};
use super::{DiagramInputs, bias_world, ndc_from_linear, planes};

const GROUND_Y: f32 = 412.0;
const P_X: f32 = 540.0;

type Pt = [f32; 2];

fn add(a: Pt, b: Pt, k: f32) -> Pt {
    [a[0] + b[0] * k, a[1] + b[1] * k]
}

fn mid(a: Pt, b: Pt) -> Pt {
    [(a[0] + b[0]) * 0.5, (a[1] + b[1]) * 0.5]
}

/// Point where the ray from `a` along `d` meets the ground line.
fn to_ground(a: Pt, d: Pt) -> Pt {
    let t = if d[1] > 1e-4 { (GROUND_Y - a[1]) / d[1] } else { 2000.0 };
    add(a, d, t.clamp(0.0, 2000.0))
}

/// Screen geometry: the light sits up-left of P for positive angles, up-right for negative.
struct Rig {
    theta: f32,
    /// Light travel direction and the direction along the shadow-map plane.
    dir: Pt,
    u: Pt,
    /// +1 when the light is on the left of P.
    side: f32,
    p: Pt,
    apex: Pt,
    len: f32,
}

fn rig(inp: &DiagramInputs) -> Rig {
    let theta = fin(inp.light_angle_deg, 45.0).clamp(-75.0, 75.0).to_radians();
    let (dir, u) = ([theta.sin(), theta.cos()], [theta.cos(), -theta.sin()]);
    let side = if theta >= 0.0 { 1.0 } else { -1.0 };
    let p = [P_X, GROUND_Y];
    let mut len = 300.0f32.min((GROUND_Y - 125.0) / dir[1]);
    if dir[0].abs() > 1e-3 {
        let room = if side > 0.0 { P_X - 95.0 } else { 865.0 - P_X };
        len = len.min(room / dir[0].abs());
    }
    Rig { theta, dir, u, side, p, apex: add(p, dir, -len), len }
}

/// Draws the light frustum, the shadow-map texel row and the light icon. Returns the centre of
/// the map plane, its half width and the icon position.
fn light(c: &mut Canvas, inp: &DiagramInputs, r: &Rig) -> (Pt, f32, Pt) {
    let (fill, edge) = (col(pal::LIGHT, 0.12), col(pal::LIGHT_DARK, 0.9));
    let (plane_c, half, icon) = if inp.orthographic {
        let half = 105.0;
        let (a, b) = (add(r.apex, r.u, -half), add(r.apex, r.u, half));
        let (ga, gb) = (to_ground(a, r.dir), to_ground(b, r.dir));
        c.polygon(&[a, b, gb, ga], fill);
        c.dashed(a, ga, edge, 2.5, 9.0);
        c.dashed(b, gb, edge, 2.5, 9.0);
        (r.apex, half, add(r.apex, r.dir, -30.0))
    } else {
        let (near, _) = planes(inp);
        let w = fin(inp.frustum_width_world, 200.0).abs();
        let half_ang = (w / (2.0 * near)).atan().clamp(0.17, 0.6);
        let ray = |s: f32| to_ground(r.apex, [(r.theta + s).sin(), (r.theta + s).cos()]);
        let (ga, gb) = (ray(-half_ang), ray(half_ang));
        c.polygon(&[r.apex, ga, gb], fill);
        c.dashed(r.apex, ga, edge, 2.5, 9.0);
        c.dashed(r.apex, gb, edge, 2.5, 9.0);
        (add(r.apex, r.dir, 48.0), 48.0 * half_ang.tan(), r.apex)
    };
    // Texel row of the shadow map; the middle texel is the one P projects to.
    let n = 11;
    let cell = 2.0 * half / n as f32;
    for i in 0..n {
        let a = add(plane_c, r.u, -half + cell * i as f32);
        let b = add(a, r.u, cell);
        let (a2, b2) = (add(a, r.dir, -13.0), add(b, r.dir, -13.0));
        let fill = col(if i == n / 2 { pal::LIGHT } else { pal::BG }, 1.0);
        c.polygon(&[a, b, b2, a2], fill);
        c.polyline(&[a, b, b2, a2, a], col(pal::INK, 1.0), 1.5, None);
    }
    c.sun(icon, col(pal::LIGHT, 1.0), col(pal::LIGHT_DARK, 1.0));
    (plane_c, half, icon)
}

fn camera(c: &mut Canvas, r: &Rig) -> Pt {
    let cam = if r.side > 0.0 { [860.0, 150.0] } else { [100.0, 150.0] };
    let to_p = (r.p[1] - cam[1]).atan2(r.p[0] - cam[0]);
    let ray = |s: f32| to_ground(cam, [(to_p + s).cos(), (to_p + s).sin()]);
    let (ga, gb) = (ray(-0.32), ray(0.32));
    c.polygon(&[cam, ga, gb], col(pal::CAMERA, 0.08));
    c.dashed(cam, ga, col(pal::CAMERA, 0.8), 2.0, 7.0);
    c.dashed(cam, gb, col(pal::CAMERA, 0.8), 2.0, 7.0);
    c.dashed(cam, r.p, col(pal::CAMERA, 1.0), 3.0, 10.0);
    c.camera_icon(cam, to_p, 1.0);
    cam
}

pub fn draw(c: &mut Canvas, inp: &DiagramInputs) {
    let r = rig(inp);
    let (plane_c, half, icon) = light(c, inp, &r);
    let (side, p, dir) = (r.side, r.p, r.dir);

    // Blocker: on the ray at the stored depth when the map holds a nearer surface, else aside.
    let recv = fin(inp.receiver_depth_linear, 113.0).max(1e-6);
    let stored = fin(inp.stored_depth_linear, recv);
    let occluded = stored < recv * (1.0 - 1e-4);
    let frac = if occluded { (stored / recv).clamp(0.35, 0.75) } else { 1.0 };
    let s = add(p, dir, -r.len * (1.0 - frac));
    let bw = 120.0;
    let (bx, by, bh) = if occluded {
        (s[0] - bw * 0.5, s[1], (GROUND_Y - s[1] - 14.0).clamp(10.0, 60.0))
    } else {
        let x = if side > 0.0 { P_X + 115.0 } else { P_X - 115.0 - bw };
        (x, GROUND_Y - 70.0, 70.0)
    };
    // Its shadow on the ground: the box corners projected along the light rays.
    let corners = [[bx, by], [bx + bw, by], [bx, by + bh], [bx + bw, by + bh]];
    let proj = corners.map(|q| {
        let d = if inp.orthographic { dir } else { [q[0] - r.apex[0], q[1] - r.apex[1]] };
        to_ground(q, d)[0]
    });
    let sx0 = proj.iter().fold(f32::MAX, |a, &b| a.min(b)).max(20.0);
    let sx1 = proj.iter().fold(f32::MIN, |a, &b| a.max(b)).min(940.0);
    let (ground, shadow) = (Some(col(pal::RECEIVER, 1.0)), Some(col(pal::SHADOW, 1.0)));
    c.rect([20.0, GROUND_Y, 920.0, 14.0], ground, None);
    c.rect([sx0, GROUND_Y, (sx1 - sx0).max(0.0), 14.0], shadow, None);
    c.rect([bx, by, bw, bh], Some(col(pal::BLOCKER, 1.0)), None);
    let cam = camera(c, &r);

    // Light ray to P: lit up to the first hit, blocked after it.
    c.line(r.apex, s, col(pal::LIGHT_DARK, 1.0), 4.0);
    if occluded {
        c.dashed(s, p, col(pal::MUTED, 1.0), 3.0, 8.0);
        c.circle(s, 7.0, Some(col(pal::LIGHT, 1.0)), Some((col(pal::INK, 1.0), 2.0)));
    }
    // Depth test in NDC (exact), shown in world units.
    let bias_w = bias_world(inp, recv);
    let lit = ndc_from_linear(inp, recv) - fin(inp.bias_ndc, 0.0) <= ndc_from_linear(inp, stored);
    if lit {
        c.circle(p, 9.0, Some(col(pal::LIT, 1.0)), Some((col(pal::INK, 1.0), 2.0)));
    } else {
        c.cross_marker(p, 10.0, pal::BLOCKED);
    }

    // Dimension lines: receiver depth on the upper side of the ray, stored depth below it.
    let up = if r.u[1] <= 0.0 { r.u } else { [-r.u[0], -r.u[1]] };
    let down = [-up[0], -up[1]];
    let side_anchor = |n: Pt| {
        if n[0] >= 0.0 { Anchor::MidLeft } else { Anchor::MidRight }
    };
    let stored_txt = c.fill("stored depth = {}", &[&num(stored)]);
    let recv_txt = c.fill("receiver depth = {}", &[&num(recv)]);
    if occluded {
        let (a, b) = (add(r.apex, down, 24.0), add(s, down, 24.0));
        c.arrow(a, b, col(pal::BLOCKER, 1.0), 2.5, true);
        c.label(&stored_txt, add(mid(a, b), down, 12.0), side_anchor(down), FS_LABEL);
    }
    let (a, b) = (add(r.apex, up, 34.0), add(p, up, 34.0));
    c.arrow(a, b, col(pal::INK, 1.0), 2.5, true);
    c.label(&recv_txt, add(mid(a, b), up, 12.0), side_anchor(up), FS_LABEL);
    let (toward_light, away) =
        if side > 0.0 { (Anchor::MidRight, Anchor::MidLeft) } else { (Anchor::MidLeft, Anchor::MidRight) };
    let p_at = [p[0] - 14.0 * side, p[1] + 4.0];
    c.text("P", p_at, toward_light, Style::em(FS_LABEL, pal::INK));
    let map_txt = c.fill("shadow map: {} texels", &[&inp.shadow_map_size_texels]);
    let end = add(add(plane_c, r.u, half * side), dir, -30.0);
    c.label(&map_txt, [end[0] + 6.0 * side, end[1]], away, FS_SMALL);
    let light_txt = ["light (perspective) · pass 1: depth", "light (orthographic) · pass 1: depth"]
        [usize::from(inp.orthographic)];
    let light_at = [icon[0] - 30.0 * side, icon[1]];
    c.label(light_txt, light_at, toward_light, FS_SMALL);
    let cam_anchor = if side > 0.0 { Anchor::BottomRight } else { Anchor::BottomLeft };
    let cam_at = [cam[0] + 20.0 * side, cam[1] - 22.0];
    c.label("camera · pass 2: compare", cam_at, cam_anchor, FS_SMALL);

    // Verdict panel under the ground.
    let y0 = GROUND_Y + 22.0;
    let first = ["first hit: P itself", "first hit: blocker"][usize::from(occluded)];
    let first = c.fill(first, &[]);
    let l1 = c.fill("{} ({})   ·   {} (P)   ·   world units", &[&stored_txt, &first, &recv_txt]);
    let (b, st) = (num(bias_w), num(stored));
    let bias_ndc = ndc(fin(inp.bias_ndc, 0.0));
    let test = c.fill("bias = {} NDC ≈ {} world   →   {} − {} ≤ {} ?", &[&bias_ndc, &b, &num(recv), &b, &st]);
    let l1_box = c.label(&l1, [20.0, y0], Anchor::TopLeft, FS_LABEL);
    let y1 = y0 + l1_box[3] + 6.0;
    let bx = c.label(&test, [20.0, y1], Anchor::TopLeft, FS_LABEL);
    let (verdict, vc) = match (inp.outside_frustum, inp.clamp_outside, lit) {
        (true, true, _) => ("outside the light frustum → lit", pal::LIT),
        (true, false, true) => ("yes → lit (wrapped lookup!)", pal::LIT),
        (true, false, false) => ("no → in shadow (wrapped lookup!)", pal::BLOCKED),
        (false, _, true) => ("yes → lit", pal::LIT),
        (false, _, false) => ("no → in shadow", pal::BLOCKED),
    };
    let at = [bx[0] + bx[2] + 14.0, y1];
    c.text(verdict, at, Anchor::TopLeft, Style::em(FS_LABEL + 2.0, vc));

    let items = [
        (Swatch::Fill(pal::LIGHT, 0.25), "light frustum"),
        (Swatch::Fill(pal::BLOCKER, 1.0), "blocker"),
        (Swatch::Fill(pal::RECEIVER, 1.0), "receiver (ground)"),
        (Swatch::Fill(pal::SHADOW, 1.0), "shadow"),
        (Swatch::Dashed(pal::CAMERA), "camera view"),
    ];
    c.legend_row(&items, [480.0, 530.0]);
}

//! Shadow mapping in two passes: light frustum and shadow map, camera, and the depth comparison
//! at one surface point P.

use super::canvas::Canvas;
use super::style::{Anchor, FS_LABEL, FS_SMALL, Style, Swatch, col, fin, ndc, num, pal};
use super::{DiagramInputs, bias_world, ndc_from_linear, ndc_per_world, planes, texel_world};

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

/// What the depth test at P got from the map, as the lookup and the comparison found it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Lookup {
    /// P is outside the light's frustum and counts as lit: the map is not read.
    NotRead,
    /// P's uv is off the map and the lookup wrapped round: another place's texel.
    Wrapped,
    /// Nothing was drawn in P's texel: the map's clear value, the far plane.
    Nothing,
    /// P's own surface, within the depth P's plane spans across one texel; with RGBA8 storage,
    /// the round trip's error (NDC).
    Itself { rgba8_error_ndc: Option<f32> },
    /// A surface nearer the light than P's own: the first hit is a blocker.
    Blocker,
    /// A surface behind P (with front faces culled, the far side of P's own object).
    Behind,
}

/// What the lookup at P found, from the probe's numbers: the twin's outside-frustum rule, then
/// the depth the shadow pass wrote (before any RGBA8 rounding) against P's own.
pub(super) fn lookup(inp: &DiagramInputs) -> Lookup {
    if inp.outside_frustum() && inp.clamp_outside {
        return Lookup::NotRead;
    }
    if inp.outside_map {
        return Lookup::Wrapped;
    }
    let recv = fin(inp.receiver_depth_linear, 113.0).max(1e-6);
    let stored_ndc = ndc_from_linear(inp, fin(inp.stored_depth_linear, recv));
    if stored_ndc >= 1.0 - 1e-6 {
        return Lookup::Nothing;
    }
    let error = inp.stored_depth_rgba8_error_ndc.filter(|e| e.is_finite());
    let written = stored_ndc - error.unwrap_or(0.0);
    // How far P's plane recedes from the light across one texel (tan of the light angle per
    // texel of width), in NDC at P's depth.
    let angle = fin(inp.light_angle_deg, 45.0).abs().min(89.0).to_radians();
    let spread = texel_world(inp, recv) * angle.tan() * ndc_per_world(inp, recv);
    let gap = written - ndc_from_linear(inp, recv);
    if gap.abs() <= spread.max(1e-6) {
        Lookup::Itself { rgba8_error_ndc: error.filter(|e| *e != 0.0) }
    } else if gap < 0.0 {
        Lookup::Blocker
    } else {
        Lookup::Behind
    }
}

/// The light frustum as drawn: cut at the far plane where P lies past it.
struct Frustum {
    /// Half width of an orthographic frustum, or half angle of a perspective one (radians).
    half: f32,
    /// Length along the light's rays before the far plane cuts them; `None` to the ground.
    far_len: Option<f32>,
}

/// Draws the light frustum, the shadow-map texel row and the light icon. Returns the centre of
/// the map plane, its half width, the icon position and where the frustum meets the ground (x
/// range).
fn light(c: &mut Canvas, inp: &DiagramInputs, r: &Rig, f: &Frustum) -> (Pt, f32, Pt, [f32; 2]) {
    let (fill, edge) = (col(pal::LIGHT, 0.12), col(pal::LIGHT_DARK, 0.9));
    // The two edges: where they start and which way they run.
    let (plane_c, half, icon, starts, dirs, cut) = if inp.orthographic {
        let (a, b) = (add(r.apex, r.u, -f.half), add(r.apex, r.u, f.half));
        (r.apex, f.half, add(r.apex, r.dir, -30.0), [a, b], [r.dir, r.dir], f.far_len)
    } else {
        let ray = |s: f32| [(r.theta + s).sin(), (r.theta + s).cos()];
        let cut = f.far_len.map(|l| l / f.half.cos());
        (add(r.apex, r.dir, 48.0), 48.0 * f.half.tan(), r.apex, [r.apex; 2], [ray(-f.half), ray(f.half)], cut)
    };
    let ground = [to_ground(starts[0], dirs[0]), to_ground(starts[1], dirs[1])];
    // Each edge ends on the ground, or at the far plane where that comes first; the far plane
    // runs between the edges down to the ground.
    let far = cut.map(|l| [add(starts[0], dirs[0], l), add(starts[1], dirs[1], l)]);
    let mut outline = vec![starts[0]];
    if starts[1] != starts[0] {
        outline.push(starts[1]);
    }
    let mut far_line = None;
    match far {
        Some([fa, fb]) if fa[1] < GROUND_Y || fb[1] < GROUND_Y => {
            let on_ground = |p: Pt, q: Pt| {
                let t = (GROUND_Y - p[1]) / (q[1] - p[1]);
                add(p, [q[0] - p[0], q[1] - p[1]], t.clamp(0.0, 1.0))
            };
            let (ea, eb) = (
                if fa[1] < GROUND_Y { fa } else { ground[0] },
                if fb[1] < GROUND_Y { fb } else { ground[1] },
            );
            // The far plane's part above the ground.
            let (la, lb) = (
                if fa[1] < GROUND_Y { fa } else { on_ground(fb, fa) },
                if fb[1] < GROUND_Y { fb } else { on_ground(fa, fb) },
            );
            outline.extend([eb, lb, la, ea]);
            far_line = Some((la, lb, [ea, eb]));
        }
        _ => outline.extend([ground[1], ground[0]]),
    }
    c.polygon(&outline, fill);
    let ends = far_line.map_or(ground, |(_, _, e)| e);
    c.dashed(starts[0], ends[0], edge, 2.5, 9.0);
    c.dashed(starts[1], ends[1], edge, 2.5, 9.0);
    if let Some((la, lb, _)) = far_line {
        c.line(la, lb, edge, 3.0);
        let high = if la[1] < lb[1] { la } else { lb };
        c.label("far plane", [high[0] + 8.0, high[1]], Anchor::MidLeft, FS_SMALL);
    }
    let foot = [ground[0][0], ground[1][0]];
    // Texel row of the shadow map; the middle texel is the one P projects to, unless P is off
    // the map.
    let n = 11;
    let cell = 2.0 * half / n as f32;
    for i in 0..n {
        let a = add(plane_c, r.u, -half + cell * i as f32);
        let b = add(a, r.u, cell);
        let (a2, b2) = (add(a, r.dir, -13.0), add(b, r.dir, -13.0));
        let fill = col(if i == n / 2 && !inp.outside_map { pal::LIGHT } else { pal::BG }, 1.0);
        c.polygon(&[a, b, b2, a2], fill);
        c.polyline(&[a, b, b2, a2, a], col(pal::INK, 1.0), 1.5, None);
    }
    c.sun(icon, col(pal::LIGHT, 1.0), col(pal::LIGHT_DARK, 1.0));
    (plane_c, half, icon, [foot[0].min(foot[1]), foot[0].max(foot[1])])
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

/// The frustum as drawn for `inp`: narrower where P must fit beside it on the ground, cut at
/// the far plane where P lies past it.
fn frustum(inp: &DiagramInputs, r: &Rig) -> Frustum {
    let recv = fin(inp.receiver_depth_linear, 113.0).max(1e-6);
    let (near, far) = planes(inp);
    let past_far = inp.outside_depth && ndc_from_linear(inp, recv) > 1.0;
    let far_len = past_far.then(|| r.len * ((far - near) / (recv - near).max(1e-6)).clamp(0.3, 0.85));
    // Room on the ground beyond the frustum's far edge for P (off the map).
    let room = 315.0;
    let half = if inp.orthographic {
        let half = 105.0f32;
        if inp.outside_map { half.min(room * r.theta.cos()) } else { half }
    } else {
        let w = fin(inp.frustum_width_world, 200.0).abs();
        let mut half_ang = (w / (2.0 * near)).atan().clamp(0.17, 0.6);
        if inp.outside_map {
            let reach = |h: f32| {
                (to_ground(r.apex, [(r.theta + h * r.side).sin(), (r.theta + h * r.side).cos()])[0] - P_X)
                    .abs()
            };
            while half_ang > 0.1 && reach(half_ang) > room - 45.0 {
                half_ang -= 0.02;
            }
        }
        half_ang
    };
    Frustum { half, far_len }
}

pub fn draw(c: &mut Canvas, inp: &DiagramInputs) {
    let mut r = rig(inp);
    let f = frustum(inp, &r);
    let (plane_c, half, icon, foot) = light(c, inp, &r, &f);
    let found = lookup(inp);
    // P off the map: on the ground beyond the frustum, its ray from the light's plane (the
    // light itself for a perspective light) passing outside it.
    let ray_start = if inp.outside_map {
        let x = if r.side > 0.0 { foot[1] + 45.0 } else { foot[0] - 45.0 };
        r.p = [x.clamp(60.0, 900.0), GROUND_Y];
        if inp.orthographic {
            let along = (r.p[0] - r.apex[0]) * r.dir[0] + (r.p[1] - r.apex[1]) * r.dir[1];
            add(r.p, r.dir, -along)
        } else {
            r.apex
        }
    } else {
        r.apex
    };
    let (side, p, dir) = (r.side, r.p, r.dir);

    // Blocker: on the ray at the stored depth when the map holds a nearer surface, else aside.
    let recv = fin(inp.receiver_depth_linear, 113.0).max(1e-6);
    let stored = fin(inp.stored_depth_linear, recv);
    let occluded = found == Lookup::Blocker;
    let frac = if occluded { (stored / recv).clamp(0.35, 0.75) } else { 1.0 };
    let s = add(p, dir, -r.len * (1.0 - frac));
    let bw = 120.0;
    let (bx, by, bh) = if occluded {
        (s[0] - bw * 0.5, s[1], (GROUND_Y - s[1] - 14.0).clamp(10.0, 60.0))
    } else if inp.outside_map {
        // Inside the frustum, away from P.
        ((foot[0] + foot[1]) * 0.5 - bw * 0.5, GROUND_Y - 70.0, 70.0)
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

    // Light ray to P: lit up to the first hit, blocked after it; outside the frustum, no light
    // of the map's reaches P at all.
    if inp.outside_frustum() {
        c.dashed(ray_start, p, col(pal::MUTED, 1.0), 3.0, 8.0);
    } else {
        c.line(r.apex, s, col(pal::LIGHT_DARK, 1.0), 4.0);
    }
    if occluded {
        c.dashed(s, p, col(pal::MUTED, 1.0), 3.0, 8.0);
        c.circle(s, 7.0, Some(col(pal::LIGHT, 1.0)), Some((col(pal::INK, 1.0), 2.0)));
    }
    // Depth test in NDC (exact), shown in world units; outside the frustum with the clamp, no
    // test: lit.
    let bias_w = bias_world(inp, recv);
    let passes = ndc_from_linear(inp, recv) - fin(inp.bias_ndc, 0.0) <= ndc_from_linear(inp, stored);
    let lit = found == Lookup::NotRead || passes;
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
    let (a, b) = (add(ray_start, up, 34.0), add(p, up, 34.0));
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

    // The legend right of the picture where the panel is wide enough (the verdict panel below
    // may then reach past the picture), else in a row at the bottom.
    let y0 = GROUND_Y + 22.0;
    let items = [
        (Swatch::Fill(pal::LIGHT, 0.25), "light frustum"),
        (Swatch::Fill(pal::BLOCKER, 1.0), "blocker"),
        (Swatch::Fill(pal::RECEIVER, 1.0), "receiver (ground)"),
        (Swatch::Fill(pal::SHADOW, 1.0), "shadow"),
        (Swatch::Dashed(pal::CAMERA), "camera view"),
    ];
    let legend_drawn =
        c.legend_fits_right(&items, c.text_right) && 64.0 + c.legend_size(&items)[1] + 8.0 <= y0;
    if legend_drawn {
        c.legend_right(&items);
    }

    // Verdict panel under the ground: what the lookup found, the test, the result.
    let (l1, l2) = match found {
        Lookup::NotRead => {
            let where_ = match (inp.outside_map, inp.outside_depth) {
                (true, true) => c.fill("P lies off the light's map and outside its depth range", &[]),
                (true, false) => c.fill("P lies off the light's map (uv outside 0..1)", &[]),
                _ => c.fill(
                    "P lies outside the light's depth range (NDC depth {})",
                    &[&ndc(ndc_from_linear(inp, recv))],
                ),
            };
            let recv_p = c.fill("receiver depth = {} (P)   ·   world units", &[&num(recv)]);
            ((where_, recv_p), c.fill("the map is not read: no depth to compare", &[]))
        }
        _ => {
            let what = match found {
                Lookup::Wrapped => c.fill("wrapped: another place's texel", &[]),
                Lookup::Nothing => c.fill("nothing stored: far plane", &[]),
                Lookup::Itself { rgba8_error_ndc: Some(e) } => {
                    c.fill("P itself, rounded by RGBA8: {} NDC", &[&ndc(e)])
                }
                Lookup::Itself { rgba8_error_ndc: None } => c.fill("first hit: P itself", &[]),
                Lookup::Blocker => c.fill("first hit: blocker", &[]),
                _ => c.fill("first hit: a surface behind P", &[]),
            };
            let stored_what = c.fill("stored depth = {} ({})", &[&num(stored), &what]);
            let recv_p = c.fill("receiver depth = {} (P)   ·   world units", &[&num(recv)]);
            let (b, st) = (num(bias_w), num(stored));
            let bias_ndc = ndc(fin(inp.bias_ndc, 0.0));
            let test = "bias = {} NDC ≈ {} world   →   {} − {} ≤ {} ?";
            ((stored_what, recv_p), c.fill(test, &[&bias_ndc, &b, &num(recv), &b, &st]))
        }
    };
    let depth_outside = inp.outside_depth && !inp.outside_map;
    let (verdict, vc) = match (found, lit) {
        (Lookup::NotRead, _) => ("outside the light frustum → lit", pal::LIT),
        (Lookup::Wrapped, true) => ("yes → lit (wrapped lookup!)", pal::LIT),
        (Lookup::Wrapped, false) => ("no → in shadow (wrapped lookup!)", pal::BLOCKED),
        (_, true) if depth_outside => ("yes → lit (depth outside 0..1!)", pal::LIT),
        (_, false) if depth_outside => ("no → in shadow (depth outside 0..1!)", pal::BLOCKED),
        (Lookup::Itself { .. }, false) => ("no → in shadow (P shadows itself)", pal::BLOCKED),
        (_, true) => ("yes → lit", pal::LIT),
        (_, false) => ("no → in shadow", pal::BLOCKED),
    };
    // What was found and P's depth, or only what was found where the panel is too narrow
    // (P's depth is on its arrow and in the test).
    let [fx, _, fw, _] = c.full_rect();
    let one_line = format!("{}   ·   {}", l1.0, l1.1);
    let l1 = if c.measure(&one_line, FS_LABEL).0 + 24.0 <= fx + fw { one_line } else { l1.0 };
    let y1 = y0 + c.label(&l1, [20.0, y0], Anchor::TopLeft, FS_LABEL)[3] + 6.0;
    let bx = c.label(&l2, [20.0, y1], Anchor::TopLeft, FS_LABEL);
    // Beside the test, or under it where the panel is too narrow.
    let vst = Style::em(FS_LABEL + 2.0, vc);
    let beside = [bx[0] + bx[2] + 14.0, y1];
    let at = if beside[0] + c.measure(verdict, vst.size).0 + 4.0 <= fx + fw {
        beside
    } else {
        [20.0, y1 + bx[3] + 6.0]
    };
    c.text(verdict, at, Anchor::TopLeft, vst);

    if !legend_drawn {
        c.legend_bottom_row(&items, [480.0, 530.0]);
    }
}

//! A light's shadow views: a sun's cascades along the camera's view axis, each slice with its
//! map's texel size against one map over the whole scene; or a point light's cube from above,
//! its four side faces as 90° wedges meeting at the seams.

use tiny_skia::ColorU8;

use super::canvas::Canvas;
use super::style::{Anchor, FS_LABEL, FS_SMALL, Style, Swatch, col, fin, num, pal};
use super::widgets::Column;
use super::{DiagramInputs, ShadowViewsPlot};
use crate::scene::CascadeSelection;

/// Drawing area: x, y, w, h.
const AREA: [f32; 4] = [20.0, 56.0, 620.0, 446.0];
/// Where the text column begins.
const COLUMN_X: f32 = 656.0;

/// One colour per cascade or cube face: the cascade-index view's (`views::cascade_index::PALETTE`).
pub const VIEW_COLORS: [ColorU8; 6] =
    [view_color(0), view_color(1), view_color(2), view_color(3), view_color(4), view_color(5)];

const fn view_color(i: usize) -> ColorU8 {
    let [r, g, b] = crate::views::cascade_index::PALETTE[i].0;
    ColorU8::from_rgba(r, g, b, 255)
}

pub fn draw(c: &mut Canvas, inp: &DiagramInputs) {
    c.rect(AREA, Some(col(pal::BG, 1.0)), Some((col(pal::MUTED, 1.0), 2.0)));
    match &inp.shadow_views {
        ShadowViewsPlot::Cascades { .. } => cascades(c, inp),
        ShadowViewsPlot::Cube { .. } => cube(c, inp),
    }
}

fn cascades(c: &mut Canvas, inp: &DiagramInputs) {
    let ShadowViewsPlot::Cascades {
        splits_world,
        widths_world,
        one_map_width_world,
        lambda,
        probe_cascade,
        selection,
        read_world,
    } = &inp.shadow_views
    else {
        return;
    };
    let map = inp.shadow_map_size_texels.max(1) as f32;
    let n = widths_world.len().min(splits_world.len().saturating_sub(1)).min(VIEW_COLORS.len());
    let far = splits_world.last().map_or(1.0, |f| fin(*f, 1.0)).max(1e-3);
    // The camera on the left, its view axis to the right; heights are not to scale.
    let (x0, x1, mid) = (AREA[0] + 70.0, AREA[0] + AREA[2] - 20.0, AREA[1] + AREA[3] * 0.45);
    let x = |d: f32| x0 + (fin(d, 0.0).clamp(0.0, far) / far) * (x1 - x0);
    let half = |d: f32| 170.0 * fin(d, 0.0).clamp(0.0, far) / far;
    // Filled: where each cascade is read along the axis, which is what the cascade-index view
    // colours; by interval that is its slice, by map it runs on to where its map stops holding.
    let read = |i: usize| read_world.get(i).copied().flatten();
    for (i, colour) in VIEW_COLORS.iter().enumerate().take(n) {
        let Some([a, b]) = read(i) else { continue };
        let poly =
            [[x(a), mid - half(a)], [x(b), mid - half(b)], [x(b), mid + half(b)], [x(a), mid + half(a)]];
        let probed = *probe_cascade == Some(i);
        c.polygon(&poly, col(*colour, if probed { 0.75 } else { 0.4 }));
        c.line(poly[1], poly[2], col(pal::INK, 1.0), if probed { 3.0 } else { 1.5 });
        let label = format!("{}", i + 1);
        c.text(
            &label,
            [0.5 * (x(a) + x(b)), mid + half(b) + 8.0],
            Anchor::TopCenter,
            Style::em(FS_LABEL, pal::INK),
        );
    }
    // Dashed: the splits between the slices (their depths are in the text column).
    for &s in splits_world.iter().take(n).skip(1) {
        c.dashed([x(s), mid - half(s)], [x(s), mid + half(s)], col(pal::INK, 1.0), 1.5, 4.0);
    }
    c.line([x0, mid - 0.0], [x1, mid - half(far)], col(pal::MUTED, 1.0), 1.5);
    c.line([x0, mid], [x1, mid + half(far)], col(pal::MUTED, 1.0), 1.5);
    c.dashed([x0, mid], [x1, mid], col(pal::MUTED, 1.0), 1.0, 5.0);
    c.camera_icon([x0 - 18.0, mid], 0.0, 0.7);
    let t = c.fill("camera's view axis · 0 .. {} world", &[&num(far)]);
    c.label(&t, [AREA[0] + 8.0, AREA[1] + AREA[3] - 8.0], Anchor::BottomLeft, FS_SMALL);

    let one_texel = fin(*one_map_width_world, 0.0).abs() / map;
    let mut items: Vec<(Swatch, String)> = Vec::new();
    for i in 0..n {
        let texel = fin(widths_world[i], 0.0).abs() / map;
        let reads = read(i).map_or_else(|| "–".to_string(), |[a, b]| format!("{}–{}", num(a), num(b)));
        let line = c.fill("{}: read {} · texel {}", &[&(i + 1), &reads, &num(texel)]);
        items.push((Swatch::Fill(VIEW_COLORS[i], 0.6), line));
    }
    let splits: Vec<String> = splits_world.iter().take(n).skip(1).map(|s| num(*s)).collect();
    let refs: Vec<(Swatch, &str)> = items.iter().map(|(s, t)| (*s, t.as_str())).collect();
    let b = c.legend(&refs, [COLUMN_X, 64.0], Anchor::TopLeft);
    // Below the legend; a second column (grown text) starts there too, clear of the legend.
    let mut text = Column::new(COLUMN_X, b[1] + b[3] + 16.0);
    text.bottom = 536.0;
    text.line(c, "(world units)");
    if n > 1 {
        let t = c.fill("splits (dashed): {}", &[&splits.join(" · ")]);
        text.line(c, &t);
        let t = c.fill("{} cascades, split with λ = {}", &[&n, &num(*lambda)]);
        text.line(c, &t);
        match selection {
            CascadeSelection::ByMap => {
                text.line(c, "picked by map: the sharpest map");
                text.line(c, "holding it, read past the split");
            }
            CascadeSelection::ByInterval => {
                text.line(c, "picked by interval: the slice");
                text.line(c, "holding its depth, to the split");
            }
        }
        let t = c.fill("one map over the scene: texel {}", &[&num(one_texel)]);
        text.line(c, &t);
        let sharpest = fin(widths_world[0], 0.0).abs() / map;
        if sharpest > 0.0 {
            let t = c.fill("cascade 1's texels: {}× smaller", &[&num(one_texel / sharpest)]);
            text.line(c, &t);
        }
        text.line(c, "spheres moved in whole texels");
    } else {
        text.line(c, "one map for the whole view:");
        text.line(c, "the same texel near and far");
    }
}

/// A side face in the top view: its index in `CUBE_FACES`, its name, the square's two corners it
/// reaches and the direction of its name from the lamp.
type Wedge = (usize, &'static str, [[f32; 2]; 2], [f32; 2]);

fn cube(c: &mut Canvas, inp: &DiagramInputs) {
    let ShadowViewsPlot::Cube { lamp_xz, probe_face } = &inp.shadow_views else { return };
    let centre = [AREA[0] + AREA[2] * 0.5, AREA[1] + AREA[3] * 0.5];
    let s = 0.42 * AREA[3];
    let corner = |sx: f32, sz: f32| [centre[0] + sx * s, centre[1] + sz * s];
    // Top view, x to the right and z down: the faces +X, -X, +Z, -Z as wedges (the CUBE_FACES order).
    let wedges: [Wedge; 4] = [
        (0, "+X", [corner(1.0, -1.0), corner(1.0, 1.0)], [0.7, 0.0]),
        (1, "-X", [corner(-1.0, 1.0), corner(-1.0, -1.0)], [-0.7, 0.0]),
        (4, "+Z", [corner(1.0, 1.0), corner(-1.0, 1.0)], [0.0, 0.7]),
        (5, "-Z", [corner(-1.0, -1.0), corner(1.0, -1.0)], [0.0, -0.7]),
    ];
    for (face, _, [a, b], _) in wedges {
        let probed = *probe_face == Some(face);
        c.polygon(&[centre, a, b], col(VIEW_COLORS[face], if probed { 0.75 } else { 0.35 }));
    }
    for (sx, sz) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
        c.dashed(centre, corner(sx, sz), col(pal::INK, 1.0), 1.5, 6.0);
    }
    c.rect([centre[0] - s, centre[1] - s, 2.0 * s, 2.0 * s], None, Some((col(pal::INK, 1.0), 2.0)));
    // The objects around the lamp, to scale; not those whose footprint holds the lamp (walls
    // round a room, seen from above, are discs over everything).
    let lamp = [fin(lamp_xz[0], 0.0), fin(lamp_xz[1], 0.0)];
    let distance = |o: &[f32; 2]| (fin(o[0], 0.0) - lamp[0]).hypot(fin(o[1], 0.0) - lamp[1]);
    let around: Vec<&([f32; 2], f32)> =
        inp.objects_xz.iter().filter(|(o, r)| distance(o) > fin(*r, 0.0).abs()).collect();
    let reach = around.iter().map(|(o, r)| distance(o) + fin(*r, 0.0).abs()).fold(1e-3, f32::max);
    let scale = 0.95 * s / reach;
    for (o, r) in around {
        let p =
            [centre[0] + (fin(o[0], 0.0) - lamp[0]) * scale, centre[1] + (fin(o[1], 0.0) - lamp[1]) * scale];
        let r = (fin(*r, 0.0).abs() * scale).clamp(2.0, s);
        c.circle(p, r, Some(col(pal::BLOCKER, 0.8)), Some((col(pal::BG, 1.0), 1.5)));
    }
    // The faces' names over the objects, near the square's edge.
    for (_, name, _, at) in wedges {
        c.text(name, corner(1.25 * at[0], 1.25 * at[1]), Anchor::TopCenter, Style::em(FS_LABEL, pal::INK));
    }
    c.sun(centre, col(pal::LIGHT, 1.0), col(pal::LIGHT_DARK, 1.0));
    c.label("top view (x →, z ↓)", [AREA[0] + 8.0, AREA[1] + AREA[3] - 8.0], Anchor::BottomLeft, FS_SMALL);

    let mut text = Column::new(COLUMN_X, 64.0);
    text.bottom = 536.0;
    text.line(c, "six 90° faces: +X −X +Y −Y +Z −Z");
    text.line(c, "(+Y, −Y: up and down, not shown)");
    text.line(c, "each face stores the distance");
    text.line(c, "to the lamp, on one scale:");
    text.line(c, "(|p − lamp| − near) / (far − near)");
    text.line(c, "a filter's taps cross the");
    text.line(c, "dashed seams to the next face");
    if let Some(face) = probe_face {
        let name = crate::probe::CUBE_FACE_NAMES.get(*face).copied().unwrap_or("?");
        let t = c.fill("the probe reads face {}", &[&name]);
        text.line(c, &t);
    }
}

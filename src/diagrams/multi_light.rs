//! Several lights in top view (XZ): objects, the camera, and each light's shadow-frustum
//! footprint (orthographic box or spot wedge), blended where they overlap.

use tiny_skia::ColorU8;

use super::canvas::Canvas;
use super::style::{Anchor, FS_LABEL, FS_SMALL, Style, Swatch, col, fin, nice_floor, num, pal};
use super::widgets::Column;
use super::{DiagramInputs, LightTopView};

/// Drawing area: x, y, w, h.
const AREA: [f32; 4] = [20.0, 56.0, 620.0, 446.0];

type Pt = [f32; 2];

fn sane(p: Pt) -> Pt {
    [fin(p[0], 0.0).clamp(-1e7, 1e7), fin(p[1], 0.0).clamp(-1e7, 1e7)]
}

fn hue(i: usize) -> ColorU8 {
    pal::LIGHTS[i % pal::LIGHTS.len()]
}

/// Footprint polygon of a light in world XZ.
fn footprint(l: &LightTopView) -> Vec<Pt> {
    let (p, t) = (sane(l.position_xz), sane(l.target_xz));
    let dist = (t[0] - p[0]).hypot(t[1] - p[1]);
    let (ax, az) = if dist > 1e-6 { ((t[0] - p[0]) / dist, (t[1] - p[1]) / dist) } else { (0.0, 1.0) };
    let hw = fin(l.half_width_world, 1.0).abs().clamp(1e-3, 1e7);
    let len = (dist * 1.7).max(hw * 2.0);
    if l.spot {
        let half = (hw / dist.max(1e-6)).atan().min(1.5);
        let base = az.atan2(ax);
        let arc = (0..=24).map(|i| {
            let a = base + half * (i as f32 / 12.0 - 1.0);
            [p[0] + len * a.cos(), p[1] + len * a.sin()]
        });
        std::iter::once(p).chain(arc).collect()
    } else {
        let (nx, nz) = (-az * hw, ax * hw);
        let f = [p[0] + ax * len, p[1] + az * len];
        vec![[p[0] + nx, p[1] + nz], [f[0] + nx, f[1] + nz], [f[0] - nx, f[1] - nz], [p[0] - nx, p[1] - nz]]
    }
}

fn bounds(pts: &[Pt]) -> (Pt, Pt) {
    pts.iter().fold(([f32::MAX; 2], [f32::MIN; 2]), |(lo, hi), p| {
        ([lo[0].min(p[0]), lo[1].min(p[1])], [hi[0].max(p[0]), hi[1].max(p[1])])
    })
}

/// World-to-screen mapping that fits the scene (and, within limits, the footprints).
struct Frame {
    mid: Pt,
    scale: f32,
    ext: f32,
}

impl Frame {
    fn new(inp: &DiagramInputs) -> Self {
        let mut pts = vec![sane(inp.camera_xz)];
        for l in &inp.lights {
            pts.extend([sane(l.position_xz), sane(l.target_xz)]);
        }
        for (o, r) in &inp.objects_xz {
            let (o, r) = (sane(*o), fin(*r, 0.0).abs().min(1e7));
            pts.extend([[o[0] - r, o[1] - r], [o[0] + r, o[1] + r]]);
        }
        // Footprints count too, but only up to one scene extent beyond the scene itself.
        let (lo, hi) = bounds(&pts);
        let e = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(10.0);
        for p in inp.lights.iter().flat_map(footprint) {
            pts.push([p[0].clamp(lo[0] - e, hi[0] + e), p[1].clamp(lo[1] - e, hi[1] + e)]);
        }
        let (lo, hi) = bounds(&pts);
        let ext = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(10.0);
        let scale = ((AREA[2] - 40.0) / (hi[0] - lo[0]).max(ext * 0.3))
            .min((AREA[3] - 40.0) / (hi[1] - lo[1]).max(ext * 0.3));
        Self { mid: [(lo[0] + hi[0]) * 0.5, (lo[1] + hi[1]) * 0.5], scale, ext }
    }

    fn px(&self, p: Pt) -> Pt {
        let (cx, cy) = (AREA[0] + AREA[2] * 0.5, AREA[1] + AREA[3] * 0.5);
        [cx + (p[0] - self.mid[0]) * self.scale, cy + (p[1] - self.mid[1]) * self.scale]
    }
}

fn light_icon(c: &mut Canvas, l: &LightTopView, p: Pt, t: Pt, hue: ColorU8) {
    let k = col(hue, 1.0);
    c.line([t[0] - 6.0, t[1] - 6.0], [t[0] + 6.0, t[1] + 6.0], k, 2.5);
    c.line([t[0] - 6.0, t[1] + 6.0], [t[0] + 6.0, t[1] - 6.0], k, 2.5);
    let rgb = l.color_rgb.map(|v| (fin(v, 1.0).clamp(0.0, 1.0) * 255.0) as u8);
    let fill = ColorU8::from_rgba(rgb[0], rgb[1], rgb[2], 255);
    c.sun(p, col(fill, 1.0), k);
}

pub fn draw(c: &mut Canvas, inp: &DiagramInputs) {
    let f = Frame::new(inp);
    c.set_clip(Some(AREA));
    c.rect(AREA, Some(col(pal::BG, 1.0)), None);
    // Grid at a nice world spacing.
    let step = nice_floor(f.ext / 5.0);
    let lines = (AREA[2].max(AREA[3]) / (f.scale * step)).ceil().min(400.0) as i32 + 1;
    let (gx, gz) = ((f.mid[0] / step).round() * step, (f.mid[1] / step).round() * step);
    for i in -lines..=lines {
        let p = f.px([gx + i as f32 * step, gz + i as f32 * step]);
        c.line([p[0], AREA[1]], [p[0], AREA[1] + AREA[3]], col(pal::GRID, 1.0), 1.0);
        c.line([AREA[0], p[1]], [AREA[0] + AREA[2], p[1]], col(pal::GRID, 1.0), 1.0);
    }
    // Footprints, translucent so overlaps mix.
    for (i, l) in inp.lights.iter().enumerate() {
        let poly: Vec<Pt> = footprint(l).into_iter().map(|p| f.px(p)).collect();
        c.polygon(&poly, col(hue(i), 0.22));
        let closed: Vec<Pt> = poly.iter().chain(poly.first()).copied().collect();
        c.polyline(&closed, col(hue(i), 1.0), 2.5, Some(9.0));
        let (p, t) = (f.px(sane(l.position_xz)), f.px(sane(l.target_xz)));
        c.dashed(p, t, col(hue(i), 1.0), 2.0, 5.0);
    }
    for (o, r) in &inp.objects_xz {
        let rp = (fin(*r, 0.0).abs() * f.scale).clamp(3.0, 2e4);
        c.circle(f.px(sane(*o)), rp, Some(col(pal::BLOCKER, 1.0)), Some((col(pal::BG, 1.0), 2.0)));
    }
    // Camera, looking at the objects' centroid.
    let cam = f.px(sane(inp.camera_xz));
    let n_obj = inp.objects_xz.len().max(1) as f32;
    let centroid = inp.objects_xz.iter().fold([0.0f32; 2], |a, (o, _)| {
        let o = sane(*o);
        [a[0] + o[0] / n_obj, a[1] + o[1] / n_obj]
    });
    let look = f.px(centroid);
    c.camera_icon(cam, (look[1] - cam[1]).atan2(look[0] - cam[0]), 0.7);
    for (i, l) in inp.lights.iter().enumerate() {
        light_icon(c, l, f.px(sane(l.position_xz)), f.px(sane(l.target_xz)), hue(i));
    }
    c.set_clip(None);
    c.rect(AREA, None, Some((col(pal::MUTED, 1.0), 2.0)));
    for (i, l) in inp.lights.iter().enumerate() {
        let p = f.px(sane(l.position_xz));
        let st = Style::em(FS_LABEL, pal::INK);
        let t = c.fill("light {}", &[&i]);
        c.text(&t, [p[0], p[1] + 26.0], Anchor::TopCenter, st);
    }
    c.text("camera", [cam[0], cam[1] + 18.0], Anchor::TopCenter, Style::em(FS_LABEL, pal::CAMERA));
    let t = c.fill("top view (x →, z ↓) · grid = {} world", &[&num(step)]);
    c.label(&t, [AREA[0] + 6.0, AREA[1] + AREA[3] - 6.0], Anchor::BottomLeft, FS_SMALL);
    legend_column(c, inp);
}

fn legend_column(c: &mut Canvas, inp: &DiagramInputs) {
    let mut items: Vec<(Swatch, String)> = (inp.lights.iter().enumerate().take(8))
        .map(|(i, l)| {
            let template = match l.spot {
                true => "light {}: spot, half-width {}",
                false => "light {}: ortho, half-width {}",
            };
            let hw = num(fin(l.half_width_world, 0.0));
            (Swatch::Fill(hue(i), 0.3), c.fill(template, &[&i, &hw]))
        })
        .collect();
    if inp.lights.len() > 8 {
        items.push((Swatch::Line(pal::MUTED), c.fill("… {} more lights", &[&(inp.lights.len() - 8)])));
    }
    items.push((Swatch::Dot(pal::BLOCKER), "object".to_string()));
    items.push((Swatch::Fill(pal::CAMERA, 1.0), "camera".to_string()));
    let refs: Vec<(Swatch, &str)> = items.iter().map(|(s, t)| (*s, t.as_str())).collect();
    let b = c.legend(&refs, [656.0, 64.0], Anchor::TopLeft);
    // No legend row below: the column may run to the foot of the diagram.
    let mut text = Column::new(656.0, b[1] + b[3] + 18.0);
    text.bottom = 536.0;
    let n = inp.lights.len();
    let t = c.fill("{} lights → {} shadow maps", &[&n, &n]);
    text.line(c, &t);
    for l in [
        "one depth pass per light;",
        "lighting from each light adds up",
        "overlap = lit by both:",
        "each shadow darkens only",
        "its own light's share",
    ] {
        text.line(c, l);
    }
}

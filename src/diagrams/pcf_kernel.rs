//! PCF kernel: a zoomed texel grid around the probe's uv, the filter and blocker-search circles,
//! and every sample at its real position, lit or blocked.

use super::DiagramInputs;
use super::canvas::Canvas;
use super::style::{Anchor, FS_LABEL, FS_SMALL, Style, Swatch, col, fin, num, pal};
use super::widgets::Column;

/// Grid panel: x, y, side.
const GRID: [f32; 3] = [50.0, 64.0, 424.0];

fn circle_pts(c: [f32; 2], r: f32) -> Vec<[f32; 2]> {
    let r = fin(r, 1.0).clamp(0.5, 1e5);
    (0..=96)
        .map(|i| {
            let a = i as f32 / 96.0 * std::f32::consts::TAU;
            [c[0] + r * a.cos(), c[1] + r * a.sin()]
        })
        .collect()
}

pub fn draw(c: &mut Canvas, inp: &DiagramInputs) {
    let r_f = fin(inp.filter_radius_texels, 5.0).abs().min(1e6);
    let r_s = fin(inp.search_radius_texels, 10.0).abs().min(1e6);
    let half = (1.2 * r_f.max(r_s)).max(1.5);
    let [gx, gy, side] = GRID;
    let ppt = side / (2.0 * half); // pixels per texel
    let centre = [gx + side * 0.5, gy + side * 0.5];
    let at = |o: [f32; 2]| [centre[0] + o[0] * ppt, centre[1] + o[1] * ppt];
    let ink = col(pal::INK, 1.0);

    // Texel grid: one line per texel, or every k-th when texels get too small.
    let mut k = 1.0f32;
    while k * ppt < 9.0 && k < 1e7 {
        k *= 2.0;
    }
    c.rect([gx, gy, side, side], Some(col(pal::BG, 1.0)), None);
    c.set_clip(Some([gx, gy, side, side]));
    // The probe lies at (fx, fy) inside its texel, so texel edges are at integers - (fx, fy).
    let [fx, fy] = inp.probe_in_texel.map(|f| if f.is_finite() { f.clamp(0.0, 1.0) } else { 0.5 });
    let first = -((half + 1.0) / k).ceil();
    for j in 0..((2.0 * half + 2.0) / k).ceil() as i32 + 2 {
        let m = (first + j as f32) * k;
        let (x, y) = (centre[0] + (m + 1.0 - fx) * ppt, centre[1] + (m + 1.0 - fy) * ppt);
        c.line([x, gy], [x, gy + side], col(pal::GRID, 1.0), 1.2);
        c.line([gx, y], [gx + side, y], col(pal::GRID, 1.0), 1.2);
    }
    let tp = ppt.max(3.0);
    c.rect([centre[0] - tp * fx, centre[1] - tp * fy, tp, tp], Some(col(pal::LIGHT, 0.45)), None);
    // Search region (dashed) and filter circle.
    c.circle(centre, (r_s * ppt).max(1.0), Some(col(pal::SEARCH, 0.14)), None);
    if let Some(p) = Canvas::poly(&circle_pts(centre, r_s * ppt), true) {
        c.stroke_path(&p, col(pal::SEARCH, 1.0), 3.0, Some(10.0));
    }
    c.circle(centre, (r_f * ppt).max(1.0), None, Some((ink, 3.0)));
    // Samples at offset * filter radius.
    let n = inp.pcf_samples.len();
    let (mut lit, mut blocked) = (0usize, 0usize);
    for (i, s) in inp.pcf_samples.iter().enumerate() {
        let o = [fin(s[0], 0.0).clamp(-1e3, 1e3) * r_f, fin(s[1], 0.0).clamp(-1e3, 1e3) * r_f];
        match inp.sample_blocked.get(i) {
            Some(true) => {
                blocked += 1;
                c.cross_marker(at(o), 8.0, pal::BLOCKED);
            }
            Some(false) => {
                lit += 1;
                c.circle(at(o), 7.5, Some(col(pal::LIT, 1.0)), Some((ink, 1.5)));
            }
            None => c.circle(at(o), 7.5, None, Some((col(pal::MUTED, 1.0), 2.0))),
        }
    }
    c.line([centre[0] - 12.0, centre[1]], [centre[0] + 12.0, centre[1]], ink, 2.0);
    c.line([centre[0], centre[1] - 12.0], [centre[0], centre[1] + 12.0], ink, 2.0);
    c.set_clip(None);
    c.rect([gx, gy, side, side], None, Some((col(pal::MUTED, 1.0), 2.0)));
    let y_f = (centre[1] + r_f * ppt + 6.0).min(gy + side - 26.0);
    let t = c.fill("filter r = {} texels", &[&num(r_f)]);
    c.label(&t, [centre[0], y_f], Anchor::TopCenter, FS_SMALL);
    // PCF has no blocker search: only PCSS draws (and labels) a search circle.
    if r_s > 0.0 {
        let y_s = (centre[1] - r_s * ppt - 6.0).max(gy + 26.0);
        let t = c.fill("search r = {} texels", &[&num(r_s)]);
        c.text(&t, [centre[0], y_s], Anchor::BottomCenter, Style::em(FS_SMALL, pal::SEARCH));
    }

    // Numbers on the right.
    let map = inp.shadow_map_size_texels.max(1) as f32;
    let mut text = Column::new(520.0, 70.0);
    text.line(c, "V = (1/N) · Σ [ d_r − bias ≤ map(uv + r·s_i) ]");
    let t = c.fill("samples N = {}", &[&n]);
    text.line(c, &t);
    let t = c.fill("filter radius r = {} texels", &[&num(r_f)]);
    text.line(c, &t);
    let t = c.fill("   = {} / {} = {} UV", &[&num(r_f), &(map as u32), &num(r_f / map)]);
    text.line(c, &t);
    if r_s > 0.0 {
        let t = c.fill("search radius = {} texels", &[&num(r_s)]);
        text.tint(c, &t, pal::SEARCH);
    }
    let grid = match k as u64 {
        1 => c.fill("grid: 1 cell = 1 texel", &[]),
        k => c.fill("grid: a line every {} texels", &[&k]),
    };
    text.tint(c, &grid, pal::MUTED);
    let hits = c.fill("blocker search: {} of {} samples hit", &[&inp.blockers_found, &inp.blocker_samples]);
    text.line(c, &hits);
    let t = c.fill("lit {}   ·   blocked {}", &[&lit, &blocked]);
    text.line(c, &t);
    if lit + blocked != n {
        let t = c.fill("({} samples without a result)", &[&(n - lit - blocked)]);
        text.tint(c, &t, pal::MUTED);
    }
    let v = if n > 0 { lit as f32 / n as f32 } else { fin(inp.visibility, 1.0) };
    let vis = if n > 0 {
        c.fill("visibility = lit / N = {} / {} = {}", &[&lit, &n, &format!("{v:.2}")])
    } else {
        c.fill("no samples: visibility = {}", &[&format!("{v:.2}")])
    };
    text.styled(c, &vis, Style::em(FS_LABEL + 3.0, pal::INK));
    let reported = fin(inp.visibility, v);
    if n > 0 && (reported - v).abs() > 0.005 {
        let t = c.fill("(reported by the shader: {})", &[&format!("{reported:.2}")]);
        text.tint(c, &t, pal::MUTED);
    }
    // The pixel's resulting shade.
    let shade = (40.0 + v.clamp(0.0, 1.0) * 200.0) as u8;
    let swatch = tiny_skia::ColorU8::from_rgba(shade, shade, shade, 255);
    text.reserve(48.0);
    c.rect([text.x, text.y + 4.0, 56.0, 40.0], Some(col(swatch, 1.0)), Some((ink, 2.0)));
    c.label("→ pixel brightness", [text.x + 68.0, text.y + 24.0], Anchor::MidLeft, FS_LABEL);

    let items = [
        (Swatch::Dot(pal::LIT), "lit sample"),
        (Swatch::HollowCross(pal::BLOCKED), "blocked sample"),
        (Swatch::Line(pal::INK), "filter circle"),
        (Swatch::Fill(pal::SEARCH, 0.2), "search region"),
        (Swatch::Fill(pal::LIGHT, 0.45), "probe texel"),
    ];
    c.legend_row(&items, [480.0, 530.0]);
}

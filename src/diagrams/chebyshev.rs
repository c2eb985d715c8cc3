//! VSM: the depths one filter window averages, as a histogram over NDC depth, with the two
//! curves a lookup can read off them at any tested depth x: the true lit share P(z >= x) and
//! Chebyshev's one-sided bound sigma² / (sigma² + (x - mu)²), which only the mean and variance
//! give. At the receiver's depth t, the gap between the two is light bleeding.

use super::canvas::Canvas;
use super::style::{Anchor, FS_LABEL, FS_SMALL, Style, Swatch, col, fin, pal};
use super::widgets::Column;
use super::{DiagramInputs, VsmPlot};

/// Plot area: x, y, w, h (visibility 0 at the bottom, 1 at the top).
const PLOT: [f32; 4] = [70.0, 92.0, 470.0, 330.0];

/// Chebyshev's bound on P(z >= x) for the window's mean and variance (1 at or before the mean).
fn bound_at(mean: f32, variance: f32, x: f32) -> f32 {
    if x <= mean {
        return 1.0;
    }
    let d = x - mean;
    variance / (variance + d * d)
}

/// The window's values, sanitised.
struct Numbers {
    lo: f32,
    hi: f32,
    bins: Vec<f32>,
    mean: f32,
    /// The variance the bound uses (at least the minimum variance).
    variance: f32,
    t: f32,
    bound: f32,
    visibility: f32,
    truth: f32,
    /// The share against the receiver's plane (light bleeding is measured from it).
    plane: f32,
    reduction: f32,
}

fn numbers(p: &VsmPlot) -> Numbers {
    let [lo, hi] = p.histogram_range_ndc.map(|v| fin(v, 0.5));
    let (lo, hi) = if hi - lo > 1e-7 { (lo, hi) } else { (lo - 1e-4, lo + 1e-4) };
    let bins: Vec<f32> = p.histogram.iter().map(|w| fin(*w, 0.0).max(0.0)).collect();
    let variance = fin(p.variance_ndc2, 0.0).max(fin(p.min_variance_ndc2, 0.0)).max(1e-12);
    Numbers {
        lo,
        hi,
        bins,
        mean: fin(p.mean_ndc, (lo + hi) * 0.5),
        variance,
        t: fin(p.tested_ndc, hi),
        bound: fin(p.chebyshev_bound, 1.0).clamp(0.0, 1.0),
        visibility: fin(p.visibility, 1.0).clamp(0.0, 1.0),
        truth: fin(p.true_lit_fraction, 1.0).clamp(0.0, 1.0),
        plane: fin(p.plane_lit_fraction, 1.0).clamp(0.0, 1.0),
        reduction: fin(p.bleed_reduction, 0.0).clamp(0.0, 0.99),
    }
}

pub fn draw(c: &mut Canvas, inp: &DiagramInputs) {
    let example = inp.vsm.is_none();
    let plot = inp.vsm.clone().unwrap_or_else(VsmPlot::example);
    let n = numbers(&plot);
    let [px, py, pw, ph] = PLOT;
    let x_of = |z: f32| px + (z - n.lo) / (n.hi - n.lo) * pw;
    let y_of = |v: f32| py + ph * (1.0 - v.clamp(0.0, 1.0));
    let ink = col(pal::INK, 1.0);
    let muted = col(pal::MUTED, 1.0);

    c.rect([px, py, pw, ph], Some(col(pal::BG, 1.0)), Some((muted, 1.5)));
    // mu ± sigma, where the bound says nothing (it is 1 up to the mean).
    let sigma = n.variance.sqrt();
    let band = [x_of(n.mean - sigma).max(px), x_of(n.mean + sigma).min(px + pw)];
    if band[1] > band[0] {
        c.rect([band[0], py, band[1] - band[0], ph], Some(col(pal::SEARCH, 0.10)), None);
    }
    // The histogram: each bin's share of the window, the largest drawn 0.9 high.
    let tallest = n.bins.iter().copied().fold(0.0f32, f32::max);
    if tallest > 0.0 {
        let w = pw / n.bins.len() as f32;
        for (i, share) in n.bins.iter().enumerate() {
            if *share > 0.0 {
                let h = (share / tallest * 0.9 * ph).max(1.5);
                let x = px + i as f32 * w;
                c.rect([x + 0.5, py + ph - h, (w - 1.0).max(0.5), h], Some(col(pal::BLOCKER, 0.45)), None);
            }
        }
    }
    // The true lit share P(z >= x): a step down at each bin (exact at the bin edges).
    let total: f32 = n.bins.iter().sum();
    let mut behind = total;
    let mut steps = vec![[px, y_of(1.0)]];
    let w = pw / n.bins.len().max(1) as f32;
    for (i, share) in n.bins.iter().enumerate() {
        let x = px + i as f32 * w;
        let before = if total > 0.0 { behind / total } else { 1.0 };
        behind -= share;
        let after = if total > 0.0 { behind.max(0.0) / total } else { 1.0 };
        steps.push([x, y_of(before)]);
        steps.push([x + w * 0.5, y_of(before)]);
        steps.push([x + w * 0.5, y_of(after)]);
    }
    steps.push([px + pw, y_of(0.0)]);
    c.set_clip(Some([px, py - 4.0, pw, ph + 8.0]));
    c.polyline(&steps, col(pal::LIT, 1.0), 3.0, None);
    // Chebyshev's bound at every x.
    let curve: Vec<[f32; 2]> = (0..=240)
        .map(|i| {
            let z = n.lo + (n.hi - n.lo) * i as f32 / 240.0;
            [x_of(z), y_of(bound_at(n.mean, n.variance, z))]
        })
        .collect();
    c.polyline(&curve, col(pal::PENUMBRA, 1.0), 3.0, None);
    if n.reduction > 0.0 {
        let reduced: Vec<[f32; 2]> = (0..=240)
            .map(|i| {
                let z = n.lo + (n.hi - n.lo) * i as f32 / 240.0;
                let p = bound_at(n.mean, n.variance, z);
                [x_of(z), y_of(((p - n.reduction) / (1.0 - n.reduction)).clamp(0.0, 1.0))]
            })
            .collect();
        c.polyline(&reduced, col(pal::PENUMBRA, 0.8), 2.0, Some(8.0));
    }
    c.set_clip(None);
    // The mean and the tested depth.
    let xm = x_of(n.mean).clamp(px, px + pw);
    c.dashed([xm, py], [xm, py + ph], col(pal::SEARCH, 1.0), 2.0, 7.0);
    c.text("μ", [xm, py - 4.0], Anchor::BottomCenter, Style::em(FS_LABEL, pal::SEARCH));
    let xt = x_of(n.t).clamp(px, px + pw);
    c.line([xt, py], [xt, py + ph], ink, 2.5);
    c.text("t", [xt, py - 4.0], Anchor::BottomCenter, Style::em(FS_LABEL, pal::INK));
    // Light bleeding: what the lookup returns (the bound, or the reduced bound) above the lit
    // share of the window measured against the receiver's plane.
    let (yv, yt) = (y_of(n.visibility), y_of(n.plane));
    if n.visibility - n.plane > 0.01 {
        c.line([xt, yv], [xt, yt], col(pal::BLOCKED, 1.0), 6.0);
        let t = c.fill("bleeding {}", &[&format!("{:.2}", n.visibility - n.plane)]);
        let anchor = if xt > px + pw * 0.6 { Anchor::MidRight } else { Anchor::MidLeft };
        let dx = if anchor == Anchor::MidRight { -10.0 } else { 10.0 };
        c.text(&t, [xt + dx, (yv + yt) * 0.5], anchor, Style::em(FS_SMALL, pal::BLOCKED));
    }
    c.circle([xt, y_of(n.bound)], 6.0, Some(col(pal::PENUMBRA, 1.0)), Some((ink, 1.5)));
    if n.visibility != n.bound {
        c.circle([xt, yv], 6.0, Some(col(pal::BG, 1.0)), Some((col(pal::PENUMBRA, 1.0), 2.5)));
    }
    c.circle([xt, y_of(n.truth)], 6.0, Some(col(pal::LIT, 1.0)), Some((ink, 1.5)));
    // Axes.
    c.label("1", [px - 6.0, py], Anchor::MidRight, FS_SMALL);
    c.label("0", [px - 6.0, py + ph], Anchor::MidRight, FS_SMALL);
    c.label(&format!("{:.4}", n.lo), [px, py + ph + 6.0], Anchor::TopLeft, FS_SMALL);
    c.label(&format!("{:.4}", n.hi), [px + pw, py + ph + 6.0], Anchor::TopRight, FS_SMALL);
    // Below the end labels: a panel's grown text would run into them on one row.
    c.label("NDC depth (nearer the light ←)", [px + pw * 0.5, py + ph + 30.0], Anchor::TopCenter, FS_SMALL);

    // Numbers on the right.
    let mut text = Column::new(580.0, 70.0);
    if example {
        text.tint(c, "an example: probe a pixel with VSM or VSSM", pal::MUTED);
    }
    let t =
        c.fill("filter window: {} texels radius", &[&format!("{:.1}", fin(plot.filter_radius_texels, 0.0))]);
    text.line(c, &t);
    let t = c.fill("μ = E[z] = {}", &[&format!("{:.4}", n.mean)]);
    text.tint(c, &t, pal::SEARCH);
    let t = c.fill("σ² = E[z²] − μ² = {}", &[&format!("{:.2e}", n.variance)]);
    text.line(c, &t);
    let t = c.fill("t = receiver − bias = {}", &[&format!("{:.4}", n.t)]);
    text.line(c, &t);
    text.em(c, "P(z ≥ t) ≤ σ² / (σ² + (t − μ)²)", pal::PENUMBRA);
    let t = c.fill("bound = {}", &[&format!("{:.3}", n.bound)]);
    text.tint(c, &t, pal::PENUMBRA);
    let t = c.fill("true lit share = {}", &[&format!("{:.3}", n.truth)]);
    text.tint(c, &t, pal::LIT);
    if (n.plane - n.truth).abs() >= 0.0005 {
        // A tilted receiver's own texels nearer than t are lit: measured against its plane.
        let t = c.fill("against the receiver's plane = {}", &[&format!("{:.3}", n.plane)]);
        text.tint(c, &t, pal::LIT);
    }
    let t = c.fill("light bleeding = {}", &[&format!("{:.3}", (n.visibility - n.plane).max(0.0))]);
    text.tint(c, &t, pal::BLOCKED);
    if n.reduction > 0.0 {
        let t = c.fill("bleed reduction a = {}: (p − a) / (1 − a)", &[&format!("{:.2}", n.reduction)]);
        text.line(c, &t);
    }
    let t = c.fill("visibility = {}", &[&format!("{:.3}", n.visibility)]);
    text.styled(c, &t, Style::em(FS_LABEL + 3.0, pal::INK));

    let items = [
        (Swatch::Fill(pal::BLOCKER, 0.45), "depths in the window"),
        (Swatch::Line(pal::LIT), "true P(z ≥ x)"),
        (Swatch::Line(pal::PENUMBRA), "Chebyshev's bound"),
        (Swatch::Fill(pal::SEARCH, 0.12), "μ ± σ"),
    ];
    c.legend_row(&items, [480.0, 530.0]);
}

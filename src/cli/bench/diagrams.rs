//! `shadowlab bench --diagrams`: how long each diagram takes to draw, in each language. The app
//! redraws the diagram on the UI thread whenever a value it shows changes (every frame of a
//! drag), so this is time a student's frame spends before the views are even shown. Two
//! timings: "drag", with the values moving every frame (numbers in the labels change, so their
//! text is shaped and rasterised anew), and "still", the same picture again (everything cached).

use std::time::Instant;

use serde::Serialize;

use super::techniques::median;
use crate::cli::{BenchArgs, CliError};
use crate::diagrams::{self, DiagramInputs, DiagramKind};
use crate::i18n::Lang;
use crate::ui::DIAGRAM_MIN_TEXT_PT;

#[derive(Serialize)]
struct DiagramRow {
    diagram: &'static str,
    lang: &'static str,
    /// Median and minimum with the inputs moving every frame.
    drag_median_ms: f64,
    drag_min_ms: f64,
    /// Median with the same inputs every frame.
    still_median_ms: f64,
}

/// The inputs of frame `i` of a drag: the light widens and the receiver, the blocker and the
/// bias move, as when a student drags the light or the probe.
fn dragged(base: &DiagramInputs, i: u32) -> DiagramInputs {
    let t = i as f32 + 1.0;
    DiagramInputs {
        light_width_world: base.light_width_world.map(|w| w * (1.0 + 0.013 * t)),
        receiver_depth_linear: base.receiver_depth_linear + 0.37 * t,
        blocker_depth_linear: base.blocker_depth_linear.map(|d| d + 0.21 * t),
        bias_ndc: base.bias_ndc * (1.0 + 0.05 * t),
        light_angle_deg: base.light_angle_deg + 0.3 * t,
        ..base.clone()
    }
}

#[derive(Serialize)]
struct DiagramReport {
    size: [u32; 2],
    frames: u32,
    min_text_px: f32,
    rows: Vec<DiagramRow>,
}

pub fn run(args: &BenchArgs) -> Result<(), CliError> {
    let [w, h] = [args.size.0, args.size.1];
    let base = DiagramInputs::default();
    // As on a screen of one pixel per point.
    let min_text_px = DIAGRAM_MIN_TEXT_PT;
    let mut rows = Vec::new();
    for kind in DiagramKind::ALL {
        for lang in [Lang::En, Lang::Zh] {
            let timed = |inputs: &DiagramInputs| {
                let start = Instant::now();
                diagrams::draw_traced(kind, inputs, lang, [w, h], min_text_px)
                    .map(|_| start.elapsed().as_secs_f64() * 1e3)
                    .map_err(|e| CliError::input(format!("--size {w}x{h}: {e}")))
            };
            // The first draw loads the fonts and fills the caches, as the app's first frame does.
            timed(&base)?;
            let drag = (0..args.frames).map(|i| timed(&dragged(&base, i))).collect::<Result<Vec<_>, _>>()?;
            let still = (0..args.frames).map(|_| timed(&base)).collect::<Result<Vec<_>, _>>()?;
            rows.push(DiagramRow {
                diagram: kind.id(),
                lang: lang.code(),
                drag_median_ms: median(&drag),
                drag_min_ms: drag.iter().copied().fold(f64::INFINITY, f64::min),
                still_median_ms: median(&still),
            });
        }
    }
    let report = DiagramReport { size: [w, h], frames: args.frames, min_text_px, rows };
    if args.json {
        let json = serde_json::to_string_pretty(&report)
            .map_err(|e| CliError { code: 1, message: e.to_string() })?;
        println!("{json}");
        return Ok(());
    }
    println!("diagrams: {w}x{h}  frames: {}  (CPU, tiny-skia and cosmic-text)", args.frames);
    println!(
        "{:<14} {:>5} {:>14} {:>12} {:>15}",
        "diagram", "lang", "drag median ms", "drag min ms", "still median ms"
    );
    for r in &report.rows {
        println!(
            "{:<14} {:>5} {:>14.2} {:>12.2} {:>15.2}",
            r.diagram, r.lang, r.drag_median_ms, r.drag_min_ms, r.still_median_ms
        );
    }
    Ok(())
}

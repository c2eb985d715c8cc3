//! `shadowlab bench --diagrams`: how long each diagram takes to draw, in each language. The app
//! redraws the diagram on the UI thread whenever a value it shows changes (every frame of a
//! drag), so this is time a student's frame spends before the views are even shown.

use std::time::Instant;

use serde::Serialize;

use super::{BenchArgs, CliError};
use crate::diagrams::{self, DiagramInputs, DiagramKind};
use crate::lessons::Lang;
use crate::ui::DIAGRAM_MIN_TEXT_PT;

#[derive(Serialize)]
struct DiagramRow {
    diagram: &'static str,
    lang: &'static str,
    median_ms: f64,
    min_ms: f64,
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
    let inputs = DiagramInputs::default();
    // As on a screen of one pixel per point.
    let min_text_px = DIAGRAM_MIN_TEXT_PT;
    let mut rows = Vec::new();
    for kind in DiagramKind::ALL {
        for (lang, lang_id) in [(Lang::En, "en"), (Lang::Zh, "zh")] {
            let draw = || {
                diagrams::draw_traced(kind, &inputs, lang, [w, h], min_text_px)
                    .map_err(|e| CliError::input(format!("--size {w}x{h}: {e}")))
            };
            // The first draw fills the glyph cache, as the app's first frame does.
            draw()?;
            let mut times: Vec<f64> = (0..args.frames)
                .map(|_| {
                    let start = Instant::now();
                    draw().map(|_| start.elapsed().as_secs_f64() * 1e3)
                })
                .collect::<Result<_, _>>()?;
            times.sort_by(f64::total_cmp);
            rows.push(DiagramRow {
                diagram: kind.id(),
                lang: lang_id,
                median_ms: times[times.len() / 2],
                min_ms: times[0],
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
    println!("{:<14} {:>5} {:>10} {:>8}", "diagram", "lang", "median ms", "min ms");
    for r in &report.rows {
        println!("{:<14} {:>5} {:>10.2} {:>8.2}", r.diagram, r.lang, r.median_ms, r.min_ms);
    }
    Ok(())
}

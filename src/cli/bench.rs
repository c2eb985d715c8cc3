//! `shadowlab bench`: median frame time per technique, and per-pass GPU times where the adapter
//! has timestamp queries.

use super::{BenchArgs, CliError, gpu};
use crate::render::FrameRequest;
use crate::scene::{Technique, load_scene};
use serde::Serialize;
use std::time::Instant;

#[derive(Serialize)]
struct BenchRow {
    technique: String,
    median_frame_ms: f64,
    min_frame_ms: f64,
    shadow_pass_ms: Option<f64>,
    camera_pass_ms: Option<f64>,
}

#[derive(Serialize)]
struct BenchReport {
    adapter: String,
    scene: String,
    size: [u32; 2],
    frames: u32,
    rows: Vec<BenchRow>,
}

fn median(values: &mut [f64]) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

/// (label, technique, filter samples, blocker samples)
const CASES: [(&str, Technique, u32, u32); 6] = [
    ("hard", Technique::Hard, 1, 1),
    ("pcf 16", Technique::Pcf, 16, 1),
    ("pcf 32", Technique::Pcf, 32, 1),
    ("pcf 64", Technique::Pcf, 64, 1),
    ("pcss 16+16", Technique::Pcss, 16, 16),
    ("pcss 32+32", Technique::Pcss, 32, 32),
];

pub fn run(args: BenchArgs) -> Result<(), CliError> {
    let base = load_scene(&args.scene, &[])?;
    let (ctx, mut renderer) = gpu()?;
    let adapter = ctx.describe();
    if !args.json {
        println!("adapter: {adapter}");
        println!(
            "scene: {}  size: {}x{}  frames: {}",
            args.scene.display(),
            args.size.0,
            args.size.1,
            args.frames
        );
        println!(
            "{:<12} {:>12} {:>10} {:>12} {:>12}",
            "technique", "median ms", "min ms", "shadow ms", "camera ms"
        );
    }
    let mut rows = Vec::new();
    for (label, technique, samples, blocker_samples) in CASES {
        let mut scene = base.clone();
        scene.shadow.technique = technique;
        scene.shadow.samples = samples;
        scene.shadow.blocker_samples = blocker_samples;
        let request = FrameRequest {
            size: args.size,
            final_color: true,
            analysis: false,
            timestamps: true,
            ..Default::default()
        };
        for _ in 0..2 {
            renderer.render(&scene, &request)?;
            renderer.wait_idle()?;
        }
        let (mut frame_ms, mut shadow_ms, mut camera_ms) = (Vec::new(), Vec::new(), Vec::new());
        for _ in 0..args.frames {
            let start = Instant::now();
            renderer.render(&scene, &request)?;
            renderer.wait_idle()?;
            frame_ms.push(start.elapsed().as_secs_f64() * 1e3);
            if let Some(times) = renderer.last_pass_times()? {
                shadow_ms.push(times.shadow_ms);
                camera_ms.push(times.camera_ms);
            }
        }
        let row = BenchRow {
            technique: label.to_string(),
            min_frame_ms: frame_ms.iter().copied().fold(f64::INFINITY, f64::min),
            median_frame_ms: median(&mut frame_ms),
            shadow_pass_ms: (!shadow_ms.is_empty()).then(|| median(&mut shadow_ms)),
            camera_pass_ms: (!camera_ms.is_empty()).then(|| median(&mut camera_ms)),
        };
        if !args.json {
            let opt = |v: Option<f64>| v.map_or("n/a".to_string(), |v| format!("{v:.2}"));
            println!(
                "{:<12} {:>12.2} {:>10.2} {:>12} {:>12}",
                row.technique,
                row.median_frame_ms,
                row.min_frame_ms,
                opt(row.shadow_pass_ms),
                opt(row.camera_pass_ms)
            );
        }
        rows.push(row);
    }
    if args.json {
        let report = BenchReport {
            adapter,
            scene: args.scene.display().to_string(),
            size: [args.size.0, args.size.1],
            frames: args.frames,
            rows,
        };
        let json = serde_json::to_string_pretty(&report)
            .map_err(|e| CliError { code: 1, message: e.to_string() })?;
        println!("{json}");
    } else if !renderer.has_timestamps() {
        println!("(this adapter has no timestamp queries: per-pass times are not available)");
    }
    Ok(())
}

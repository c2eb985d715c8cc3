//! `shadowlab bench`: frame time per technique on an animated scene (the GAMES202 homework
//! workload by default), with per-pass GPU times where the adapter has timestamp queries.
//!
//! Each timed frame advances scene time by 1/30 s, so lights orbit and objects spin and every
//! shadow map is redrawn as it would be in the app; `--still` keeps the time fixed.

use crate::cli::{BenchArgs, CliError, DEFAULT_BENCH_SCENE, gpu};
use crate::render::FrameRequest;
use crate::scene::{BiasMode, Scene, Technique, load_scene};
use serde::Serialize;
use std::time::Instant;

/// Scene time between two timed frames, seconds (a 30 frames/s playback).
const FRAME_STEP_S: f32 = 1.0 / 30.0;

#[derive(Serialize)]
struct BenchRow {
    technique: String,
    /// The bias mode the row ran with.
    bias_mode: String,
    /// Wall-clock time of render + wait, per frame: median and minimum.
    median_frame_ms: f64,
    min_frame_ms: f64,
    /// GPU time of all shadow passes and of the camera pass (medians), where timestamps exist.
    shadow_pass_ms: Option<f64>,
    camera_pass_ms: Option<f64>,
    /// Every timed frame, in order.
    frames: Vec<FrameTimes>,
}

#[derive(Serialize)]
struct FrameTimes {
    time_s: f32,
    frame_ms: f64,
    shadow_pass_ms: Option<f64>,
    camera_pass_ms: Option<f64>,
}

#[derive(Serialize)]
struct BenchReport {
    adapter: String,
    scene: String,
    overrides: Vec<String>,
    size: [u32; 2],
    frames: u32,
    start_time_s: f32,
    animated: bool,
    rows: Vec<BenchRow>,
}

pub fn median(values: &[f64]) -> f64 {
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    sorted[sorted.len() / 2]
}

/// One row: a label, a technique, its sample counts and bias mode (`None` keeps the scene's value).
struct Case {
    label: String,
    technique: Technique,
    samples: Option<u32>,
    blocker_samples: Option<u32>,
    bias_mode: Option<BiasMode>,
    /// Light 0 as the scene has it, or made a lamp or given cascades where it stands.
    light0: Light0,
}

/// What a row does to light 0: the cost of more maps against the scene's own.
#[derive(Clone, Copy, PartialEq)]
enum Light0 {
    AsIs,
    /// A point light where it stands: six cube faces instead of its one map.
    Point,
    /// A sun with this many cascades (1: one map over its extent).
    Cascades(u32),
}

/// The rows: `none` (shading without any shadow lookup: the per-pixel floor), hard, PCF and PCSS
/// at 16 and 32 samples, and both at the scene's own sample counts (50 + 50 on the homework);
/// then VSM, and PCF and PCSS again with the receiver-plane bias, where the scene uses another. With a bias
/// that does not grow with the kernel, a floor tilted to the light finds itself in the blocker
/// search, so PCSS filters every pixel; with the plane it filters only near real blockers.
/// Last, hard and PCF with light 0 made a point light where it stands: what six maps cost
/// against one; and for a sun, with four cascades (or one map, where it has cascades).
fn cases(scene: &Scene) -> Vec<Case> {
    let case = |label: String, technique, samples, blocker_samples| Case {
        label,
        technique,
        samples,
        blocker_samples,
        bias_mode: None,
        light0: Light0::AsIs,
    };
    let (n, nb) = (scene.shadow.samples, scene.shadow.blocker_samples);
    let mut out = vec![
        case("none".into(), Technique::None, None, None),
        case("hard".into(), Technique::Hard, None, None),
    ];
    let mut pcf_counts = vec![16, 32];
    if !pcf_counts.contains(&n) {
        pcf_counts.push(n);
    }
    for s in &pcf_counts {
        out.push(case(format!("pcf {s}"), Technique::Pcf, Some(*s), None));
    }
    let mut pcss_counts = vec![(16, 16), (32, 32)];
    if !pcss_counts.contains(&(n, nb)) {
        pcss_counts.push((n, nb));
    }
    for (s, b) in pcss_counts {
        out.push(case(format!("pcss {b}+{s}"), Technique::Pcss, Some(s), Some(b)));
    }
    // VSM filters over the PCF radius with eight reads of the moments, whatever the radius.
    out.push(case("vsm".into(), Technique::Vsm, None, None));
    out.push(case("vssm".into(), Technique::Vssm, None, None));
    if scene.shadow.bias_mode != BiasMode::ReceiverPlane {
        let plane = Some(BiasMode::ReceiverPlane);
        out.push(Case {
            bias_mode: plane,
            ..case(format!("pcf {n} plane-bias"), Technique::Pcf, None, None)
        });
        let label = format!("pcss {nb}+{n} plane-bias");
        out.push(Case { bias_mode: plane, ..case(label, Technique::Pcss, None, None) });
    }
    // The cost of six maps: light 0 as a lamp where it stands, against its own rows above.
    if scene.lights.first().is_some_and(|l| !l.stores_distance()) {
        for (label, technique, samples) in [
            ("point-light hard".to_string(), Technique::Hard, None),
            (format!("point-light pcf {n}"), Technique::Pcf, Some(n)),
        ] {
            out.push(Case { light0: Light0::Point, ..case(label, technique, samples, None) });
        }
    }
    // The cost of cascades: a sun's four against its one map (or one map against its cascades).
    if let Some(sun) = scene.lights.first().filter(|l| l.is_orthographic()) {
        let (count, name) = if sun.cascades.is_cascaded() { (1, "one-map") } else { (4, "4-cascade") };
        for (label, technique, samples) in [
            (format!("{name} hard"), Technique::Hard, None),
            (format!("{name} pcf {n}"), Technique::Pcf, Some(n)),
        ] {
            out.push(Case { light0: Light0::Cascades(count), ..case(label, technique, samples, None) });
        }
    }
    out
}

/// `--only` picks rows by label ("pcss 50+50") or by technique name ("pcss": all its rows).
fn selected(case: &Case, only: &[String]) -> bool {
    only.is_empty()
        || only.iter().any(|o| {
            let o = o.trim();
            case.label == o || case.label.split(' ').next() == Some(o)
        })
}

pub fn run(args: BenchArgs) -> Result<(), CliError> {
    let scene_path = args.scene.clone().unwrap_or_else(|| crate::shipped_path(DEFAULT_BENCH_SCENE));
    let base = load_scene(&scene_path, &args.set)?;
    let cases: Vec<Case> = cases(&base).into_iter().filter(|c| selected(c, &args.only)).collect();
    if cases.is_empty() {
        return Err(CliError::input(format!(
            "--only {}: no such row (rows: {})",
            args.only.join(","),
            self::cases(&base).iter().map(|c| c.label.as_str()).collect::<Vec<_>>().join(", ")
        )));
    }
    let (ctx, mut renderer) = gpu()?;
    let adapter = ctx.describe();
    let animated = !args.still;
    let start_time_s = args.time.unwrap_or(0.0);
    if !args.json {
        println!("adapter: {adapter}");
        println!(
            "scene: {}  size: {}x{}  frames: {}  time: {start_time_s} s{}",
            scene_path.display(),
            args.size.0,
            args.size.1,
            args.frames,
            if animated { " (+1/30 s per frame)" } else { " (still)" }
        );
        println!(
            "{:<22} {:>12} {:>10} {:>12} {:>12}",
            "technique", "median ms", "min ms", "shadow ms", "camera ms"
        );
    }
    let mut rows = Vec::new();
    for case in cases {
        let mut scene = base.clone();
        scene.shadow.technique = case.technique;
        if let Some(s) = case.samples {
            scene.shadow.samples = s;
        }
        if let Some(b) = case.blocker_samples {
            scene.shadow.blocker_samples = b;
        }
        if let Some(mode) = case.bias_mode {
            scene.shadow.bias_mode = mode;
        }
        if let Some(light) = scene.lights.first_mut() {
            match case.light0 {
                Light0::AsIs => {}
                Light0::Point => {
                    light.kind = crate::scene::LightKind::Point;
                    // A sun's angular size has no meaning at a point; a lamp has a width.
                    light.size = crate::scene::LightSize::Width { width_world: 0.0 };
                    light.cascades = crate::scene::Cascades::default();
                }
                Light0::Cascades(count) => light.cascades.count = count,
            }
        }
        let request_at = |time_s| FrameRequest {
            time_s,
            size: args.size,
            final_color: true,
            analysis: false,
            timestamps: true,
            ..Default::default()
        };
        for _ in 0..2 {
            renderer.render(&scene, &request_at(start_time_s))?;
            renderer.wait_idle()?;
        }
        let mut frames = Vec::new();
        for i in 0..args.frames {
            let time_s = if animated { start_time_s + i as f32 * FRAME_STEP_S } else { start_time_s };
            let start = Instant::now();
            renderer.render(&scene, &request_at(time_s))?;
            renderer.wait_idle()?;
            let frame_ms = start.elapsed().as_secs_f64() * 1e3;
            let times = renderer.last_pass_times()?;
            frames.push(FrameTimes {
                time_s,
                frame_ms,
                shadow_pass_ms: times.map(|t| t.shadow_ms),
                camera_pass_ms: times.map(|t| t.camera_ms),
            });
        }
        let frame_ms: Vec<f64> = frames.iter().map(|f| f.frame_ms).collect();
        let shadow_ms: Vec<f64> = frames.iter().filter_map(|f| f.shadow_pass_ms).collect();
        let camera_ms: Vec<f64> = frames.iter().filter_map(|f| f.camera_pass_ms).collect();
        let row = BenchRow {
            technique: case.label,
            bias_mode: scene.shadow.bias_mode.name().to_string(),
            min_frame_ms: frame_ms.iter().copied().fold(f64::INFINITY, f64::min),
            median_frame_ms: median(&frame_ms),
            shadow_pass_ms: (!shadow_ms.is_empty()).then(|| median(&shadow_ms)),
            camera_pass_ms: (!camera_ms.is_empty()).then(|| median(&camera_ms)),
            frames,
        };
        if !args.json {
            let opt = |v: Option<f64>| v.map_or("n/a".to_string(), |v| format!("{v:.2}"));
            println!(
                "{:<22} {:>12.2} {:>10.2} {:>12} {:>12}",
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
            scene: scene_path.display().to_string(),
            overrides: args.set.iter().map(|(k, v)| format!("{k}={v}")).collect(),
            size: [args.size.0, args.size.1],
            frames: args.frames,
            start_time_s,
            animated,
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

//! The command line: `render`, `probe`, `bench`. Exit codes: 2 for bad input (files, keys,
//! values, no adapter), 1 for a rendering failure. Errors are one line naming what and where.

mod bench;

use crate::export;
use crate::render::{FrameRequest, GpuContext, RenderError, Renderer};
use crate::scene::{Scene, SceneError, load_scene};
use crate::views::{self, View};
use clap::{Args, Parser, Subcommand};
use std::path::{Path, PathBuf};

#[derive(Parser, Debug)]
#[command(
    name = "shadowlab",
    version,
    about = "Learn real-time shadows: shadow maps, bias, PCF, PCSS. With no command, opens the app."
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Render a scene (or one of its debug views) to a PNG.
    Render(RenderArgs),
    /// Print, as JSON, everything about the surface under one pixel.
    Probe(ProbeArgs),
    /// Time every technique on this machine's adapter.
    Bench(BenchArgs),
}

#[derive(Args, Debug, Clone)]
pub struct FrameArgs {
    /// Scene file (TOML).
    #[arg(long)]
    pub scene: PathBuf,
    /// Override a scene value: a [shadow] key (`technique=pcss`) or `camera.KEY`, `light.N.KEY`, `object.N.KEY`.
    #[arg(long = "set", value_name = "KEY=VALUE", value_parser = parse_key_value)]
    pub set: Vec<(String, String)>,
    /// Scene time, seconds (lights orbit, objects spin).
    #[arg(long, default_value_t = 0.0, value_parser = parse_time)]
    pub time: f32,
    /// Image size, pixels.
    #[arg(long, default_value = "960x540", value_parser = parse_size)]
    pub size: (u32, u32),
}

#[derive(Args, Debug)]
pub struct RenderArgs {
    #[command(flatten)]
    pub frame: FrameArgs,
    /// What to show: final, visibility, shadow-map, blocker-radius, penumbra, blockers, reference, error.
    #[arg(long, default_value = "final", value_parser = parse_view)]
    pub view: View,
    /// The light the debug views describe.
    #[arg(long, default_value_t = 0)]
    pub light: usize,
    /// Output PNG file.
    #[arg(long)]
    pub out: PathBuf,
}

#[derive(Args, Debug)]
pub struct ProbeArgs {
    #[command(flatten)]
    pub frame: FrameArgs,
    /// Pixel to probe, x,y from the top-left corner.
    #[arg(long, value_parser = parse_pixel)]
    pub pixel: (u32, u32),
    /// Skip the ground truth (faster).
    #[arg(long)]
    pub no_reference: bool,
}

#[derive(Args, Debug)]
pub struct BenchArgs {
    #[arg(long, default_value = "assets/scenes/games202.toml")]
    pub scene: PathBuf,
    #[arg(long, default_value = "960x540", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Timed frames per technique (after two warm-up frames).
    #[arg(long, default_value_t = 30, value_parser = clap::value_parser!(u32).range(1..=10_000))]
    pub frames: u32,
    /// Print JSON instead of a table.
    #[arg(long)]
    pub json: bool,
}

/// A failure with its exit code.
#[derive(Debug)]
pub struct CliError {
    pub code: i32,
    pub message: String,
}

impl CliError {
    pub fn input(message: impl Into<String>) -> Self {
        Self { code: 2, message: message.into() }
    }
}

impl From<SceneError> for CliError {
    fn from(e: SceneError) -> Self {
        Self::input(e.to_string())
    }
}

impl From<RenderError> for CliError {
    fn from(e: RenderError) -> Self {
        let code = match e {
            RenderError::NoAdapter(_) | RenderError::Limits(_) | RenderError::Usage(_) => 2,
            RenderError::Device(_) | RenderError::Readback(_) => 1,
        };
        Self { code, message: e.to_string() }
    }
}

impl From<export::ExportError> for CliError {
    fn from(e: export::ExportError) -> Self {
        Self { code: 1, message: e.to_string() }
    }
}

fn parse_key_value(s: &str) -> Result<(String, String), String> {
    let (k, v) = s.split_once('=').ok_or_else(|| format!("`{s}` is not KEY=VALUE"))?;
    if k.trim().is_empty() {
        return Err(format!("`{s}` has an empty key"));
    }
    Ok((k.trim().to_string(), v.trim().to_string()))
}

fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(|| format!("`{s}` is not WIDTHxHEIGHT"))?;
    let parse = |v: &str| v.trim().parse::<u32>().ok().filter(|&n| (1..=16384).contains(&n));
    match (parse(w), parse(h)) {
        (Some(w), Some(h)) => Ok((w, h)),
        _ => Err(format!("`{s}` is not WIDTHxHEIGHT with sides 1..=16384")),
    }
}

fn parse_pixel(s: &str) -> Result<(u32, u32), String> {
    let (x, y) = s.split_once(',').ok_or_else(|| format!("`{s}` is not X,Y"))?;
    match (x.trim().parse(), y.trim().parse()) {
        (Ok(x), Ok(y)) => Ok((x, y)),
        _ => Err(format!("`{s}` is not X,Y with whole non-negative numbers")),
    }
}

/// Longest scene time accepted, seconds (a day: beyond it f32 time loses sub-frame precision).
pub const MAX_TIME_S: f32 = 86_400.0;

fn parse_time(s: &str) -> Result<f32, String> {
    match s.parse::<f32>() {
        Ok(t) if t.is_finite() && t.abs() <= MAX_TIME_S => Ok(t),
        _ => Err(format!("`{s}` is not a number of seconds in -{MAX_TIME_S}..={MAX_TIME_S}")),
    }
}

fn parse_view(s: &str) -> Result<View, String> {
    View::from_name(s).ok_or_else(|| {
        let names: Vec<_> = View::ALL.iter().map(|v| v.name()).collect();
        format!("unknown view `{s}` (expected one of {})", names.join(", "))
    })
}

/// The checks every command makes before touching the GPU.
fn load(frame: &FrameArgs) -> Result<Scene, CliError> {
    Ok(load_scene(&frame.scene, &frame.set)?)
}

pub fn gpu() -> Result<(GpuContext, Renderer), CliError> {
    let ctx = GpuContext::new_headless()?;
    let renderer = Renderer::new(&ctx.device, &ctx.queue)?;
    Ok((ctx, renderer))
}

fn check_out_path(out: &Path) -> Result<(), CliError> {
    if out.is_dir() {
        return Err(CliError::input(format!("{}: is a folder, not a file", out.display())));
    }
    let is_png = out.extension().is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if !is_png {
        return Err(CliError::input(format!("{}: the output must be a .png file", out.display())));
    }
    let dir = out.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
    if !dir.is_dir() {
        return Err(CliError::input(format!("{}: folder {} does not exist", out.display(), dir.display())));
    }
    Ok(())
}

pub fn run(command: Command) -> Result<(), CliError> {
    match command {
        Command::Render(args) => render(args),
        Command::Probe(args) => probe(args),
        Command::Bench(args) => bench::run(args),
    }
}

fn render(args: RenderArgs) -> Result<(), CliError> {
    check_out_path(&args.out)?;
    let scene = load(&args.frame)?;
    if args.light >= scene.lights.len().max(1) {
        return Err(CliError::input(format!(
            "--light {}: {} has {} light(s)",
            args.light,
            args.frame.scene.display(),
            scene.lights.len()
        )));
    }
    if scene.lights.is_empty() && args.view != View::Final {
        return Err(CliError::input(format!(
            "{}: the scene has no lights, so no `{}` view",
            args.frame.scene.display(),
            args.view.name()
        )));
    }
    let (_ctx, mut renderer) = gpu()?;
    let request = FrameRequest {
        time_s: args.frame.time,
        size: args.frame.size,
        selected_light: args.light,
        final_color: args.view == View::Final,
        analysis: args.view != View::Final,
        timestamps: false,
    };
    renderer.render(&scene, &request)?;
    let (image, summary) = match args.view {
        View::Final => (renderer.read_color()?, None),
        View::ShadowMap => {
            let map = renderer.read_shadow_map(args.light)?;
            let (image, legend) = views::shadow_map_image(&map, &renderer.frame_lights[args.light]);
            (image, Some(legend.to_string()))
        }
        View::Visibility => {
            let a = renderer.read_analysis()?;
            (
                views::gray_image(&a, |i| a.shadow[i][0]),
                Some("visibility: black = shadowed, white = lit".into()),
            )
        }
        View::BlockerRadius | View::Penumbra | View::Blockers => {
            let a = renderer.read_analysis()?;
            let (label, unit, channel) = match args.view {
                View::BlockerRadius => ("blocker-search radius", "texels", 1),
                View::Penumbra => ("penumbra width", "texels", 2),
                _ => ("blockers found", "taps", 3),
            };
            let (image, legend) = views::heat_image(&a, label, unit, |i| a.shadow[i][channel]);
            (image, Some(legend.to_string()))
        }
        View::Reference | View::Error => {
            let a = renderer.read_analysis()?;
            let reference = renderer.render_reference(&scene, args.light)?;
            if args.view == View::Reference {
                let note = format!("reference: {} hard shadows averaged", scene.shadow.reference_samples);
                (views::gray_image(&a, |i| reference[i]), Some(note))
            } else {
                let (image, legend, mae) = views::error_image(&a, &reference);
                (image, Some(format!("{legend}\nmean absolute error: {mae:.5}")))
            }
        }
    };
    export::write_png(&args.out, &image)?;
    println!(
        "wrote {} ({}x{}, view {}, light {})",
        args.out.display(),
        image.width(),
        image.height(),
        args.view.name(),
        args.light
    );
    if let Some(summary) = summary {
        println!("{summary}");
    }
    Ok(())
}

fn probe(args: ProbeArgs) -> Result<(), CliError> {
    let scene = load(&args.frame)?;
    let (w, h) = args.frame.size;
    if args.pixel.0 >= w || args.pixel.1 >= h {
        return Err(CliError::input(format!(
            "--pixel {},{} is outside the {w}x{h} image",
            args.pixel.0, args.pixel.1
        )));
    }
    let (_ctx, mut renderer) = gpu()?;
    let request = FrameRequest { time_s: args.frame.time, size: args.frame.size, ..Default::default() };
    let report = crate::probe::probe(&mut renderer, &scene, &request, args.pixel, !args.no_reference)?;
    let json =
        serde_json::to_string_pretty(&report).map_err(|e| CliError { code: 1, message: e.to_string() })?;
    println!("{json}");
    Ok(())
}

//! The command line: `render`, `probe`, `bench`. Exit codes: 2 for bad input (files, keys,
//! values, no adapter), 1 for a rendering failure. Errors are one line naming what and where.

mod bench;
#[path = "export.rs"]
mod export_cmd;
mod homework;
mod homework_class;
mod homework_lights;
mod parse;

pub use parse::MAX_TIME_S;
use parse::{parse_key_value, parse_pixel, parse_size, parse_time, parse_view};

use crate::export;
use crate::lessons;
use crate::render::{FrameRequest, GpuContext, RenderError, Renderer};
use crate::scene::{Scene, SceneError, load_scene};
use crate::views::{self, View};
use clap::{Args, Parser, Subcommand};
use std::path::{Path, PathBuf};

#[derive(Parser, Debug)]
#[command(
    name = "shadowlab",
    version,
    about = "Learn real-time shadows: shadow maps, bias, PCF, PCSS, VSM. With no command, opens the app.",
    args_conflicts_with_subcommands = true
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
    #[command(flatten)]
    pub open: OpenArgs,
}

/// What the app opens on (no command given).
#[derive(Args, Debug, Default)]
pub struct OpenArgs {
    /// Open this in the app: a scene (.toml), a lesson (its id or number, or a lesson .toml) or a
    /// model (.obj).
    #[arg(value_name = "FILE")]
    pub file: Option<String>,
    /// Open the app on this lesson (id or number, see `shadowlab lessons`).
    #[arg(long)]
    pub lesson: Option<String>,
    /// The lesson's step, from 1.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
    pub step: Option<u32>,
    /// The app's language: en or zh.
    #[arg(long, value_parser = export_cmd::parse_lang)]
    pub lang: Option<crate::i18n::Lang>,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Render a scene (or one of its debug views) to a PNG.
    Render(RenderArgs),
    /// Print, as JSON, everything about the surface under one pixel.
    Probe(ProbeArgs),
    /// Time every technique on this machine's adapter.
    Bench(BenchArgs),
    /// List the lessons and their steps.
    Lessons,
    /// Export lessons as slides (PNG) with an index.html that shows them in order.
    Export(ExportArgs),
    /// Run a student's GAMES202 homework shader (phongFragment.glsl) beside shadowlab's own
    /// technique and the ground truth; write the pictures and what the checks found.
    Homework(homework::HomeworkArgs),
}

#[derive(Args, Debug, Clone)]
pub struct FrameArgs {
    /// Scene file (TOML).
    #[arg(long, required_unless_present = "lesson", conflicts_with = "lesson")]
    pub scene: Option<PathBuf>,
    /// A lesson's step instead of a scene: the lesson's id (see `shadowlab lessons`) or number.
    #[arg(long)]
    pub lesson: Option<String>,
    /// The lesson's step, from 1.
    #[arg(long, requires = "lesson", default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..))]
    pub step: u32,
    /// Override a scene value: a [shadow] key (`technique=pcss`) or `camera.KEY`, `light.N.KEY`, `object.N.KEY`.
    #[arg(long = "set", value_name = "KEY=VALUE", value_parser = parse_key_value)]
    pub set: Vec<(String, String)>,
    /// Scene time, seconds (lights orbit, objects spin); a lesson step sets its own.
    #[arg(long, value_parser = parse_time)]
    pub time: Option<f32>,
    /// Image size, pixels.
    #[arg(long, default_value = "960x540", value_parser = parse_size)]
    pub size: (u32, u32),
}

#[derive(Args, Debug)]
pub struct RenderArgs {
    #[command(flatten)]
    pub frame: FrameArgs,
    /// What to show: final, visibility, shadow-map, blocker-radius, penumbra, blockers,
    /// blocker-depth, moments, texel-density, cascade-index, reference, error (default: final, or
    /// the lesson step's view).
    #[arg(long, value_parser = parse_view)]
    pub view: Option<View>,
    /// The light the debug views describe (default: 0, or the lesson step's light).
    #[arg(long)]
    pub light: Option<usize>,
    /// Output PNG file.
    #[arg(long)]
    pub out: PathBuf,
}

#[derive(Args, Debug)]
pub struct ProbeArgs {
    #[command(flatten)]
    pub frame: FrameArgs,
    /// Pixel to probe, x,y from the top-left corner (default with --lesson: the step's own probe,
    /// a pixel of its 960x540 frame: the numbers the lesson text quotes).
    #[arg(long, value_parser = parse_pixel)]
    pub pixel: Option<(u32, u32)>,
    /// Skip the ground truth (faster).
    #[arg(long)]
    pub no_reference: bool,
}

#[derive(Args, Debug)]
pub struct BenchArgs {
    /// Scene file (default: the GAMES202 homework workload, assets/scenes/homework.toml).
    #[arg(long)]
    pub scene: Option<PathBuf>,
    /// Override a scene value, as for `render`.
    #[arg(long = "set", value_name = "KEY=VALUE", value_parser = parse_key_value)]
    pub set: Vec<(String, String)>,
    /// Scene time of the first frame, seconds.
    #[arg(long, value_parser = parse_time)]
    pub time: Option<f32>,
    /// Keep the scene time fixed (by default each frame advances it by 1/30 s).
    #[arg(long)]
    pub still: bool,
    /// Only these rows: a label ("pcss 50+50") or a technique (none, hard, pcf, pcss, vsm, vssm); comma-separated.
    #[arg(long, value_delimiter = ',')]
    pub only: Vec<String>,
    #[arg(long, default_value = "1280x720", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Timed frames per row (after two warm-up frames; with --diagrams, per diagram and language
    /// after one).
    #[arg(long, default_value_t = 15, value_parser = clap::value_parser!(u32).range(1..=10_000))]
    pub frames: u32,
    /// Print JSON instead of a table (every frame's times; with --diagrams, the median and the
    /// minimum of each row).
    #[arg(long)]
    pub json: bool,
    /// Drive the app instead (offscreen, 1600x900): drag the light-width slider, then the light
    /// on the shadow map, in the PCSS lesson with a probe pinned; report UI frames per second,
    /// view refreshes per second and the time from release to the full-quality frame. Needs a
    /// build with `--features bench-app`.
    #[arg(long, conflicts_with_all = ["scene", "set", "time", "still", "only", "frames"])]
    pub app: bool,
    /// Time the diagrams instead (CPU), in English and Chinese at --size: --frames draws with
    /// the values moving every frame, as while a value they show is dragged, and --frames of the
    /// same picture.
    #[arg(long, conflicts_with_all = ["app", "scene", "set", "time", "still", "only"])]
    pub diagrams: bool,
    /// With --app: run the session in a real window (needs a display; `xvfb-run -a` where there
    /// is none), painted as the app paints here.
    #[arg(long, requires = "app")]
    pub window: bool,
    /// With --app: seconds of dragging per phase (longer where no new image has reached the views
    /// by then, until one has).
    #[arg(long, default_value_t = 5.0, requires = "app")]
    pub seconds: f32,
    /// With --app --window: play the PCSS and multi-light lessons this many seconds instead, a
    /// probe pinned, overlays on, the view switched every few seconds; report images rendered,
    /// scene time played and memory from a settled baseline to the end (the verdict: its trend
    /// over the second half).
    #[arg(long, value_name = "SECONDS", requires = "app")]
    pub soak: Option<f32>,
    /// With --soak: play this lesson step instead of the PCSS and multi-light ones (LESSON:STEP,
    /// a lesson by id or number, its step from 1; repeat it for several, played in turn), e.g.
    /// `--soak-lesson more-maps:1 --soak-lesson more-maps:5` for a lamp's cube and a sun's cascades.
    #[arg(long, value_name = "LESSON:STEP", requires = "soak")]
    pub soak_lesson: Vec<String>,
}

/// The scene `bench` measures when none is given.
pub const DEFAULT_BENCH_SCENE: &str = "assets/scenes/homework.toml";

#[derive(Args, Debug)]
pub struct ExportArgs {
    /// Lesson id (see `shadowlab lessons`) or number, or `all`.
    #[arg(long, default_value = "all")]
    pub lesson: String,
    /// Language of the slides: en or zh.
    #[arg(long, default_value = "en", value_parser = export_cmd::parse_lang)]
    pub lang: crate::i18n::Lang,
    /// Slide size, pixels.
    #[arg(long, default_value = "1920x1080", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Output folder (created if missing).
    #[arg(long)]
    pub out: PathBuf,
    /// Folder of lesson files (default: the lessons shipped with shadowlab).
    #[arg(long, hide = true)]
    pub lessons_dir: Option<PathBuf>,
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
        match e {
            export::ExportError::Render(e) => e.into(),
            // A folder that cannot be made is the user's input, as a bad path is.
            export::ExportError::Folder { .. } => Self::input(e.to_string()),
            _ => Self { code: 1, message: e.to_string() },
        }
    }
}

/// What a frame's arguments resolve to: the scene, a label for messages, and the defaults a
/// lesson step gives.
struct Resolved {
    scene: Scene,
    label: String,
    time_s: f32,
    view: View,
    light: usize,
    /// The lesson step's probe pixel (in `lessons::PROBE_FRAME`).
    probe: Option<(u32, u32)>,
    /// The homework the lesson step checks (its final view is the student's picture).
    homework: Option<lessons::StepHomework>,
}

/// The checks every command makes before touching the GPU.
fn load(frame: &FrameArgs) -> Result<Resolved, CliError> {
    if let Some(id) = &frame.lesson {
        let lessons =
            lessons::load_all(&lessons::default_dir()).map_err(|e| CliError::input(e.to_string()))?;
        let lesson = lessons::find(&lessons, id).map_err(|e| CliError::input(e.to_string()))?;
        let step = lesson.steps.get(frame.step as usize - 1).ok_or_else(|| {
            CliError::input(format!(
                "--step {}: lesson `{}` has {} steps",
                frame.step,
                lesson.id,
                lesson.steps.len()
            ))
        })?;
        let mut overrides = step.overrides.clone();
        overrides.extend(frame.set.iter().map(|(key, value)| crate::scene::Override::parse(key, value)));
        return Ok(Resolved {
            scene: step.source.build(&overrides)?,
            label: format!("lesson {} step {}", lesson.id, frame.step),
            time_s: frame.time.unwrap_or(step.time_s),
            view: step.view,
            light: step.light,
            probe: step.probe.map(|[x, y]| (x, y)),
            homework: step.homework.clone(),
        });
    }
    let path = frame.scene.as_deref().ok_or_else(|| CliError::input("give --scene FILE or --lesson ID"))?;
    Ok(Resolved {
        scene: load_scene(path, &frame.set)?,
        label: path.display().to_string(),
        time_s: frame.time.unwrap_or(0.0),
        view: View::Final,
        light: 0,
        probe: None,
        homework: None,
    })
}

pub fn gpu() -> Result<(GpuContext, Renderer), CliError> {
    let ctx = GpuContext::new_headless()?;
    let renderer = Renderer::new(&ctx.device, &ctx.queue)?;
    Ok((ctx, renderer))
}

/// A progress bar's rate as a whole number per second.
pub(crate) fn per_second(state: &indicatif::ProgressState, w: &mut dyn std::fmt::Write) {
    let _ = write!(w, "{:.0}/s", state.per_sec());
}

/// A progress bar's rate with one decimal (slides come a few a second).
pub(crate) fn per_second_decimal(state: &indicatif::ProgressState, w: &mut dyn std::fmt::Write) {
    let _ = write!(w, "{:.1}/s", state.per_sec());
}

/// On a terminal, a progress bar (samples, rate, time left) while a ground truth accumulates;
/// nothing where stderr is not a terminal.
fn show_ground_truth_progress(renderer: &mut Renderer) {
    use std::io::IsTerminal;
    if !std::io::stderr().is_terminal() {
        return;
    }
    let mut bar: Option<indicatif::ProgressBar> = None;
    renderer.set_reference_ticker(Some(Box::new(move |done, total| {
        // One bar per ground truth (a probe takes one per light).
        if bar.as_ref().is_some_and(indicatif::ProgressBar::is_finished) {
            bar = None;
        }
        let bar = bar.get_or_insert_with(|| {
            let bar = indicatif::ProgressBar::new(u64::from(total));
            let template = "ground truth {bar:30.cyan/blue} {pos}/{len} hard shadows · {rate} · {eta} left";
            if let Ok(style) = indicatif::ProgressStyle::with_template(template) {
                bar.set_style(style.progress_chars("█▌ ").with_key("rate", per_second));
            }
            bar
        });
        bar.set_position(u64::from(done));
        if done >= total {
            bar.finish_and_clear();
        }
    })));
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
        Command::Lessons => list_lessons(),
        Command::Export(args) => export_cmd::run(args),
        Command::Homework(args) => match &args.class {
            Some(class) => homework_class::run(class, &args),
            None => homework::run(args),
        },
    }
}

fn list_lessons() -> Result<(), CliError> {
    let lessons = lessons::load_all(&lessons::default_dir()).map_err(|e| CliError::input(e.to_string()))?;
    for (i, lesson) in lessons.iter().enumerate() {
        println!("{}. {}  ({})  {}", i + 1, lesson.title.en, lesson.id, lesson.title.zh);
        for (j, step) in lesson.steps.iter().enumerate() {
            println!("   {}. {}  |  {}", j + 1, step.title.en, step.title.zh);
        }
    }
    Ok(())
}

fn render(args: RenderArgs) -> Result<(), CliError> {
    check_out_path(&args.out)?;
    let resolved = load(&args.frame)?;
    let scene = resolved.scene;
    let view = args.view.unwrap_or(resolved.view);
    let light = args.light.unwrap_or(resolved.light);
    if light >= scene.lights.len().max(1) {
        return Err(CliError::input(format!(
            "--light {light}: {} has {} light(s)",
            resolved.label,
            scene.lights.len()
        )));
    }
    if scene.lights.is_empty() && view != View::Final {
        return Err(CliError::input(format!(
            "{}: the scene has no lights, so no `{}` view",
            resolved.label,
            view.name()
        )));
    }
    let (_ctx, mut renderer) = gpu()?;
    show_ground_truth_progress(&mut renderer);
    let (mut image, summary) = views::render_view(
        &mut renderer,
        &scene,
        view,
        light,
        resolved.time_s,
        args.frame.size,
        crate::i18n::Lang::En,
    )?;
    // A lesson step that checks a homework shows the student's picture, as the app does.
    if let Some(hw) = resolved.homework.as_ref().filter(|_| view == View::Final) {
        let (fragment, shadow) = (&hw.fragment, hw.shadow_fragment.as_deref());
        image = crate::homework::homework_picture(
            &renderer,
            fragment,
            shadow,
            &scene,
            args.frame.size,
            resolved.time_s,
        )
        .map_err(CliError::input)?;
    }
    export::write_png(&args.out, &image)?;
    println!(
        "wrote {} ({}x{}, view {}, light {light})",
        args.out.display(),
        image.width(),
        image.height(),
        view.name()
    );
    if let Some(summary) = summary {
        println!("{summary}");
    }
    warn_of_empty_picture(&resolved.label, &scene, resolved.time_s, args.frame.size);
    Ok(())
}

/// A scene that loaded but shows nothing says so on stderr (once the command has done its work,
/// so a refusal stays one line).
fn warn_of_empty_picture(label: &str, scene: &Scene, time_s: f32, (w, h): (u32, u32)) {
    for warning in scene.warnings(time_s, w as f32 / h as f32) {
        eprintln!("shadowlab: warning: {label}: {warning}");
    }
}

fn probe(args: ProbeArgs) -> Result<(), CliError> {
    let resolved = load(&args.frame)?;
    let scene = resolved.scene;
    let (w, h) = args.frame.size;
    let pixel = match (args.pixel, resolved.probe) {
        (Some(pixel), _) => pixel,
        (None, Some(pixel)) => pixel,
        (None, None) => {
            return Err(CliError::input(format!(
                "--pixel X,Y is needed: {} names no probe pixel",
                resolved.label
            )));
        }
    };
    if pixel.0 >= w || pixel.1 >= h {
        return Err(CliError::input(format!("--pixel {},{} is outside the {w}x{h} image", pixel.0, pixel.1)));
    }
    let (_ctx, mut renderer) = gpu()?;
    show_ground_truth_progress(&mut renderer);
    let request = FrameRequest { time_s: resolved.time_s, size: args.frame.size, ..Default::default() };
    let report = crate::probe::probe(&mut renderer, &scene, &request, pixel, !args.no_reference)?;
    let json =
        serde_json::to_string_pretty(&report).map_err(|e| CliError { code: 1, message: e.to_string() })?;
    println!("{json}");
    warn_of_empty_picture(&resolved.label, &scene, resolved.time_s, args.frame.size);
    Ok(())
}

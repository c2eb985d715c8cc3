//! `shadowlab homework SHADER.glsl --out DIR`: a student's GAMES202 shader run as the framework
//! runs it, beside shadowlab's own technique and the ground truth; the pictures and the findings
//! written to DIR (`report.json`; with `--json` on stdout too). A shader that does not compile
//! exits 2 with `FILE:LINE: message` on the student's own line (and a report saying so).
//! `--class DIR` checks a whole class instead (`homework_class`).

use super::{CliError, parse_key_value, parse_size, parse_time};
use crate::homework::{
    HomeworkProgram, HomeworkRenderer, HomeworkReport, HomeworkRequest, HomeworkSource, MapKind,
    ShaderSource, SubmissionReport, run_check,
};
use crate::i18n::Lang;
use crate::scene::load_scene;
use clap::Args;
use std::path::{Path, PathBuf};

/// The scene a homework is checked on, unless `--scene` says otherwise.
pub const DEFAULT_HOMEWORK_SCENE: &str = "assets/scenes/homework_check.toml";

#[derive(Args, Debug)]
pub struct HomeworkArgs {
    /// The student's homework: their phongFragment.glsl (the framework's WebGL1 GLSL), their
    /// homework folder, or a .zip of it (the framework's files are found wherever they lie).
    #[arg(value_name = "PATH", required_unless_present = "class")]
    pub shader: Option<PathBuf>,
    /// A class instead: every submission in DIR (each sub-folder and each .zip) checked by this
    /// program as a process of its own; each one's pictures and report.json in OUT/NAME, and the
    /// class report in OUT: index.html, index_zh.html and grades.csv.
    #[arg(
        long,
        value_name = "DIR",
        conflicts_with_all = ["shader", "shadow_shader", "vertex", "scene", "set", "time", "light", "json"]
    )]
    pub class: Option<PathBuf>,
    /// With --class: seconds one submission's check may take before it is stopped.
    #[arg(
        long,
        value_name = "SECONDS",
        default_value = "120",
        value_parser = super::parse::parse_timeout,
        requires = "class"
    )]
    pub timeout: std::time::Duration,
    /// With --class: how many checks run at once.
    #[arg(
        long,
        value_name = "N",
        default_value_t = 1,
        value_parser = clap::value_parser!(u32).range(1..=64),
        requires = "class"
    )]
    pub jobs: u32,
    /// With --class: check every submission again, even those checked already and unchanged.
    #[arg(long, requires = "class")]
    pub force: bool,
    /// The student's shadowFragment.glsl (its `pack`); default: the framework's.
    #[arg(long, value_name = "FILE")]
    pub shadow_shader: Option<PathBuf>,
    /// The student's phongVertex.glsl; default: the framework's.
    #[arg(long, value_name = "FILE")]
    pub vertex: Option<PathBuf>,
    /// The student's lights/DirectionalLight.js (their CalcLightMVP builds the light); default:
    /// the one in the submission's folder, else the framework's light.
    #[arg(long, value_name = "FILE")]
    pub light_script: Option<PathBuf>,
    /// The student's engine.js (where the light is); default: the submission's, else the
    /// framework's (0, 80, 80).
    #[arg(long, value_name = "FILE")]
    pub engine: Option<PathBuf>,
    /// Scene file (default: assets/scenes/homework_check.toml, the framework's light and map).
    #[arg(long)]
    pub scene: Option<PathBuf>,
    /// Override a scene value, as for `render` (`light.0.extent=150`, `light.0.width=8`).
    #[arg(long = "set", value_name = "KEY=VALUE", value_parser = parse_key_value)]
    pub set: Vec<(String, String)>,
    /// Picture size, pixels; checks at other sizes may count pixel-sized things differently.
    #[arg(long, default_value = crate::homework::CHECK_SIZE_ARG, value_parser = parse_size)]
    pub size: (u32, u32),
    /// Scene time, seconds.
    #[arg(long, value_parser = parse_time, default_value = "0")]
    pub time: f32,
    /// The light whose map the shader reads.
    #[arg(long, default_value_t = 0)]
    pub light: usize,
    /// The folder the pictures and report.json go to (made if missing; its parent must exist).
    #[arg(long)]
    pub out: PathBuf,
    /// Print the report as JSON on stdout too.
    #[arg(long)]
    pub json: bool,
    /// The language of the findings' explanations: en or zh.
    #[arg(long, value_parser = super::export_cmd::parse_lang, default_value = "en")]
    pub lang: Lang,
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> Result<(), CliError> {
    let path = dir.join(name);
    crate::files::write_atomic(&path, bytes).map_err(|e| CliError::input(format!("{}: {e}", path.display())))
}

fn png(image: &image::RgbaImage) -> Result<Vec<u8>, CliError> {
    let mut bytes = Vec::new();
    image
        .write_to(&mut std::io::Cursor::new(&mut bytes), image::ImageFormat::Png)
        .map_err(|e| CliError { code: 1, message: format!("cannot encode a PNG: {e}") })?;
    Ok(bytes)
}

fn report_json(report: &HomeworkReport) -> Result<String, CliError> {
    serde_json::to_string_pretty(report).map_err(|e| CliError { code: 1, message: e.to_string() })
}

pub fn run(args: HomeworkArgs) -> Result<(), CliError> {
    let Some(shader_path) = args.shader.clone() else {
        return Err(CliError::input("give the homework's PATH, or --class DIR"));
    };
    if args.out.exists() && !args.out.is_dir() {
        return Err(CliError::input(format!("{}: is a file, not a folder", args.out.display())));
    }
    let parent = args.out.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    if !parent.is_dir() {
        return Err(CliError::input(format!(
            "{}: folder {} does not exist",
            args.out.display(),
            parent.display()
        )));
    }
    let scene_path =
        args.scene.clone().unwrap_or_else(|| crate::shipped::shipped_path(DEFAULT_HOMEWORK_SCENE));
    let scene = load_scene(&scene_path, &args.set)?;
    if args.light >= scene.lights.len() {
        return Err(CliError::input(format!(
            "--light {}: {} has {} light(s)",
            args.light,
            scene_path.display(),
            scene.lights.len()
        )));
    }
    let mut source = HomeworkSource::read(&shader_path).map_err(|e| CliError::input(e.to_string()))?;
    let read = |path: &Path| ShaderSource::read(path).map_err(|e| CliError::input(e.to_string()));
    if let Some(path) = &args.vertex {
        source.files.phong_vertex = read(path)?;
    }
    if let Some(path) = &args.shadow_shader {
        source.files.shadow_fragment = read(path)?;
    }
    if let Some(path) = &args.light_script {
        source.light_script = Some(read(path)?);
    }
    if let Some(path) = &args.engine {
        source.engine = Some(read(path)?);
    }
    let files = source.files.clone();
    let shader = files.phong_fragment.clone();
    let program = match HomeworkProgram::translate(files) {
        Ok(program) => program,
        Err(e) => {
            // The report says it too, for a grader reading the folder.
            let mut report = HomeworkReport::not_compiled(&shader.name, &e);
            report.submission = Some(SubmissionReport::of(&source));
            let text = report_json(&report)?;
            std::fs::create_dir_all(&args.out)
                .map_err(|err| CliError::input(format!("{}: {err}", args.out.display())))?;
            write(&args.out, "report.json", text.as_bytes())?;
            if args.json {
                println!("{text}");
            }
            return Err(CliError::input(e.to_string()));
        }
    };
    let (ctx, mut renderer) = super::gpu()?;
    let homework = HomeworkRenderer::new(&ctx.device, &ctx.queue, &program)
        .map_err(|e| CliError::input(format!("{}: {e}", shader.name)))?;
    let request =
        HomeworkRequest { time_s: args.time, size: args.size, light: args.light, map: MapKind::Framework };
    // The desktop's engine runs the page at once: it is never Pending here.
    let std::task::Poll::Ready(student) =
        crate::homework::student_light::student_light(&source, &scene, args.light, args.time)
    else {
        return Err(CliError { code: 1, message: "the student's page did not finish running".into() });
    };
    let student = student.ok_or_else(|| CliError::input(format!("--light {}: no such light", args.light)))?;
    if let Some(refused) = &student.refused {
        return Err(CliError::input(refused.clone()));
    }
    if let Some(error) = &student.report.error {
        eprintln!("shadowlab: warning: {error}; checked with the framework's light instead");
    }
    let mut outcome =
        run_check(&homework, &mut renderer, &shader, &student.scene, &student.light, &request, args.lang)
            .map_err(|e| CliError { code: 1, message: format!("{}: {e}", shader.name) })?;
    outcome.report.set_light(Some(student.report));
    outcome.report.submission = Some(SubmissionReport::of(&source));
    let light_pictures = super::homework_lights::check_each_light(
        &super::homework_lights::Check {
            homework: &homework,
            shader: &shader,
            source: &source,
            scene: &scene,
        },
        &mut renderer,
        &request,
        (args.light, args.time, args.lang),
        &mut outcome.report,
    )?;
    // Everything encoded before the first file is written: a failure leaves no partial folder.
    let text = report_json(&outcome.report)?;
    let mut pictures = vec![
        ("student.png".to_string(), png(&outcome.student_picture())?),
        ("student_lossless_map.png".into(), png(&outcome.student_picture_lossless_map())?),
        ("reference.png".into(), png(&outcome.shadowlab_picture)?),
        ("visibility.png".into(), png(&outcome.visibility_picture(false))?),
        ("ground_truth.png".into(), png(&outcome.visibility_picture(true))?),
        ("difference.png".into(), png(&outcome.difference_picture())?),
    ];
    if let Some(map) = outcome.map_picture() {
        pictures.push(("student_map.png".into(), png(&map)?));
    }
    for (name, picture) in light_pictures {
        pictures.push((name, png(&picture)?));
    }
    std::fs::create_dir_all(&args.out)
        .map_err(|e| CliError::input(format!("{}: {e}", args.out.display())))?;
    for (name, bytes) in &pictures {
        write(&args.out, name, bytes)?;
    }
    write(&args.out, "report.json", text.as_bytes())?;
    if args.json {
        println!("{text}");
    } else {
        print_summary(&outcome.report, &args.out);
    }
    Ok(())
}

fn print_summary(report: &HomeworkReport, out: &Path) {
    println!("{}: compiled; calls {}", report.shader, report.calls.join(", "));
    if let Some(f) = &report.figures {
        let num = |v: Option<f64>| v.map_or("n/a".to_string(), |v| format!("{v:.3}"));
        println!(
            "  compared with shadowlab's {}: mean |difference| {}, to the ground truth {}",
            report.compared_with.unwrap_or("-"),
            num(f.mean_abs_difference),
            num(f.mean_abs_difference_to_ground_truth)
        );
        println!(
            "  NaN share {:.4}, lit mean {}, umbra mean {}, penumbra pixels {} (ground truth {})",
            f.nan_fraction,
            num(f.lit_area_mean),
            num(f.umbra_mean),
            f.penumbra_pixels,
            f.penumbra_pixels_ground_truth
        );
        if let (Some((x, y)), Some(theirs), Some(truth)) =
            (f.penumbra_pixel, f.penumbra_width_world, f.penumbra_width_world_ground_truth)
        {
            println!("  penumbra width at pixel {x}, {y}: {theirs:.2} world units (ground truth {truth:.2})");
        }
    }
    if report.findings.is_empty() {
        println!("  no findings");
    }
    for finding in &report.findings {
        println!("  {} ({} step {}): {}", finding.id, finding.lesson, finding.step, finding.explanation);
    }
    println!("  pictures and report.json in {}", out.display());
}

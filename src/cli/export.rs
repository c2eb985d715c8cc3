//! `shadowlab export`: every step of the chosen lessons as PNG slides (plus the camera view,
//! shadow map and diagram of each on their own) and one `index.html` showing them in order.
//!
//! Everything is checked before the first file is written: the lessons (all of them), the
//! language's font, the output folder and the GPU. Rendering is deterministic: each step's own
//! time and the scene's noise seed, no wall clock.

use super::{CliError, ExportArgs, gpu};
use crate::diagrams::{self, TextRenderer};
use crate::export::html::{LessonEntry, SlideEntry, index_html};
use crate::export::slide::{MIN_SIZE, SlideLayout, SlideText, compose};
use crate::export::step::render_step;
use crate::export::write_atomic;
use crate::i18n::Lang;
use crate::lessons::{self, Lesson};
use crate::scene::Scene;
use image::imageops::{FilterType, resize};
use std::io::{IsTerminal, Write};
use std::path::Path;

pub fn parse_lang(s: &str) -> Result<Lang, String> {
    Lang::from_code(s).ok_or_else(|| format!("`{s}` is not a language shadowlab speaks (expected en or zh)"))
}

/// Lesson ids become folder names: keep them to letters, digits, `-` and `_`.
fn check_id(lesson: &Lesson) -> Result<(), CliError> {
    let ok =
        !lesson.id.is_empty() && lesson.id.chars().all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_');
    if ok {
        Ok(())
    } else {
        Err(CliError::input(format!(
            "{}: lesson id `{}` must be letters, digits, `-` or `_` (it names the output folder)",
            lesson.path.display(),
            lesson.id
        )))
    }
}

/// Export progress: a bar with the rate and the time left on a terminal, one line per step
/// otherwise (logs, CI).
enum Progress {
    Bar(indicatif::ProgressBar),
    Lines,
}

impl Progress {
    fn new(total: usize) -> Self {
        if !std::io::stderr().is_terminal() {
            return Progress::Lines;
        }
        let bar = indicatif::ProgressBar::new(total as u64);
        let style = indicatif::ProgressStyle::with_template(
            "{bar:30.cyan/blue} {pos}/{len} slides · {rate} · {eta} left · {msg}",
        );
        if let Ok(style) = style {
            bar.set_style(style.progress_chars("█▌ ").with_key("rate", super::per_second_decimal));
        }
        Progress::Bar(bar)
    }

    /// Step `done` (from 1) of `total` is starting.
    fn start(&mut self, done: usize, total: usize, line: &str) {
        match self {
            Progress::Bar(bar) => {
                bar.set_position(done.saturating_sub(1) as u64);
                bar.set_message(line.to_string());
            }
            Progress::Lines => {
                let mut err = std::io::stderr().lock();
                let _ = writeln!(err, "[{done}/{total}] {line}");
                let _ = err.flush();
            }
        }
    }

    /// A warning on its own line (the bar is drawn again below it).
    fn warn(&mut self, message: &str) {
        let line = format!("shadowlab: warning: {message}");
        match self {
            Progress::Bar(bar) => bar.println(line),
            Progress::Lines => eprintln!("{line}"),
        }
    }

    fn finish(&self) {
        if let Progress::Bar(bar) = self {
            bar.finish_and_clear();
        }
    }
}

fn failed(what: &str, e: impl std::fmt::Display) -> CliError {
    CliError { code: 1, message: format!("{what}: {e}") }
}

pub fn run(args: ExportArgs) -> Result<(), CliError> {
    let (w, h) = args.size;
    if w < MIN_SIZE.0 || h < MIN_SIZE.1 || w > diagrams::MAX_SIDE_PX || h > diagrams::MAX_SIDE_PX {
        return Err(CliError::input(format!(
            "--size {w}x{h}: slides need {}x{} to {max}x{max} pixels",
            MIN_SIZE.0,
            MIN_SIZE.1,
            max = diagrams::MAX_SIDE_PX
        )));
    }
    let dir = args.lessons_dir.clone().unwrap_or_else(lessons::default_dir);
    let all = lessons::load_all(&dir).map_err(|e| CliError::input(e.to_string()))?;
    if all.is_empty() {
        return Err(CliError::input(format!("{}: no lessons (*.toml) in this folder", dir.display())));
    }
    let selected: Vec<&Lesson> = if args.lesson == "all" {
        all.iter().collect()
    } else {
        vec![lessons::find(&all, &args.lesson).map_err(|e| CliError::input(e.to_string()))?]
    };
    for lesson in &selected {
        check_id(lesson)?;
    }
    // A font check, not a translation.
    if args.lang == Lang::Zh && !TextRenderer::shared().covers('中') {
        return Err(CliError::input(
            "Chinese slides need a CJK font and none is installed: \
             install fonts-noto-cjk (apt-get install fonts-noto-cjk)",
        ));
    }
    if args.out.exists() && !args.out.is_dir() {
        return Err(CliError::input(format!("{}: is a file, not a folder", args.out.display())));
    }
    // Every step's scene, loaded before anything is rendered or written.
    let mut scenes: Vec<Vec<Scene>> = Vec::with_capacity(selected.len());
    for lesson in &selected {
        let loaded = lesson
            .steps
            .iter()
            .enumerate()
            .map(|(i, step)| {
                step.scene()
                    .map_err(|e| CliError::input(format!("{}: step {}: {e}", lesson.path.display(), i + 1)))
            })
            .collect::<Result<Vec<_>, _>>()?;
        scenes.push(loaded);
    }

    let (_ctx, mut renderer) = gpu()?;
    let make_dir = |path: &Path| {
        std::fs::create_dir_all(path)
            .map_err(|e| CliError::input(format!("{}: cannot create the folder: {e}", path.display())))
    };
    make_dir(&args.out)?;

    let layout = SlideLayout::new(w, h);
    let camera_size = (layout.camera.w, layout.camera.h);
    let total: usize = selected.iter().map(|l| l.steps.len()).sum();
    let mut progress = Progress::new(total);
    let mut done = 0;
    // On failure the progress line is finished before the error is printed.
    let mut export_all = || -> Result<Vec<LessonEntry>, CliError> {
        let mut entries = Vec::with_capacity(selected.len());
        for (lesson, scenes) in selected.iter().zip(&scenes) {
            let lesson_dir = args.out.join(&lesson.id);
            make_dir(&lesson_dir)?;
            let mut slides = Vec::with_capacity(lesson.steps.len());
            for (i, (step, scene)) in lesson.steps.iter().zip(scenes).enumerate() {
                done += 1;
                progress.start(done, total, &format!("{} step {}/{}", lesson.id, i + 1, lesson.steps.len()));
                let pictures = render_step(&mut renderer, lesson, i, scene, camera_size, args.lang)?;
                let map_panel = pictures.shadow_map.as_ref().map(|(img, _)| {
                    resize(img, layout.shadow_map.w, layout.shadow_map.h, FilterType::Triangle)
                });
                let d = layout.diagram;
                let diagram = diagrams::draw(pictures.diagram, &pictures.inputs, args.lang, d.w, d.h)
                    .map_err(|e| failed("diagram", e))?;
                // The text's live numbers, from the probe and the camera panel this slide shows.
                let body = step.text_filled(args.lang, pictures.live());
                let try_this = step.try_this_filled(args.lang, pictures.live());
                let text = SlideText {
                    lang: args.lang,
                    lesson_title: lesson.title.get(args.lang),
                    step_number: i + 1,
                    step_count: lesson.steps.len(),
                    step_title: step.title.get(args.lang),
                    body: &body,
                    try_this: try_this.iter().map(String::as_str).collect(),
                };
                let slide = compose(&layout, &text, &pictures, map_panel.as_ref(), &diagram)
                    .ok_or_else(|| failed("slide", format!("cannot allocate a {w}x{h} image")))?;

                let name = |what: &str| format!("step-{:02}-{what}.png", i + 1);
                let write_pixmap = |what: &str, pixmap: &tiny_skia::Pixmap| {
                    let path = lesson_dir.join(name(what));
                    let bytes =
                        diagrams::encode_png(pixmap).map_err(|e| failed(&path.display().to_string(), e))?;
                    write_atomic(&path, &bytes).map_err(CliError::from)
                };
                crate::export::write_png(&lesson_dir.join(name("camera")), &pictures.camera)?;
                match &map_panel {
                    Some(map) => crate::export::write_png(&lesson_dir.join(name("shadow-map")), map)?,
                    None => {
                        // A scene without lights: the panel as the slide shows it.
                        let blank = image::RgbaImage::from_pixel(
                            layout.shadow_map.w,
                            layout.shadow_map.h,
                            image::Rgba([238, 240, 236, 255]),
                        );
                        crate::export::write_png(&lesson_dir.join(name("shadow-map")), &blank)?;
                    }
                }
                write_pixmap("diagram", &diagram)?;
                write_pixmap("slide", &slide.pixmap)?;
                for label in &slide.shortened {
                    progress.warn(&format!(
                        "{}: step {}: \"{label}\" is too long for its place on a {w}x{h} slide and \
                         was shortened",
                        lesson.path.display(),
                        i + 1,
                    ));
                }
                if slide.text_cut {
                    progress.warn(&format!(
                        "{}: step {}: the {} text is too long for a {w}x{h} slide and was cut \
                         (index.html has all of it)",
                        lesson.path.display(),
                        i + 1,
                        args.lang.code()
                    ));
                }

                let rel = |what: &str| format!("{}/{}", lesson.id, name(what));
                slides.push(SlideEntry {
                    title: step.title.get(args.lang).to_string(),
                    body: body.clone(),
                    try_this: try_this.clone(),
                    slide: rel("slide"),
                    camera: rel("camera"),
                    shadow_map: rel("shadow-map"),
                    diagram: rel("diagram"),
                });
            }
            entries.push(LessonEntry {
                id: lesson.id.clone(),
                title: lesson.title.get(args.lang).to_string(),
                summary: lesson.summary.get(args.lang).to_string(),
                slides,
            });
        }
        Ok(entries)
    };
    let entries = export_all();
    progress.finish();
    let entries = entries?;
    let index = args.out.join("index.html");
    write_atomic(&index, index_html(args.lang, &entries).as_bytes())?;
    println!(
        "exported {total} slide{} from {} lesson{} ({}, {w}x{h}) to {}; open {}",
        if total == 1 { "" } else { "s" },
        entries.len(),
        if entries.len() == 1 { "" } else { "s" },
        args.lang.code(),
        args.out.display(),
        index.display()
    );
    Ok(())
}

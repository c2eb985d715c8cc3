//! `shadowlab export`: the arguments checked, then `export::lessons` writes every step of the
//! chosen lessons as PNG slides and one `index.html`, with a progress bar here.
//!
//! Everything is checked before the first file is written: the lessons (all of them), the
//! language's font, the output folder and the GPU. Rendering is deterministic: each step's own
//! time and the scene's noise seed, no wall clock.

use super::{CliError, ExportArgs, gpu};
use crate::diagrams::{self, TextRenderer};
use crate::export::lessons::{ExportEvent, export_lessons};
use crate::export::slide::MIN_SIZE;
use crate::i18n::Lang;
use crate::lessons::{self, Lesson};
use crate::scene::Scene;
use std::io::{IsTerminal, Write};

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

/// Every character of the lessons' Chinese text has a glyph. The CJK font built in holds
/// shadowlab's own text only: a lesson of one's own may need the system's (a font check, not a
/// translation).
fn check_font_covers(lessons: &[&Lesson]) -> Result<(), CliError> {
    let mut chars = std::collections::BTreeSet::new();
    for lesson in lessons {
        let steps = lesson
            .steps
            .iter()
            .flat_map(|s| [&s.title.zh, &s.text.zh].into_iter().chain(s.try_this.iter().map(|t| &t.text.zh)));
        for text in [&lesson.title.zh, &lesson.summary.zh].into_iter().chain(steps) {
            chars.extend(text.chars().filter(|c| !c.is_whitespace() && !c.is_control()));
        }
    }
    let renderer = TextRenderer::shared();
    let missing: Vec<char> = chars.into_iter().filter(|c| !renderer.covers(*c)).collect();
    if missing.is_empty() {
        return Ok(());
    }
    let shown: String = missing.iter().take(12).collect();
    let more = if missing.len() > 12 { "..." } else { "" };
    Err(CliError::input(format!(
        "no font has {shown}{more} (the Chinese font built in holds only shadowlab's own text): \
         install fonts-noto-cjk (apt-get install fonts-noto-cjk)"
    )))
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
    if args.lang == Lang::Zh {
        check_font_covers(&selected)?;
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
    let total: usize = selected.iter().map(|l| l.steps.len()).sum();
    let mut progress = Progress::new(total);
    let exported =
        export_lessons(&mut renderer, &selected, &scenes, &args.out, args.lang, args.size, &mut |event| {
            match event {
                ExportEvent::Step { done, total, line } => progress.start(done, total, &line),
                ExportEvent::Warning(message) => progress.warn(&message),
            }
        });
    // On failure the progress line is finished before the error is printed.
    progress.finish();
    let (index, entries) = exported?;
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

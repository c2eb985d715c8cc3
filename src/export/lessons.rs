//! The export loop: every step of some lessons as a slide (plus its camera view, shadow map and
//! diagram on their own) in a folder per lesson, and `index.html` showing them in order. The
//! caller checks its inputs first and hears of each step and each warning as they come.

use super::html::{LessonEntry, SlideEntry, index_html};
use super::slide::{SlideLayout, SlideText, compose};
use super::step::render_step;
use super::{ExportError, write_atomic, write_png};
use crate::diagrams;
use crate::i18n::Lang;
use crate::lessons::Lesson;
use crate::render::Renderer;
use crate::scene::Scene;
use std::path::{Path, PathBuf};

/// What the loop reports as it goes.
pub enum ExportEvent {
    /// Step `done` (from 1) of `total` is starting: `line` names it.
    Step { done: usize, total: usize, line: String },
    /// Something the slides lost (a label shortened, text cut); the export goes on.
    Warning(String),
}

/// Render and write every step of `lessons` (`scenes[l][s]` is step s of lesson l, loaded) as
/// `size` slides in `lang` under `out`, then the index page; returns the index page's path and
/// the lessons as the index lists them.
pub fn export_lessons(
    renderer: &mut Renderer,
    lessons: &[&Lesson],
    scenes: &[Vec<Scene>],
    out: &Path,
    lang: Lang,
    size: (u32, u32),
    report: &mut dyn FnMut(ExportEvent),
) -> Result<(PathBuf, Vec<LessonEntry>), ExportError> {
    make_dir(out)?;
    let layout = SlideLayout::new(size.0, size.1);
    let total: usize = lessons.iter().map(|l| l.steps.len()).sum();
    let mut done = 0;
    let mut entries = Vec::with_capacity(lessons.len());
    for (lesson, scenes) in lessons.iter().zip(scenes) {
        let lesson_dir = out.join(&lesson.id);
        make_dir(&lesson_dir)?;
        let mut slides = Vec::with_capacity(lesson.steps.len());
        for (i, scene) in scenes.iter().enumerate() {
            done += 1;
            let line = format!("{} step {}/{}", lesson.id, i + 1, lesson.steps.len());
            report(ExportEvent::Step { done, total, line });
            slides.push(export_step(renderer, &layout, lesson, i, scene, &lesson_dir, lang, report)?);
        }
        entries.push(LessonEntry {
            id: lesson.id.clone(),
            title: lesson.title.get(lang).to_string(),
            summary: lesson.summary.get(lang).to_string(),
            slides,
        });
    }
    let index = out.join("index.html");
    write_atomic(&index, index_html(lang, &entries).as_bytes())?;
    Ok((index, entries))
}

fn make_dir(path: &Path) -> Result<(), ExportError> {
    std::fs::create_dir_all(path)
        .map_err(|e| ExportError::Folder { path: path.display().to_string(), reason: e.to_string() })
}

/// One step: its pictures rendered, the slide composed, five files written.
#[allow(clippy::too_many_arguments)]
fn export_step(
    renderer: &mut Renderer,
    layout: &SlideLayout,
    lesson: &Lesson,
    i: usize,
    scene: &Scene,
    lesson_dir: &Path,
    lang: Lang,
    report: &mut dyn FnMut(ExportEvent),
) -> Result<SlideEntry, ExportError> {
    let (w, h) = layout.size;
    let step = &lesson.steps[i];
    let pictures = render_step(renderer, lesson, i, scene, (layout.camera.w, layout.camera.h), lang)?;
    let map_panel = pictures
        .shadow_map
        .as_ref()
        .map(|(img, _)| super::slide::map_panel_image(img, layout.shadow_map.w, layout.shadow_map.h));
    let d = layout.diagram;
    let diagram = diagrams::draw(pictures.diagram, &pictures.inputs, lang, d.w, d.h)
        .map_err(|e| ExportError::Draw(format!("diagram: {e}")))?;
    // The text's live numbers, from the probe and the camera panel this slide shows.
    let body = step.text_filled(lang, pictures.live());
    let try_this = step.try_this_filled(lang, pictures.live());
    let text = SlideText {
        lang,
        lesson_title: lesson.title.get(lang),
        step_number: i + 1,
        step_count: lesson.steps.len(),
        step_title: step.title.get(lang),
        body: &body,
        try_this: try_this.iter().map(String::as_str).collect(),
    };
    let slide = compose(layout, &text, &pictures, map_panel.as_ref(), &diagram)
        .ok_or_else(|| ExportError::Draw(format!("slide: cannot allocate a {w}x{h} image")))?;

    let name = |what: &str| format!("step-{:02}-{what}.png", i + 1);
    let write_pixmap = |what: &str, pixmap: &tiny_skia::Pixmap| {
        let path = lesson_dir.join(name(what));
        let bytes = diagrams::encode_png(pixmap)
            .map_err(|e| ExportError::Encode { path: path.display().to_string(), reason: e.to_string() })?;
        write_atomic(&path, &bytes)
    };
    write_png(&lesson_dir.join(name("camera")), &pictures.camera)?;
    // A scene without lights: the panel as the slide shows it.
    let blank = || {
        image::RgbaImage::from_pixel(
            layout.shadow_map.w,
            layout.shadow_map.h,
            image::Rgba([238, 240, 236, 255]),
        )
    };
    write_png(&lesson_dir.join(name("shadow-map")), &map_panel.unwrap_or_else(blank))?;
    write_pixmap("diagram", &diagram)?;
    write_pixmap("slide", &slide.pixmap)?;
    let place = format!("{}: step {}", lesson.path.display(), i + 1);
    for label in &slide.shortened {
        report(ExportEvent::Warning(format!(
            "{place}: \"{label}\" is too long for its place on a {w}x{h} slide and was shortened"
        )));
    }
    if slide.text_cut {
        report(ExportEvent::Warning(format!(
            "{place}: the {} text is too long for a {w}x{h} slide and was cut (index.html has all of it)",
            lang.code()
        )));
    }
    let rel = |what: &str| format!("{}/{}", lesson.id, name(what));
    Ok(SlideEntry {
        title: step.title.get(lang).to_string(),
        body,
        try_this,
        slide: rel("slide"),
        camera: rel("camera"),
        shadow_map: rel("shadow-map"),
        diagram: rel("diagram"),
    })
}

//! The lesson panel: step navigation, the step's title, what to look at, what to try, and the
//! probe's numbers when the step names the probe.

use super::ShadowlabApp;
use crate::lessons::{Lang, Panel};
use egui::{RichText, Ui};

pub fn show(app: &mut ShadowlabApp, ui: &mut Ui) {
    let lang = app.lang;
    let tr = move |en: &'static str| crate::i18n::tr(lang, en);
    let Some((lesson, step, index)) = app.current_step() else { return };
    let count = lesson.steps.len();
    let lesson_title = lesson.title.get(lang).to_string();
    let title = step.title.get(lang).to_string();
    // Live numbers from the probe on screen (or "…" while it is worked out).
    let text = step.text_filled(lang, app.probe.as_ref());
    let tries = step.try_this_filled(lang, app.probe.as_ref());
    let lesson_probe = step.probe.map(|[x, y]| super::ProbeAt::LessonFrame(x, y));
    // Navigation first, so it stays in reach however long the text is.
    ui.horizontal(|ui| {
        if ui.button(tr("Previous")).on_hover_text(tr("Left arrow")).clicked() {
            app.step_lesson(-1);
        }
        ui.label(RichText::new(format!("{} {} / {count}", tr("step"), index + 1)).weak());
        if ui.button(tr("Next")).on_hover_text(tr("Right arrow")).clicked() {
            app.step_lesson(1);
        }
    });
    // Present mode (F5): larger text for a projector, and a way back.
    let (body, heading) = if app.present { (22.0, 30.0) } else { (15.0, 20.0) };
    if app.present {
        ui.label(RichText::new(tr("F5 or Esc: leave present mode")).weak());
    } else {
        ui.checkbox(&mut app.show_all_panels, tr("show every panel"));
    }
    ui.separator();
    ui.label(RichText::new(lesson_title).small());
    ui.label(RichText::new(title).size(heading).strong());
    ui.add_space(4.0);
    ui.label(RichText::new(text).size(body));
    // The numbers follow whatever probe is pinned; say so when it is not the lesson's own.
    if lesson_probe.is_some() && app.probe_at != lesson_probe {
        let (note, back) = match lang {
            Lang::En => ("The numbers above are read at your probe.", "Back to the lesson's probe"),
            Lang::Zh => ("上面的数字取自你放置的探针。", "回到本课的探针"),
        };
        ui.horizontal_wrapped(|ui| {
            ui.label(RichText::new(note).italics());
            if ui.button(back).clicked() {
                app.probe_at = lesson_probe;
                app.mark_dirty();
            }
        });
    }
    if !tries.is_empty() {
        ui.add_space(8.0);
        ui.strong(match lang {
            Lang::En => "Try this",
            Lang::Zh => "试一试",
        });
        for t in tries {
            ui.label(RichText::new(format!("• {t}")).size(body * 0.8));
        }
    }
    if app.panel_visible(Panel::Probe) && app.probe_report().is_some() {
        ui.add_space(8.0);
        ui.separator();
        super::inspector::probe_values(app, ui);
    }
}

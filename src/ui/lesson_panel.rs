//! The lesson panel: the step's title, what to look at, and what to try.

use super::ShadowlabApp;
use egui::{RichText, Ui};

pub fn show(app: &mut ShadowlabApp, ui: &mut Ui) {
    let lang = app.lang;
    let Some((lesson, step, index)) = app.current_step() else { return };
    let count = lesson.steps.len();
    let lesson_title = lesson.title.get(lang).to_string();
    let title = step.title.get(lang).to_string();
    let text = step.text.get(lang).to_string();
    let tries: Vec<String> = step.try_this.iter().map(|t| t.get(lang).to_string()).collect();
    ui.label(RichText::new(lesson_title).small());
    ui.heading(title);
    ui.label(RichText::new(format!("step {} / {count}", index + 1)).weak());
    ui.separator();
    ui.label(RichText::new(text).size(15.0));
    if !tries.is_empty() {
        ui.add_space(8.0);
        ui.strong(match lang {
            crate::lessons::Lang::En => "Try this",
            crate::lessons::Lang::Zh => "试一试",
        });
        for t in tries {
            ui.label(format!("• {t}"));
        }
    }
    ui.add_space(12.0);
    ui.horizontal(|ui| {
        if ui.button("Previous").on_hover_text("Left arrow").clicked() {
            app.step_lesson(-1);
        }
        if ui.button("Next").on_hover_text("Right arrow").clicked() {
            app.step_lesson(1);
        }
    });
}

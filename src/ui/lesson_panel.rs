//! The lesson panel: step navigation, the step's title, what to look at, what to try, and the
//! probe's numbers when the step names the probe.

use super::AppState;
use crate::i18n::Lang;
use crate::lessons::Panel;
use egui::{RichText, Ui};

/// The Apply button's tooltip: each control it sets and the value.
fn what_apply_sets(prompt: &crate::lessons::TryThis, lang: Lang) -> String {
    let tr = |en: &'static str| crate::i18n::tr(lang, en);
    let mut lines = vec![tr("set what this prompt says").to_string()];
    for o in &prompt.overrides {
        let (key, value) = (&o.key, o.value_text());
        let control = super::control_label(key).map_or(key.as_str(), tr);
        let light = key.strip_prefix("light.").and_then(|k| k.split('.').next());
        let of_light = light.map(|n| format!(" ({} {n})", tr("light"))).unwrap_or_default();
        lines.push(format!("{control}{of_light} = {}", super::value_label(key, &value, lang)));
    }
    if let Some(t) = prompt.time_s {
        lines.push(format!("{} = {t}", tr("time (s)")));
    }
    if let Some(v) = prompt.view {
        lines.push(format!("{} = {}", tr("view"), v.label(lang)));
    }
    lines.join("\n")
}

fn step_prompts(state: &AppState) -> Vec<crate::lessons::TryThis> {
    state.current_step().map(|(_, s, _)| s.try_this.clone()).unwrap_or_default()
}

pub fn show(state: &mut AppState, ui: &mut Ui) {
    let lang = state.lang;
    let tr = move |en: &'static str| crate::i18n::tr(lang, en);
    let Some((lesson, step, index)) = state.current_step() else { return };
    let count = lesson.steps.len();
    let lesson_title = lesson.title.get(lang).to_string();
    let title = step.title.get(lang).to_string();
    // Live numbers from the probe and the view on screen (or "…" while they are worked out).
    let text = step.text_filled(lang, state.live_sources());
    let tries = step.try_this_filled(lang, state.live_sources());
    let lesson_probe = step.probe.map(|[x, y]| super::ProbeAt::LessonFrame(x, y));
    let plays = step.play;
    // Navigation first, so it stays in reach however long the text is.
    ui.horizontal(|ui| {
        if ui.button(tr("Previous")).on_hover_text(tr("Left arrow")).clicked() {
            state.step_lesson(-1);
        }
        ui.label(RichText::new(format!("{} {} / {count}", tr("step"), index + 1)).weak());
        if ui.button(tr("Next")).on_hover_text(tr("Right arrow")).clicked() {
            state.step_lesson(1);
        }
    });
    // Present mode (F5): larger text for a projector, and a way back.
    let (body, heading) = if state.present { (22.0, 30.0) } else { (15.0, 20.0) };
    if state.present {
        ui.label(RichText::new(tr("F5 or Esc: leave present mode")).weak());
    } else {
        ui.checkbox(&mut state.show_all_panels, tr("show every panel"));
    }
    ui.separator();
    // Where in the course this is, readable at a glance.
    ui.label(
        RichText::new(format!("{lesson_title} · {} {}", tr("step"), index + 1)).size(body * 0.85).weak(),
    );
    ui.label(RichText::new(title).size(heading).strong());
    if plays {
        ui.label(RichText::new(tr("▶ this step plays: the scene moves")).size(body * 0.85).italics());
    }
    ui.add_space(4.0);
    // The text describes the step as set: once a setting moves, its fixed figures and sentences
    // may no longer hold, so it says so, is greyed, and offers the way back.
    let changed = state.changed_from_step();
    if changed.is_empty() {
        ui.label(RichText::new(text).size(body));
    } else {
        let names: Vec<&str> = changed.iter().map(|c| tr(c)).collect();
        ui.label(
            RichText::new(format!(
                "{} {}",
                tr("You changed the step's settings; the text below describes the step as it was set:"),
                names.join(", ")
            ))
            .size(body * 0.85)
            .color(egui::Color32::from_rgb(255, 200, 90)),
        );
        if state.applied_try_this.is_none() && ui.button(tr("Back to the step's settings")).clicked() {
            state.back_to_step_settings();
        }
        ui.label(RichText::new(text).size(body).weak());
    }
    // The numbers follow whatever probe is pinned; say so when it is not the lesson's own.
    if lesson_probe.is_some() && state.probe_at != lesson_probe {
        let note =
            tr("The numbers above are read at your probe; the sentences around them describe the lesson's.");
        let back = tr("Back to the lesson's probe");
        ui.horizontal_wrapped(|ui| {
            ui.label(RichText::new(note).italics());
            if ui.button(back).clicked() {
                state.probe_at = lesson_probe;
                state.mark_dirty();
            }
        });
    }
    // A step that checks a homework: what the check found, right under the text.
    if state.homework.is_some() {
        ui.add_space(8.0);
        ui.separator();
        super::homework_panel::show(state, ui);
        ui.separator();
    }
    if !tries.is_empty() {
        ui.add_space(8.0);
        ui.strong(tr("Try this"));
        let prompts = step_prompts(state);
        for (i, t) in tries.iter().enumerate() {
            ui.label(RichText::new(format!("• {t}")).size(body * 0.8));
            let prompt = prompts.get(i).filter(|p| p.applies_anything());
            ui.horizontal(|ui| {
                if let Some(p) = prompt
                    && ui.button(tr("Apply")).on_hover_text(what_apply_sets(p, lang)).clicked()
                {
                    state.apply_try_this(i);
                }
                if state.applied_try_this == Some(i) {
                    ui.label(RichText::new(tr("applied")).weak());
                    if ui.button(tr("Back to the step's settings")).clicked() {
                        state.back_to_step_settings();
                    }
                }
            });
        }
    }
    if state.panel_visible(Panel::Probe) && state.probe_report().is_some() {
        ui.add_space(8.0);
        ui.separator();
        super::probe_panel::probe_values(state, ui);
    }
}

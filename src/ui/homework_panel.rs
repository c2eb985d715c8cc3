//! The homework panel: the student's shader (watched for changes), its error on their own line,
//! which picture the camera view shows, the comparison's figures and what the checks found, each
//! with a way to the lesson step that teaches it.

use super::AppState;
use crate::app::homework::HomeworkPicture;
use crate::i18n::{Lang, fill, tr};
use egui::{Color32, RichText, Ui};

/// A figure to three decimals, or "…" while it is worked out.
fn figure(value: Option<f64>) -> String {
    value.map_or_else(|| "…".to_string(), |v| format!("{v:.3}"))
}

/// The lesson step a finding points at, as "lesson title, step N" in `lang`.
pub(super) fn lesson_link(
    state: &AppState,
    lesson: &str,
    step: usize,
    lang: Lang,
) -> Option<(usize, String)> {
    let index = state.lessons.iter().position(|l| l.id == lesson)?;
    let l = &state.lessons[index];
    let step_title = l.steps.get(step.checked_sub(1)?)?.title.get(lang);
    Some((index, format!("{} · {} {step}: {step_title}", l.title.get(lang), tr(lang, "step"))))
}

/// `homework1/src/lights/DirectionalLight.js:32` as `DirectionalLight.js:32`.
fn file_and_line(from: &str, lang: crate::i18n::Lang) -> String {
    // The report's `framework` names no file: said in the panel's language.
    if from == "framework" {
        return tr(lang, "the framework's").to_string();
    }
    from.rsplit(['/', '\\']).next().unwrap_or(from).to_string()
}

/// The way back to the class the student was opened from.
fn back_to_class(state: &mut AppState, ui: &mut Ui) {
    let lang = state.lang;
    let Some(class) = state.class.as_mut() else { return };
    let label = fill(lang, "← class {} ({} submissions)", &[&class.name(), &class.members]);
    if ui.link(label).clicked() {
        class.showing = true;
    }
}

pub fn show(state: &mut AppState, ui: &mut Ui) {
    let lang = state.lang;
    if state.homework.is_none() {
        return;
    }
    back_to_class(state, ui);
    let Some(homework) = state.homework.as_ref() else { return };
    ui.heading(RichText::new(tr(lang, "Your homework")).size(20.0));
    ui.label(RichText::new(homework.name()).monospace().strong())
        .on_hover_text(homework.path.display().to_string());
    // A file handed over as bytes (a page's drop) has no disk copy to watch.
    let watched = if crate::files::is_handed_over(&homework.path) {
        tr(lang, "handed over, not watched: after an edit, drop the file again").to_string()
    } else {
        fill(
            lang,
            "watching the file: save it in your editor and the check runs again ({} reloads)",
            &[&homework.reloads],
        )
    };
    ui.label(RichText::new(watched).weak());
    if let Some(error) = &homework.error {
        ui.add_space(6.0);
        ui.label(
            RichText::new(tr(lang, "does not compile")).strong().color(Color32::from_rgb(255, 120, 110)),
        );
        ui.label(RichText::new(error.to_string()).monospace().color(Color32::from_rgb(255, 170, 160)));
        if homework.program.is_some() {
            ui.label(RichText::new(tr(lang, "the picture is the last version that compiled")).weak());
        }
    }
    if let Some(message) = &homework.gpu_error {
        ui.label(RichText::new(message).monospace().color(Color32::from_rgb(255, 170, 160)));
    }
    ui.add_space(6.0);
    ui.label(RichText::new(tr(lang, "the camera view shows")).strong());
    let mut picture = homework.picture;
    ui.horizontal_wrapped(|ui| {
        for p in HomeworkPicture::ALL {
            ui.selectable_value(&mut picture, p, tr(lang, p.label()));
        }
    });
    let outcome = homework.outcome.clone();
    let checked = homework.checked();
    if let Some(h) = state.homework.as_mut() {
        h.picture = picture;
    }
    let Some(outcome) = outcome else {
        if state.homework.as_ref().is_some_and(|h| h.program.is_some()) {
            ui.label(RichText::new(tr(lang, "checking…")).weak());
        }
        return;
    };
    if !checked {
        ui.label(RichText::new(tr(lang, "checking the new version…")).weak());
    }
    let report = &outcome.report;
    ui.add_space(6.0);
    egui::Grid::new("homework figures").num_columns(2).striped(true).show(ui, |ui| {
        let mut row = |name: &'static str, value: String| {
            ui.label(tr(lang, name));
            ui.label(RichText::new(value).monospace());
            ui.end_row();
        };
        row("functions that ran", if report.calls.is_empty() { "-".into() } else { report.calls.join(", ") });
        row("visibility from", report.visibility_function.unwrap_or("-").to_string());
        let technique = report.compared_with.and_then(crate::scene::Technique::from_name);
        row("compared with shadowlab's", technique.map_or("-", |t| t.label(lang)).to_string());
        if let Some(f) = &report.figures {
            row("mean |difference| to shadowlab's", figure(f.mean_abs_difference));
            row("mean |difference| to the ground truth", figure(f.mean_abs_difference_to_ground_truth));
            row("NaN or infinite visibility", format!("{:.2}%", 100.0 * f.nan_fraction));
            row("mean visibility where fully lit", figure(f.lit_area_mean));
            row("mean visibility in the umbra", figure(f.umbra_mean));
            row(
                "penumbra pixels (ground truth)",
                format!("{} ({})", f.penumbra_pixels, f.penumbra_pixels_ground_truth),
            );
        }
    });
    // The light the check drew with (theirs where their DirectionalLight.js builds one) and the
    // one their shader behaves as: sentences that wrap, not grid rows that widen the panel.
    let light = report.light.as_ref().map_or_else(
        || tr(lang, "the framework's").to_string(),
        |l| match (&l.error, l.frustum.width_world) {
            (Some(_), _) => tr(lang, "the framework's (yours did not run)").to_string(),
            // The file's name and line: the path inside the submission is in report.json.
            (None, Some(width)) => fill(lang, "{}, {:.0} wide", &[&file_and_line(&l.from, lang), &width]),
            (None, None) => file_and_line(&l.from, lang),
        },
    );
    ui.label(fill(lang, "light from {}", &[&light]));
    page_lights(state, ui, report);
    if let Some(fit) = report.light_width.as_ref() {
        if let Some(bound) = fit.narrower_than_world {
            ui.label(fill(
                lang,
                "your penumbrae behave as a light narrower than {:.2} world units: not measurable with this map",
                &[&bound],
            ));
        } else if let Some(width) = fit.measured_width_world() {
            ui.label(fill(lang, "your penumbrae behave as a light {:.2} world units wide", &[&width]));
        } else if fit.law_holds == Some(false) {
            ui.label(tr(lang, "your penumbrae follow no one light's width"));
        }
    }
    if let Some(error) = report.light.as_ref().and_then(|l| l.error.as_ref()) {
        ui.label(
            RichText::new(fill(lang, "your light did not run: {}", &[error]))
                .monospace()
                .color(Color32::from_rgb(255, 170, 160)),
        );
    }
    if let Some(probe) = state.probe_at.and_then(|at| state.homework.as_ref()?.probe(at)) {
        ui.add_space(6.0);
        ui.label(
            RichText::new(fill(lang, "at the probe (pixel {}, {})", &[&probe.pixel.0, &probe.pixel.1]))
                .strong(),
        );
        let value = |v: f32| if v.is_finite() { format!("{v:.4}") } else { format!("{v}") };
        egui::Grid::new("homework probe").num_columns(2).striped(true).show(ui, |ui| {
            for (name, returned) in crate::homework::RECORDED_FUNCTIONS.iter().zip(probe.returned) {
                ui.label(RichText::new(*name).monospace());
                ui.label(
                    RichText::new(returned.map_or_else(|| tr(lang, "not called").to_string(), value))
                        .monospace(),
                );
                ui.end_row();
            }
            ui.label(tr(lang, "your visibility"));
            ui.label(RichText::new(probe.visibility.map_or("-".to_string(), |(v, _)| value(v))).monospace());
            ui.end_row();
            ui.label(tr(lang, "shadowlab's"));
            ui.label(RichText::new(value(probe.shadowlab)).monospace());
            ui.end_row();
            ui.label(tr(lang, "ground truth"));
            ui.label(RichText::new(value(probe.ground_truth)).monospace());
            ui.end_row();
            if let Some((theirs, truth)) = probe.penumbra_widths {
                ui.label(tr(lang, "penumbra width (world units)"));
                ui.label(
                    RichText::new(fill(lang, "{:.2}, ground truth {:.2}", &[&theirs, &truth])).monospace(),
                );
                ui.end_row();
            }
        });
    }
    ui.add_space(8.0);
    if report.findings.is_empty() {
        ui.label(
            RichText::new(tr(lang, "No findings: your shadows match the ground truth."))
                .color(Color32::from_rgb(140, 220, 140)),
        );
    }
    let mut open_step = None;
    for finding in &report.findings {
        ui.group(|ui| {
            ui.label(RichText::new(finding.id).monospace().strong().color(Color32::from_rgb(255, 200, 90)));
            ui.label(&finding.explanation);
            if let Some((index, label)) = lesson_link(state, finding.lesson, finding.step, lang)
                && ui.link(format!("→ {label}")).clicked()
            {
                open_step = Some((index, finding.step - 1));
            }
        });
    }
    if let Some((lesson, step)) = open_step {
        state.go_to_step(lesson, step);
    }
}

/// The page's lights with a map of their own, and the times of its animation where one had moved:
/// choosing one checks it (the bonus: each light on its own, as its pass and its map draw it).
fn page_lights(state: &mut AppState, ui: &mut Ui, report: &crate::homework::HomeworkReport) {
    use crate::homework::student_light::PageLight;
    let lang = state.lang;
    let Some(homework) = state.homework.as_mut() else { return };
    // Where the page made no light the check could use, the framework's is listed first.
    let inserted = usize::from(report.lights.first().is_some_and(|l| l.made_at == "framework"));
    let choices: Vec<(usize, &crate::homework::student_light::LightEntry)> = report
        .lights
        .iter()
        .enumerate()
        .skip(inserted)
        .filter(|(_, l)| l.error.is_none())
        .map(|(listed, l)| (listed - inserted, l))
        .collect();
    if choices.len() < 2 && choices.iter().all(|(_, l)| l.moved_at_s.is_empty()) {
        return;
    }
    ui.add_space(4.0);
    ui.label(RichText::new(tr(lang, "the page's lights: the check is of the one chosen")).strong());
    // Until one is chosen, the check is of the light its report marks as checked.
    let current = homework.page_light.or_else(|| {
        choices.iter().find(|(_, l)| l.checked).map(|(index, _)| PageLight { index: *index, time_s: None })
    });
    let mut chosen = current.unwrap_or(PageLight { index: 0, time_s: None });
    ui.horizontal_wrapped(|ui| {
        for (index, light) in &choices {
            let label = format!("{} {} ({})", index + 1, light.kind, file_and_line(&light.made_at, lang));
            if ui.selectable_label(chosen.index == *index, label).clicked() {
                chosen = PageLight { index: *index, time_s: None };
            }
        }
    });
    if let Some((_, light)) = choices.iter().find(|(i, _)| *i == chosen.index)
        && !light.moved_at_s.is_empty()
    {
        ui.horizontal_wrapped(|ui| {
            ui.label(tr(lang, "its animation at"));
            if ui.selectable_label(chosen.time_s.is_none(), tr(lang, "the first frames")).clicked() {
                chosen.time_s = None;
            }
            for &t in &light.moved_at_s {
                if ui.selectable_label(chosen.time_s == Some(t), format!("{t:.1} s")).clicked() {
                    chosen.time_s = Some(t);
                }
            }
        });
    }
    if Some(chosen) != current {
        homework.page_light = Some(chosen);
        state.mark_dirty();
    }
}

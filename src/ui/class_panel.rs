//! The class panel: a class of homeworks as a TA reads it. While the class is checked, how far it
//! has come; then the findings ranked by how many students have them (each with the lesson step
//! that teaches it and who has it) and every student with how their check ended; a student's
//! name opens their homework, and the homework panel has a way back.

use super::AppState;
use crate::export::class_report::{self, Severity, Status};
use crate::i18n::{Lang, fill, tr};
use egui::{Color32, RichText, Ui};

const MISTAKE: Color32 = Color32::from_rgb(255, 200, 90);
const LATENT: Color32 = Color32::from_rgb(170, 190, 230);
const PROBLEM: Color32 = Color32::from_rgb(255, 170, 160);

/// What a click in the panel asks for, done once the panel is drawn.
enum Action {
    Student(usize),
    Step(usize, usize),
}

/// The lesson step that teaches a finding: (lesson, step from 0, "lesson title · step N: title").
fn lesson_step(state: &AppState, id: &str, lang: Lang) -> Option<(usize, usize, String)> {
    let kind = crate::homework::findings::FINDINGS.iter().find(|k| k.id == id)?;
    let (index, label) = super::homework_panel::lesson_link(state, kind.lesson, kind.step, lang)?;
    Some((index, kind.step - 1, label))
}

pub fn show(state: &mut AppState, ui: &mut Ui) {
    let lang = state.lang;
    let Some(class) = state.class.as_ref() else { return };
    ui.heading(RichText::new(tr(lang, "Class")).size(20.0));
    ui.label(RichText::new(class.name()).monospace().strong()).on_hover_text(class.dir.display().to_string());
    if let Some(error) = &class.error {
        ui.label(RichText::new(error).monospace().color(PROBLEM));
    }
    if class.running() {
        let share = if class.members > 0 { class.done as f32 / class.members as f32 } else { 0.0 };
        ui.add(
            egui::ProgressBar::new(share)
                // No spinner: at the fill's edge it covers the count.
                .text(fill(lang, "{} of {} checked", &[&class.done, &class.members])),
        );
        ui.label(RichText::new(tr(lang, "each submission is checked as a process of its own")).weak());
        return;
    }
    if class.rows.is_empty() {
        return;
    }
    let counts: Vec<String> = Status::ALL
        .iter()
        .map(|&s| (s, class.count(s)))
        .filter(|&(_, n)| n > 0)
        .map(|(s, n)| format!("{n} {}", s.shown(lang)))
        .collect();
    ui.label(fill(lang, "{} submissions", &[&class.rows.len()]).to_string() + ": " + &counts.join(", "));
    ui.label(RichText::new(tr(lang, "class report:")).weak());
    ui.add(egui::Label::new(RichText::new(class.out.display().to_string()).monospace().weak()).wrap())
        .on_hover_text(class.out.join(class_report::INDEX_EN).display().to_string());
    let mut action = None;
    ui.add_space(8.0);
    ui.label(RichText::new(tr(lang, "Findings across the class")).strong());
    if class.ranked.is_empty() {
        ui.label(
            RichText::new(tr(lang, "No student has a finding.")).color(Color32::from_rgb(140, 220, 140)),
        );
    }
    for ranked in &class.ranked {
        ui.group(|ui| {
            let (kind, colour) = match ranked.severity {
                Severity::Mistake => ("mistake@class", MISTAKE),
                Severity::Latent => ("latent@class", LATENT),
            };
            ui.horizontal_wrapped(|ui| {
                ui.label(RichText::new(&ranked.id).monospace().strong().color(colour));
                ui.label(format!(
                    "{} · {}",
                    tr(lang, kind),
                    fill(lang, "{} students", &[&ranked.students.len()])
                ));
            });
            if let Some(text) = class_report::description(lang, &ranked.id) {
                ui.label(text);
            }
            if let Some((lesson, step, label)) = lesson_step(state, &ranked.id, lang)
                && ui.link(format!("→ {label}")).clicked()
            {
                action = Some(Action::Step(lesson, step));
            }
            ui.horizontal_wrapped(|ui| {
                for &i in &ranked.students {
                    if ui.link(&class.rows[i].name).clicked() {
                        action = Some(Action::Student(i));
                    }
                }
            });
        });
    }
    ui.add_space(8.0);
    ui.label(RichText::new(tr(lang, "Students")).strong());
    egui::Grid::new("class students").num_columns(2).striped(true).show(ui, |ui| {
        for (i, row) in class.rows.iter().enumerate() {
            let opened = class.opened == Some(i);
            let name = RichText::new(&row.name).strong();
            if ui.selectable_label(opened, name).on_hover_text(&row.path).clicked() {
                action = Some(Action::Student(i));
            }
            let findings: Vec<&str> =
                row.report.iter().flat_map(|r| &r.findings).map(|f| f.id.as_str()).collect();
            let colour = if row.status == Status::Checked { Color32::GRAY } else { PROBLEM };
            if row.status == Status::Checked && !findings.is_empty() {
                // Each id whole: the line breaks between ids, never inside one.
                ui.horizontal_wrapped(|ui| {
                    for id in findings {
                        ui.add(egui::Label::new(RichText::new(id).monospace().color(colour)).extend());
                    }
                });
            } else {
                let said = match row.status {
                    Status::Checked => tr(lang, "no findings").to_string(),
                    status if row.message.is_empty() => status.shown(lang).to_string(),
                    status => format!("{}: {}", status.shown(lang), row.message),
                };
                ui.add(egui::Label::new(RichText::new(said).monospace().color(colour)).wrap());
            }
            ui.end_row();
        }
    });
    match action {
        Some(Action::Student(i)) => state.open_class_student(i),
        Some(Action::Step(lesson, step)) => state.go_to_step(lesson, step),
        None => {}
    }
}

//! The top bar (scene and lesson picker, file box, playback, screenshot, language), the status
//! bar (errors, timings) and the shortcut help.

use super::{ShadowlabApp, Source};
use crate::i18n::Lang;
use crate::i18n::{fill, tr};
use crate::shipped_path;
use std::path::PathBuf;

/// The status bar's error headline.
const ERROR_RED: egui::Color32 = egui::Color32::from_rgb(255, 120, 110);

impl ShadowlabApp {
    pub(super) fn top_bar(&mut self, ui: &mut egui::Ui) {
        let lang = self.state.lang;
        let tr = move |en: &'static str| tr(lang, en);
        ui.horizontal_wrapped(|ui| {
            ui.strong("shadowlab");
            ui.separator();
            self.lesson_selector(ui);
            self.scene_selector(ui);
            let file_label = ui.label(tr("file"));
            let field = ui
                .add(
                    egui::TextEdit::singleline(&mut self.open_path)
                        .hint_text(tr("scene, lesson, .obj or .glsl path"))
                        .desired_width(150.0),
                )
                .labelled_by(file_label.id);
            if std::mem::take(&mut self.focus_path_box) {
                field.request_focus();
            }
            let entered = field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
            if (ui.button(tr("Open")).clicked() || entered) && !self.open_path.trim().is_empty() {
                let path = PathBuf::from(self.open_path.trim());
                self.state.open_any(&path);
            }
            let browse = ui
                .add_enabled(!self.browsing(), egui::Button::new(tr("Browse…")))
                .on_hover_text(tr("the desktop's Open dialog: a scene or lesson (.toml), a model (.obj) or a homework shader (.glsl)"));
            if browse.clicked() {
                self.browse(ui.ctx());
            }
            ui.separator();
            let play_label = tr(if self.state.playing { "Pause" } else { "Play" });
            if ui.button(play_label).on_hover_text(tr("Space")).clicked() {
                self.state.playing = !self.state.playing;
            }
            let time_label = ui.label(tr("time (s)"));
            let range = 0.0..=crate::app::PLAYBACK_RANGE_S;
            let time = ui
                .add(egui::Slider::new(&mut self.state.time_s, range).max_decimals(2))
                .on_hover_text(tr("playback loops back to 0 at the end of the range"));
            if time.labelled_by(time_label.id).changed() {
                self.state.mark_dirty();
            }
            let speed_label = ui.label(tr("speed"));
            ui.add(egui::DragValue::new(&mut self.state.speed).speed(0.05).range(0.0..=10.0).suffix("×"))
                .labelled_by(speed_label.id);
            ui.separator();
            if ui.button(tr("Screenshot")).on_hover_text(tr("S: window and each view as PNGs")).clicked() {
                self.request_screenshot(ui.ctx());
            }
            let lang_label = ui.label(tr("language"));
            // Each language named in itself, not a translation.
            egui::ComboBox::from_id_salt("lang")
                .selected_text(match self.state.lang {
                    Lang::En => "English",
                    Lang::Zh => "中文",
                })
                .show_ui(ui, |ui| {
                    ui.selectable_value(&mut self.state.lang, Lang::En, "English");
                    ui.selectable_value(&mut self.state.lang, Lang::Zh, "中文");
                })
                .response
                .labelled_by(lang_label.id);
            if ui.button(tr("F1 Help")).clicked() {
                self.state.show_help = !self.state.show_help;
            }
            if ui
                .button(tr("Present (F5)"))
                .on_hover_text(tr("camera view, map, diagram and lesson text, large"))
                .clicked()
            {
                self.state.present = true;
            }
        });
    }

    /// The lessons come first: a teacher opens one, a student steps through it.
    pub(super) fn lesson_selector(&mut self, ui: &mut egui::Ui) {
        let lang = self.state.lang;
        let tr = move |en: &'static str| tr(lang, en);
        let current = match &self.state.source {
            Source::Lesson { lesson, step } => self
                .lessons
                .get(*lesson)
                .map(|l| {
                    // Short enough for one top-bar line; the list shows the whole titles.
                    let title = l.title.get(lang);
                    let short: String = title.chars().take(24).collect();
                    let cut = if short.len() < title.len() { "…" } else { "" };
                    format!("{}. {short}{cut} · {}/{}", lesson + 1, step + 1, l.steps.len())
                })
                .unwrap_or_default(),
            Source::Scene(_) => tr("(none: explore freely)").to_string(),
        };
        let mut choice = None;
        let label = ui.label(tr("lesson"));
        let combo =
            egui::ComboBox::from_id_salt("lesson").selected_text(current).width(250.0).show_ui(ui, |ui| {
                for (i, lesson) in self.state.lessons.iter().enumerate() {
                    let selected = matches!(self.state.source, Source::Lesson { lesson, .. } if lesson == i);
                    let item =
                        ui.selectable_label(selected, format!("{}. {}", i + 1, lesson.title.get(lang)));
                    if item.on_hover_text(lesson.summary.get(lang)).clicked() {
                        choice = Some(i);
                    }
                }
            });
        combo.response.labelled_by(label.id);
        if let Some(lesson) = choice {
            self.state.go_to_step(lesson, 0);
        }
    }

    /// The shipped scenes, to explore without a lesson.
    pub(super) fn scene_selector(&mut self, ui: &mut egui::Ui) {
        let lang = self.state.lang;
        let tr = move |en: &'static str| tr(lang, en);
        let current = match &self.state.source {
            Source::Scene(p) => p.file_name().map(|n| n.to_string_lossy().to_string()).unwrap_or_default(),
            Source::Lesson { lesson, step } => self
                .lessons
                .get(*lesson)
                .and_then(|l| l.steps.get(*step))
                .and_then(|s| s.scene_path.file_name())
                .map(|n| n.to_string_lossy().to_string())
                .unwrap_or_default(),
        };
        let mut choice: Option<PathBuf> = None;
        let label = ui.label(tr("scene"));
        let combo =
            // Tall enough for the shipped scenes and the recent files without scrolling.
            egui::ComboBox::from_id_salt("source").selected_text(current).width(130.0).height(520.0).show_ui(ui, |ui| {
                let mut scenes: Vec<PathBuf> = crate::files::folder_entries(&shipped_path("assets/scenes")).unwrap_or_default();
                let ships = |p: &PathBuf| p.file_name().is_some_and(|n| crate::built_in::ships(&n.to_string_lossy()));
                scenes.retain(|p| p.extension().is_some_and(|e| e == "toml") && ships(p));
                scenes.sort();
                for path in scenes {
                    let name = path.file_name().map(|n| n.to_string_lossy().to_string()).unwrap_or_default();
                    if ui.selectable_label(self.state.source == Source::Scene(path.clone()), name).clicked() {
                        choice = Some(path);
                    }
                }
                // Files opened from elsewhere (those since moved or deleted are left out).
                let recent: Vec<&PathBuf> = self.state.settings.recent_files.iter().filter(|p| crate::files::exists(p)).collect();
                let current = match &self.state.source {
                    Source::Scene(p) => std::fs::canonicalize(p).ok(),
                    Source::Lesson { .. } => None,
                };
                if !recent.is_empty() {
                    ui.separator();
                    ui.weak(tr("recent"));
                    for path in recent {
                        let name = path.file_name().map(|n| n.to_string_lossy().to_string()).unwrap_or_default();
                        let selected = current.as_ref() == Some(path);
                        let item = ui.selectable_label(selected, name).on_hover_text(path.display().to_string());
                        if item.clicked() {
                            choice = Some(path.clone());
                        }
                    }
                }
            });
        combo.response.labelled_by(label.id);
        if let Some(path) = choice {
            self.state.open(&path);
        }
    }

    /// On start: the lessons, with what each teaches, or free exploration.
    pub(super) fn lesson_list(&mut self, ctx: &egui::Context) {
        if !self.state.show_lesson_list {
            return;
        }
        let lang = self.state.lang;
        let tr = move |en: &'static str| tr(lang, en);
        let mut open = true;
        let mut choice = None;
        egui::Window::new(tr("Lessons"))
            .open(&mut open)
            .collapsible(false)
            .resizable(false)
            .default_width(560.0)
            .anchor(egui::Align2::CENTER_CENTER, egui::Vec2::ZERO)
            .show(ctx, |ui| {
                for (i, lesson) in self.state.lessons.iter().enumerate() {
                    if ui
                        .button(
                            egui::RichText::new(format!("{}. {}", i + 1, lesson.title.get(lang))).size(17.0),
                        )
                        .clicked()
                    {
                        choice = Some(Some(i));
                    }
                    ui.label(lesson.summary.get(lang));
                    ui.add_space(6.0);
                }
                ui.separator();
                if ui.button(tr("Explore freely (no lesson)")).clicked() {
                    choice = Some(None);
                }
            });
        if let Some(lesson) = choice {
            if let Some(i) = lesson {
                self.state.go_to_step(i, 0);
            }
            open = false;
        }
        self.state.show_lesson_list = open;
    }

    /// The error and the last message at the left, the timings at the right. The timings are
    /// laid out first; the messages share what is left of them (a long path must neither run
    /// under the timings nor widen the window's layout), each cut with an ellipsis where it does
    /// not fit and then shown whole on hover, once.
    pub(super) fn status_bar(&mut self, ui: &mut egui::Ui) {
        let timings = self.state.settings.show_timings.then(|| self.timing_text(ui.ctx()));
        // One row high even when empty (as a horizontal row is), so the views keep their size
        // when a message comes and goes.
        ui.set_min_height(ui.spacing().interact_size.y);
        egui::Sides::new().shrink_left().truncate().show(
            ui,
            |ui| self.status_messages(ui),
            |ui| {
                if let Some(timings) = timings {
                    ui.label(timings);
                }
            },
        );
    }

    /// The error (headline, details and its dismiss button) and the status message, within the
    /// width `ui` has. Where both are too long, the error keeps at least 60% of the text's room.
    fn status_messages(&mut self, ui: &mut egui::Ui) {
        let lang = self.state.lang;
        let status = (!self.state.status.is_empty()).then_some(self.state.status.as_str());
        let Some(error) = &self.state.error else {
            if let Some(status) = status {
                ui.add(egui::Label::new(status).truncate());
            }
            return;
        };
        let spacing = ui.spacing().item_spacing.x;
        let body = egui::TextStyle::Body.resolve(ui.style());
        let plain = egui::TextFormat::simple(body.clone(), ui.visuals().text_color());
        let headline = format!("{}: {}", tr(lang, "Error"), tr(lang, error.what));
        let mut text = egui::text::LayoutJob::default();
        text.append(&headline, 0.0, egui::TextFormat::simple(body, ERROR_RED));
        text.append(&error.detail, spacing, plain.clone());
        let one_line_width =
            |ui: &egui::Ui, job: egui::text::LayoutJob| ui.fonts_mut(|f| f.layout_job(job)).size().x;
        let dismiss = tr(lang, "dismiss");
        let dismiss_id = egui::Id::NULL.with("status bar: dismiss width");
        // The button's width from the last frame that drew it (before that, from its text).
        let dismiss_width = ui.data(|d| d.get_temp::<f32>(dismiss_id)).unwrap_or_else(|| {
            let mut label = egui::text::LayoutJob::default();
            label.append(
                dismiss,
                0.0,
                egui::TextFormat::simple(egui::TextStyle::Button.resolve(ui.style()), egui::Color32::WHITE),
            );
            one_line_width(ui, label) + 2.0 * ui.spacing().button_padding.x
        });
        let mut room = (ui.available_width() - dismiss_width - spacing).max(0.0);
        if let Some(status) = status {
            // Less the separator and the spacing around it; the status gets what the error leaves.
            room = (room - 3.0 * spacing).max(0.0);
            let mut line = egui::text::LayoutJob::default();
            line.append(status, 0.0, plain);
            room = (room - one_line_width(ui, line)).max(room * 0.6);
        }
        let cut = one_line_width(ui, text.clone()) > room;
        let height = ui.spacing().interact_size.y;
        let label = egui::Label::new(text).truncate().show_tooltip_when_elided(false);
        let shown = ui.allocate_ui(egui::vec2(room, height), |ui| ui.add(label)).inner;
        if cut {
            // The whole error on hover, once: the headline, the details below it.
            shown.on_hover_ui(|ui| {
                ui.colored_label(ERROR_RED, &headline);
                ui.label(&error.detail);
            });
        }
        let button = ui.small_button(dismiss);
        ui.data_mut(|d| d.insert_temp(dismiss_id, button.rect.width()));
        if button.clicked() {
            self.state.error = None;
        }
        if let Some(status) = status {
            ui.separator();
            ui.add(egui::Label::new(status).truncate());
        }
    }

    pub(super) fn help_window(&mut self, ctx: &egui::Context) {
        let lang = self.state.lang;
        let mut open = self.state.show_help;
        egui::Window::new(tr(lang, "Shortcuts")).open(&mut open).collapsible(false).show(ctx, |ui| {
            egui::Grid::new("keys").striped(true).show(ui, |ui| {
                for (key, what) in [
                    ("Left / Right", "previous / next lesson step"),
                    ("Space", "play / pause"),
                    ("S", "screenshot (window and each view)"),
                    ("F1", "this help"),
                    ("R", "reset the camera"),
                    ("F5", "present mode (Esc leaves it)"),
                    ("Left-drag (camera view)", "orbit"),
                    ("Right- or middle-drag", "pan"),
                    ("Wheel", "zoom"),
                    ("Click", "pin the probe"),
                    ("Double-click", "focus the camera on a point"),
                    ("Drag (shadow map)", "move the light"),
                    ("Drop a .toml or .obj", "open it"),
                ] {
                    ui.strong(tr(lang, key));
                    ui.label(tr(lang, what));
                    ui.end_row();
                }
            });
        });
        self.state.show_help = open;
    }

    /// The status bar's timings: the UI's own frame time, the last render per pass and the
    /// resolution it was rendered at.
    pub(super) fn timing_text(&self, ctx: &egui::Context) -> String {
        let ui_ms = ctx.input(|i| i.unstable_dt) * 1e3;
        let shown = &self.render.shown;
        let lang = self.state.lang;
        let mut text = fill(lang, "UI {} ms", &[&format!("{ui_ms:.0}")]);
        // Nothing rendered yet (or no views at all, in a browser without WebGPU): no render
        // figures to give, rather than "0 ms at 0x0".
        if self.render.frames_shown == 0 {
            return text;
        }
        text += &fill(lang, " · render {} ms", &[&format!("{:.0}", shown.render_ms)]);
        if let Some(t) = shown.pass_times {
            let (shadow, camera) = (format!("{:.1}", t.shadow_ms), format!("{:.1}", t.camera_ms));
            text += &fill(lang, " (GPU shadow {} ms, camera {} ms)", &[&shadow, &camera]);
        }
        text += &fill(lang, " at {}x{}", &[&shown.size.0, &shown.size.1]);
        if shown.preview {
            text += tr(lang, " · preview");
        }
        if let Some(waited) = self.render_is_slow() {
            text += &fill(lang, " · rendering {} s", &[&format!("{:.1}", waited.as_secs_f32())]);
        }
        text
    }
}

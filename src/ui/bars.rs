//! The top bar (scene and lesson picker, file box, playback, screenshot, language), the status
//! bar (errors, timings) and the shortcut help.

use super::{ShadowlabApp, Source, shipped_path};
use crate::i18n::tr;
use crate::lessons::Lang;
use std::path::PathBuf;

impl ShadowlabApp {
    pub(super) fn top_bar(&mut self, ui: &mut egui::Ui) {
        let lang = self.lang;
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
                        .hint_text(tr("scene, lesson or .obj path"))
                        .desired_width(150.0),
                )
                .labelled_by(file_label.id);
            if std::mem::take(&mut self.focus_path_box) {
                field.request_focus();
            }
            let entered = field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
            if (ui.button(tr("Open")).clicked() || entered) && !self.open_path.trim().is_empty() {
                let path = PathBuf::from(self.open_path.trim());
                self.open_any(&path);
            }
            let browse = ui
                .add_enabled(!self.browsing(), egui::Button::new(tr("Browse…")))
                .on_hover_text(tr("the desktop's Open dialog: a scene or lesson (.toml) or a model (.obj)"));
            if browse.clicked() {
                self.browse(ui.ctx());
            }
            ui.separator();
            let play_label = tr(if self.playing { "Pause" } else { "Play" });
            if ui.button(play_label).on_hover_text(tr("Space")).clicked() {
                self.playing = !self.playing;
            }
            let time_label = ui.label(tr("time (s)"));
            let range = 0.0..=super::rendering::PLAYBACK_RANGE_S;
            let time = ui
                .add(egui::Slider::new(&mut self.time_s, range).max_decimals(2))
                .on_hover_text(tr("playback loops back to 0 at the end of the range"));
            if time.labelled_by(time_label.id).changed() {
                self.mark_dirty();
            }
            let speed_label = ui.label(tr("speed"));
            ui.add(egui::DragValue::new(&mut self.speed).speed(0.05).range(0.0..=10.0).suffix("×"))
                .labelled_by(speed_label.id);
            ui.separator();
            if ui.button(tr("Screenshot")).on_hover_text(tr("S: window and each view as PNGs")).clicked() {
                self.request_screenshot(ui.ctx());
            }
            let lang_label = ui.label(tr("language"));
            egui::ComboBox::from_id_salt("lang")
                .selected_text(match self.lang {
                    Lang::En => "English",
                    Lang::Zh => "中文",
                })
                .show_ui(ui, |ui| {
                    ui.selectable_value(&mut self.lang, Lang::En, "English");
                    ui.selectable_value(&mut self.lang, Lang::Zh, "中文");
                })
                .response
                .labelled_by(lang_label.id);
            if ui.button(tr("F1 Help")).clicked() {
                self.show_help = !self.show_help;
            }
            if ui
                .button(tr("Present (F5)"))
                .on_hover_text(tr("camera view, map, diagram and lesson text, large"))
                .clicked()
            {
                self.present = true;
            }
        });
    }

    /// The lessons come first: a teacher opens one, a student steps through it.
    pub(super) fn lesson_selector(&mut self, ui: &mut egui::Ui) {
        let lang = self.lang;
        let tr = move |en: &'static str| tr(lang, en);
        let current = match &self.source {
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
                for (i, lesson) in self.lessons.iter().enumerate() {
                    let selected = matches!(self.source, Source::Lesson { lesson, .. } if lesson == i);
                    let item =
                        ui.selectable_label(selected, format!("{}. {}", i + 1, lesson.title.get(lang)));
                    if item.on_hover_text(lesson.summary.get(lang)).clicked() {
                        choice = Some(i);
                    }
                }
            });
        combo.response.labelled_by(label.id);
        if let Some(lesson) = choice {
            self.go_to_step(lesson, 0);
        }
    }

    /// The shipped scenes, to explore without a lesson.
    pub(super) fn scene_selector(&mut self, ui: &mut egui::Ui) {
        let lang = self.lang;
        let tr = move |en: &'static str| tr(lang, en);
        let current = match &self.source {
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
                let mut scenes: Vec<PathBuf> = std::fs::read_dir(shipped_path("assets/scenes"))
                    .map(|d| d.filter_map(|e| e.ok().map(|e| e.path())).collect())
                    .unwrap_or_default();
                scenes.retain(|p| p.extension().is_some_and(|e| e == "toml"));
                scenes.sort();
                for path in scenes {
                    let name = path.file_name().map(|n| n.to_string_lossy().to_string()).unwrap_or_default();
                    if ui.selectable_label(self.source == Source::Scene(path.clone()), name).clicked() {
                        choice = Some(path);
                    }
                }
                // Files opened from elsewhere (those since moved or deleted are left out).
                let recent: Vec<&PathBuf> = self.settings.recent_files.iter().filter(|p| p.exists()).collect();
                let current = match &self.source {
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
            self.open(&path);
        }
    }

    /// On start: the lessons, with what each teaches, or free exploration.
    pub(super) fn lesson_list(&mut self, ctx: &egui::Context) {
        if !self.show_lesson_list {
            return;
        }
        let lang = self.lang;
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
                for (i, lesson) in self.lessons.iter().enumerate() {
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
                self.go_to_step(i, 0);
            }
            open = false;
        }
        self.show_lesson_list = open;
    }

    pub(super) fn status_bar(&mut self, ui: &mut egui::Ui) {
        let lang = self.lang;
        let tr = move |en: &'static str| tr(lang, en);
        ui.horizontal(|ui| {
            if let Some(error) = self.error.clone() {
                let headline = format!("{}: {}", tr("Error"), tr(error.what));
                ui.colored_label(egui::Color32::from_rgb(255, 120, 110), headline);
                ui.add(egui::Label::new(&error.detail).truncate()).on_hover_text(&error.detail);
                if ui.small_button(tr("dismiss")).clicked() {
                    self.error = None;
                }
                ui.separator();
            }
            // Truncated: a long message (the saved files' paths) must not widen the window's layout.
            ui.add(egui::Label::new(&self.status).truncate()).on_hover_text(&self.status);
            if !self.settings.show_timings {
                return;
            }
            ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                ui.label(self.timing_text(ui.ctx()));
            });
        });
    }

    pub(super) fn help_window(&mut self, ctx: &egui::Context) {
        let lang = self.lang;
        let mut open = self.show_help;
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
        self.show_help = open;
    }

    /// The status bar's timings: the UI's own frame time, the last render per pass and the
    /// resolution it was rendered at.
    pub(super) fn timing_text(&self, ctx: &egui::Context) -> String {
        let ui_ms = ctx.input(|i| i.unstable_dt) * 1e3;
        let shown = &self.shown;
        let zh = self.lang == Lang::Zh;
        let mut text = if zh {
            format!("界面 {ui_ms:.0} ms · 渲染 {:.0} ms", shown.render_ms)
        } else {
            format!("UI {ui_ms:.0} ms · render {:.0} ms", shown.render_ms)
        };
        if let Some(t) = shown.pass_times {
            text += &if zh {
                format!("（GPU 阴影趟 {:.1} ms，相机趟 {:.1} ms）", t.shadow_ms, t.camera_ms)
            } else {
                format!(" (GPU shadow {:.1} ms, camera {:.1} ms)", t.shadow_ms, t.camera_ms)
            };
        }
        text += &if zh {
            format!("，分辨率 {}x{}", shown.size.0, shown.size.1)
        } else {
            format!(" at {}x{}", shown.size.0, shown.size.1)
        };
        if shown.preview {
            text += if zh { " · 预览" } else { " · preview" };
        }
        if let Some(waited) = self.render_is_slow() {
            let label = if zh { "渲染中" } else { "rendering" };
            text += &format!(" · {label} {:.1} s", waited.as_secs_f32());
        }
        text
    }
}

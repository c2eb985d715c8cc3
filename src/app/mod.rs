//! The app's state and what a user does to it, without egui and without threads: the scene and
//! where it came from, the lesson position, language, playback, probe, overlays, view and the
//! actions (open, step, apply a "Try this", reset). The window (src/ui) draws it and turns clicks
//! into these actions; tests and tools drive it directly; renders are asked for through a
//! [`scheduler::RenderScheduler`].

pub mod class;
pub mod homework;
pub mod launch;
pub mod link;
mod obj_scene;
pub mod scheduler;
pub mod settings;

pub use launch::main_file;
pub use obj_scene::scene_for_obj;
pub use settings::Settings;

use crate::i18n::Lang;
use crate::lessons::{self, Lesson};
use crate::probe::ProbeReport;
use crate::scene::{Camera, Scene, Technique, load_scene, parse_scene_str};
use crate::shipped_path;
use crate::views::View;
use crate::views::overlays::Overlay;
use std::path::{Path, PathBuf};

/// Where the current scene came from.
#[derive(Clone, Debug, PartialEq)]
pub enum Source {
    Scene(PathBuf),
    Lesson { lesson: usize, step: usize },
}

/// A/B comparison: the right part of the camera view shows technique `b`.
#[derive(Clone, Debug)]
pub struct AbSplit {
    pub b: Technique,
    /// Divider position, 0..1 of the view width.
    pub divider: f32,
    /// A drag that started on the divider moves it until release, however fast the pointer goes.
    pub grabbed: bool,
}

/// Everything the app shows and remembers, apart from how it is drawn.
pub struct AppState {
    pub scene: Scene,
    /// The scene as loaded (the reset button returns to it).
    pub base_scene: Scene,
    pub source: Source,
    /// Scenes opened so far (the views reset their zoom when it changes).
    pub scenes_opened: u64,
    pub time_s: f32,
    pub playing: bool,
    pub speed: f32,
    pub selected_light: usize,
    /// Where the probe is pinned, if anywhere.
    pub probe_at: Option<ProbeAt>,
    pub probe: Option<ProbeReport>,
    /// Turn the camera to the probe's surface point once the probe finds it (a double-click).
    pub focus_on_probe: bool,
    pub overlays: Vec<Overlay>,
    /// What the camera panel shows (a lesson step sets it).
    pub view: View,
    pub ab: Option<AbSplit>,
    pub lessons: Vec<Lesson>,
    pub lang: Lang,
    pub diagram: crate::diagrams::DiagramKind,
    pub settings: Settings,
    /// A problem to show (bad file, bad value); the last good scene stays.
    pub error: Option<AppError>,
    pub status: String,
    pub show_help: bool,
    /// Present mode (F5): the camera view, the map, the diagram and the lesson text, large, for a
    /// projector; everything else hidden.
    pub present: bool,
    /// The lesson list shown on start (the window only; tests and tools start without it).
    pub show_lesson_list: bool,
    /// In a lesson: show every panel, not only the ones the step names.
    pub show_all_panels: bool,
    /// The step's "Try this" prompt whose Apply button was pressed last (cleared by a new step).
    pub applied_try_this: Option<usize>,
    /// The probe whose ground truth was asked for in the probe panel: worked out for it (and
    /// again as the settings change) until the probe moves or another scene opens.
    pub probe_truth_asked: Option<ProbeAt>,
    /// Something changed: render again.
    pub dirty: bool,
    /// The view's ground truth, per pixel, once complete (kept while nothing it depends on changes).
    pub reference: Option<Vec<f32>>,
    /// The view's mean absolute error against its ground truth, once that is complete.
    pub mean_abs_error: Option<f32>,
    /// The ground truth at the probe, per light asked for: (light, samples averaged, samples in
    /// all). Asked for and not started yet counts as 0 done.
    pub probe_truth_progress: Vec<(usize, u32, u32)>,
    /// A student's homework shader open beside the scene (`open_homework`).
    pub homework: Option<homework::HomeworkState>,
    /// A class of homeworks open beside it (`open_class`): the class report's ranked findings
    /// and students, each a click from their homework.
    pub class: Option<class::ClassState>,
    /// The program that checks a class (`homework --class`): this one on the desktop; none in
    /// the page, which starts no processes.
    pub class_checker: Option<PathBuf>,
}

const DEFAULT_SCENE: &str = "assets/scenes/games202.toml";

impl AppState {
    /// The state a session starts in: the shipped lessons, the last scene (or the default one),
    /// and the last lesson step where `settings` remember one.
    pub fn new(settings: Settings) -> Self {
        let (lessons, lesson_error) = match lessons::load_all(&shipped_path("lessons")) {
            Ok(l) => (l, None),
            Err(e) => (Vec::new(), Some(AppError::new("could not load the lessons", e))),
        };
        let default_path = shipped_path(DEFAULT_SCENE);
        let mut error = lesson_error;
        let wanted = settings.last_scene.clone().unwrap_or_else(|| default_path.clone());
        let scene = match load_scene(&wanted, &[]) {
            Ok(s) => s,
            Err(e) => {
                error = Some(AppError::new("could not open the scene", e));
                match load_scene(&default_path, &[]) {
                    Ok(s) => s,
                    Err(e) => fallback_scene(&e.to_string()),
                }
            }
        };
        let source = Source::Scene(scene.path.clone().unwrap_or(default_path));
        let mut state = Self {
            base_scene: scene.clone(),
            scene,
            source,
            scenes_opened: 0,
            time_s: 0.0,
            playing: false,
            speed: 1.0,
            selected_light: 0,
            probe_at: None,
            probe: None,
            focus_on_probe: false,
            overlays: settings.overlays.clone(),
            view: View::Final,
            ab: None,
            lessons,
            lang: settings.lang,
            diagram: crate::diagrams::DiagramKind::PcssTriangles,
            settings,
            error,
            status: String::new(),
            show_help: false,
            present: false,
            show_lesson_list: false,
            show_all_panels: false,
            applied_try_this: None,
            probe_truth_asked: None,
            dirty: true,
            reference: None,
            mean_abs_error: None,
            probe_truth_progress: Vec::new(),
            homework: None,
            class: None,
            class_checker: class::checker(),
        };
        if let Some((id, step)) = state.settings.last_lesson.clone()
            && let Some(index) = state.lessons.iter().position(|l| l.id == id)
        {
            state.go_to_step(index, step);
        }
        state
    }

    /// Replace the scene, keeping the old one if the new one fails.
    pub fn open(&mut self, path: &Path) {
        let is_obj = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("obj"));
        let loaded =
            if is_obj { scene_for_obj(path) } else { load_scene(path, &[]).map_err(|e| e.to_string()) };
        match loaded {
            Ok(scene) => {
                // A scene that shows nothing says so (the CLI prints the same warnings).
                let warnings = scene.warnings(0.0, 16.0 / 9.0);
                self.homework = None;
                self.show_lesson_list = false;
                self.set_fresh_scene(scene, Source::Scene(path.to_path_buf()));
                self.settings.last_scene =
                    (!is_obj && !crate::files::is_handed_over(path)).then(|| path.to_path_buf());
                self.settings.last_lesson = None;
                // The shipped scenes are listed anyway; anything else is a recent file.
                let shipped = std::fs::canonicalize(shipped_path("assets/scenes")).ok();
                let canonical = std::fs::canonicalize(path).ok();
                if canonical.zip(shipped).is_none_or(|(p, dir)| p.parent() != Some(dir.as_path())) {
                    self.settings.remember_file(path);
                }
                self.error = None;
                self.status = format!("{} {}", crate::i18n::tr(self.lang, "opened"), path.display());
                if !warnings.is_empty() {
                    let warning = crate::i18n::tr(self.lang, "warning");
                    self.status = format!("{} · {warning}: {}", self.status, warnings.join(" · "));
                }
            }
            Err(e) => self.error = Some(AppError::new("could not open the scene", e)),
        }
    }

    /// A scene opened anew starts clean: nothing of the last one's probe, overlays, view or zoom.
    fn set_fresh_scene(&mut self, scene: Scene, source: Source) {
        self.set_scene(scene, source);
        self.probe_at = None;
        self.overlays.clear();
        self.view = View::Final;
        self.scenes_opened += 1;
    }

    fn set_scene(&mut self, scene: Scene, source: Source) {
        self.base_scene = scene.clone();
        self.scene = scene;
        self.source = source;
        self.selected_light = self.selected_light.min(self.scene.lights.len().saturating_sub(1));
        self.probe = None;
        self.probe_truth_asked = None;
        self.mark_dirty();
    }

    pub fn mark_dirty(&mut self) {
        self.dirty = true;
        self.reference = None;
    }

    /// Back to the scene (or lesson step) as loaded.
    pub fn reset(&mut self) {
        self.scene = self.base_scene.clone();
        self.mark_dirty();
    }

    pub fn reset_camera(&mut self) {
        self.scene.camera = self.base_scene.camera;
        self.mark_dirty();
    }

    /// Show step `step` of lesson `lesson`: its scene, time, overlays, probe and diagram.
    pub fn go_to_step(&mut self, lesson: usize, step: usize) {
        let Some(l) = self.lessons.get(lesson) else { return };
        let step = step.min(l.steps.len().saturating_sub(1));
        let s = l.steps[step].clone();
        let id = l.id.clone();
        match s.scene() {
            Ok(scene) => {
                self.homework = None;
                self.set_scene(scene, Source::Lesson { lesson, step });
                self.time_s = s.time_s;
                self.playing = s.play;
                self.overlays = s.overlays.clone();
                self.view = s.view;
                self.selected_light = s.light;
                self.probe_at = s.probe.map(|[x, y]| ProbeAt::LessonFrame(x, y));
                if let Some(d) = s.diagram {
                    self.diagram = d;
                }
                self.settings.last_lesson = Some((id, step));
                self.applied_try_this = None;
                // A step that checks a homework opens it as a student's shader would be.
                if let Some(hw) = &s.homework {
                    self.homework = Some(homework::HomeworkState::open(
                        &hw.fragment,
                        hw.shadow_fragment.as_deref(),
                        None,
                    ));
                }
                // However the lesson was opened (list, picker, arrow keys), the start list is done.
                self.show_lesson_list = false;
                self.error = None;
            }
            Err(e) => {
                let detail = format!("{}: step {}: {e}", l.path.display(), step + 1);
                self.error = Some(AppError::new("could not show this lesson step", detail));
            }
        }
    }

    /// Apply the current step's "Try this" prompt `index`: the step's settings with the prompt's
    /// changes on top, keeping the camera and the probe where the student has them.
    pub fn apply_try_this(&mut self, index: usize) {
        let Some((lesson, step, step_index)) = self.current_step() else { return };
        let (path, step) = (lesson.path.clone(), step.clone());
        let Some(prompt) = step.try_this.get(index) else { return };
        match step.scene_with_try_this(index) {
            Ok(mut scene) => {
                scene.camera = self.scene.camera;
                self.scene = scene;
                self.time_s = prompt.time_s.unwrap_or(step.time_s);
                // A prompt that names a moment shows that moment, not one playing past it.
                if prompt.time_s.is_some() {
                    self.playing = false;
                }
                self.view = prompt.view.unwrap_or(step.view);
                self.applied_try_this = Some(index);
                self.error = None;
                self.mark_dirty();
            }
            Err(e) => {
                let detail =
                    format!("{}: step {}: try this {}: {e}", path.display(), step_index + 1, index + 1);
                self.error = Some(AppError::new("could not apply this prompt", detail));
            }
        }
    }

    /// Undo an applied prompt: the step's own settings, camera and probe kept.
    pub fn back_to_step_settings(&mut self) {
        let Some((_, step, _)) = self.current_step() else { return };
        let (time_s, view, play) = (step.time_s, step.view, step.play);
        let camera = self.scene.camera;
        self.scene = self.base_scene.clone();
        self.scene.camera = camera;
        (self.time_s, self.view, self.playing, self.applied_try_this) = (time_s, view, play, None);
        self.mark_dirty();
    }

    /// What differs from the current step's own settings (camera and probe aside), as the
    /// inspector names it; empty where nothing does. The text's fixed figures and sentences
    /// describe the step as set.
    pub fn changed_from_step(&self) -> Vec<&'static str> {
        let Some((_, step, _)) = self.current_step() else { return Vec::new() };
        let (now, base) = (&self.scene, &self.base_scene);
        let mut changed = Vec::new();
        if now.shadow != base.shadow {
            changed.push("shadow settings");
        }
        if now.lights != base.lights {
            changed.push("lights");
        }
        let same_object = |a: &crate::scene::Object, b: &crate::scene::Object| {
            (a.translate, a.rotate_deg, a.scale, a.spin_deg_per_s, a.color)
                == (b.translate, b.rotate_deg, b.scale, b.spin_deg_per_s, b.color)
        };
        if now.objects.len() != base.objects.len()
            || now.objects.iter().zip(&base.objects).any(|(a, b)| !same_object(a, b))
            || now.ambient != base.ambient
        {
            changed.push("objects");
        }
        if self.time_s != step.time_s || self.playing != step.play {
            changed.push("time (s)");
        }
        if self.view != step.view {
            changed.push("view");
        }
        changed
    }

    /// Step forward (+1) or back (-1) through the lessons.
    pub fn step_lesson(&mut self, delta: i32) {
        let (lesson, step) = match self.source {
            Source::Lesson { lesson, step } => (lesson, step),
            Source::Scene(_) => {
                if !self.lessons.is_empty() {
                    self.go_to_step(0, 0);
                }
                return;
            }
        };
        let steps = self.lessons[lesson].steps.len();
        if delta > 0 {
            if step + 1 < steps {
                self.go_to_step(lesson, step + 1);
            } else if lesson + 1 < self.lessons.len() {
                self.go_to_step(lesson + 1, 0);
            }
        } else if step > 0 {
            self.go_to_step(lesson, step - 1);
        } else if lesson > 0 {
            let last = self.lessons[lesson - 1].steps.len().saturating_sub(1);
            self.go_to_step(lesson - 1, last);
        }
    }

    pub fn current_step(&self) -> Option<(&Lesson, &lessons::Step, usize)> {
        match self.source {
            Source::Lesson { lesson, step } => {
                self.lessons.get(lesson).and_then(|l| l.steps.get(step).map(|s| (l, s, step)))
            }
            Source::Scene(_) => None,
        }
    }

    /// Whether `panel` is shown: everything outside lessons, the step's panels inside one.
    pub fn panel_visible(&self, panel: lessons::Panel) -> bool {
        match self.current_step() {
            Some((_, step, _)) if !self.show_all_panels => step.panels.contains(&panel),
            _ => match panel {
                lessons::Panel::KernelPlot => self.settings.show_kernel_plot,
                _ => true,
            },
        }
    }

    pub fn probe_report(&self) -> Option<&ProbeReport> {
        self.probe.as_ref()
    }

    /// Work out the ground truth at the pinned probe for the selected light (the probe panel's
    /// button); it follows the settings until the probe moves.
    pub fn ask_probe_truth(&mut self) {
        if self.probe_at.is_some() {
            self.probe_truth_asked = self.probe_at;
            // A new job with the ground truth added; whatever else the views have stays.
            self.dirty = true;
        }
    }

    /// The lights whose ground truth at the probe the next render works out: those the current
    /// step quotes `{probe.visibility_reference}` for, and the selected one where the probe
    /// panel asked for it.
    pub fn probe_truth_lights(&self) -> Vec<usize> {
        let mut lights = match self.current_step() {
            Some((_, step, _)) => step.quoted_lights("visibility_reference"),
            None => Vec::new(),
        };
        if self.probe_truth_asked.is_some() && self.probe_truth_asked == self.probe_at {
            lights.push(self.selected_light);
        }
        lights.retain(|&l| l < self.scene.lights.len());
        lights.sort_unstable();
        lights.dedup();
        lights
    }

    pub fn camera(&self) -> &Camera {
        &self.scene.camera
    }

    /// The ground truth at the probe for `light` as it accumulates: (samples averaged, samples in
    /// all); None where it was not asked for.
    pub fn probe_reference_progress(&self, light: usize) -> Option<(u32, u32)> {
        self.probe_truth_progress.iter().find(|(l, ..)| *l == light).map(|&(_, done, total)| (done, total))
    }

    /// What the lesson text's live numbers are filled from: the probe on screen and the view's
    /// own numbers (its mean error against the ground truth, once that is complete).
    pub fn live_sources(&self) -> lessons::live::Sources<'_> {
        let frame =
            lessons::live::FrameValues { mean_abs_error: self.reference.as_ref().and(self.mean_abs_error) };
        lessons::live::Sources { probe: self.probe.as_ref(), frame }
    }

    /// Scene time advances by `dt_s` of wall-clock time times the speed while playing. A stall
    /// (window dragged, machine asleep) does not jump the scene; past the end of the time range
    /// playback starts again from 0, so a demo left running keeps moving.
    pub fn advance_playback(&mut self, dt_s: f32) {
        if self.playing {
            self.time_s = (self.time_s + dt_s.min(0.5) * self.speed).rem_euclid(PLAYBACK_RANGE_S);
            self.reference = None;
            self.dirty = true;
        }
    }
}

/// The time range of playback and of the time slider, seconds (playback loops over it).
pub const PLAYBACK_RANGE_S: f32 = 60.0;

/// A minimal scene for when even the shipped scene is missing.
fn fallback_scene(why: &str) -> Scene {
    let text = "[camera]\nposition = [4.0, 3.0, 4.0]\n[[object]]\nmesh = \"cube\"\n[[light]]\nkind = \"directional\"\nposition = [2.0, 6.0, 3.0]\nextent = 4.0\nfar = 20.0\n";
    match parse_scene_str(text, Path::new("."), "<built-in>", &[]) {
        Ok(scene) => scene,
        Err(e) => panic!("the built-in scene must parse ({e}); loading the shipped scene failed: {why}"),
    }
}

/// A problem the status bar shows: what failed, in the reader's language, and the details
/// (file, line, key) as the command line prints them.
#[derive(Clone, Debug, PartialEq)]
pub struct AppError {
    /// English key of the headline (translated by `crate::i18n`).
    pub what: &'static str,
    pub detail: String,
}

impl AppError {
    pub fn new(what: &'static str, detail: impl std::fmt::Display) -> Self {
        Self { what, detail: detail.to_string() }
    }
}

impl std::fmt::Display for AppError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.what, self.detail)
    }
}

/// Where the probe is pinned.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ProbeAt {
    /// A point of the camera view as fractions of its width and height (a click; survives resizing).
    View(f32, f32),
    /// A lesson step's probe: a pixel of the lesson's own frame (`lessons::PROBE_FRAME`), probed
    /// in that frame, so the numbers are those of `shadowlab probe --lesson` and of the slides,
    /// whatever the view's size and shape. The marker goes where that surface point appears.
    LessonFrame(u32, u32),
}

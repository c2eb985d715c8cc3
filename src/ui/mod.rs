//! The inspector app: the camera view beside the light's shadow map, live parameters, the pixel
//! probe with its samples drawn on the map, overlays, lessons and diagrams.

mod bars;
mod dialog;
mod inspector;
pub mod launch;
mod lesson_panel;
mod panels;
mod rendering;
mod screenshots;
mod settings;
mod view_panels;
mod window;
mod worker;

pub use inspector::{control_label, value_label};
pub use panels::DIAGRAM_MIN_TEXT_PT;
pub use rendering::PLAYBACK_RANGE_S;
pub use settings::Settings;
pub use window::{
    clear_paints_panels, configure_wgpu, display_available, run, ui_painter, window_options,
    window_render_options,
};

use crate::i18n::Lang;
use crate::lessons::{self, Lesson};
use crate::probe::ProbeReport;
use crate::render::Analysis;
use crate::scene::{Camera, Scene, Technique, load_scene, parse_scene_str};
use crate::views::View;
use crate::views::overlays::Overlay;
use rendering::{Shown, Submitted};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use worker::RenderWorker;

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

pub struct ShadowlabApp {
    /// Renders off the UI thread (None where no GPU device could be had).
    worker: Option<RenderWorker>,
    /// What the views show: the last finished render.
    shown: Shown,
    /// The job the views wait for, and the newest one shown.
    submitted: Submitted,
    shown_job: u64,
    frames_shown: u64,
    /// Wall-clock time of the last UI frame (playback advances by it).
    last_tick: Option<std::time::Instant>,
    /// Why there is no GPU view (shown in place of the views).
    gpu_error: Option<String>,
    pub scene: Scene,
    /// The scene as loaded (the reset button returns to it).
    base_scene: Scene,
    pub source: Source,
    pub time_s: f32,
    pub playing: bool,
    pub speed: f32,
    pub selected_light: usize,
    /// Where the probe is pinned, if anywhere.
    pub probe_at: Option<ProbeAt>,
    pub probe: Option<ProbeReport>,
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
    /// Point the camera at the probe's surface point once the probe is computed (double-click).
    focus_on_probe: bool,
    /// The probe whose ground truth was asked for in the probe panel: worked out for it (and
    /// again as the settings change) until the probe moves or another scene opens.
    probe_truth_asked: Option<ProbeAt>,
    /// Something changed: render again.
    dirty: bool,
    /// The user is dragging in a view: render previews.
    interacting: bool,
    /// Previews render at 1/preview_divisor of the view's width and height (2..=4, adapted to
    /// how long they take).
    preview_divisor: u32,
    analysis: Option<Analysis>,
    reference: Option<Vec<f32>>,
    view_state: view_panels::ViewState,
    panel_state: panels::PanelState,
    open_path: String,
    /// The Open dialog, while it is up.
    open_dialog: Option<dialog::OpenDialog>,
    /// Give the path box the keyboard on the next frame (no dialog here).
    focus_path_box: bool,
    screenshot: Arc<Mutex<Option<Arc<egui::ColorImage>>>>,
    screenshot_pending: bool,
}

const DEFAULT_SCENE: &str = "assets/scenes/games202.toml";

pub use crate::shipped_path;

/// A scene around one OBJ file: the model on a floor under a directional light, scaled to fit.
pub fn scene_for_obj(path: &Path) -> Result<Scene, String> {
    let name = path.file_name().map(|n| n.to_string_lossy().to_string()).unwrap_or_default();
    let dir = path.parent().unwrap_or(Path::new("."));
    let mesh = crate::scene::mesh::load_obj(path).map_err(|e| e.to_string())?;
    let (lo, hi) = mesh.bounds();
    let extent = (hi - lo).max_element().max(1e-6);
    let scale = 10.0 / extent;
    let lift = -lo.y * scale;
    // The light's frustum fitted to the model and its shadow: the model's footprint (half its
    // XZ diagonal from the origin) plus how far its top's shadow reaches along the light, with a
    // 15% margin. The light shines from (10, 40, 20) towards the origin.
    let size = (hi - lo) * scale;
    let centre_xz = ((lo + hi) * 0.5 * scale).truncate();
    let footprint = centre_xz.length() + 0.5 * (size.x * size.x + size.z * size.z).sqrt();
    let light_dir = glam::Vec3::new(10.0, 40.0, 20.0).normalize();
    let reach = size.y * (light_dir.x * light_dir.x + light_dir.z * light_dir.z).sqrt() / light_dir.y;
    let light_extent = 1.15 * (footprint + reach);
    let text = format!(
        r#"[camera]
position = [18.0, 14.0, 18.0]
target = [0.0, 4.0, 0.0]
fov_deg = 50.0
[[object]]
name = "floor"
name_zh = "地面"
mesh = "plane"
scale = [60.0, 1.0, 60.0]
[[object]]
name = {name:?}
mesh = {name:?}
scale = {scale}
translate = [0.0, {lift}, 0.0]
[[light]]
kind = "directional"
position = [10.0, 40.0, 20.0]
extent = {light_extent}
far = 120.0
width = 2.0
"#
    );
    parse_scene_str(&text, dir, &path.display().to_string(), &[]).map_err(|e| e.to_string())
}

impl ShadowlabApp {
    pub fn new(cc: &eframe::CreationContext<'_>) -> Self {
        let settings: Settings =
            cc.storage.and_then(|s| eframe::get_value(s, settings::STORAGE_KEY)).unwrap_or_default();
        install_cjk_font(&cc.egui_ctx);
        cc.egui_ctx.set_visuals(egui::Visuals::dark());
        let (worker, gpu_error) = spawn_worker(cc);
        let mut app = Self::with_settings(worker, gpu_error, settings);
        // A first start (or one that ended outside a lesson) offers the lessons.
        app.show_lesson_list = app.current_step().is_none();
        app
    }

    fn with_settings(worker: Option<RenderWorker>, gpu_error: Option<String>, settings: Settings) -> Self {
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
        let mut app = Self {
            worker,
            shown: Shown::default(),
            submitted: Submitted::default(),
            shown_job: 0,
            frames_shown: 0,
            last_tick: None,
            gpu_error,
            base_scene: scene.clone(),
            scene,
            source,
            time_s: 0.0,
            playing: false,
            speed: 1.0,
            selected_light: 0,
            probe_at: None,
            probe: None,
            overlays: settings.overlays.clone(),
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
            focus_on_probe: false,
            probe_truth_asked: None,
            dirty: true,
            interacting: false,
            preview_divisor: 2,
            analysis: None,
            reference: None,
            view_state: Default::default(),
            view: View::Final,
            panel_state: Default::default(),
            open_path: String::new(),
            open_dialog: None,
            focus_path_box: false,
            screenshot: Arc::new(Mutex::new(None)),
            screenshot_pending: false,
        };
        if let Some((id, step)) = app.settings.last_lesson.clone()
            && let Some(index) = app.lessons.iter().position(|l| l.id == id)
        {
            app.go_to_step(index, step);
        }
        app
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
                self.set_scene(scene, Source::Scene(path.to_path_buf()));
                // A new scene starts clean: nothing of the last one's probe, overlays, view or zoom.
                self.probe_at = None;
                self.overlays.clear();
                self.view = View::Final;
                self.view_state.reset_zoom();
                self.settings.last_scene = (!is_obj).then(|| path.to_path_buf());
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
    /// Size of the smallest text in the diagram on screen, points (`None` before one is drawn).
    pub fn smallest_diagram_text_pt(&self) -> Option<f32> {
        self.panel_state.smallest_diagram_text_pt
    }

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

    /// What the lesson text's live numbers are filled from: the probe on screen and the view's
    /// own numbers (its mean error against the ground truth, once that is complete).
    pub fn live_sources(&self) -> lessons::live::Sources<'_> {
        let frame = lessons::live::FrameValues {
            mean_abs_error: self.reference.as_ref().and(self.shown.mean_abs_error),
        };
        lessons::live::Sources { probe: self.probe.as_ref(), frame }
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
    fn probe_truth_lights(&self) -> Vec<usize> {
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

    /// Why there is no GPU view, or the last rendering error, if any.
    pub fn gpu_problem(&self) -> Option<String> {
        self.gpu_error.clone().or_else(|| self.error.as_ref().map(AppError::to_string))
    }

    /// The camera view as last rendered (for screenshots and tests).
    pub fn camera_image(&self) -> Option<image::RgbaImage> {
        self.shown.color.clone()
    }

    /// The lines under the camera view: the view's legend, then the overlays' (as painted).
    pub fn legend_lines(&self) -> Vec<String> {
        self.view_state.legend_lines()
    }

    /// The overlays as last composed over the camera view (translucent), if any is on.
    pub fn overlay_image(&self) -> Option<&image::RgbaImage> {
        self.view_state.overlay_picture.as_ref()
    }

    /// The B side of the A/B split as last rendered, when the split is on.
    pub fn camera_image_b(&self) -> Option<image::RgbaImage> {
        self.ab.as_ref()?;
        self.shown.color_b.clone()
    }

    fn handle_keys(&mut self, ctx: &egui::Context) {
        if ctx.egui_wants_keyboard_input() {
            return;
        }
        let (right, left, space, s, f1, r) = ctx.input(|i| {
            (
                i.key_pressed(egui::Key::ArrowRight),
                i.key_pressed(egui::Key::ArrowLeft),
                i.key_pressed(egui::Key::Space),
                i.key_pressed(egui::Key::S),
                i.key_pressed(egui::Key::F1),
                i.key_pressed(egui::Key::R),
            )
        });
        if ctx.input(|i| i.key_pressed(egui::Key::F5)) {
            self.present = !self.present;
        }
        if ctx.input(|i| i.key_pressed(egui::Key::Escape)) {
            self.present = false;
            self.show_lesson_list = false;
        }
        if right {
            self.step_lesson(1);
        }
        if left {
            self.step_lesson(-1);
        }
        if space {
            self.playing = !self.playing;
        }
        if s {
            self.request_screenshot(ctx);
        }
        if f1 {
            self.show_help = !self.show_help;
        }
        if r {
            self.reset_camera();
        }
    }

    fn handle_dropped_files(&mut self, ctx: &egui::Context) {
        let dropped: Vec<PathBuf> =
            ctx.input(|i| i.raw.dropped_files.iter().map(|f| f.path().to_path_buf()).collect());
        if let Some(path) = dropped.last() {
            self.open_any(path);
        }
    }

    /// Open what the path box, a drop or the dialog names: a scene or lesson (.toml), a model
    /// (.obj), or a shipped lesson's id. A bad path keeps what is shown and says why.
    pub fn open_any(&mut self, path: &Path) {
        // Scenes and models through `open` (loaded once, the old scene kept if this one fails);
        // lesson files and lesson ids as the command line takes them.
        if path.exists() && !launch::is_lesson_file(path) {
            return self.open(path);
        }
        match launch::resolve(Some(&path.to_string_lossy()), None, None, None) {
            Ok(launch) => self.apply_launch(launch),
            Err(e) => self.error = Some(AppError::new("could not open the scene", e)),
        }
    }

    /// Show the desktop's Open dialog; without one, point at the path box.
    pub fn browse(&mut self, ctx: &egui::Context) {
        if self.open_dialog.is_some() {
            return;
        }
        let folder = std::path::absolute(shipped_path("assets/scenes")).unwrap_or_default();
        let ctx = ctx.clone();
        self.open_dialog = Some(dialog::OpenDialog::open(folder, move || ctx.request_repaint()));
    }

    /// Act on the dialog's answer once it is in.
    fn poll_open_dialog(&mut self) {
        let Some(outcome) = self.open_dialog.as_ref().and_then(dialog::OpenDialog::poll) else { return };
        self.open_dialog = None;
        match outcome {
            dialog::DialogOutcome::Picked(path) => self.open_any(&path),
            dialog::DialogOutcome::Cancelled => {}
            dialog::DialogOutcome::Unavailable => {
                self.status = crate::i18n::tr(
                    self.lang,
                    "no file dialog on this desktop (no xdg-desktop-portal): type a path in the box, or drop a file on the window",
                )
                .into();
                self.focus_path_box = true;
            }
        }
    }

    /// The Open dialog is up.
    pub fn browsing(&self) -> bool {
        self.open_dialog.is_some()
    }
}

/// The render worker, waking egui whenever it has news: on a device of eframe's adapter where
/// the window paints with wgpu, on one of its own where it paints with OpenGL.
fn spawn_worker(cc: &eframe::CreationContext<'_>) -> (Option<RenderWorker>, Option<String>) {
    let ctx = cc.egui_ctx.clone();
    let wake = move || ctx.request_repaint();
    let adapter = match cc.wgpu_render_state.as_ref() {
        Some(rs) => Ok(rs.adapter.clone()),
        None => crate::render::headless_adapter().map_err(|e| e.to_string()),
    };
    match adapter {
        Ok(adapter) => (Some(RenderWorker::spawn(adapter, wake)), None),
        Err(e) => (None, Some(e)),
    }
}

/// Where some widgets were last drawn, for tools that drive the app (`bench --app --window`).
pub const LANDMARK_LIGHT_WIDTH: &str = "light-width slider";
pub const LANDMARK_SHADOW_MAP: &str = "shadow-map picture";
pub const LANDMARK_CAMERA_VIEW: &str = "camera view";

fn set_landmark(ctx: &egui::Context, name: &'static str, rect: egui::Rect) {
    ctx.data_mut(|d| d.insert_temp(egui::Id::NULL.with(("landmark", name)), rect));
}

/// The rectangle a landmark widget occupied in the last frame that drew it.
pub fn landmark(ctx: &egui::Context, name: &'static str) -> Option<egui::Rect> {
    ctx.data(|d| d.get_temp::<egui::Rect>(egui::Id::NULL.with(("landmark", name))))
}

/// A minimal scene for when even the shipped scene is missing.
fn fallback_scene(why: &str) -> Scene {
    let text = "[camera]\nposition = [4.0, 3.0, 4.0]\n[[object]]\nmesh = \"cube\"\n[[light]]\nkind = \"directional\"\nposition = [2.0, 6.0, 3.0]\nextent = 4.0\nfar = 20.0\n";
    match parse_scene_str(text, Path::new("."), "<built-in>", &[]) {
        Ok(scene) => scene,
        Err(e) => panic!("the built-in scene must parse ({e}); loading the shipped scene failed: {why}"),
    }
}

fn install_cjk_font(ctx: &egui::Context) {
    let Some(cjk) = crate::diagrams::system_cjk_font() else { return };
    let mut fonts = egui::FontDefinitions::default();
    // The same face the diagrams and slides fall back to (Simplified Chinese in a collection).
    let mut data = egui::FontData::from_static(cjk.bytes.as_slice());
    data.index = cjk.face_index;
    fonts.font_data.insert("cjk".to_owned(), Arc::new(data));
    for family in [egui::FontFamily::Proportional, egui::FontFamily::Monospace] {
        fonts.families.entry(family).or_default().push("cjk".to_owned());
    }
    ctx.set_fonts(fonts);
}

impl eframe::App for ShadowlabApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        let ctx = ui.ctx().clone();
        self.handle_keys(&ctx);
        self.handle_dropped_files(&ctx);
        self.poll_open_dialog();
        self.save_screenshot_if_ready();
        self.advance_time(std::time::Instant::now());
        self.receive_renders(&ctx);
        // Dragging a slider (or anything else) asks for previews until it is let go.
        self.interacting = ctx.dragged_id().is_some();
        if self.playing {
            ctx.request_repaint();
        } else if self.render_pending() {
            // Finished frames wake the UI themselves; this only keeps "rendering..." counting.
            // (Repainting flat out would take the CPU a software rasteriser renders with.)
            ctx.request_repaint_after(std::time::Duration::from_millis(250));
        }
        if self.screenshot_pending {
            ctx.request_repaint();
        }
        let screen = ui.max_rect();
        if !self.present {
            egui::Panel::top("top").show(ui, |ui| self.top_bar(ui));
            egui::Panel::bottom("status").show(ui, |ui| self.status_bar(ui));
            // Panel sizes are kept between runs, but never beyond a share of this window: a size
            // saved in a large window (or shrunk in a tiny one) must not crowd out the views.
            let inspector = egui::Panel::left("inspector")
                .resizable(true)
                .default_size(self.settings.inspector_width.clamp(220.0, (screen.width() * 0.3).max(220.0)))
                .max_size((screen.width() * 0.35).max(220.0))
                .show(ui, |ui| {
                    egui::ScrollArea::vertical().show(ui, |ui| inspector::show(self, ui));
                });
            self.settings.inspector_width = inspector.response.rect.width();
        }
        if self.current_step().is_some() {
            let panel = if self.present {
                // A third of the screen for the text, at a size the back row can read.
                egui::Panel::right("lesson (present)")
                    .resizable(false)
                    .exact_size((screen.width() * 0.3).max(360.0))
            } else {
                egui::Panel::right("lesson")
                    .resizable(true)
                    .default_size(320.0)
                    .max_size((screen.width() * 0.35).max(240.0))
            };
            panel.show(ui, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| lesson_panel::show(self, ui));
            });
        }
        if self.panel_visible(lessons::Panel::Diagram) || self.panel_visible(lessons::Panel::KernelPlot) {
            if self.present {
                egui::Panel::bottom("diagrams (present)")
                    .resizable(false)
                    .exact_size(screen.height() * 0.4)
                    .show(ui, |ui| panels::show_bottom(self, ui));
            } else {
                let diagrams = egui::Panel::bottom("diagrams")
                    .resizable(true)
                    .default_size(
                        // A third of the window at most: 300 at 1600x900 (14 pt diagram text),
                        // less on a smaller screen, where the camera view comes first.
                        self.settings.diagram_height.clamp(140.0, (screen.height() * 0.34).max(140.0)),
                    )
                    .max_size((screen.height() * 0.45).max(140.0))
                    .show(ui, |ui| panels::show_bottom(self, ui));
                self.settings.diagram_height = diagrams.response.rect.height();
            }
        }
        egui::CentralPanel::default().show(ui, |ui| view_panels::show(self, ui));
        self.help_window(&ctx);
        self.lesson_list(&ctx);
        if self.dirty {
            ctx.request_repaint();
        }
    }

    fn clear_color(&self, _visuals: &egui::Visuals) -> [f32; 4] {
        window::window_clear_color()
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        self.settings.overlays = self.overlays.clone();
        self.settings.lang = self.lang;
        eframe::set_value(storage, settings::STORAGE_KEY, &self.settings);
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

/// Build the app for tests and tools, with explicit settings (no storage).
pub fn app_for_test(cc: &eframe::CreationContext<'_>, settings: Settings) -> ShadowlabApp {
    install_cjk_font(&cc.egui_ctx);
    let (worker, gpu_error) = spawn_worker(cc);
    ShadowlabApp::with_settings(worker, gpu_error, settings)
}

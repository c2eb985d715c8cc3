//! The inspector app: the camera view beside the light's shadow map, live parameters, the pixel
//! probe with its samples drawn on the map, overlays, lessons and diagrams.

mod bars;
mod camera_marks;
mod camera_panel;
mod camera_pictures;
mod class_panel;
#[cfg(not(target_arch = "wasm32"))]
mod dialog;
mod homework_panel;
mod homework_view;
#[cfg(feature = "test-hooks")]
mod hooks;
mod inspector;
mod lesson_panel;
mod map_panel;
mod memory;
#[cfg(target_arch = "wasm32")]
mod page;
#[cfg(target_arch = "wasm32")]
mod page_files;
mod panels;
mod probe_panel;
mod rendering;
mod screenshots;
mod view_panels;
mod window;

pub use crate::app::launch;
pub use crate::app::{
    AbSplit, AppError, AppState, PLAYBACK_RANGE_S, ProbeAt, Settings, Source, scene_for_obj,
};
#[cfg(feature = "test-hooks")]
pub use hooks::{
    LANDMARK_CAMERA_VIEW, LANDMARK_LIGHT_WIDTH, LANDMARK_SHADOW_MAP, app_for_test, app_with_scheduler,
    landmark,
};
pub use inspector::{control_label, value_label};
pub use memory::{TrimStats, return_free_pages, trim_stats};
pub use panels::DIAGRAM_MIN_TEXT_PT;
pub use window::{clear_paints_panels, configure_wgpu, window_render_options};
#[cfg(not(target_arch = "wasm32"))]
pub use window::{display_available, run, ui_painter, window_options};

#[cfg(not(target_arch = "wasm32"))]
use crate::app::scheduler::WorkerThread;
use crate::app::scheduler::{FrameDriven, RenderScheduler};
use crate::lessons;
#[cfg(not(target_arch = "wasm32"))]
use crate::shipped_path;
use std::sync::{Arc, Mutex};

/// The window: the app's state (`state`, which field access reads through to) and what only
/// drawing it needs: the render session, the panels that keep state of their own, the Open
/// dialog, screenshots.
pub struct ShadowlabApp {
    pub state: AppState,
    /// Rendering the views: the scheduler, what it sent, what is waited for.
    render: rendering::RenderSession,
    /// Wall-clock time of the last UI frame (playback advances by it).
    last_tick: Option<web_time::Instant>,
    camera_panel: camera_panel::CameraPanel,
    map_panel: map_panel::MapPanel,
    diagram_panel: panels::DiagramPanel,
    /// The top bar's path box.
    open_path: String,
    /// The Open dialog, while it is up.
    #[cfg(not(target_arch = "wasm32"))]
    open_dialog: Option<dialog::OpenDialog>,
    /// Give the path box the keyboard on the next frame (no dialog here).
    focus_path_box: bool,
    screenshot: Arc<Mutex<Option<Arc<egui::ColorImage>>>>,
    screenshot_pending: bool,
    /// When the homework's files were last looked at (they are watched a few times a second).
    homework_watched: Option<web_time::Instant>,
}

impl std::ops::Deref for ShadowlabApp {
    type Target = AppState;
    fn deref(&self) -> &AppState {
        &self.state
    }
}

impl std::ops::DerefMut for ShadowlabApp {
    fn deref_mut(&mut self) -> &mut AppState {
        &mut self.state
    }
}

impl ShadowlabApp {
    pub fn new(cc: &eframe::CreationContext<'_>) -> Self {
        let settings: Settings = cc
            .storage
            .and_then(|s| eframe::get_value(s, crate::app::settings::STORAGE_KEY))
            .unwrap_or_default();
        install_cjk_font(&cc.egui_ctx);
        cc.egui_ctx.set_visuals(egui::Visuals::dark());
        let kind =
            if cfg!(target_arch = "wasm32") { SchedulerKind::FrameDriven } else { SchedulerKind::Thread };
        let (worker, gpu_error) = spawn_worker(cc, kind);
        let mut app = Self::with_settings(worker, gpu_error, settings);
        // A first start (or one that ended outside a lesson) offers the lessons.
        app.state.show_lesson_list = app.state.current_step().is_none();
        #[cfg(target_arch = "wasm32")]
        page::open_link(&mut app.state);
        app
    }

    fn with_settings(
        worker: Option<Box<dyn RenderScheduler>>,
        gpu_error: Option<String>,
        settings: Settings,
    ) -> Self {
        Self {
            state: AppState::new(settings),
            render: rendering::RenderSession::new(worker, gpu_error),
            last_tick: None,
            camera_panel: Default::default(),
            map_panel: Default::default(),
            diagram_panel: Default::default(),
            open_path: String::new(),
            #[cfg(not(target_arch = "wasm32"))]
            open_dialog: None,
            focus_path_box: false,
            screenshot: Arc::new(Mutex::new(None)),
            screenshot_pending: false,
            homework_watched: None,
        }
    }

    /// Size of the smallest text in the diagram on screen, points (`None` before one is drawn).
    pub fn smallest_diagram_text_pt(&self) -> Option<f32> {
        self.diagram_panel.smallest_diagram_text_pt
    }

    /// Why there is no GPU view, or the last rendering error, if any.
    pub fn gpu_problem(&self) -> Option<String> {
        self.render.gpu_error.clone().or_else(|| self.state.error.as_ref().map(AppError::to_string))
    }

    /// The camera view as last rendered (for screenshots and tests).
    pub fn camera_image(&self) -> Option<image::RgbaImage> {
        self.render.shown.color.clone()
    }

    /// The lines under the camera view: the view's legend, then the overlays' (as painted).
    pub fn legend_lines(&self) -> Vec<String> {
        self.camera_panel.legend_lines()
    }

    /// The overlays as last composed over the camera view (translucent), if any is on.
    pub fn overlay_image(&self) -> Option<&image::RgbaImage> {
        self.camera_panel.overlay_picture()
    }

    /// The B side of the A/B split as last rendered, when the split is on.
    pub fn camera_image_b(&self) -> Option<image::RgbaImage> {
        self.state.ab.as_ref()?;
        self.render.shown.color_b.clone()
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
            self.state.present = !self.state.present;
        }
        if ctx.input(|i| i.key_pressed(egui::Key::Escape)) {
            self.state.present = false;
            self.state.show_lesson_list = false;
        }
        if right {
            self.state.step_lesson(1);
        }
        if left {
            self.state.step_lesson(-1);
        }
        if space {
            self.state.playing = !self.state.playing;
        }
        if s {
            self.request_screenshot(ctx);
        }
        if f1 {
            self.state.show_help = !self.state.show_help;
        }
        if r {
            self.state.reset_camera();
        }
    }

    fn handle_dropped_files(&mut self, ctx: &egui::Context) {
        let dropped: Vec<egui::DroppedFileHandle> = ctx.input(|i| i.raw.dropped_files.clone());
        // A desktop drop gives paths; a page's gives bytes, read as they come and handed over.
        #[cfg(target_arch = "wasm32")]
        let arrived = {
            page_files::read(dropped, ctx.clone());
            page_files::take_arrived()
        };
        #[cfg(not(target_arch = "wasm32"))]
        let arrived =
            vec![dropped.iter().map(|f| f.path().to_path_buf()).collect::<Vec<std::path::PathBuf>>()];
        for files in arrived {
            self.state.open_files(&files);
        }
    }

    /// Show the desktop's Open dialog; without one, point at the path box.
    pub fn browse(&mut self, ctx: &egui::Context) {
        // A page has the browser's own dialog (what is picked arrives with the dropped files).
        #[cfg(target_arch = "wasm32")]
        page_files::pick(ctx);
        #[cfg(not(target_arch = "wasm32"))]
        if self.open_dialog.is_none() {
            let folder = std::path::absolute(shipped_path("assets/scenes")).unwrap_or_default();
            let ctx = ctx.clone();
            self.open_dialog = Some(dialog::OpenDialog::open(folder, move || ctx.request_repaint()));
        }
    }

    /// Act on the dialog's answer once it is in.
    #[cfg(not(target_arch = "wasm32"))]
    fn poll_open_dialog(&mut self) {
        let Some(outcome) = self.open_dialog.as_ref().and_then(dialog::OpenDialog::poll) else { return };
        self.open_dialog = None;
        match outcome {
            dialog::DialogOutcome::Picked(path) => self.state.open_any(&path),
            dialog::DialogOutcome::Cancelled => {}
            dialog::DialogOutcome::Unavailable => {
                let why = "no file dialog on this desktop (no xdg-desktop-portal): type a path in the box, or drop a file on the window";
                self.state.status = crate::i18n::tr(self.state.lang, why).into();
                self.focus_path_box = true;
            }
        }
    }

    /// The Open dialog is up (a page's is the browser's, not tracked).
    pub fn browsing(&self) -> bool {
        #[cfg(target_arch = "wasm32")]
        return false;
        #[cfg(not(target_arch = "wasm32"))]
        self.open_dialog.is_some()
    }
}

/// The render worker, waking egui whenever it has news: on a device of eframe's adapter where
/// the window paints with wgpu, on one of its own where it paints with OpenGL.
#[cfg(not(target_arch = "wasm32"))]
fn spawn_worker(
    cc: &eframe::CreationContext<'_>,
    kind: SchedulerKind,
) -> (Option<Box<dyn RenderScheduler>>, Option<String>) {
    let ctx = cc.egui_ctx.clone();
    let wake = move || ctx.request_repaint();
    let adapter = match cc.wgpu_render_state.as_ref() {
        Some(rs) => Ok(rs.adapter.clone()),
        None => crate::render::headless_adapter().map_err(|e| e.to_string()),
    };
    match adapter {
        Ok(adapter) => {
            let scheduler: Box<dyn RenderScheduler> = match kind {
                SchedulerKind::Thread => Box::new(WorkerThread::spawn(adapter, wake)),
                SchedulerKind::FrameDriven => Box::new(FrameDriven::new(adapter)),
            };
            (Some(scheduler), None)
        }
        Err(e) => (None, Some(e)),
    }
}

/// A page's renderer: the frame-driven scheduler on eframe's own device (a browser's adapter gives
/// one device; there is no thread to give a worker).
#[cfg(target_arch = "wasm32")]
fn spawn_worker(
    cc: &eframe::CreationContext<'_>,
    _kind: SchedulerKind,
) -> (Option<Box<dyn RenderScheduler>>, Option<String>) {
    match cc.wgpu_render_state.as_ref() {
        Some(rs) => {
            let scheduler = FrameDriven::on_device(rs.adapter.clone(), rs.device.clone(), rs.queue.clone());
            (Some(Box::new(scheduler)), None)
        }
        None => (None, Some("this browser gave the page no WebGPU or WebGL2 device".into())),
    }
}

/// Which render scheduler the app runs (`crate::app::scheduler`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SchedulerKind {
    /// A render thread with a device of its own (the desktop app).
    Thread,
    /// Renders from the UI's frame callback, a stage per frame (the page; tested natively).
    FrameDriven,
}

fn install_cjk_font(ctx: &egui::Context) {
    // The same face the diagrams and slides fall back to: the system's (Simplified Chinese in a
    // collection), else the subset built in.
    let cjk = crate::diagrams::cjk_font();
    if !cjk.is_present() {
        return;
    }
    let mut fonts = egui::FontDefinitions::default();
    let mut data = egui::FontData::from_static(cjk.data());
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
        #[cfg(not(target_arch = "wasm32"))]
        self.poll_open_dialog();
        self.save_screenshot_if_ready();
        self.advance_time(web_time::Instant::now());
        self.watch_homework(&ctx);
        self.watch_class(&ctx);
        self.receive_renders(&ctx);
        memory::return_free_pages_now_and_then();
        #[cfg(target_arch = "wasm32")]
        {
            page::publish(self.render.frames_shown, &self.state);
            page::follow(&self.state);
        }
        // Dragging a slider (or anything else) asks for previews until it is let go.
        self.render.interacting = ctx.dragged_id().is_some();
        if self.state.playing || self.render.worker.as_ref().is_some_and(|w| w.needs_polling()) {
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
        if !self.state.present {
            egui::Panel::top("top").show(ui, |ui| self.top_bar(ui));
            egui::Panel::bottom("status").show(ui, |ui| self.status_bar(ui));
            // Panel sizes are kept between runs, but never beyond a share of this window: a size
            // saved in a large window (or shrunk in a tiny one) must not crowd out the views.
            let inspector = egui::Panel::left("inspector")
                .resizable(true)
                .default_size(
                    self.state.settings.inspector_width.clamp(220.0, (screen.width() * 0.3).max(220.0)),
                )
                .max_size((screen.width() * 0.35).max(220.0))
                .show(ui, |ui| {
                    egui::ScrollArea::vertical().show(ui, |ui| inspector::show(&mut self.state, ui));
                });
            self.state.settings.inspector_width = inspector.response.rect.width();
        }
        let class_shown =
            self.state.class.as_ref().is_some_and(|c| c.showing || self.state.homework.is_none());
        if self.state.current_step().is_none()
            && (self.state.homework.is_some() || class_shown)
            && !self.state.present
        {
            egui::Panel::right("homework")
                .resizable(true)
                .default_size(340.0)
                .max_size((screen.width() * 0.35).max(260.0))
                .show(ui, |ui| {
                    egui::ScrollArea::vertical().show(ui, |ui| {
                        if class_shown {
                            class_panel::show(&mut self.state, ui);
                        } else {
                            homework_panel::show(&mut self.state, ui);
                        }
                    });
                });
        }
        if self.state.current_step().is_some() {
            let panel = if self.state.present {
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
                egui::ScrollArea::vertical().show(ui, |ui| lesson_panel::show(&mut self.state, ui));
            });
        }
        if self.state.panel_visible(lessons::Panel::Diagram)
            || self.state.panel_visible(lessons::Panel::KernelPlot)
        {
            self.diagram_panel.picture_px = self.render.shown.size;
            if self.state.present {
                egui::Panel::bottom("diagrams (present)")
                    .resizable(false)
                    .exact_size(screen.height() * 0.4)
                    .show(ui, |ui| self.diagram_panel.ui(ui, &mut self.state));
            } else {
                let diagrams = egui::Panel::bottom("diagrams")
                    .resizable(true)
                    .default_size(
                        // A third of the window at most: 300 at 1600x900 (14 pt diagram text),
                        // less on a smaller screen, where the camera view comes first.
                        self.state.settings.diagram_height.clamp(140.0, (screen.height() * 0.34).max(140.0)),
                    )
                    .max_size((screen.height() * 0.45).max(140.0))
                    .show(ui, |ui| self.diagram_panel.ui(ui, &mut self.state));
                self.state.settings.diagram_height = diagrams.response.rect.height();
            }
        }
        egui::CentralPanel::default().show(ui, |ui| view_panels::show(self, ui));
        self.help_window(&ctx);
        self.lesson_list(&ctx);
        if self.state.dirty {
            ctx.request_repaint();
        }
    }

    fn clear_color(&self, _visuals: &egui::Visuals) -> [f32; 4] {
        window::window_clear_color()
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        self.state.settings.overlays = self.state.overlays.clone();
        self.state.settings.lang = self.state.lang;
        eframe::set_value(storage, crate::app::settings::STORAGE_KEY, &self.state.settings);
    }
}

//! What drives the app from outside, for the app tests and `shadowlab bench --app` only (the
//! `test-hooks` feature; the shipped app has none of it): the app built with settings and a
//! scheduler of one's choice, and where some widgets were last drawn.

use super::{SchedulerKind, Settings, ShadowlabApp, install_cjk_font, spawn_worker};

/// Landmarks: widgets whose rectangle a panel records as it draws them, so that a driver finds
/// them in a real window, where there is no accessibility tree to query.
pub const LANDMARK_LIGHT_WIDTH: &str = "light-width slider";
pub const LANDMARK_SHADOW_MAP: &str = "shadow-map picture";
pub const LANDMARK_CAMERA_VIEW: &str = "camera view";

pub(super) fn set_landmark(ctx: &egui::Context, name: &'static str, rect: egui::Rect) {
    ctx.data_mut(|d| d.insert_temp(egui::Id::NULL.with(("landmark", name)), rect));
}

/// The rectangle a landmark widget occupied in the last frame that drew it.
pub fn landmark(ctx: &egui::Context, name: &'static str) -> Option<egui::Rect> {
    ctx.data(|d| d.get_temp::<egui::Rect>(egui::Id::NULL.with(("landmark", name))))
}

/// The app with explicit settings (no storage) and the desktop's render thread.
pub fn app_for_test(cc: &eframe::CreationContext<'_>, settings: Settings) -> ShadowlabApp {
    app_with_scheduler(cc, settings, SchedulerKind::Thread)
}

/// [`app_for_test`] with the render scheduler of one's choice.
pub fn app_with_scheduler(
    cc: &eframe::CreationContext<'_>,
    settings: Settings,
    kind: SchedulerKind,
) -> ShadowlabApp {
    install_cjk_font(&cc.egui_ctx);
    let (worker, gpu_error) = spawn_worker(cc, kind);
    ShadowlabApp::with_settings(worker, gpu_error, settings)
}

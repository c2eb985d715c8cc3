//! The centre: the camera panel beside the shadow-map panel (resizable split), or, without a
//! GPU view, why there is none.

use super::ShadowlabApp;
use super::camera_marks::CameraPaint;
use super::camera_panel::CameraLayout;
use crate::browser::NoWebGpu;
use crate::i18n::tr;
use crate::views::View;
use egui::{Color32, Rect, Sense, Ui, pos2, vec2};

impl ShadowlabApp {
    /// Say why in place of the views, and render none: the page's device is WebGL2's, which
    /// the renderer cannot run on (the lessons, diagrams and panels need no GPU of their own).
    pub fn without_webgpu(&mut self, why: NoWebGpu) {
        self.render.worker = None;
        self.render.gpu_error = Some(why.reason().to_owned());
    }
}

/// In place of the views: why there are none (for a page without WebGPU, what works and which
/// browsers have it).
fn no_views(app: &ShadowlabApp, ui: &mut Ui) {
    let lang = app.state.lang;
    let why = app.render.gpu_error.as_deref().unwrap_or("unknown reason");
    let Some(no_webgpu) = NoWebGpu::from_reason(why) else {
        ui.centered_and_justified(|ui| ui.label(format!("{}: {}", tr(lang, "No GPU view"), tr(lang, why))));
        return;
    };
    ui.vertical_centered(|ui| {
        ui.add_space((ui.available_height() * 0.2).max(8.0));
        ui.set_max_width(ui.available_width().min(620.0));
        // Brighter than the panels' labels: this text stands in for the views.
        let heading = tr(lang, "The camera view and the shadow map need WebGPU");
        ui.label(egui::RichText::new(heading).heading().color(Color32::from_gray(230)));
        ui.add_space(10.0);
        for text in [
            no_webgpu.reason(),
            "The page runs on WebGL2 instead, which has no storage buffers or compute shaders, and shadowlab renders the views with both. The lessons, the diagrams and the panels work without them.",
            "For the views, open this page in a browser with WebGPU: Chrome or Edge 113 or later, Safari 26 or later, Firefox 141 or later on Windows.",
        ] {
            ui.label(egui::RichText::new(tr(lang, text)).size(15.0).color(Color32::from_gray(205)));
            ui.add_space(6.0);
        }
    });
}

/// The two view panels side by side; the render they show asked for at the camera picture's size.
pub fn show(app: &mut ShadowlabApp, ui: &mut Ui) {
    app.map_panel.follow_scene(app.state.scenes_opened);
    if app.render.worker.is_none() {
        no_views(app, ui);
        return;
    }
    let full = ui.available_rect_before_wrap();
    let show_map = app.state.panel_visible(crate::lessons::Panel::ShadowMap);
    let split = if show_map { app.state.settings.split.clamp(0.25, 0.85) } else { 1.0 };
    let divider_x = full.left() + full.width() * split;
    let left = Rect::from_min_max(full.min, pos2(divider_x - 3.0, full.bottom()));
    let map_rect = Rect::from_min_max(pos2(divider_x + 3.0, full.top()), full.max);
    let camera = CameraLayout::new(ui, &app.state, left);

    if show_map {
        // The split between the two views.
        let divider =
            Rect::from_min_max(pos2(divider_x - 3.0, full.top()), pos2(divider_x + 3.0, full.bottom()));
        let divider_response = ui.interact(divider, ui.scope_id().with("split"), Sense::drag());
        if divider_response.dragged() {
            app.state.settings.split = ((divider_x + divider_response.drag_delta().x - full.left())
                / full.width())
            .clamp(0.25, 0.85);
        }
        let divider_color = if divider_response.hovered() { Color32::GRAY } else { Color32::from_gray(60) };
        ui.painter().rect_filled(divider.shrink2(vec2(2.0, 0.0)), 0.0, divider_color);
    }
    app.schedule_render(camera.picture_px(ui.ctx().pixels_per_point()));
    let slow = app.render_is_slow();
    app.camera_panel.ui(ui, &camera, &mut app.state, &app.render.shown, slow);
    if show_map {
        app.map_panel.ui(ui, map_rect, &mut app.state, &app.render.shown);
    }
    ui.allocate_rect(full, Sense::hover());
}

impl ShadowlabApp {
    /// The view the camera panel shows now: the chosen one once it is worked out for the frame
    /// on screen, the shaded image until then (a preview while dragging, the first frame).
    pub fn camera_panel_view(&self) -> View {
        self.camera_panel.view_shown(&self.state, &self.render.shown)
    }

    /// What the camera panel painted in the last frame.
    pub fn camera_paint(&self) -> &CameraPaint {
        self.camera_panel.painted()
    }
}

//! The centre: the camera view beside the light's shadow map (resizable split).
//! Camera view: orbit/pan/zoom, click to pin the probe, overlays, A/B divider, light frustum.
//! Shadow map: linear depth with a legend, hover readout, the probe's uv, search and filter
//! circles and every tap at its real size; drag to move the light.

use super::ShadowlabApp;
use super::rendering::color_image;
use crate::browser::NoWebGpu;
use crate::i18n::Lang;
use crate::i18n::tr;
use crate::views::View;
use crate::views::overlays::Overlay;
use egui::{Color32, Pos2, Rect, Sense, Ui, pos2, vec2};

/// Texture caches, rebuilt after each render.
#[derive(Default)]
pub struct ViewState {
    pub(super) stale: bool,
    pub(super) overlay: Option<egui::TextureHandle>,
    pub(super) legends: Vec<String>,
    /// The camera panel's debug view (visibility, heatmaps, reference, error) and its legend.
    pub(super) view_image: Option<egui::TextureHandle>,
    pub(super) view_legend: Option<String>,
    /// The language the legends were written in (a new language writes them again).
    pub(super) legend_lang: Option<Lang>,
    /// The pictures behind `view_image` and `overlay`, for the per-view screenshot.
    pub(super) view_picture: Option<image::RgbaImage>,
    pub(super) overlay_picture: Option<image::RgbaImage>,
    /// What the camera panel painted in the last frame (for tests).
    pub(super) painted: CameraPaint,
}

/// What the camera panel painted: where the picture went and which marks were drawn on it.
#[derive(Clone, Debug, PartialEq)]
pub struct CameraPaint {
    /// The view shown.
    pub view: Option<View>,
    /// The panel's area and the picture inside it (a lesson's frame is letterboxed in the area).
    pub area: Rect,
    pub picture: Rect,
    /// Camera-space marks: the overlays' image, the light frusta, the probe's crosshair.
    pub overlay: bool,
    pub frusta: bool,
    pub probe_crosshair: Option<Pos2>,
    /// The probe's texel circled on a light-space view (the shadow map, the moments).
    pub probe_texel: Vec<Pos2>,
    /// The A/B split's labels.
    pub ab_labels: Vec<Rect>,
    /// The view selector.
    pub selector: Rect,
    /// The lines under the picture, as painted.
    pub legend: Vec<String>,
}

impl Default for CameraPaint {
    fn default() -> Self {
        Self {
            view: None,
            area: Rect::NOTHING,
            picture: Rect::NOTHING,
            overlay: false,
            frusta: false,
            probe_crosshair: None,
            probe_texel: Vec::new(),
            ab_labels: Vec::new(),
            selector: Rect::NOTHING,
            legend: Vec::new(),
        }
    }
}

impl ViewState {
    pub fn invalidate(&mut self) {
        self.stale = true;
    }
}

fn refresh(app: &mut ShadowlabApp, ctx: &egui::Context) {
    if !app.view_state.stale && app.view_state.legend_lang == Some(app.state.lang) {
        return;
    }
    app.view_state.stale = false;
    app.view_state.legend_lang = Some(app.state.lang);
    let light = app.render.shown.lights.get(app.state.selected_light).copied();
    // The debug view from the analysis pass (and the ground truth).
    app.view_state.view_image = None;
    app.view_state.view_legend = None;
    app.view_state.view_picture = None;
    app.view_state.overlay_picture = None;
    if let Some(analysis) = &app.render.shown.analysis {
        // The samples of the ground truth shown (it was worked out for the frame on screen).
        let samples = app
            .render
            .shown
            .reference_progress
            .map_or(app.state.scene.shadow.reference_samples, |(_, all)| all);
        let light_and_params = light.as_ref().map(|l| (l, &app.render.shown.params));
        if let Some((image, legend)) = crate::views::analysis_view(
            app.state.view,
            analysis,
            app.state.reference.as_deref(),
            samples,
            light_and_params,
            app.state.lang,
        ) {
            app.view_state.view_image =
                Some(ctx.load_texture("debug view", color_image(&image), egui::TextureOptions::NEAREST));
            app.view_state.view_legend = Some(legend);
            app.view_state.view_picture = Some(image);
        } else if app.state.view == View::Moments {
            app.view_state.view_legend =
                Some(tr(app.state.lang, "the moments view needs the vsm or vssm technique").into());
        }
    }
    // Overlays from the analysis pass.
    app.view_state.overlay = None;
    app.view_state.legends.clear();
    if let Some(analysis) = &app.render.shown.analysis {
        let overlays: Vec<Overlay> = app
            .overlays
            .iter()
            .copied()
            .filter(|&o| !crate::views::overlays::hidden_by_view(app.camera_view_kind(), o))
            .collect();
        let (image, legends) = crate::views::overlays::compose(
            app.state.lang,
            &overlays,
            analysis,
            light.as_ref(),
            app.state.reference.as_deref(),
        );
        app.view_state.legends = legends;
        if !overlays.is_empty() {
            app.view_state.overlay =
                Some(ctx.load_texture("overlay", color_image(&image), egui::TextureOptions::NEAREST));
            app.view_state.overlay_picture = Some(image);
        }
    }
}

impl ViewState {
    /// The view's legend lines, then the overlays'.
    pub fn legend_lines(&self) -> Vec<String> {
        let view = self.view_legend.iter().flat_map(|l| l.lines()).map(String::from);
        view.chain(self.legends.iter().cloned()).collect()
    }
}

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
    let legend_font = egui::FontId::proportional(if app.state.present { 18.0 } else { 13.0 });
    // Room for the legends the view and overlays will have, known before they are worked out
    // (sized by what is asked, not by what arrives, so the view does not change size with them).
    let line_height = ui.fonts_mut(|f| f.row_height(&legend_font));
    let legend_height = (app.legend_lines_expected() as f32 * line_height + 8.0)
        .clamp(40.0, (left.height() * 0.35).max(40.0));
    let area = Rect::from_min_max(left.min, pos2(left.right(), left.bottom() - legend_height));
    // A lesson's frame is shown whole, letterboxed: cropped to the panel's shape, its probe and
    // what the text points at could fall outside.
    let camera_rect = match app.state.current_step() {
        Some(_) => letterbox(area, crate::lessons::PROBE_FRAME),
        None => area,
    };
    let legend_rect = Rect::from_min_max(pos2(left.left(), camera_rect.bottom()), left.max);

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
    let ppp = ui.ctx().pixels_per_point();
    let size_px =
        ((camera_rect.width() * ppp).max(16.0) as u32, (camera_rect.height() * ppp).max(16.0) as u32);
    app.schedule_render(size_px);
    refresh(app, ui.ctx());

    app.view_state.painted = CameraPaint { area, ..Default::default() };
    super::camera_panel::camera_view(app, ui, camera_rect);
    let painter = ui.painter_at(legend_rect);
    let mut y = legend_rect.top() + 4.0;
    let waiting = [String::from(tr(
        app.state.lang,
        if app.render.interacting {
            "(overlays refresh when you let go)"
        } else {
            "(working out the overlays...)"
        },
    ))];
    let shown_view = app.camera_panel_view();
    let stale =
        app.render.shown.overlays_stale() && (app.view_state.overlay.is_some() || shown_view != View::Final);
    let legend_lines = app.view_state.legend_lines();
    let mut lines: Vec<&str> = Vec::new();
    if stale {
        lines.push(&waiting[0]);
    } else if !is_light_space(shown_view) {
        // A light-space view has its own caption; the camera's legends are about other pictures.
        lines.extend(legend_lines.iter().map(String::as_str));
    }
    let ab_note;
    if app.state.ab.is_some() && app.state.view != View::Final {
        ab_note =
            tr(app.state.lang, "the A/B split compares the shaded pictures: the view returns when it is off");
        lines.push(ab_note);
    }
    app.view_state.painted.legend = lines.iter().map(|l| l.to_string()).collect();
    // Wrapped to the view's width: a long legend takes a second line rather than being cut.
    for legend in lines {
        let galley = painter.layout(
            legend.to_string(),
            legend_font.clone(),
            Color32::LIGHT_GRAY,
            legend_rect.width() - 8.0,
        );
        let height = galley.size().y;
        painter.galley(pos2(legend_rect.left() + 4.0, y), galley, Color32::LIGHT_GRAY);
        y += height;
    }
    if show_map {
        app.map_panel.ui(ui, map_rect, &mut app.state, &app.render.shown);
    }
    ui.allocate_rect(full, Sense::hover());
}

/// The largest rectangle of the frame's shape in `area`, centred across and at its top.
pub(super) fn letterbox(area: Rect, (frame_w, frame_h): (u32, u32)) -> Rect {
    let aspect = frame_w as f32 / frame_h as f32;
    let width = area.width().min(area.height() * aspect).max(1.0);
    let size = vec2(width, width / aspect);
    Rect::from_min_size(pos2(area.center().x - size.x * 0.5, area.top()), size)
}

/// Views of the light's map rather than of the camera's picture.
pub(super) fn is_light_space(view: View) -> bool {
    matches!(view, View::ShadowMap | View::Moments)
}

impl ShadowlabApp {
    /// The view the camera panel is set to show: the chosen one, or the shaded picture while
    /// the A/B split compares two of them.
    pub fn camera_view_kind(&self) -> View {
        if self.state.ab.is_some() { View::Final } else { self.state.view }
    }

    /// The view the camera panel shows now: the chosen one once it is worked out for the frame
    /// on screen, the shaded image until then (a preview while dragging, the first frame).
    pub fn camera_panel_view(&self) -> View {
        let view = self.camera_view_kind();
        let ready = match view {
            View::Final => true,
            View::ShadowMap => self.render.shown.map.is_some(),
            _ => self.view_state.view_image.is_some() && !self.render.shown.overlays_stale(),
        };
        if ready { view } else { View::Final }
    }

    /// Lines of legend the view and the overlays will take (wrapping aside).
    fn legend_lines_expected(&self) -> usize {
        let view = self.camera_view_kind();
        let of_view = match view {
            View::Final | View::ShadowMap => 0,
            View::Moments | View::Error => 2,
            _ => 1,
        };
        let overlays = self
            .overlays
            .iter()
            .filter(|&&o| o != Overlay::LightFrustum && !crate::views::overlays::hidden_by_view(view, o))
            .count();
        (of_view + overlays + usize::from(self.state.ab.is_some())).max(1)
    }

    /// What the camera panel painted in the last frame.
    pub fn camera_paint(&self) -> &CameraPaint {
        &self.view_state.painted
    }
}

/// What the camera panel shows: a drop-down in its top-left corner (lesson steps set it too).
pub(super) fn view_selector(app: &mut ShadowlabApp, ui: &mut Ui, rect: Rect) {
    let corner = Rect::from_min_size(rect.min + vec2(8.0, 8.0), vec2(190.0, 24.0));
    let mut child = ui.new_child(egui::UiBuilder::new().max_rect(corner));
    let before = app.state.view;
    let response = egui::ComboBox::from_id_salt("camera view")
        .selected_text(format!("{}: {}", tr(app.state.lang, "view"), app.state.view.label(app.state.lang)))
        // Every view in reach without scrolling.
        .height(f32::INFINITY)
        .show_ui(&mut child, |ui| {
            for view in View::ALL {
                ui.selectable_value(&mut app.state.view, view, view.label(app.state.lang));
            }
        })
        .response
        .on_hover_text(tr(app.state.lang, "What the camera panel shows (`--view` in the CLI)"));
    app.view_state.painted.selector = response.rect;
    if app.state.view != before {
        // The analysis pass (and the ground truth) may be needed now.
        app.state.mark_dirty();
        app.view_state.invalidate();
    }
}

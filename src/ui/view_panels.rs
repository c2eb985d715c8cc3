//! The centre: the camera view beside the light's shadow map (resizable split).
//! Camera view: orbit/pan/zoom, click to pin the probe, overlays, A/B divider, light frustum.
//! Shadow map: linear depth with a legend, hover readout, the probe's uv, search and filter
//! circles and every tap at its real size; drag to move the light.

use super::worker::MapView;
use super::{ProbeAt, ShadowlabApp};
use crate::i18n::Lang;
use crate::i18n::tr;
use crate::shadow::depth_linear_from_ndc;
use crate::shadow::{DepthImage, LightGpu};
use crate::views::View;
use crate::views::overlays::Overlay;
use egui::{Color32, Pos2, Rect, Sense, Stroke, Ui, Vec2, pos2, vec2};
use glam::{Mat4, Vec4};

/// Texture caches, rebuilt after each render.
#[derive(Default)]
pub struct ViewState {
    stale: bool,
    overlay: Option<egui::TextureHandle>,
    legends: Vec<String>,
    /// The camera panel's debug view (visibility, heatmaps, reference, error) and its legend.
    view_image: Option<egui::TextureHandle>,
    view_legend: Option<String>,
    /// The language the legends were written in (a new language writes them again).
    legend_lang: Option<Lang>,
    /// The pictures behind `view_image` and `overlay`, for the per-view screenshot.
    pub(super) view_picture: Option<image::RgbaImage>,
    pub(super) overlay_picture: Option<image::RgbaImage>,
    map: Option<(egui::TextureHandle, DepthImage, LightGpu)>,
    /// Linear depth range of the shown map, world units.
    map_range: (f32, f32),
    /// One small picture per light (several lights only).
    thumbnails: Vec<egui::TextureHandle>,
    /// Zoom of the shadow-map panel (1 = whole map) and the uv at its centre.
    zoom: f32,
    zoom_centre: (f32, f32),
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

    /// The whole map again (a new scene).
    pub fn reset_zoom(&mut self) {
        self.zoom = 1.0;
        self.zoom_centre = (0.5, 0.5);
    }

    /// The map panel is zoomed in (its picture then needs every texel).
    pub fn zoomed(&self) -> bool {
        self.zoom > 1.0
    }

    /// The shadow map shown: its depths and the light it was rendered for.
    pub fn map(&self) -> Option<(&DepthImage, &LightGpu)> {
        self.map.as_ref().map(|(_, depth, light)| (depth, light))
    }
}

fn color_image(image: &image::RgbaImage) -> egui::ColorImage {
    egui::ColorImage::from_rgba_unmultiplied(
        [image.width() as usize, image.height() as usize],
        image.as_raw(),
    )
}

fn refresh(app: &mut ShadowlabApp, ctx: &egui::Context) {
    if !app.view_state.stale && app.view_state.legend_lang == Some(app.lang) {
        return;
    }
    app.view_state.stale = false;
    app.view_state.legend_lang = Some(app.lang);
    let light = app.shown.lights.get(app.selected_light).copied();
    // The debug view from the analysis pass (and the ground truth).
    app.view_state.view_image = None;
    app.view_state.view_legend = None;
    app.view_state.view_picture = None;
    app.view_state.overlay_picture = None;
    if let Some(analysis) = &app.analysis {
        let samples = app.scene.shadow.reference_samples;
        let light_and_params = light.as_ref().map(|l| (l, &app.shown.params));
        if let Some((image, legend)) = crate::views::analysis_view(
            app.view,
            analysis,
            app.reference.as_deref(),
            samples,
            light_and_params,
            app.lang,
        ) {
            app.view_state.view_image =
                Some(ctx.load_texture("debug view", color_image(&image), egui::TextureOptions::NEAREST));
            app.view_state.view_legend = Some(legend);
            app.view_state.view_picture = Some(image);
        } else if app.view == View::Moments {
            app.view_state.view_legend =
                Some(tr(app.lang, "the moments view needs the vsm or vssm technique").into());
        }
    }
    // Overlays from the analysis pass.
    app.view_state.overlay = None;
    app.view_state.legends.clear();
    if let Some(analysis) = &app.analysis {
        let overlays: Vec<Overlay> = app
            .overlays
            .iter()
            .copied()
            .filter(|&o| !crate::views::overlays::hidden_by_view(app.camera_view_kind(), o))
            .collect();
        let (image, legends) = crate::views::overlays::compose(
            app.lang,
            &overlays,
            analysis,
            light.as_ref(),
            app.reference.as_deref(),
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

    /// Show a new shadow-map picture (from the render worker).
    pub fn set_map(&mut self, ctx: &egui::Context, map: MapView) {
        self.map_range = map.range;
        let texture = ctx.load_texture("shadow map", color_image(&map.image), egui::TextureOptions::NEAREST);
        self.map = Some((texture, map.depth, map.light));
    }

    /// Thumbnails of every light's map (several lights only).
    pub fn set_thumbnails(&mut self, ctx: &egui::Context, images: &[image::RgbaImage]) {
        self.thumbnails = images
            .iter()
            .enumerate()
            .map(|(i, image)| {
                ctx.load_texture(format!("thumbnail {i}"), color_image(image), egui::TextureOptions::LINEAR)
            })
            .collect();
    }
}

pub fn show(app: &mut ShadowlabApp, ui: &mut Ui) {
    if app.worker.is_none() {
        ui.centered_and_justified(|ui| {
            ui.label(format!(
                "{}: {}",
                crate::i18n::tr(app.lang, "No GPU view"),
                app.gpu_error.clone().unwrap_or_else(|| crate::i18n::tr(app.lang, "unknown reason").into())
            ));
        });
        return;
    }
    let full = ui.available_rect_before_wrap();
    let show_map = app.panel_visible(crate::lessons::Panel::ShadowMap);
    let split = if show_map { app.settings.split.clamp(0.25, 0.85) } else { 1.0 };
    let divider_x = full.left() + full.width() * split;
    let left = Rect::from_min_max(full.min, pos2(divider_x - 3.0, full.bottom()));
    let map_rect = Rect::from_min_max(pos2(divider_x + 3.0, full.top()), full.max);
    let legend_font = egui::FontId::proportional(if app.present { 18.0 } else { 13.0 });
    // Room for the legends the view and overlays will have, known before they are worked out
    // (sized by what is asked, not by what arrives, so the view does not change size with them).
    let line_height = ui.fonts_mut(|f| f.row_height(&legend_font));
    let legend_height = (app.legend_lines_expected() as f32 * line_height + 8.0)
        .clamp(40.0, (left.height() * 0.35).max(40.0));
    let area = Rect::from_min_max(left.min, pos2(left.right(), left.bottom() - legend_height));
    // A lesson's frame is shown whole, letterboxed: cropped to the panel's shape, its probe and
    // what the text points at could fall outside.
    let camera_rect = match app.current_step() {
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
            app.settings.split = ((divider_x + divider_response.drag_delta().x - full.left()) / full.width())
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
    camera_view(app, ui, camera_rect);
    let painter = ui.painter_at(legend_rect);
    let mut y = legend_rect.top() + 4.0;
    let waiting = [String::from(tr(
        app.lang,
        if app.interacting { "(overlays refresh when you let go)" } else { "(working out the overlays...)" },
    ))];
    let shown_view = app.camera_panel_view();
    let stale = app.overlays_stale() && (app.view_state.overlay.is_some() || shown_view != View::Final);
    let legend_lines = app.view_state.legend_lines();
    let mut lines: Vec<&str> = Vec::new();
    if stale {
        lines.push(&waiting[0]);
    } else if !is_light_space(shown_view) {
        // A light-space view has its own caption; the camera's legends are about other pictures.
        lines.extend(legend_lines.iter().map(String::as_str));
    }
    let ab_note;
    if app.ab.is_some() && app.view != View::Final {
        ab_note = tr(app.lang, "the A/B split compares the shaded pictures: the view returns when it is off");
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
        shadow_map_panel(app, ui, map_rect);
    }
    ui.allocate_rect(full, Sense::hover());
}

/// The largest rectangle of the frame's shape in `area`, centred across and at its top.
fn letterbox(area: Rect, (frame_w, frame_h): (u32, u32)) -> Rect {
    let aspect = frame_w as f32 / frame_h as f32;
    let width = area.width().min(area.height() * aspect).max(1.0);
    let size = vec2(width, width / aspect);
    Rect::from_min_size(pos2(area.center().x - size.x * 0.5, area.top()), size)
}

/// Views of the light's map rather than of the camera's picture.
fn is_light_space(view: View) -> bool {
    matches!(view, View::ShadowMap | View::Moments)
}

impl ShadowlabApp {
    /// The view the camera panel is set to show: the chosen one, or the shaded picture while
    /// the A/B split compares two of them.
    pub fn camera_view_kind(&self) -> View {
        if self.ab.is_some() { View::Final } else { self.view }
    }

    /// The view the camera panel shows now: the chosen one once it is worked out for the frame
    /// on screen, the shaded image until then (a preview while dragging, the first frame).
    pub fn camera_panel_view(&self) -> View {
        let view = self.camera_view_kind();
        let ready = match view {
            View::Final => true,
            View::ShadowMap => self.view_state.map.is_some(),
            _ => self.view_state.view_image.is_some() && !self.overlays_stale(),
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
        (of_view + overlays + usize::from(self.ab.is_some())).max(1)
    }

    /// What the camera panel painted in the last frame.
    pub fn camera_paint(&self) -> &CameraPaint {
        &self.view_state.painted
    }
}

/// What the camera panel shows: a drop-down in its top-left corner (lesson steps set it too).
fn view_selector(app: &mut ShadowlabApp, ui: &mut Ui, rect: Rect) {
    let corner = Rect::from_min_size(rect.min + vec2(8.0, 8.0), vec2(190.0, 24.0));
    let mut child = ui.new_child(egui::UiBuilder::new().max_rect(corner));
    let before = app.view;
    let response = egui::ComboBox::from_id_salt("camera view")
        .selected_text(format!("{}: {}", tr(app.lang, "view"), app.view.label(app.lang)))
        // Every view in reach without scrolling.
        .height(f32::INFINITY)
        .show_ui(&mut child, |ui| {
            for view in View::ALL {
                ui.selectable_value(&mut app.view, view, view.label(app.lang));
            }
        })
        .response
        .on_hover_text(tr(app.lang, "What the camera panel shows (`--view` in the CLI)"));
    app.view_state.painted.selector = response.rect;
    if app.view != before {
        // The analysis pass (and the ground truth) may be needed now.
        app.mark_dirty();
        app.view_state.invalidate();
    }
}

/// Where the probe's marker goes in the camera view: the clicked point, or, for a lesson's probe
/// (probed in the lesson's own frame), where its surface point projects in this view.
fn probe_marker(app: &ShadowlabApp, rect: Rect) -> Option<Pos2> {
    let (fx, fy) = app.probe_fraction(rect.width() / rect.height().max(1.0))?;
    Some(pos2(rect.left() + fx * rect.width(), rect.top() + fy * rect.height()))
}

impl ShadowlabApp {
    /// The probe's marker as fractions of a camera view of this aspect (width / height).
    pub(super) fn probe_fraction(&self, aspect: f32) -> Option<(f32, f32)> {
        match self.probe_at? {
            ProbeAt::View(fx, fy) => Some((fx, fy)),
            ProbeAt::LessonFrame(..) => {
                let world = glam::Vec3::from(self.probe.as_ref()?.world_position?);
                let clip = self.scene.camera.clip_from_world(aspect) * world.extend(1.0);
                (clip.w > 0.0).then(|| {
                    let ndc = clip.truncate() / clip.w;
                    (ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5)
                })
            }
        }
    }

    /// The probe's shadow-map uv for the selected light, if the probe has one.
    fn probe_map_uv(&self) -> Option<[f32; 2]> {
        let report = self.probe.as_ref()?;
        report.lights.iter().find(|l| l.light == self.selected_light).map(|l| l.shadow_map_uv)
    }
}

/// The probe's texel on a light-space picture of the map occupying `square`.
fn mark_texel(painter: &egui::Painter, square: Rect, uv: [f32; 2]) -> Pos2 {
    let p = pos2(square.left() + uv[0] * square.width(), square.top() + uv[1] * square.height());
    painter.circle_stroke(p, 7.0, Stroke::new(2.0, Color32::from_rgb(255, 210, 0)));
    p
}

fn camera_view(app: &mut ShadowlabApp, ui: &mut Ui, rect: Rect) {
    let response = ui.interact(rect, ui.scope_id().with("camera view"), Sense::click_and_drag());
    super::set_landmark(ui.ctx(), super::LANDMARK_CAMERA_VIEW, rect);
    // The letterbox around a lesson's frame.
    ui.painter().rect_filled(app.view_state.painted.area, 0.0, Color32::from_gray(12));
    let painter = ui.painter_at(rect);
    let uv = Rect::from_min_max(Pos2::ZERO, pos2(1.0, 1.0));
    let shown_view = app.camera_panel_view();
    let probe_uv = app.probe_map_uv();
    let mut probe_texel = Vec::new();
    match (shown_view, &app.view_state.view_image, &app.view_state.map) {
        (View::ShadowMap, _, Some((texture, ..))) => {
            // The light's map, square, in the middle of the panel.
            painter.rect_filled(rect, 0.0, Color32::from_gray(20));
            let square = Rect::from_center_size(rect.center(), Vec2::splat(rect.width().min(rect.height())));
            painter.image(texture.id(), square, uv, Color32::WHITE);
            probe_texel.extend(probe_uv.map(|uv| mark_texel(&painter, square, uv)));
        }
        (View::Moments, Some(texture), _) => {
            // Two square panels side by side, their shape kept, in the middle of the panel.
            painter.rect_filled(rect, 0.0, Color32::from_gray(20));
            let [w, h] = texture.size().map(|s| s as f32);
            let scale = (rect.width() / w).min(rect.height() / h);
            let pair = Rect::from_center_size(rect.center(), vec2(w, h) * scale);
            painter.image(texture.id(), pair, uv, Color32::WHITE);
            // The same texel in both square panels (mean depth, standard deviation), which
            // stand at the pair's two ends (views::moments_image).
            if let Some(uv) = probe_uv {
                let side = pair.height();
                for left in [pair.left(), pair.right() - side] {
                    let square = Rect::from_min_size(pos2(left, pair.top()), Vec2::splat(side));
                    probe_texel.push(mark_texel(&painter, square, uv));
                }
            }
        }
        (View::Final, ..) | (View::ShadowMap, _, None) | (_, None, _) => {
            if let Some(texture) = &app.shown.camera {
                painter.image(texture.id(), rect, uv, Color32::WHITE);
            }
        }
        (_, Some(texture), _) => {
            painter.image(texture.id(), rect, uv, Color32::WHITE);
        }
    }
    let mut ab_labels = Vec::new();
    let mut a_side = rect;
    if let (Some(ab), Some(id_b)) = (&app.ab, app.shown.camera_b.as_ref().map(|t| t.id())) {
        let x = rect.left() + rect.width() * ab.divider;
        a_side.max.x = x;
        let right = Rect::from_min_max(pos2(x, rect.top()), rect.max);
        let uv_right = Rect::from_min_max(pos2(ab.divider, 0.0), pos2(1.0, 1.0));
        painter.image(id_b, right, uv_right, Color32::WHITE);
        painter.line_segment([pos2(x, rect.top()), pos2(x, rect.bottom())], Stroke::new(2.0, Color32::WHITE));
        // Below the view selector, so neither hides the other wherever the divider is.
        let y = rect.top() + 44.0;
        let mut label = |text: &str, pos: Pos2, align: egui::Align2| {
            let galley =
                painter.layout_no_wrap(text.into(), egui::FontId::proportional(15.0), Color32::WHITE);
            let r = align.anchor_size(pos, galley.size()).expand(3.0);
            painter.rect_filled(r, 3.0, Color32::from_black_alpha(150));
            painter.galley(r.min + vec2(3.0, 3.0), galley, Color32::WHITE);
            ab_labels.push(r);
        };
        label(app.scene.shadow.technique.label(app.lang), pos2(x - 8.0, y), egui::Align2::RIGHT_TOP);
        label(ab.b.label(app.lang), pos2(x + 8.0, y), egui::Align2::LEFT_TOP);
    }
    // Camera-space marks belong on the camera's picture, never on a view of the light's map.
    let camera_space = !is_light_space(shown_view);
    // Overlays come from the last full-quality frame: over a preview of other settings they
    // would show the old numbers, so they wait for the release. They describe side A only.
    let overlay = app.view_state.overlay.as_ref().filter(|_| !app.overlays_stale() && camera_space);
    if let Some(overlay) = overlay {
        let a_uv = Rect::from_min_max(Pos2::ZERO, pos2((a_side.width() / rect.width()).min(1.0), 1.0));
        painter.image(overlay.id(), a_side, a_uv, Color32::WHITE);
    }
    let frusta = camera_space && app.overlays.contains(&crate::views::overlays::Overlay::LightFrustum);
    if frusta {
        draw_light_frusta(app, &painter, rect);
    }
    render_progress(app, &painter, rect);
    let crosshair = probe_marker(app, rect).filter(|_| camera_space);
    if let Some(p) = crosshair {
        painter.circle_stroke(p, 7.0, Stroke::new(2.0, Color32::from_rgb(255, 210, 0)));
        painter.line_segment([p - vec2(12.0, 0.0), p + vec2(12.0, 0.0)], Stroke::new(1.5, Color32::BLACK));
        painter.line_segment([p - vec2(0.0, 12.0), p + vec2(0.0, 12.0)], Stroke::new(1.5, Color32::BLACK));
    }
    let painted = &mut app.view_state.painted;
    painted.view = Some(shown_view);
    painted.picture = rect;
    painted.overlay = overlay.is_some();
    painted.frusta = frusta;
    painted.probe_crosshair = crosshair;
    painted.probe_texel = probe_texel;
    painted.ab_labels = ab_labels;

    view_selector(app, ui, rect);

    // Interaction: the A/B divider first, then the camera.
    let mut handled = false;
    if let Some(ab) = &mut app.ab
        && let Some(pos) = response.interact_pointer_pos()
    {
        // Grabbed on press (near the divider), held until release.
        let x = rect.left() + rect.width() * ab.divider;
        if response.drag_started_by(egui::PointerButton::Primary) {
            let press = ui.input(|i| i.pointer.press_origin()).unwrap_or(pos);
            ab.grabbed = (press.x - x).abs() < 12.0;
        }
        if ab.grabbed && response.dragged_by(egui::PointerButton::Primary) {
            ab.divider = ((pos.x - rect.left()) / rect.width()).clamp(0.02, 0.98);
            handled = true;
        }
        if response.drag_stopped() {
            ab.grabbed = false;
        }
    }
    let delta = response.drag_delta();
    app.interacting = response.dragged() && delta != Vec2::ZERO;
    if !handled && response.dragged_by(egui::PointerButton::Primary) && delta != Vec2::ZERO {
        app.scene.camera.orbit(-delta.x * 0.008, -delta.y * 0.008);
        app.mark_dirty();
    }
    if response.dragged_by(egui::PointerButton::Secondary) || response.dragged_by(egui::PointerButton::Middle)
    {
        let distance = (app.scene.camera.position - app.scene.camera.target).length();
        let world_per_point = distance / rect.height().max(1.0);
        app.scene.camera.pan(-delta.x * world_per_point, delta.y * world_per_point);
        app.mark_dirty();
    }
    if response.hovered() {
        let scroll = ui.input(|i| i.smooth_scroll_delta.y);
        if scroll != 0.0 {
            app.scene.camera.zoom((-scroll * 0.002).exp());
            app.mark_dirty();
        }
    }
    let pointer_fraction =
        |pos: Pos2| ProbeAt::View((pos.x - rect.left()) / rect.width(), (pos.y - rect.top()) / rect.height());
    if response.double_clicked() {
        // Focus: the probe finds the surface point; the camera turns to it once it is known.
        if let Some(pos) = response.interact_pointer_pos() {
            app.probe_at = Some(pointer_fraction(pos));
            app.focus_on_probe = true;
            app.mark_dirty();
        }
    } else if response.clicked()
        && let Some(pos) = response.interact_pointer_pos()
    {
        app.probe_at = Some(pointer_fraction(pos));
        app.mark_dirty();
    }
}

/// The depth colour ramp with its range in world units.
fn legend_bar(ui: &mut Ui, lang: Lang, (lo, hi): (f32, f32), present: bool) {
    // Readable on a projector too.
    let text = |ui: &mut Ui, s: String| {
        let text = egui::RichText::new(s);
        ui.label(if present { text.size(18.0) } else { text.small() })
    };
    let bar = if present { vec2(216.0, 18.0) } else { vec2(140.0, 10.0) };
    ui.horizontal_wrapped(|ui| {
        text(ui, format!("{lo:.1}"));
        let (rect, _) = ui.allocate_exact_size(bar, Sense::hover());
        let steps = 28;
        for k in 0..steps {
            let c = crate::views::heat_color(k as f32 / (steps - 1) as f32);
            let x0 = rect.left() + rect.width() * k as f32 / steps as f32;
            let cell = Rect::from_min_max(
                pos2(x0, rect.top()),
                pos2(x0 + rect.width() / steps as f32 + 0.5, rect.bottom()),
            );
            ui.painter().rect_filled(cell, 0.0, Color32::from_rgb(c[0], c[1], c[2]));
        }
        text(ui, format!("{hi:.1} {}", tr(lang, "world units from the light")));
        text(ui, tr(lang, "· white: nothing stored · wheel: zoom").into());
    });
}

/// "rendering..." over a view whose frame is slow (or not there yet), and the ground truth's
/// progress while it accumulates.
fn render_progress(app: &ShadowlabApp, painter: &egui::Painter, rect: Rect) {
    let label = |text: String, pos: Pos2, align: egui::Align2| {
        let font = egui::FontId::proportional(14.0);
        let galley = painter.layout_no_wrap(text, font, Color32::WHITE);
        let r = align.anchor_size(pos, galley.size()).expand(4.0);
        painter.rect_filled(r, 3.0, Color32::from_black_alpha(170));
        painter.galley(r.min + vec2(4.0, 4.0), galley, Color32::WHITE);
    };
    if app.shown.camera.is_none() || app.render_is_slow().is_some() {
        let waited = app.render_is_slow().map_or(0.0, |d| d.as_secs_f32());
        label(
            format!("{} {waited:.1} s", tr(app.lang, "rendering...")),
            rect.right_top() + vec2(-8.0, 8.0),
            egui::Align2::RIGHT_TOP,
        );
    }
    if let Some((done, total)) = app.shown.reference_progress
        && done < total
    {
        let bar = Rect::from_min_size(rect.left_bottom() + vec2(8.0, -14.0), vec2(rect.width() - 16.0, 6.0));
        painter.rect_filled(bar, 2.0, Color32::from_black_alpha(160));
        let filled =
            Rect::from_min_size(bar.min, vec2(bar.width() * done as f32 / total.max(1) as f32, bar.height()));
        painter.rect_filled(filled, 2.0, Color32::from_rgb(255, 210, 0));
        label(
            match app.lang {
                Lang::En => format!("ground truth {done} / {total} samples"),
                Lang::Zh => format!("真实结果 {done} / {total} 个采样"),
            },
            bar.left_top() + vec2(0.0, -6.0),
            egui::Align2::LEFT_BOTTOM,
        );
    }
}

/// Project a world point with `clip_from_world` into `rect`; None behind the eye.
fn draw_light_frusta(app: &ShadowlabApp, painter: &egui::Painter, rect: Rect) {
    use crate::views::overlays::{FRUSTUM_OTHER, FRUSTUM_SELECTED, light_frustum_edges};
    let camera = app.scene.camera.clip_from_world(rect.width() / rect.height().max(1.0));
    let at = |p: [f32; 2]| pos2(rect.left() + p[0] * rect.width(), rect.top() + p[1] * rect.height());
    for (a, b, selected) in light_frustum_edges(&camera, &app.shown.lights, app.selected_light) {
        let [r, g, bl] = if selected { FRUSTUM_SELECTED } else { FRUSTUM_OTHER };
        painter.line_segment([at(a), at(b)], Stroke::new(1.5, Color32::from_rgb(r, g, bl)));
    }
}

fn shadow_map_panel(app: &mut ShadowlabApp, ui: &mut Ui, rect: Rect) {
    let mut child = ui.new_child(egui::UiBuilder::new().max_rect(rect));
    let ui = &mut child;
    // Nothing of the map panel spills over the panel beside it (the lesson text).
    ui.set_clip_rect(rect.intersect(ui.clip_rect()));
    let light_count = app.scene.lights.len();
    ui.horizontal(|ui| {
        ui.strong(tr(app.lang, "Shadow map"));
        for i in 0..light_count {
            let selected = app.selected_light == i;
            let clicked = match app.view_state.thumbnails.get(i) {
                Some(t) => ui
                    .add(
                        egui::Button::image_and_text(
                            egui::Image::new(t).fit_to_exact_size(vec2(40.0, 40.0)),
                            format!("{} {i}", tr(app.lang, "light")),
                        )
                        .selected(selected),
                    )
                    .clicked(),
                None => ui.selectable_label(selected, format!("{} {i}", tr(app.lang, "light"))).clicked(),
            };
            if clicked && !selected {
                app.selected_light = i;
                app.mark_dirty();
            }
        }
    });
    legend_bar(ui, app.lang, app.view_state.map_range, app.present);
    let zoom = app.view_state.zoom.max(1.0);
    let Some((texture, map, light)) = &app.view_state.map else {
        ui.label(tr(app.lang, "no light in this scene"));
        return;
    };
    let avail = ui.available_rect_before_wrap();
    // The column's own width: a long legend line must not widen the map past it.
    let side = rect.width().min(avail.height() - 60.0).max(64.0);
    let map_rect = Rect::from_min_size(avail.min, vec2(side, side));
    let response = ui.allocate_rect(map_rect, Sense::click_and_drag());
    super::set_landmark(ui.ctx(), super::LANDMARK_SHADOW_MAP, map_rect);
    let painter = ui.painter_at(map_rect);
    // The part of the map shown: all of it, or a window of 1/zoom around the zoom centre.
    let half = 0.5 / zoom;
    let (cx, cy) = app.view_state.zoom_centre;
    let (cx, cy) =
        if zoom > 1.0 { (cx.clamp(half, 1.0 - half), cy.clamp(half, 1.0 - half)) } else { (0.5, 0.5) };
    let shown = Rect::from_min_max(pos2(cx - half, cy - half), pos2(cx + half, cy + half));
    painter.image(texture.id(), map_rect, shown, Color32::WHITE);
    let side = side * zoom;
    let to_rect = |uv: [f32; 2]| {
        pos2(map_rect.left() + (uv[0] - shown.left()) * side, map_rect.top() + (uv[1] - shown.top()) * side)
    };

    // The probe on the map, at its real size.
    if let Some(report) = &app.probe
        && let Some(l) = report.lights.iter().find(|l| l.light == app.selected_light)
    {
        let centre = to_rect(l.shadow_map_uv);
        if l.blocker_search_radius_uv > 0.0 {
            painter.circle_stroke(
                centre,
                l.blocker_search_radius_uv * side,
                Stroke::new(1.5, Color32::from_rgb(86, 180, 233)),
            );
        }
        if l.filter_radius_uv > 0.0 {
            painter.circle_stroke(centre, l.filter_radius_uv * side, Stroke::new(1.5, Color32::WHITE));
        }
        for tap in &l.taps {
            let p = to_rect(tap.uv);
            let (fill, search) = match tap.kind.as_str() {
                "blocker-search" => (tap.value > 0.5, true),
                _ => (tap.value < 0.5, false),
            };
            let color = if fill { Color32::from_rgb(204, 121, 167) } else { Color32::from_rgb(0, 158, 115) };
            if search {
                painter.circle_stroke(p, 2.5, Stroke::new(1.0, color));
            } else {
                painter.circle_filled(p, 2.5, color);
            }
        }
        painter.circle_stroke(centre, 4.0, Stroke::new(2.0, Color32::from_rgb(255, 210, 0)));
    }
    let info_pos = pos2(map_rect.left(), map_rect.bottom() + 4.0);
    let mut info = String::from(tr(
        app.lang,
        "drag to move the light · blue: blocker search · white: filter · green lit, pink blocked",
    ));
    if let Some(pos) = response.hover_pos() {
        let u = (shown.left() + (pos.x - map_rect.left()) / side).clamp(0.0, 0.9999);
        let v = (shown.top() + (pos.y - map_rect.top()) / side).clamp(0.0, 0.9999);
        let (tx, ty) = ((u * map.size as f32) as u32, (v * map.size as f32) as u32);
        let z = map.depth_ndc[(ty * map.size + tx) as usize];
        if z < 1.0 {
            let ndc = Vec4::new(u * 2.0 - 1.0, 1.0 - v * 2.0, z, 1.0);
            let w = Mat4::from_cols_array_2d(&light.clip_from_world).inverse() * ndc;
            let p = w.truncate() / w.w;
            let d = depth_linear_from_ndc(light, z);
            info = match app.lang {
                Lang::En => format!(
                    "texel {tx},{ty} · stored {z:.5} NDC = {d:.3} world · point ({:.2}, {:.2}, {:.2})",
                    p.x, p.y, p.z
                ),
                Lang::Zh => format!(
                    "纹素 {tx},{ty} · 存储 {z:.5} NDC = {d:.3} 世界单位 · 点 ({:.2}, {:.2}, {:.2})",
                    p.x, p.y, p.z
                ),
            };
        } else {
            info = match app.lang {
                Lang::En => format!("texel {tx},{ty} · nothing stored (cleared to 1.0)"),
                Lang::Zh => format!("纹素 {tx},{ty} · 没有存储任何东西（清除值 1.0）"),
            };
        }
    }
    // Wrapped to the map's width: the column may be narrow.
    let info_font = egui::FontId::proportional(if app.present { 18.0 } else { 13.0 });
    let galley = ui.painter().layout(info, info_font, Color32::LIGHT_GRAY, side);
    ui.painter().galley(info_pos, galley, Color32::LIGHT_GRAY);

    // Wheel over the map zooms around the probe (or the pointer), to see taps at texel scale.
    let map_size = map.size;
    let probe_uv = app
        .probe
        .as_ref()
        .and_then(|r| r.lights.iter().find(|l| l.light == app.selected_light))
        .map(|l| (l.shadow_map_uv[0], l.shadow_map_uv[1]));
    if response.hovered() {
        let scroll = ui.input(|i| i.smooth_scroll_delta.y);
        if scroll != 0.0 {
            let max_zoom = (map_size as f32 / 16.0).max(1.0);
            let was_zoomed = app.view_state.zoomed();
            app.view_state.zoom = (zoom * (scroll * 0.004).exp()).clamp(1.0, max_zoom);
            if app.view_state.zoomed() != was_zoomed {
                // The picture's resolution follows the zoom.
                app.dirty = true;
            }
            let pointer = response.hover_pos().map(|p| {
                (shown.left() + (p.x - map_rect.left()) / side, shown.top() + (p.y - map_rect.top()) / side)
            });
            if let Some(centre) = probe_uv.or(pointer) {
                app.view_state.zoom_centre = centre;
            }
        }
    }

    // Dragging on the map moves the light: yaw about its up axis, pitch towards it.
    if response.dragged() && response.drag_delta() != Vec2::ZERO {
        let d = response.drag_delta();
        if let Some(l) = app.scene.lights.get_mut(app.selected_light) {
            let offset = l.position - l.target;
            let up = l.up.normalize_or(glam::Vec3::Y);
            let yawed = glam::Quat::from_axis_angle(up, -d.x * 0.005) * offset;
            let right = yawed.cross(up).normalize_or(glam::Vec3::X);
            let pitched = glam::Quat::from_axis_angle(right, -d.y * 0.005) * yawed;
            if pitched.normalize().dot(up).abs() < 0.995 {
                l.position = l.target + pitched;
            } else {
                l.position = l.target + yawed;
            }
        }
        app.interacting = true;
        app.mark_dirty();
    }
}

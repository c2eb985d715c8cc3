//! The camera view: the picture (or a debug view), the overlays and the legend under it, the A/B
//! divider, light frusta, the probe's crosshair; orbit, pan and zoom, click to pin the probe.

use super::camera_marks::{self, CameraPaint};
use super::camera_pictures::{CameraPictures, view_kind};
use super::homework_view::HomeworkTextures;
use super::rendering::Shown;
use super::{AppState, ProbeAt};
use crate::i18n::tr;
use crate::views::View;
use crate::views::overlays::Overlay;
use egui::{Color32, Pos2, Rect, Sense, Stroke, Ui, Vec2, pos2, vec2};
use std::time::Duration;

/// The camera panel, which owns what it makes of the frame shown (the debug view, the overlays,
/// the homework's pictures) and what it painted last.
#[derive(Default)]
pub struct CameraPanel {
    pictures: CameraPictures,
    homework_textures: HomeworkTextures,
    /// What the panel painted in the last frame (for tests).
    painted: CameraPaint,
}

/// Where the camera panel draws: its area, the picture in it and the legend's lines under it.
pub(super) struct CameraLayout {
    area: Rect,
    /// A lesson's frame is shown whole, letterboxed in the area: cropped to the panel's shape, its
    /// probe and what the text points at could fall outside.
    picture: Rect,
    legend: Rect,
    legend_font: egui::FontId,
}

impl CameraLayout {
    /// The panel in `rect`, with room under the picture for the legends the view and overlays
    /// will have, known before they are worked out (sized by what is asked, not by what arrives,
    /// so the view does not change size with them).
    pub(super) fn new(ui: &Ui, state: &AppState, rect: Rect) -> Self {
        let legend_font = egui::FontId::proportional(if state.present { 18.0 } else { 13.0 });
        let line_height = ui.fonts_mut(|f| f.row_height(&legend_font));
        let legend_height = (legend_lines_expected(state) as f32 * line_height + 8.0)
            .clamp(40.0, (rect.height() * 0.35).max(40.0));
        let area = Rect::from_min_max(rect.min, pos2(rect.right(), rect.bottom() - legend_height));
        // A homework's pictures are its check's, of `CHECK_SIZE`'s shape: shadowlab's side of the
        // A/B split is rendered at the same shape so that the two agree pixel for pixel.
        let picture = match (state.current_step(), &state.homework) {
            (Some(_), _) => letterbox(area, crate::lessons::PROBE_FRAME),
            (None, Some(_)) => letterbox(area, crate::homework::CHECK_SIZE),
            (None, None) => area,
        };
        let legend = Rect::from_min_max(pos2(rect.left(), picture.bottom()), rect.max);
        Self { area, picture, legend, legend_font }
    }

    /// The picture's size in pixels: what the renders are asked for.
    pub(super) fn picture_px(&self, pixels_per_point: f32) -> (u32, u32) {
        let size = self.picture.size() * pixels_per_point;
        (size.x.max(16.0) as u32, size.y.max(16.0) as u32)
    }
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

/// Lines of legend the view and the overlays will take (wrapping aside).
fn legend_lines_expected(state: &AppState) -> usize {
    let view = view_kind(state);
    let of_view = match view {
        View::Final | View::ShadowMap => 0,
        View::Moments | View::Error | View::TexelDensity | View::CascadeIndex => 2,
        _ => 1,
    };
    let overlays = state
        .overlays
        .iter()
        .filter(|&&o| o != Overlay::LightFrustum && !crate::views::overlays::hidden_by_view(view, o))
        .count();
    (of_view + overlays + usize::from(state.ab.is_some())).max(1)
}

impl CameraPanel {
    /// The view the panel shows now: the chosen one once it is worked out for the frame on
    /// screen, the shaded image until then (a preview while dragging, the first frame).
    pub(super) fn view_shown(&self, state: &AppState, shown: &Shown) -> View {
        let view = view_kind(state);
        let ready = match view {
            View::Final => true,
            View::ShadowMap => shown.map.is_some(),
            _ => self.pictures.view_image.is_some() && !shown.overlays_stale(),
        };
        if ready { view } else { View::Final }
    }

    /// What the panel painted in the last frame.
    pub(super) fn painted(&self) -> &CameraPaint {
        &self.painted
    }

    /// The lines under the picture: the view's legend, then the overlays' (as made).
    pub(super) fn legend_lines(&self) -> Vec<String> {
        self.pictures.legend_lines()
    }

    /// The debug view's picture, as last made.
    pub(super) fn view_picture(&self) -> Option<&image::RgbaImage> {
        self.pictures.view_picture.as_ref()
    }

    /// The overlays as last composed over the camera view (translucent), if any is on.
    pub(super) fn overlay_picture(&self) -> Option<&image::RgbaImage> {
        self.pictures.overlay_picture.as_ref()
    }

    /// The picture, its marks, the view selector and the legend, from the frame `shown` (`slow`:
    /// how long the next one has been waited for, once that is worth saying).
    pub(super) fn ui(
        &mut self,
        ui: &mut Ui,
        layout: &CameraLayout,
        state: &mut AppState,
        shown: &Shown,
        slow: Option<Duration>,
    ) {
        self.pictures.refresh(ui.ctx(), state, shown);
        self.painted = CameraPaint { area: layout.area, ..Default::default() };
        let rect = layout.picture;
        let response = ui.interact(rect, ui.scope_id().with("camera view"), Sense::click_and_drag());
        #[cfg(feature = "test-hooks")]
        super::hooks::set_landmark(ui.ctx(), super::hooks::LANDMARK_CAMERA_VIEW, rect);
        self.picture(ui, rect, state, shown, slow);
        self.view_selector(ui, state, rect);
        let dragging = interact(ui, &response, rect, state);
        self.legend(ui, layout, state, shown, dragging);
    }

    /// The homework picture shown in place of shadowlab's final picture, once the check of what
    /// is open has come (the last version that compiled stays while an edit does not).
    fn homework_picture(&mut self, ctx: &egui::Context, state: &AppState) -> Option<egui::TextureId> {
        let homework = state.homework.as_ref()?;
        let outcome = homework.outcome.clone()?;
        Some(self.homework_textures.get(ctx, &outcome, homework.picture))
    }

    /// The view shown (or the homework's picture, and the A/B split's other side) with its marks
    /// over it, noted in `painted`.
    fn picture(&mut self, ui: &Ui, rect: Rect, state: &AppState, shown: &Shown, slow: Option<Duration>) {
        // The letterbox around a lesson's frame.
        ui.painter().rect_filled(self.painted.area, 0.0, Color32::from_gray(12));
        let painter = ui.painter_at(rect);
        let uv = Rect::from_min_max(Pos2::ZERO, pos2(1.0, 1.0));
        let shown_view = self.view_shown(state, shown);
        let probe_uv = camera_marks::probe_map_uv(state);
        let mut probe_texel = Vec::new();
        // While a homework is checked the final picture is the homework's (the A/B split then puts
        // shadowlab's technique beside it).
        let mut homework_shown = None;
        match (shown_view, &self.pictures.view_image, &shown.map) {
            (View::ShadowMap, _, Some(map)) => {
                // The light's map (a point light's faces unfolded, 4 x 3), its shape kept, in the
                // middle of the panel.
                painter.rect_filled(rect, 0.0, Color32::from_gray(20));
                let [w, h] = map.texture.size().map(|s| s as f32);
                let scale = (rect.width() / w).min(rect.height() / h);
                let picture = Rect::from_center_size(rect.center(), vec2(w, h) * scale);
                painter.image(map.texture.id(), picture, uv, Color32::WHITE);
                let at = camera_marks::probe_picture_uv(state, map);
                probe_texel.extend(at.map(|uv| camera_marks::mark_texel(&painter, picture, uv)));
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
                        probe_texel.push(camera_marks::mark_texel(&painter, square, uv));
                    }
                }
            }
            (View::Final, ..) | (View::ShadowMap, _, None) | (_, None, _) => {
                if let Some(id) = self.homework_picture(ui.ctx(), state) {
                    painter.image(id, rect, uv, Color32::WHITE);
                    homework_shown = state.homework.as_ref().map(|h| h.picture);
                } else if let Some(texture) = &shown.camera {
                    painter.image(texture.id(), rect, uv, Color32::WHITE);
                }
            }
            (_, Some(texture), _) => {
                painter.image(texture.id(), rect, uv, Color32::WHITE);
            }
        }
        let mut ab_labels = Vec::new();
        let mut a_side = rect;
        if let (Some(ab), Some(id_b)) = (&state.ab, shown.camera_b.as_ref().map(|t| t.id())) {
            let x = rect.left() + rect.width() * ab.divider;
            a_side.max.x = x;
            let right = Rect::from_min_max(pos2(x, rect.top()), rect.max);
            let uv_right = Rect::from_min_max(pos2(ab.divider, 0.0), pos2(1.0, 1.0));
            painter.image(id_b, right, uv_right, Color32::WHITE);
            painter.line_segment(
                [pos2(x, rect.top()), pos2(x, rect.bottom())],
                Stroke::new(2.0, Color32::WHITE),
            );
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
            let left = match homework_shown {
                Some(picture) => tr(state.lang, picture.label()),
                None => state.scene.shadow.technique.label(state.lang),
            };
            label(left, pos2(x - 8.0, y), egui::Align2::RIGHT_TOP);
            label(ab.b.label(state.lang), pos2(x + 8.0, y), egui::Align2::LEFT_TOP);
        }
        // Camera-space marks belong on the camera's picture, never on a view of the light's map.
        let camera_space = !is_light_space(shown_view);
        // Overlays come from the last full-quality frame: over a preview of other settings they
        // would show the old numbers, so they wait for the release. They describe side A only.
        let overlay = self.pictures.overlay.as_ref().filter(|_| !shown.overlays_stale() && camera_space);
        if let Some(overlay) = overlay {
            let a_uv = Rect::from_min_max(Pos2::ZERO, pos2((a_side.width() / rect.width()).min(1.0), 1.0));
            painter.image(overlay.id(), a_side, a_uv, Color32::WHITE);
        }
        let frusta = camera_space && state.overlays.contains(&Overlay::LightFrustum);
        if frusta {
            camera_marks::draw_light_frusta(&painter, rect, state, shown);
        }
        camera_marks::render_progress(&painter, rect, state, shown, slow);
        let crosshair = camera_marks::probe_marker(state, rect).filter(|_| camera_space);
        if let Some(p) = crosshair {
            camera_marks::draw_crosshair(&painter, p);
        }
        let painted = &mut self.painted;
        painted.view = Some(shown_view);
        painted.picture = rect;
        painted.overlay = overlay.is_some();
        painted.frusta = frusta;
        painted.probe_crosshair = crosshair;
        painted.probe_texel = probe_texel;
        painted.ab_labels = ab_labels;
    }

    /// What the panel shows: a drop-down in its top-left corner (lesson steps set it too).
    fn view_selector(&mut self, ui: &mut Ui, state: &mut AppState, rect: Rect) {
        let corner = Rect::from_min_size(rect.min + vec2(8.0, 8.0), vec2(190.0, 24.0));
        let mut child = ui.new_child(egui::UiBuilder::new().max_rect(corner));
        let before = state.view;
        let lang = state.lang;
        let response = egui::ComboBox::from_id_salt("camera view")
            .selected_text(format!("{}: {}", tr(lang, "view"), state.view.label(lang)))
            // Every view in reach without scrolling.
            .height(f32::INFINITY)
            .show_ui(&mut child, |ui| {
                for view in View::ALL {
                    ui.selectable_value(&mut state.view, view, view.label(lang));
                }
            })
            .response
            .on_hover_text(tr(lang, "What the camera panel shows (`--view` in the CLI)"));
        self.painted.selector = response.rect;
        if state.view != before {
            // The analysis pass (and the ground truth) may be needed now.
            state.mark_dirty();
            self.pictures.invalidate();
        }
    }

    /// The legends under the picture, wrapped to its width; while the overlays wait for a
    /// frame, why.
    fn legend(&mut self, ui: &Ui, layout: &CameraLayout, state: &AppState, shown: &Shown, dragging: bool) {
        let legend_rect = layout.legend;
        let painter = ui.painter_at(legend_rect);
        let mut y = legend_rect.top() + 4.0;
        let waiting = [String::from(tr(
            state.lang,
            if dragging { "(overlays refresh when you let go)" } else { "(working out the overlays...)" },
        ))];
        let shown_view = self.view_shown(state, shown);
        let stale = shown.overlays_stale() && (self.pictures.overlay.is_some() || shown_view != View::Final);
        let legend_lines = self.pictures.legend_lines();
        let mut lines: Vec<&str> = Vec::new();
        if stale {
            lines.push(&waiting[0]);
        } else if !is_light_space(shown_view) {
            // A light-space view has its own caption; the camera's legends are about other pictures.
            lines.extend(legend_lines.iter().map(String::as_str));
        }
        let ab_note;
        if state.ab.is_some() && state.view != View::Final {
            ab_note =
                tr(state.lang, "the A/B split compares the shaded pictures: the view returns when it is off");
            lines.push(ab_note);
        }
        self.painted.legend = lines.iter().map(|l| l.to_string()).collect();
        // Wrapped to the view's width: a long legend takes a second line rather than being cut.
        for legend in lines {
            let galley = painter.layout(
                legend.to_string(),
                layout.legend_font.clone(),
                Color32::LIGHT_GRAY,
                legend_rect.width() - 8.0,
            );
            let height = galley.size().y;
            painter.galley(pos2(legend_rect.left() + 4.0, y), galley, Color32::LIGHT_GRAY);
            y += height;
        }
    }
}

/// Interaction: the A/B divider first, then the camera (orbit, pan, zoom), a click pins the
/// probe and a double-click focuses on its point. Whether the view is being dragged.
fn interact(ui: &Ui, response: &egui::Response, rect: Rect, state: &mut AppState) -> bool {
    let mut handled = false;
    if let Some(ab) = &mut state.ab
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
    if !handled && response.dragged_by(egui::PointerButton::Primary) && delta != Vec2::ZERO {
        state.scene.camera.orbit(-delta.x * 0.008, -delta.y * 0.008);
        state.mark_dirty();
    }
    if response.dragged_by(egui::PointerButton::Secondary) || response.dragged_by(egui::PointerButton::Middle)
    {
        let distance = (state.scene.camera.position - state.scene.camera.target).length();
        let world_per_point = distance / rect.height().max(1.0);
        state.scene.camera.pan(-delta.x * world_per_point, delta.y * world_per_point);
        state.mark_dirty();
    }
    if response.hovered() {
        let scroll = ui.input(|i| i.smooth_scroll_delta.y);
        if scroll != 0.0 {
            state.scene.camera.zoom((-scroll * 0.002).exp());
            state.mark_dirty();
        }
    }
    let pointer_fraction =
        |pos: Pos2| ProbeAt::View((pos.x - rect.left()) / rect.width(), (pos.y - rect.top()) / rect.height());
    if response.double_clicked() {
        // Focus: the probe finds the surface point; the camera turns to it once it is known.
        if let Some(pos) = response.interact_pointer_pos() {
            state.probe_at = Some(pointer_fraction(pos));
            state.focus_on_probe = true;
            state.mark_dirty();
        }
    } else if response.clicked()
        && let Some(pos) = response.interact_pointer_pos()
    {
        state.probe_at = Some(pointer_fraction(pos));
        state.mark_dirty();
    }
    response.dragged() && delta != Vec2::ZERO
}

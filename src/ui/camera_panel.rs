//! The camera view: the picture (or a debug view), the overlays and the legend under it, the A/B
//! divider, light frusta, the probe's crosshair; orbit, pan and zoom, click to pin the probe.

use super::view_panels::{is_light_space, view_selector};
use super::{ProbeAt, ShadowlabApp};
use crate::i18n::tr;
use crate::views::View;
use egui::{Color32, Pos2, Rect, Sense, Stroke, Ui, Vec2, pos2, vec2};

/// Where the probe's marker goes in the camera view: the clicked point, or, for a lesson's probe
/// (probed in the lesson's own frame), where its surface point projects in this view.
pub(super) fn probe_marker(app: &ShadowlabApp, rect: Rect) -> Option<Pos2> {
    let (fx, fy) = app.probe_fraction(rect.width() / rect.height().max(1.0))?;
    Some(pos2(rect.left() + fx * rect.width(), rect.top() + fy * rect.height()))
}

impl ShadowlabApp {
    /// The probe's marker as fractions of a camera view of this aspect (width / height).
    pub(super) fn probe_fraction(&self, aspect: f32) -> Option<(f32, f32)> {
        match self.state.probe_at? {
            ProbeAt::View(fx, fy) => Some((fx, fy)),
            ProbeAt::LessonFrame(..) => {
                let world = glam::Vec3::from(self.state.probe.as_ref()?.world_position?);
                let clip = self.state.scene.camera.clip_from_world(aspect) * world.extend(1.0);
                (clip.w > 0.0).then(|| {
                    let ndc = clip.truncate() / clip.w;
                    (ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5)
                })
            }
        }
    }

    /// The probe's shadow-map uv for the selected light, if the probe has one.
    fn probe_map_uv(&self) -> Option<[f32; 2]> {
        let report = self.state.probe.as_ref()?;
        report.lights.iter().find(|l| l.light == self.state.selected_light).map(|l| l.shadow_map_uv)
    }
}

/// The probe's texel on a light-space picture of the map occupying `square`.
pub(super) fn mark_texel(painter: &egui::Painter, square: Rect, uv: [f32; 2]) -> Pos2 {
    let p = pos2(square.left() + uv[0] * square.width(), square.top() + uv[1] * square.height());
    painter.circle_stroke(p, 7.0, Stroke::new(2.0, Color32::from_rgb(255, 210, 0)));
    p
}

/// The homework picture the camera view shows in place of shadowlab's final picture, once the
/// check of what is open has come (the last version that compiled stays while an edit does not).
fn homework_picture(app: &mut ShadowlabApp, ctx: &egui::Context) -> Option<egui::TextureId> {
    let homework = app.state.homework.as_ref()?;
    let outcome = homework.outcome.clone()?;
    let picture = homework.picture;
    Some(app.homework_textures.get(ctx, &outcome, picture))
}

pub(super) fn camera_view(app: &mut ShadowlabApp, ui: &mut Ui, rect: Rect) {
    let response = ui.interact(rect, ui.scope_id().with("camera view"), Sense::click_and_drag());
    super::set_landmark(ui.ctx(), super::LANDMARK_CAMERA_VIEW, rect);
    // The letterbox around a lesson's frame.
    ui.painter().rect_filled(app.view_state.painted.area, 0.0, Color32::from_gray(12));
    let painter = ui.painter_at(rect);
    let uv = Rect::from_min_max(Pos2::ZERO, pos2(1.0, 1.0));
    let shown_view = app.camera_panel_view();
    let probe_uv = app.probe_map_uv();
    let mut probe_texel = Vec::new();
    // While a homework is checked the final picture is the homework's (the A/B split then puts
    // shadowlab's technique beside it).
    let mut homework_shown = None;
    match (shown_view, &app.view_state.view_image, &app.render.shown.map) {
        (View::ShadowMap, _, Some(map)) => {
            // The light's map, square, in the middle of the panel.
            painter.rect_filled(rect, 0.0, Color32::from_gray(20));
            let square = Rect::from_center_size(rect.center(), Vec2::splat(rect.width().min(rect.height())));
            painter.image(map.texture.id(), square, uv, Color32::WHITE);
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
            if let Some(id) = homework_picture(app, ui.ctx()) {
                painter.image(id, rect, uv, Color32::WHITE);
                homework_shown = app.state.homework.as_ref().map(|h| h.picture);
            } else if let Some(texture) = &app.render.shown.camera {
                painter.image(texture.id(), rect, uv, Color32::WHITE);
            }
        }
        (_, Some(texture), _) => {
            painter.image(texture.id(), rect, uv, Color32::WHITE);
        }
    }
    let mut ab_labels = Vec::new();
    let mut a_side = rect;
    if let (Some(ab), Some(id_b)) = (&app.state.ab, app.render.shown.camera_b.as_ref().map(|t| t.id())) {
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
        let left = match homework_shown {
            Some(picture) => tr(app.state.lang, picture.label()),
            None => app.state.scene.shadow.technique.label(app.state.lang),
        };
        label(left, pos2(x - 8.0, y), egui::Align2::RIGHT_TOP);
        label(ab.b.label(app.state.lang), pos2(x + 8.0, y), egui::Align2::LEFT_TOP);
    }
    // Camera-space marks belong on the camera's picture, never on a view of the light's map.
    let camera_space = !is_light_space(shown_view);
    // Overlays come from the last full-quality frame: over a preview of other settings they
    // would show the old numbers, so they wait for the release. They describe side A only.
    let overlay =
        app.view_state.overlay.as_ref().filter(|_| !app.render.shown.overlays_stale() && camera_space);
    if let Some(overlay) = overlay {
        let a_uv = Rect::from_min_max(Pos2::ZERO, pos2((a_side.width() / rect.width()).min(1.0), 1.0));
        painter.image(overlay.id(), a_side, a_uv, Color32::WHITE);
    }
    let frusta = camera_space && app.state.overlays.contains(&crate::views::overlays::Overlay::LightFrustum);
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
    if let Some(ab) = &mut app.state.ab
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
    app.render.interacting = response.dragged() && delta != Vec2::ZERO;
    if !handled && response.dragged_by(egui::PointerButton::Primary) && delta != Vec2::ZERO {
        app.state.scene.camera.orbit(-delta.x * 0.008, -delta.y * 0.008);
        app.state.mark_dirty();
    }
    if response.dragged_by(egui::PointerButton::Secondary) || response.dragged_by(egui::PointerButton::Middle)
    {
        let distance = (app.state.scene.camera.position - app.state.scene.camera.target).length();
        let world_per_point = distance / rect.height().max(1.0);
        app.state.scene.camera.pan(-delta.x * world_per_point, delta.y * world_per_point);
        app.state.mark_dirty();
    }
    if response.hovered() {
        let scroll = ui.input(|i| i.smooth_scroll_delta.y);
        if scroll != 0.0 {
            app.state.scene.camera.zoom((-scroll * 0.002).exp());
            app.state.mark_dirty();
        }
    }
    let pointer_fraction =
        |pos: Pos2| ProbeAt::View((pos.x - rect.left()) / rect.width(), (pos.y - rect.top()) / rect.height());
    if response.double_clicked() {
        // Focus: the probe finds the surface point; the camera turns to it once it is known.
        if let Some(pos) = response.interact_pointer_pos() {
            app.state.probe_at = Some(pointer_fraction(pos));
            app.state.focus_on_probe = true;
            app.state.mark_dirty();
        }
    } else if response.clicked()
        && let Some(pos) = response.interact_pointer_pos()
    {
        app.state.probe_at = Some(pointer_fraction(pos));
        app.state.mark_dirty();
    }
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
    if app.render.shown.camera.is_none() || app.render_is_slow().is_some() {
        let waited = app.render_is_slow().map_or(0.0, |d| d.as_secs_f32());
        label(
            format!("{} {waited:.1} s", tr(app.state.lang, "rendering...")),
            rect.right_top() + vec2(-8.0, 8.0),
            egui::Align2::RIGHT_TOP,
        );
    }
    if let Some((done, total)) = app.render.shown.reference_progress
        && done < total
    {
        let bar = Rect::from_min_size(rect.left_bottom() + vec2(8.0, -14.0), vec2(rect.width() - 16.0, 6.0));
        painter.rect_filled(bar, 2.0, Color32::from_black_alpha(160));
        let filled =
            Rect::from_min_size(bar.min, vec2(bar.width() * done as f32 / total.max(1) as f32, bar.height()));
        painter.rect_filled(filled, 2.0, Color32::from_rgb(255, 210, 0));
        label(
            crate::i18n::fill(app.state.lang, "ground truth {} / {} samples", &[&done, &total]),
            bar.left_top() + vec2(0.0, -6.0),
            egui::Align2::LEFT_BOTTOM,
        );
    }
}

/// Project a world point with `clip_from_world` into `rect`; None behind the eye.
fn draw_light_frusta(app: &ShadowlabApp, painter: &egui::Painter, rect: Rect) {
    use crate::views::overlays::{FRUSTUM_OTHER, FRUSTUM_SELECTED, light_frustum_edges};
    let camera = app.state.scene.camera.clip_from_world(rect.width() / rect.height().max(1.0));
    let at = |p: [f32; 2]| pos2(rect.left() + p[0] * rect.width(), rect.top() + p[1] * rect.height());
    for (a, b, selected) in light_frustum_edges(&camera, &app.render.shown.lights, app.state.selected_light) {
        let [r, g, bl] = if selected { FRUSTUM_SELECTED } else { FRUSTUM_OTHER };
        painter.line_segment([at(a), at(b)], Stroke::new(1.5, Color32::from_rgb(r, g, bl)));
    }
}

//! What the camera panel draws over its picture: the probe's marks, the light frusta and the
//! render's progress; and what it painted, for tests.

use super::rendering::Shown;
use super::{AppState, ProbeAt};
use crate::i18n::tr;
use crate::shadow::ShadowViewGpu;
use crate::views::View;
use egui::{Color32, Pos2, Rect, Stroke, pos2, vec2};
use std::time::Duration;

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

/// The probe's marker as fractions of a camera view of this aspect (width / height): the
/// clicked point, or, for a lesson's probe (probed in the lesson's own frame), where its surface
/// point projects in this view.
pub(super) fn probe_fraction(state: &AppState, aspect: f32) -> Option<(f32, f32)> {
    match state.probe_at? {
        ProbeAt::View(fx, fy) => Some((fx, fy)),
        ProbeAt::LessonFrame(..) => {
            let world = glam::Vec3::from(state.probe.as_ref()?.world_position?);
            let clip = state.scene.camera.clip_from_world(aspect) * world.extend(1.0);
            (clip.w > 0.0).then(|| {
                let ndc = clip.truncate() / clip.w;
                (ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5)
            })
        }
    }
}

/// Where the probe's marker goes in the camera view occupying `rect`.
pub(super) fn probe_marker(state: &AppState, rect: Rect) -> Option<Pos2> {
    let (fx, fy) = probe_fraction(state, rect.width() / rect.height().max(1.0))?;
    Some(pos2(rect.left() + fx * rect.width(), rect.top() + fy * rect.height()))
}

/// The probe's crosshair at `p`.
pub(super) fn draw_crosshair(painter: &egui::Painter, p: Pos2) {
    painter.circle_stroke(p, 7.0, Stroke::new(2.0, Color32::from_rgb(255, 210, 0)));
    painter.line_segment([p - vec2(12.0, 0.0), p + vec2(12.0, 0.0)], Stroke::new(1.5, Color32::BLACK));
    painter.line_segment([p - vec2(0.0, 12.0), p + vec2(0.0, 12.0)], Stroke::new(1.5, Color32::BLACK));
}

/// The probe's shadow-map uv for the selected light, if the probe has one.
pub(super) fn probe_map_uv(state: &AppState) -> Option<[f32; 2]> {
    let report = state.probe.as_ref()?;
    report.lights.iter().find(|l| l.light == state.selected_light).map(|l| l.shadow_map_uv)
}

/// The probe's place on the shown map's picture (0..1 over it): its uv, or on a light with
/// several maps (a cube's cross, a sun's cascades), its uv on the tile it read.
pub(super) fn probe_picture_uv(state: &AppState, map: &super::rendering::MapPicture) -> Option<[f32; 2]> {
    let report = state.probe.as_ref()?;
    let l = report.lights.iter().find(|l| l.light == state.selected_light)?;
    if map.tiles.is_empty() {
        return Some(l.shadow_map_uv);
    }
    let views: Vec<ShadowViewGpu> = map.tiles.iter().map(|t| t.1).collect();
    let own = l.shadow_view.checked_sub(map.index).filter(|&i| i < views.len())?;
    Some(crate::views::MapsLayout::of(&views).picture_uv(&views, own, l.shadow_map_uv))
}

/// The probe's texel on a light-space picture of the map occupying `square`.
pub(super) fn mark_texel(painter: &egui::Painter, square: Rect, uv: [f32; 2]) -> Pos2 {
    let p = pos2(square.left() + uv[0] * square.width(), square.top() + uv[1] * square.height());
    painter.circle_stroke(p, 7.0, Stroke::new(2.0, Color32::from_rgb(255, 210, 0)));
    p
}

/// "rendering..." over a view whose frame is slow (or not there yet), and the ground truth's
/// progress while it accumulates.
pub(super) fn render_progress(
    painter: &egui::Painter,
    rect: Rect,
    state: &AppState,
    shown: &Shown,
    slow: Option<Duration>,
) {
    let label = |text: String, pos: Pos2, align: egui::Align2| {
        let font = egui::FontId::proportional(14.0);
        let galley = painter.layout_no_wrap(text, font, Color32::WHITE);
        let r = align.anchor_size(pos, galley.size()).expand(4.0);
        painter.rect_filled(r, 3.0, Color32::from_black_alpha(170));
        painter.galley(r.min + vec2(4.0, 4.0), galley, Color32::WHITE);
    };
    if shown.camera.is_none() || slow.is_some() {
        let waited = slow.map_or(0.0, |d| d.as_secs_f32());
        label(
            format!("{} {waited:.1} s", tr(state.lang, "rendering...")),
            rect.right_top() + vec2(-8.0, 8.0),
            egui::Align2::RIGHT_TOP,
        );
    }
    if let Some((done, total)) = shown.reference_progress
        && done < total
    {
        let bar = Rect::from_min_size(rect.left_bottom() + vec2(8.0, -14.0), vec2(rect.width() - 16.0, 6.0));
        painter.rect_filled(bar, 2.0, Color32::from_black_alpha(160));
        let filled =
            Rect::from_min_size(bar.min, vec2(bar.width() * done as f32 / total.max(1) as f32, bar.height()));
        painter.rect_filled(filled, 2.0, Color32::from_rgb(255, 210, 0));
        label(
            crate::i18n::fill(state.lang, "ground truth {} / {} samples", &[&done, &total]),
            bar.left_top() + vec2(0.0, -6.0),
            egui::Align2::LEFT_BOTTOM,
        );
    }
}

/// Every shadow view's frustum as the frame shown had it, projected into the camera view in `rect`.
pub(super) fn draw_light_frusta(painter: &egui::Painter, rect: Rect, state: &AppState, shown: &Shown) {
    use crate::views::overlays::{FRUSTUM_OTHER, FRUSTUM_SELECTED, light_frustum_edges};
    let camera = state.scene.camera.clip_from_world(rect.width() / rect.height().max(1.0));
    let at = |p: [f32; 2]| pos2(rect.left() + p[0] * rect.width(), rect.top() + p[1] * rect.height());
    for (a, b, selected) in light_frustum_edges(&camera, &shown.views, state.selected_light) {
        let [r, g, bl] = if selected { FRUSTUM_SELECTED } else { FRUSTUM_OTHER };
        painter.line_segment([at(a), at(b)], Stroke::new(1.5, Color32::from_rgb(r, g, bl)));
    }
}

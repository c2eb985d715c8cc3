//! The shadow-map panel: linear depth with a colour bar, hover readout, the probe's uv with its
//! search and filter circles and every tap at its real size; wheel to zoom, drag to move the light.
//! A point light's six cube faces show unfolded into a cross (`views::CUBE_CROSS_CELLS`), its taps
//! on the face each one read.

use super::AppState;
use super::rendering::Shown;
use crate::i18n::{Lang, fill, tr};
use crate::shadow::{ShadowViewGpu, depth_linear_from_ndc};
use crate::views::MapsLayout;
use egui::{Color32, Rect, Sense, Stroke, Ui, Vec2, pos2, vec2};
use glam::{Mat4, Vec4};

/// The shadow-map panel, which owns its zoom (the map's picture is the render session's: the
/// camera panel shows it too).
pub struct MapPanel {
    /// 1 = the whole map.
    zoom: f32,
    /// The uv at the centre of the panel while zoomed.
    zoom_centre: (f32, f32),
    /// `AppState::scenes_opened` when the zoom was last reset.
    scenes_opened: u64,
}

impl Default for MapPanel {
    fn default() -> Self {
        Self { zoom: 1.0, zoom_centre: (0.5, 0.5), scenes_opened: 0 }
    }
}

impl MapPanel {
    /// The whole map again once another scene is open.
    pub fn follow_scene(&mut self, scenes_opened: u64) {
        if self.scenes_opened != scenes_opened {
            self.scenes_opened = scenes_opened;
            self.zoom = 1.0;
            self.zoom_centre = (0.5, 0.5);
        }
    }

    /// The panel is zoomed in (its picture then needs every texel).
    pub fn zoomed(&self) -> bool {
        self.zoom > 1.0
    }

    /// The light buttons, the colour bar and the map shown, in `rect`.
    pub(super) fn ui(&mut self, ui: &mut Ui, rect: Rect, state: &mut AppState, shown: &Shown) {
        let mut child = ui.new_child(egui::UiBuilder::new().max_rect(rect));
        let ui = &mut child;
        // Nothing of the map panel spills over the panel beside it (the lesson text).
        ui.set_clip_rect(rect.intersect(ui.clip_rect()));
        let lang = state.lang;
        let light_count = state.scene.lights.len();
        ui.horizontal(|ui| {
            ui.strong(tr(lang, "Shadow map"));
            for i in 0..light_count {
                let selected = state.selected_light == i;
                let clicked = match shown.thumbnails.get(i) {
                    Some(t) => ui
                        .add(
                            egui::Button::image_and_text(
                                egui::Image::new(t).fit_to_exact_size(vec2(40.0, 40.0)),
                                format!("{} {i}", tr(lang, "light")),
                            )
                            .selected(selected),
                        )
                        .clicked(),
                    None => ui.selectable_label(selected, format!("{} {i}", tr(lang, "light"))).clicked(),
                };
                if clicked && !selected {
                    state.selected_light = i;
                    state.mark_dirty();
                }
            }
        });
        let range = shown.map.as_ref().map_or((0.0, 0.0), |m| m.range);
        legend_bar(ui, lang, range, state.present);
        let zoom = self.zoom.max(1.0);
        let Some(shown_map) = &shown.map else {
            ui.label(tr(lang, "no light in this scene"));
            return;
        };
        let (map, shadow_view) = (&shown_map.depth, &shown_map.view);
        // A light with several maps: a cube's six faces in a cross, a sun's cascades in a row.
        let tile_views: Vec<ShadowViewGpu> = shown_map.tiles.iter().map(|t| t.1).collect();
        let layout = MapsLayout::of(if tile_views.is_empty() {
            std::slice::from_ref(shadow_view)
        } else {
            &tile_views
        });
        let tiled = !tile_views.is_empty();
        let cube = shadow_view.cube == 1 && tiled;
        // The picture's height per unit of width.
        let aspect = layout.aspect();
        let avail = ui.available_rect_before_wrap();
        // The column's own width: a long legend line must not widen the map past it.
        let side = rect.width().min((avail.height() - 60.0) / aspect).max(64.0);
        let map_rect = Rect::from_min_size(avail.min, vec2(side, side * aspect));
        let response = ui.allocate_rect(map_rect, Sense::click_and_drag());
        #[cfg(feature = "test-hooks")]
        super::hooks::set_landmark(ui.ctx(), super::hooks::LANDMARK_SHADOW_MAP, map_rect);
        let painter = ui.painter_at(map_rect);
        // The part of the map shown: all of it, or a window of 1/zoom around the zoom centre.
        let half = 0.5 / zoom;
        let (cx, cy) = self.zoom_centre;
        let (cx, cy) =
            if zoom > 1.0 { (cx.clamp(half, 1.0 - half), cy.clamp(half, 1.0 - half)) } else { (0.5, 0.5) };
        let window = Rect::from_min_max(pos2(cx - half, cy - half), pos2(cx + half, cy + half));
        painter.image(shown_map.texture.id(), map_rect, window, Color32::WHITE);
        let side = side * zoom;
        let to_rect = |uv: [f32; 2]| {
            pos2(
                map_rect.left() + (uv[0] - window.left()) * side,
                map_rect.top() + (uv[1] - window.top()) * side * aspect,
            )
        };
        // Screen pixels per uv of one map (a tile is a column's width).
        let face_side = side / layout.columns as f32;
        let views = shown_map.index..shown_map.index + tile_views.len().max(1);
        // Where uv of the frame's view `view_index` lies in the picture: on its tile (a uv past a
        // cube face's edge on the face its direction falls in, `map_tap`).
        let picture_uv = |view_index: usize, uv: [f32; 2]| -> [f32; 2] {
            if !tiled {
                return uv;
            }
            layout.picture_uv(&tile_views, view_index.saturating_sub(shown_map.index), uv)
        };

        // The probe on the map, at its real size, where it looked up this very view.
        let probe = state.probe.as_ref().and_then(|r| {
            r.lights.iter().find(|l| l.light == state.selected_light && views.contains(&l.shadow_view))
        });
        if let Some(l) = probe {
            let centre = to_rect(picture_uv(l.shadow_view, l.shadow_map_uv));
            if l.blocker_search_radius_uv > 0.0 {
                painter.circle_stroke(
                    centre,
                    l.blocker_search_radius_uv * face_side,
                    Stroke::new(1.5, Color32::from_rgb(86, 180, 233)),
                );
            }
            if l.filter_radius_uv > 0.0 {
                painter.circle_stroke(
                    centre,
                    l.filter_radius_uv * face_side,
                    Stroke::new(1.5, Color32::WHITE),
                );
            }
            for tap in &l.taps {
                let p = to_rect(picture_uv(l.shadow_view, tap.uv));
                let (fill, search) = match tap.kind.as_str() {
                    "blocker-search" => (tap.value > 0.5, true),
                    _ => (tap.value < 0.5, false),
                };
                let color =
                    if fill { Color32::from_rgb(204, 121, 167) } else { Color32::from_rgb(0, 158, 115) };
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
            lang,
            "drag to move the light · blue: blocker search · white: filter · green lit, pink blocked",
        ));
        let hovered = response.hover_pos().and_then(|pos| {
            let u = (window.left() + (pos.x - map_rect.left()) / side).clamp(0.0, 0.9999);
            let v = (window.top() + (pos.y - map_rect.top()) / (side * aspect)).clamp(0.0, 0.9999);
            if !tiled {
                return Some((map, *shadow_view, u, v));
            }
            // Which tile, and where in it.
            let (i, [u, v]) = layout.cell_at(u, v)?;
            let (map, view) = shown_map.tiles.get(i)?;
            Some((map, *view, u, v))
        });
        if let Some((map, view, u, v)) = hovered {
            let shadow_view = &view;
            let (tx, ty) = ((u * map.size as f32) as u32, (v * map.size as f32) as u32);
            let z = map.depth_ndc[(ty * map.size + tx) as usize];
            if z < 1.0 {
                let d = depth_linear_from_ndc(shadow_view, z);
                let p = if cube {
                    // A cube face stores the distance: the point is that far along the texel's ray.
                    let [forward, up, right] = crate::shadow::cube_face_axes(view.face);
                    let ray = (forward + right * (2.0 * u - 1.0) + up * (1.0 - 2.0 * v)).normalize();
                    Vec4::from(view.origin).truncate() + ray * d
                } else {
                    let ndc = Vec4::new(u * 2.0 - 1.0, 1.0 - v * 2.0, z, 1.0);
                    let w = Mat4::from_cols_array_2d(&shadow_view.clip_from_world).inverse() * ndc;
                    w.truncate() / w.w
                };
                info = fill(
                    lang,
                    "texel {},{} · stored {} NDC = {} world · point ({}, {}, {})",
                    &[
                        &tx,
                        &ty,
                        &format!("{z:.5}"),
                        &format!("{d:.3}"),
                        &format!("{:.2}", p.x),
                        &format!("{:.2}", p.y),
                        &format!("{:.2}", p.z),
                    ],
                );
            } else {
                info = fill(lang, "texel {},{} · nothing stored (cleared to 1.0)", &[&tx, &ty]);
            }
            if cube {
                info = format!("{} · {info}", crate::probe::CUBE_FACE_NAMES[view.face as usize]);
            } else if tiled {
                let texel = view.frustum_width_world / view.map_size_texels;
                let name =
                    fill(lang, "cascade {} · texel {} world", &[&(view.face + 1), &format!("{texel:.3}")]);
                info = format!("{name} · {info}");
            }
        }
        // Wrapped to the map's width: the column may be narrow.
        let info_font = egui::FontId::proportional(if state.present { 18.0 } else { 13.0 });
        let galley = ui.painter().layout(info, info_font, Color32::LIGHT_GRAY, side);
        ui.painter().galley(info_pos, galley, Color32::LIGHT_GRAY);

        // Wheel over the map zooms around the probe (or the pointer), to see taps at texel scale.
        if response.hovered() {
            let scroll = ui.input(|i| i.smooth_scroll_delta.y);
            if scroll != 0.0 {
                let max_zoom = (map.size as f32 * layout.columns as f32 / 16.0).max(1.0);
                let was_zoomed = self.zoomed();
                self.zoom = (zoom * (scroll * 0.004).exp()).clamp(1.0, max_zoom);
                if self.zoomed() != was_zoomed {
                    // The picture's resolution follows the zoom.
                    state.dirty = true;
                }
                let pointer = response.hover_pos().map(|p| {
                    (
                        window.left() + (p.x - map_rect.left()) / side,
                        window.top() + (p.y - map_rect.top()) / (side * aspect),
                    )
                });
                let at_probe = probe.map(|l| {
                    let uv = picture_uv(l.shadow_view, l.shadow_map_uv);
                    (uv[0], uv[1])
                });
                if let Some(centre) = at_probe.or(pointer) {
                    self.zoom_centre = centre;
                }
            }
        }

        // Dragging on the map moves the light: yaw about its up axis, pitch towards it.
        if response.dragged() && response.drag_delta() != Vec2::ZERO {
            let d = response.drag_delta();
            if let Some(l) = state.scene.lights.get_mut(state.selected_light) {
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
            state.mark_dirty();
        }
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

//! The bottom panel: the live diagram for the current step (or the one picked) and the
//! sample-pattern plot of the current kernel.

use super::AppState;
use crate::diagrams::{self, DiagramInputs, DiagramKind};
use crate::i18n::Lang;
use crate::lessons::Panel;
use crate::shadow::kernels;
use egui::{Color32, Rect, Sense, Stroke, Ui, pos2, vec2};

/// The bottom panel, which owns the drawn diagram (redrawn when what it was drawn from changes).
#[derive(Default)]
pub struct DiagramPanel {
    diagram: Option<(egui::TextureHandle, DiagramKey)>,
    /// Size of the smallest text in the diagram on screen, points.
    pub smallest_diagram_text_pt: Option<f32>,
    /// The camera picture shown, pixels (the app sets it before each frame's `ui`).
    pub picture_px: (u32, u32),
}

/// What a diagram texture was drawn from: kind, live inputs, language and size in pixels.
#[derive(PartialEq)]
struct DiagramKey {
    kind: DiagramKind,
    inputs: DiagramInputs,
    lang: Lang,
    size_px: (u32, u32),
    present: bool,
}

/// The diagrams' inputs; `picture_px` is the camera picture shown (its shape is what the
/// renderer fitted a sun's cascades to).
fn live_inputs(state: &AppState, picture_px: (u32, u32)) -> DiagramInputs {
    let probe = state.probe.as_ref();
    let light_probe = probe.and_then(|p| p.lights.iter().find(|l| l.light == state.selected_light));
    // The probe's own frame where there is a probe: its cascade is the one the text quotes.
    let (width, height) = probe.map_or(picture_px, |p| (p.size[0], p.size[1]));
    let aspect = if width > 0 && height > 0 { width as f32 / height as f32 } else { 16.0 / 9.0 };
    diagrams::live::inputs_from_scene(
        &state.scene,
        state.selected_light,
        state.time_s,
        light_probe,
        probe.and_then(|p| p.normal),
        aspect,
    )
}

impl DiagramPanel {
    /// The diagram tabs, the diagram and the sample pattern, from `state`.
    pub fn ui(&mut self, ui: &mut Ui, state: &mut AppState) {
        let show_diagram = state.panel_visible(Panel::Diagram);
        // Tabs wrap in a narrow panel rather than widen it over its neighbours.
        ui.horizontal_wrapped(|ui| {
            if show_diagram {
                ui.strong(crate::i18n::tr(state.lang, "Diagram"));
                for kind in DiagramKind::ALL {
                    if ui
                        .selectable_label(state.diagram == kind, kind.label(state.lang))
                        .on_hover_text(crate::i18n::tr(state.lang, kind.title()))
                        .clicked()
                    {
                        state.diagram = kind;
                    }
                }
                ui.separator();
            }
            if state.current_step().is_none() {
                ui.checkbox(
                    &mut state.settings.show_kernel_plot,
                    crate::i18n::tr(state.lang, "sample pattern"),
                );
            }
        });
        // On a projector the diagram takes the whole width (the sample pattern beside it is left out).
        let show_plot = state.panel_visible(Panel::KernelPlot) && !(state.present && show_diagram);
        let avail = ui.available_rect_before_wrap();
        let plot_width = match (show_plot, show_diagram) {
            (false, _) => 0.0,
            (true, true) => avail.height().min(avail.width() * 0.3),
            (true, false) => avail.width(),
        };
        let diagram_rect =
            Rect::from_min_max(avail.min, pos2(avail.right() - plot_width - 8.0, avail.bottom()));
        let plot_rect = Rect::from_min_max(pos2(avail.right() - plot_width, avail.top()), avail.max);
        if show_diagram {
            self.diagram(ui, state, diagram_rect);
        }
        if show_plot {
            kernel_plot(state, ui, plot_rect);
        }
        ui.allocate_rect(avail, Sense::hover());
    }
}

/// Smallest diagram text on screen, points: readable from the back of a classroom.
pub const DIAGRAM_MIN_TEXT_PT: f32 = 14.0;
/// The same in present mode, points.
pub const PRESENT_DIAGRAM_MIN_TEXT_PT: f32 = 18.0;

impl DiagramPanel {
    fn diagram(&mut self, ui: &mut Ui, state: &mut AppState, rect: Rect) {
        // The whole width (text columns and legend use what is wider than 16:9), at most 16:9
        // tall, drawn at the screen's pixel density.
        let (w, h) = (rect.width(), rect.height().min(rect.width() * 9.0 / 16.0));
        let ppp = ui.ctx().pixels_per_point();
        let size_px = ((w * ppp).max(32.0) as u32, (h * ppp).max(18.0) as u32);
        let key = DiagramKey {
            kind: state.diagram,
            inputs: live_inputs(state, self.picture_px),
            lang: state.lang,
            size_px,
            present: state.present,
        };
        let current = self.diagram.as_ref().is_some_and(|(_, drawn)| *drawn == key);
        if !current {
            // On a projector, the lesson text's size (the diagram is read from the back row too).
            let min_text_pt = if state.present { PRESENT_DIAGRAM_MIN_TEXT_PT } else { DIAGRAM_MIN_TEXT_PT };
            let min_text_px = min_text_pt * ppp;
            match diagrams::draw_traced(key.kind, &key.inputs, key.lang, [size_px.0, size_px.1], min_text_px)
            {
                Ok((pixmap, texts)) => {
                    let smallest_px = texts.iter().map(|(_, px)| *px).fold(f32::INFINITY, f32::min);
                    self.smallest_diagram_text_pt = Some(smallest_px / ppp);
                    let image = egui::ColorImage::from_rgba_premultiplied(
                        [pixmap.width() as usize, pixmap.height() as usize],
                        pixmap.data(),
                    );
                    let texture = ui.ctx().load_texture("diagram", image, egui::TextureOptions::LINEAR);
                    self.diagram = Some((texture, key));
                }
                Err(e) => state.error = Some(super::AppError::new("could not draw the diagram", e)),
            }
        }
        if let Some((texture, ..)) = &self.diagram {
            let shown = Rect::from_min_size(rect.min, vec2(w, h));
            ui.painter().image(
                texture.id(),
                shown,
                Rect::from_min_max(pos2(0.0, 0.0), pos2(1.0, 1.0)),
                Color32::WHITE,
            );
        }
    }
}

fn kernel_plot(state: &AppState, ui: &mut Ui, rect: Rect) {
    let painter = ui.painter_at(rect);
    painter.rect_filled(rect, 4.0, Color32::from_gray(24));
    let s = &state.scene.shadow;
    let seed = state
        .probe
        .as_ref()
        .map(|p| kernels::pixel_seed((p.pixel[0], p.pixel[1]), s.noise_seed, s.rotate_per_pixel))
        .unwrap_or_else(|| kernels::pixel_seed((0, 0), s.noise_seed, s.rotate_per_pixel));
    let points = kernels::kernel_points(s.pcf_kernel, s.samples, seed);
    // The caption wraps within the plot (a narrow plot used to cut it), the disk below it.
    let caption = crate::i18n::fill(
        state.lang,
        "{} · {} taps{}",
        &[
            &s.pcf_kernel.label(state.lang),
            &points.len(),
            &if s.rotate_per_pixel { crate::i18n::tr(state.lang, " · rotated per pixel") } else { "" },
        ],
    );
    let galley = painter.layout(
        caption,
        egui::FontId::proportional(13.0),
        Color32::LIGHT_GRAY,
        (rect.width() - 12.0).max(20.0),
    );
    let caption_height = galley.size().y;
    painter.galley(pos2(rect.left() + 6.0, rect.top() + 4.0), galley, Color32::LIGHT_GRAY);
    let top = rect.top() + 4.0 + caption_height + 6.0;
    let radius = ((rect.width() - 12.0).min(rect.bottom() - top - 6.0) * 0.5).max(4.0);
    let centre = pos2(rect.center().x, top + radius);
    painter.circle_stroke(centre, radius, Stroke::new(1.0, Color32::GRAY));
    painter.line_segment(
        [centre - vec2(radius, 0.0), centre + vec2(radius, 0.0)],
        Stroke::new(0.5, Color32::DARK_GRAY),
    );
    painter.line_segment(
        [centre - vec2(0.0, radius), centre + vec2(0.0, radius)],
        Stroke::new(0.5, Color32::DARK_GRAY),
    );
    for (i, p) in points.iter().enumerate() {
        let t = i as f32 / points.len().max(1) as f32;
        let color = Color32::from_rgb((86.0 + 160.0 * t) as u8, (180.0 - 60.0 * t) as u8, 233);
        painter.circle_filled(centre + vec2(p.x, -p.y) * radius, 3.0, color);
    }
}

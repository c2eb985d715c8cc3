//! What the camera panel makes of the frame shown: the debug view and the overlays as textures,
//! their legends, and the pictures behind them (for the per-view screenshot).

use super::AppState;
use super::rendering::{Shown, color_image};
use crate::i18n::{Lang, tr};
use crate::views::View;
use crate::views::overlays::Overlay;

/// The view the camera panel is set to show: the chosen one, or the shaded picture while the A/B
/// split compares two of them.
pub(super) fn view_kind(state: &AppState) -> View {
    if state.ab.is_some() { View::Final } else { state.view }
}

/// The debug view (visibility, heatmaps, reference, error) and the overlays, made again when
/// what is shown changes, the language changes or another view is picked.
#[derive(Default)]
pub(super) struct CameraPictures {
    /// What they were made from: `Shown::changes` and the legends' language (none: make them again).
    made_from: Option<(u64, Lang)>,
    /// The debug view and its legend.
    pub(super) view_image: Option<egui::TextureHandle>,
    view_legend: Option<String>,
    /// The overlays on, in one image, and their legends.
    pub(super) overlay: Option<egui::TextureHandle>,
    legends: Vec<String>,
    /// The pictures behind `view_image` and `overlay`, for the per-view screenshot.
    pub(super) view_picture: Option<image::RgbaImage>,
    pub(super) overlay_picture: Option<image::RgbaImage>,
}

impl CameraPictures {
    /// Make them again on the next frame.
    pub(super) fn invalidate(&mut self) {
        self.made_from = None;
    }

    /// The view's legend lines, then the overlays'.
    pub(super) fn legend_lines(&self) -> Vec<String> {
        let view = self.view_legend.iter().flat_map(|l| l.lines()).map(String::from);
        view.chain(self.legends.iter().cloned()).collect()
    }

    /// Make the pictures of what is shown, unless they are made already.
    pub(super) fn refresh(&mut self, ctx: &egui::Context, state: &AppState, shown: &Shown) {
        if self.made_from == Some((shown.changes, state.lang)) {
            return;
        }
        self.made_from = Some((shown.changes, state.lang));
        let light = shown.light_view(state.selected_light);
        // The debug view from the analysis pass (and the ground truth).
        self.view_image = None;
        self.view_legend = None;
        self.view_picture = None;
        self.overlay_picture = None;
        if let Some(analysis) = &shown.analysis {
            // The samples of the ground truth shown (it was worked out for the frame on screen).
            let samples =
                shown.reference_progress.map_or(state.scene.shadow.reference_samples, |(_, all)| all);
            let light_and_params = light.as_ref().map(|l| (l, &shown.params));
            if let Some((image, legend)) = crate::views::analysis_view(
                state.view,
                analysis,
                state.reference.as_deref(),
                samples,
                light_and_params,
                &shown.views,
                state.lang,
            ) {
                self.view_image =
                    Some(ctx.load_texture("debug view", color_image(&image), egui::TextureOptions::NEAREST));
                self.view_legend = Some(legend);
                self.view_picture = Some(image);
            } else if state.view == View::Moments {
                self.view_legend =
                    Some(tr(state.lang, "the moments view needs the vsm or vssm technique").into());
            }
        }
        // Overlays from the analysis pass.
        self.overlay = None;
        self.legends.clear();
        if let Some(analysis) = &shown.analysis {
            let overlays: Vec<Overlay> = state
                .overlays
                .iter()
                .copied()
                .filter(|&o| !crate::views::overlays::hidden_by_view(view_kind(state), o))
                .collect();
            let (image, legends) = crate::views::overlays::compose(
                state.lang,
                &overlays,
                analysis,
                light.as_ref().map(|l| &l.view),
                state.reference.as_deref(),
            );
            self.legends = legends;
            if !overlays.is_empty() {
                self.overlay =
                    Some(ctx.load_texture("overlay", color_image(&image), egui::TextureOptions::NEAREST));
                self.overlay_picture = Some(image);
            }
        }
    }
}

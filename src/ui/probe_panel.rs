//! The probe's numbers: for the pinned pixel and each light, where it lands in the map, the
//! depths and bias, the blocker search, the penumbra and filter, the visibility on the GPU, in
//! the twin and (on request, or where the lesson quotes it) the ground truth.

use super::AppState;
use crate::i18n::{fill, tr as translate};
use egui::Ui;

pub(super) fn probe_values(state: &mut AppState, ui: &mut Ui) {
    let lang = state.lang;
    let tr = move |en: &'static str| translate(lang, en);
    ui.heading(tr("Probe"));
    let Some(report) = state.probe_report() else {
        ui.label(tr("click the camera view to pin a probe"));
        return;
    };
    // A lesson's probe is a pixel of the lesson's own frame, not of this view.
    let ([x, y], [w, h]) = (report.pixel, report.size);
    let lesson_frame = matches!(state.probe_at, Some(super::ProbeAt::LessonFrame(..)));
    let pixel = match lesson_frame {
        true => fill(lang, "pixel {},{} of the lesson's {}x{} frame", &[&x, &y, &w, &h]),
        false => fill(lang, "pixel {},{}", &[&x, &y]),
    };
    if !report.hit {
        ui.label(format!("{pixel}: {}", tr("no surface")));
        return;
    }
    let object = report.object.as_deref().map_or("?", |name| state.scene.object_label(name, lang));
    ui.label(fill(lang, "{}, on {}", &[&pixel, &object]));
    let Some(l) = report.lights.iter().find(|l| l.light == state.selected_light) else { return };
    let truth = match (l.visibility_reference, state.probe_reference_progress(l.light)) {
        (Some(value), progress) => Truth::Value(value, progress.map(|(_, total)| total)),
        (None, Some((done, total))) if done < total => Truth::Accumulating(done, total),
        _ => Truth::NotAsked,
    };
    let mut ask = false;
    egui::Grid::new("probe").striped(true).num_columns(2).show(ui, |ui| {
        let mut row = |name: &str, value: String| {
            ui.label(name);
            // Wraps at the " · " between units rather than running past a narrow column.
            ui.add(
                egui::Label::new(egui::RichText::new(value).monospace()).wrap_mode(egui::TextWrapMode::Wrap),
            );
            ui.end_row();
        };
        if let Some(face) = &l.cube_face {
            row(tr("cube face"), face.clone());
        }
        if let Some(c) = &l.cascade {
            row(
                tr("cascade"),
                fill(
                    lang,
                    "{} of {} · texel {} world",
                    &[&(c.index + 1), &c.count, &format!("{:.3}", c.texel_world)],
                ),
            );
            if let (Some(depth), Some([near, far])) = (c.view_depth_world, c.slice_world) {
                let slice = format!("{near:.1}–{far:.1}");
                let t = fill(lang, "{} world · in the slice {}", &[&format!("{depth:.2}"), &slice]);
                row(tr("depth along the view axis"), t);
            }
            if !c.uv_in_sharper.is_empty() {
                let misses: Vec<String> =
                    c.uv_in_sharper.iter().map(|uv| format!("({:.2}, {:.2})", uv[0], uv[1])).collect();
                row(tr("sharper cascades miss it at uv"), misses.join(" "));
            }
        }
        row(tr("shadow-map uv"), format!("{:.4}, {:.4}", l.shadow_map_uv[0], l.shadow_map_uv[1]));
        row(tr("texel"), format!("{}, {}", l.shadow_map_texel[0], l.shadow_map_texel[1]));
        row(
            tr("receiver depth"),
            format!("{:.4} NDC · {:.3} {}", l.receiver_depth_ndc, l.receiver_depth_linear, tr("world")),
        );
        row(
            tr("stored depth"),
            format!("{:.4} NDC · {:.3} {}", l.stored_depth_ndc, l.stored_depth_linear, tr("world")),
        );
        if let Some(v) = &l.vsm {
            row(
                tr("VSM mean, variance"),
                format!("{:.4} NDC, {:.2e} NDC²", v.mean_depth_ndc, v.variance_ndc2),
            );
            row(
                tr("Chebyshev bound / true share"),
                format!("{:.3} / {:.3}", v.chebyshev_bound, v.true_lit_fraction),
            );
            if v.visibility != v.chebyshev_bound {
                row(tr("after bleed reduction"), format!("{:.3}", v.visibility));
            }
        }
        if let Some(error) = l.stored_depth_rgba8_error_ndc {
            row(tr("RGBA8 round trip"), format!("{error:+.6} NDC"));
        }
        row(tr("bias"), format!("{:.6} NDC", l.bias_ndc));
        if let Some(per_texel) = l.receiver_plane_depth_per_texel_world {
            row(tr("receiver plane"), format!("{per_texel:.4} {} / {}", tr("world"), tr("texel")));
        }
        row(tr("N·L"), format!("{:.3}", l.n_dot_l));
        row(tr("blocker search"), format!("{:.2} {}", l.blocker_search_radius_texels, tr("texels")));
        row(tr("blockers found"), format!("{} / {}", l.blockers_found, l.blocker_samples));
        row(
            tr("avg blocker depth"),
            l.avg_blocker_depth_linear.map_or(tr("none").into(), |d| format!("{d:.3} {}", tr("world"))),
        );
        if let Some(v) = &l.vssm {
            let depth = |d: Option<f32>| d.map_or(tr("none").into(), |d| format!("{d:.3}"));
            row(
                tr("VSSM / true / PCSS blocker depth"),
                format!(
                    "{:.3} / {} / {} {}",
                    v.estimated_blocker_depth_linear,
                    depth(v.footprint_blocker_depth_linear),
                    depth(v.pcss_blocker_depth_linear),
                    tr("world")
                ),
            );
        }
        row(tr("penumbra width"), format!("{:.4} {}", l.penumbra_width_world, tr("world")));
        row(
            tr("filter radius"),
            format!("{:.2} {} ({} {})", l.filter_radius_texels, tr("texels"), l.filter_samples, tr("taps")),
        );
        row(tr("visibility (CPU twin)"), format!("{:.4}", l.visibility_twin));
        row(tr("visibility (GPU)"), format!("{:.4}", l.visibility_gpu));
        // The ground truth at this pixel: on demand (a few seconds on a software rasteriser), or
        // at once where the lesson text quotes it.
        ui.label(tr("ground truth"));
        let fill = |template, args: &[&dyn std::fmt::Display]| crate::i18n::fill(lang, template, args);
        let value = |text: String| egui::RichText::new(text).monospace();
        match truth {
            Truth::Value(v, Some(total)) => {
                ui.label(value(fill("{} ({} samples)", &[&format!("{v:.4}"), &total])));
            }
            Truth::Value(v, None) => {
                ui.label(value(format!("{v:.4}")));
            }
            Truth::Accumulating(done, total) => {
                ui.label(value(fill("{} / {} samples…", &[&done, &total])));
            }
            Truth::NotAsked => {
                ask = ui
                    .button(tr("work it out"))
                    .on_hover_text(tr(
                        "average the ground truth's hard shadows at this pixel (a few seconds)",
                    ))
                    .clicked();
            }
        }
        ui.end_row();
    });
    if ask {
        state.ask_probe_truth();
    }
}

/// The probe panel's ground-truth row.
enum Truth {
    /// Known (with the samples averaged, where this probe worked it out).
    Value(f32, Option<u32>),
    /// Samples done of all.
    Accumulating(u32, u32),
    NotAsked,
}

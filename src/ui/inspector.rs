//! The inspector: every scene, light and `[shadow]` parameter, with units in the labels, then
//! the probe's numbers (src/ui/probe_panel.rs). Any change re-renders at once. Each control is
//! drawn from its row of src/scene/parameters (label, span, scale), which the loader checks by.

use super::{AbSplit, AppState};
use crate::i18n::Lang;
use crate::i18n::tr as translate;
use crate::scene::parameters::{self as params, Control, Field, Parameter};
use crate::scene::{
    BiasMode, CascadeSelection, DepthStorage, Kernel, LightKind, LightSize, Projection, Technique,
};
use crate::views::overlays::Overlay;
use egui::{Response, Slider, Ui};

fn combo<T: Copy + PartialEq>(
    lang: Lang,
    ui: &mut Ui,
    label: &str,
    value: &mut T,
    all: &[T],
    name: impl Fn(T, Lang) -> &'static str,
    key: Option<&str>,
) -> bool {
    let mut changed = false;
    let response = egui::ComboBox::from_label(label).selected_text(name(*value, lang)).show_ui(ui, |ui| {
        for &option in all {
            changed |= ui.selectable_value(value, option, name(option, lang)).changed();
        }
    });
    if let Some(key) = key {
        response.response.on_hover_text(key_hint(lang, key));
    }
    changed
}

/// The English label of the inspector control that sets scene key `key` (`light.2.width`
/// finds the light-width slider), or `None` when the app has no control a lesson may name for
/// it: "Try this" prompts name the control, and the tests check they do.
pub fn control_label(key: &str) -> Option<&'static str> {
    params::named(key).map(|p| p.label)
}

/// `value` of scene key `key` as the inspector shows it in `lang`: a technique, bias mode,
/// kernel, depth storage or cascade selection by its label in the combo box, anything else as it is.
pub fn value_label<'a>(key: &str, value: &'a str, lang: Lang) -> &'a str {
    let label = match key {
        "technique" => Technique::from_name(value).map(|v| v.label(lang)),
        "bias_mode" => BiasMode::from_name(value).map(|v| v.label(lang)),
        "pcf_kernel" => Kernel::from_name(value).map(|v| v.label(lang)),
        "depth_storage" => DepthStorage::from_name(value).map(|v| v.label(lang)),
        k if k.starts_with("light.") && k.ends_with(".cascade_selection") => {
            CascadeSelection::from_name(value).map(|v| v.label(lang))
        }
        _ => None,
    };
    label.unwrap_or(value)
}

/// The hover text naming a widget's key in scene and lesson files (`--set KEY=VALUE`).
fn key_hint(lang: Lang, key: &str) -> String {
    crate::i18n::fill(lang, "scene key `{}` (lessons and --set use it)", &[&key])
}

/// `response` with the row's key on hover, where the row names it.
fn hinted(lang: Lang, row: &Parameter, response: Response) -> Response {
    if row.named { response.on_hover_text(key_hint(lang, row.key)) } else { response }
}

/// The slider of a row over a number, from `lo` to `hi`. A value the loader took beyond the span
/// (a scene's or a lesson's) is kept as it is: only the user's own edits stay within the span.
fn slider<'a, N: egui::emath::Numeric>(
    lang: Lang,
    row: &Parameter,
    value: &'a mut N,
    (lo, hi): (f32, f32),
    log: bool,
) -> Slider<'a> {
    let (lo, hi) = (N::from_f64(f64::from(lo)), N::from_f64(f64::from(hi)));
    Slider::new(value, lo..=hi)
        .logarithmic(log)
        .clamping(egui::SliderClamping::Edits)
        .text(translate(lang, row.label))
}

/// The slider of a light's or the camera's row over `value`: the row's span (a near plane's up to
/// a share of the far plane `other_plane`, a far plane's from beyond the near plane), with the key
/// on hover where the row names it.
fn number(lang: Lang, ui: &mut Ui, row: &Parameter, value: &mut f32, other_plane: f32) -> Response {
    let (lo, hi, log) = match (row.control, row.values) {
        (Control::Slider { lo, hi, log }, _) => (lo, hi, log),
        (Control::NearSlider { lo, below_far }, _) => (lo, other_plane * below_far, true),
        (Control::FarSlider { beyond_near, hi }, _) => (other_plane * beyond_near, hi, true),
        // Not a slider (the table's tests hold every row to its control): what the loader accepts.
        (_, params::Values::Real { lo, hi }) => (lo, hi, false),
        _ => (f32::MIN, f32::MAX, false),
    };
    let response = ui.add(slider(lang, row, value, (lo, hi), log));
    hinted(lang, row, response)
}

/// The control of a `[shadow]` row over its field; true when the user changed the value.
fn shadow_control(lang: Lang, ui: &mut Ui, row: &Parameter, field: Field<'_>) -> bool {
    let label = translate(lang, row.label);
    let key = row.named.then_some(row.key);
    let response = match (field, row.control) {
        (Field::Real(v), Control::Slider { lo, hi, log }) => ui.add(slider(lang, row, v, (lo, hi), log)),
        (Field::Int(v), Control::Slider { lo, hi, log }) => ui.add(slider(lang, row, v, (lo, hi), log)),
        (Field::Count(v), Control::Slider { lo, hi, log }) => ui.add(slider(lang, row, v, (lo, hi), log)),
        (Field::Count(v), Control::Drag) => ui.add(egui::DragValue::new(v).prefix(format!("{label} "))),
        (Field::Switch(v), Control::Checkbox) => ui.checkbox(v, label),
        (Field::Technique(v), _) => return combo(lang, ui, label, v, Technique::ALL, Technique::label, key),
        (Field::BiasMode(v), _) => return combo(lang, ui, label, v, BiasMode::ALL, BiasMode::label, key),
        (Field::Kernel(v), _) => return combo(lang, ui, label, v, Kernel::ALL, Kernel::label, key),
        (Field::DepthStorage(v), _) => {
            return combo(lang, ui, label, v, DepthStorage::ALL, DepthStorage::label, key);
        }
        // A control that does not fit its field (the table's tests hold every row to its field).
        _ => return false,
    };
    hinted(lang, row, response).changed()
}

pub fn show(state: &mut AppState, ui: &mut Ui) {
    let lang = state.lang;
    let tr = move |en: &'static str| translate(lang, en);
    let mut changed = false;
    // The `[shadow]` rows in their sections, with what the inspector shows beside some of them.
    let mut section = None;
    for row in &params::SHADOW {
        if section != Some(row.section) {
            if section.is_some() {
                ui.separator();
            }
            if !row.section.is_empty() {
                ui.heading(tr(row.section));
            }
            section = Some(row.section);
        }
        let Some(field) = row.field else { continue };
        changed |= shadow_control(lang, ui, row, field(&mut state.scene.shadow));
        match row.key {
            "technique" => changed |= ab_split(state, ui),
            "samples" if state.scene.shadow.pcf_kernel == Kernel::Grid => {
                let side = crate::shadow::kernels::grid_side(state.scene.shadow.samples);
                ui.small(crate::i18n::fill(
                    lang,
                    "grid uses {}×{} = {} taps",
                    &[&side, &side, &(side * side)],
                ));
            }
            _ => {}
        }
    }

    ui.separator();
    changed |= lights(state, ui);

    ui.separator();
    ui.heading(tr("Camera"));
    if let Projection::Perspective { fov_deg } = &mut state.scene.camera.projection {
        changed |= number(lang, ui, &params::CAMERA_FOV, fov_deg, 0.0).changed();
    }
    if ui.button(tr("Reset camera (R)")).clicked() {
        state.reset_camera();
    }

    ui.separator();
    ui.heading(tr("Overlays"));
    for overlay in Overlay::ALL {
        let mut on = state.overlays.contains(&overlay);
        if ui.checkbox(&mut on, tr(overlay.name())).changed() {
            if on {
                state.overlays.push(overlay);
            } else {
                state.overlays.retain(|o| *o != overlay);
            }
            changed = true;
        }
    }

    ui.separator();
    if ui.button(tr("Reset to scene/lesson values")).clicked() {
        state.reset();
    }
    if cfg!(target_arch = "wasm32") {
        // A page has no folder to write to.
        ui.label(tr("in the page, screenshots are downloads (PNG files in the browser's download folder)"));
    } else {
        ui.horizontal(|ui| {
            let label = ui.label(tr("screenshot folder"));
            let mut folder = state.settings.screenshot_dir.display().to_string();
            if ui.text_edit_singleline(&mut folder).labelled_by(label.id).changed() {
                state.settings.screenshot_dir = folder.into();
            }
        });
    }
    ui.separator();
    super::probe_panel::probe_values(state, ui);
    if changed {
        state.mark_dirty();
    }
}

/// The A/B split's checkbox and, while it is on, the technique on its right side.
fn ab_split(state: &mut AppState, ui: &mut Ui) -> bool {
    let lang = state.lang;
    let tr = move |en: &'static str| translate(lang, en);
    let mut changed = false;
    let mut ab_on = state.ab.is_some();
    if ui
        .checkbox(&mut ab_on, tr("A/B split against"))
        .on_hover_text(tr("drag the divider in the camera view"))
        .changed()
    {
        state.ab = ab_on.then_some(AbSplit { b: Technique::Hard, divider: 0.5, grabbed: false });
        changed = true;
    }
    if let Some(ab) = &mut state.ab {
        changed |= combo(lang, ui, tr("right side"), &mut ab.b, Technique::ALL, Technique::label, None);
    }
    changed
}

fn lights(state: &mut AppState, ui: &mut Ui) -> bool {
    let lang = state.lang;
    let tr = move |en: &'static str| translate(lang, en);
    let mut changed = false;
    ui.heading(tr("Lights"));
    let count = state.scene.lights.len();
    if count == 0 {
        ui.label(tr("this scene has no lights"));
        return false;
    }
    ui.horizontal(|ui| {
        for i in 0..count {
            if ui.selectable_label(state.selected_light == i, format!("{} {i}", tr("light"))).clicked() {
                state.selected_light = i;
                changed = true;
            }
        }
    });
    let Some(light) = state.scene.lights.get_mut(state.selected_light) else { return changed };
    for (row, point) in
        [(&params::LIGHT_POSITION, &mut light.position), (&params::LIGHT_TARGET, &mut light.target)]
    {
        ui.horizontal(|ui| {
            let name = hinted(lang, row, ui.label(tr(row.label)));
            for (axis, prefix) in ["x ", "y ", "z "].into_iter().enumerate() {
                let value = egui::DragValue::new(&mut point[axis])
                    .speed(0.5)
                    .max_decimals(2)
                    .range(-params::MAX_COORDINATE..=params::MAX_COORDINATE)
                    .prefix(prefix);
                changed |= ui.add(value).labelled_by(name.id).changed();
            }
        });
    }
    let sizes = match params::LIGHT_SHADOW_MAP_SIZE.control {
        Control::Sizes(sizes) => sizes,
        _ => &[],
    };
    let mut size = light.shadow_map_size;
    egui::ComboBox::from_label(tr(params::LIGHT_SHADOW_MAP_SIZE.label))
        .selected_text(format!("{size}²"))
        .show_ui(ui, |ui| {
            for &option in sizes {
                ui.selectable_value(&mut size, option, format!("{option}²"));
            }
        });
    if size != light.shadow_map_size {
        light.shadow_map_size = size;
        changed = true;
    }
    match &mut light.kind {
        LightKind::Directional { extent_world } => {
            ui.label(tr("directional light, orthographic map"));
            changed |= number(lang, ui, &params::LIGHT_EXTENT, extent_world, 0.0).changed();
            let cascades = &mut light.cascades;
            let row = &params::LIGHT_CASCADES;
            let count = ui.add(slider(
                lang,
                row,
                &mut cascades.count,
                (1.0, crate::scene::MAX_CASCADES as f32),
                false,
            ));
            changed |= hinted(lang, row, count).changed();
            if cascades.is_cascaded() {
                changed |=
                    number(lang, ui, &params::LIGHT_CASCADE_LAMBDA, &mut cascades.lambda, 0.0).changed();
                let row = &params::LIGHT_CASCADE_SELECTION;
                let (all, label) = (CascadeSelection::ALL, CascadeSelection::label);
                changed |= combo(lang, ui, tr(row.label), &mut cascades.selection, all, label, Some(row.key));
            }
        }
        LightKind::Spot { fov_deg } => {
            ui.label(tr("spot light, perspective map"));
            changed |= number(lang, ui, &params::LIGHT_FOV, fov_deg, 0.0).changed();
        }
        LightKind::Point => {
            ui.label(tr("point light, a cube map of six faces"));
        }
    }
    let far = light.far;
    changed |= number(lang, ui, &params::LIGHT_NEAR, &mut light.near, far).changed();
    let near = light.near;
    changed |= number(lang, ui, &params::LIGHT_FAR, &mut light.far, near).changed();
    let directional = light.is_orthographic();
    match &mut light.size {
        LightSize::Width { width_world } => {
            let slider = number(lang, ui, &params::LIGHT_WIDTH, width_world, 0.0);
            #[cfg(feature = "test-hooks")]
            super::hooks::set_landmark(ui.ctx(), super::hooks::LANDMARK_LIGHT_WIDTH, slider.rect);
            changed |= slider.changed();
            if directional && ui.small_button(tr("use an angular diameter instead")).clicked() {
                light.size = LightSize::AngularDiameter { angular_diameter_deg: 0.53 };
                changed = true;
            }
        }
        LightSize::AngularDiameter { angular_diameter_deg } => {
            changed |= number(lang, ui, &params::LIGHT_ANGULAR_DIAMETER, angular_diameter_deg, 0.0).changed();
            if ui.small_button(tr("use a width instead")).clicked() {
                light.size = LightSize::Width { width_world: 2.0 };
                changed = true;
            }
        }
    }
    changed |= number(lang, ui, &params::LIGHT_INTENSITY, &mut light.intensity, 0.0).changed();
    changed |= number(lang, ui, &params::LIGHT_ORBIT, &mut light.orbit_deg_per_s, 0.0).changed();
    changed
}

//! The inspector: every scene, light and `[shadow]` parameter, with units in the labels, then
//! the probe's numbers (src/ui/probe_panel.rs). Any change re-renders at once.

use super::{AbSplit, AppState};
use crate::i18n::Lang;
use crate::i18n::tr as translate;
use crate::scene::{BiasMode, DepthStorage, Kernel, LightKind, LightSize, Projection, Technique};
use crate::views::overlays::Overlay;
use egui::{Slider, Ui};

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

/// The hover text naming a widget's key in scene and lesson files (`--set KEY=VALUE`).
/// The inspector control of each scene key a lesson may change (`light.N.*` for any light),
/// by its English label: "Try this" prompts name the control, and the tests check they do.
const CONTROLS: &[(&str, &str)] = &[
    ("technique", "technique"),
    ("bias_mode", "bias mode"),
    ("bias", "bias (NDC depth)"),
    ("slope_bias", "slope bias (NDC)"),
    ("adaptive_c", "adaptive c (× half texel)"),
    ("normal_offset_texels", "normal offset (texels)"),
    ("depth_bias_constant", "hardware bias (depth units)"),
    ("depth_bias_slope", "hardware slope bias"),
    ("cull_front_faces", "cull front faces in the shadow pass"),
    ("clamp_outside", "outside the light frustum = lit"),
    ("pcf_kernel", "kernel"),
    ("samples", "samples"),
    ("radius_texels", "radius (texels)"),
    ("rotate_per_pixel", "rotate the pattern per pixel"),
    ("blocker_samples", "blocker samples"),
    ("min_filter_radius_texels", "min filter radius (texels)"),
    ("search_radius_scale", "search radius (× light cone)"),
    ("depth_storage", "depth storage"),
    ("ortho_near_factor", "near / d on orthographic maps (NVIDIA's factor)"),
    ("vsm_min_variance", "VSM min variance (NDC²)"),
    ("vsm_bleed_reduction", "VSM bleed reduction"),
    ("reference_samples", "ground-truth samples"),
    ("light.N.shadow_map_size", "shadow map (texels)"),
    ("light.N.extent", "half-width (world units)"),
    ("light.N.near", "near (world units)"),
    ("light.N.far", "far (world units)"),
    ("light.N.width", "light width (world units)"),
    ("light.N.angular_diameter_deg", "angular diameter (°)"),
    ("light.N.intensity", "intensity"),
    ("light.N.orbit_deg_per_s", "orbit (°/s)"),
    ("light.N.position", "position"),
    ("light.N.target", "target"),
];

/// The English label of the inspector control that sets scene key `key` (`light.2.width`
/// finds the light-width slider), or `None` when the app has no control for it.
pub fn control_label(key: &str) -> Option<&'static str> {
    let parts: Vec<&str> = key.split('.').collect();
    let key = match parts.as_slice() {
        ["light", n, rest] if n.parse::<usize>().is_ok() => format!("light.N.{rest}"),
        _ => key.to_string(),
    };
    CONTROLS.iter().find(|(k, _)| *k == key).map(|(_, label)| *label)
}

/// `value` of scene key `key` as the inspector shows it in `lang`: a technique, bias mode,
/// kernel or depth storage by its label in the combo box, anything else as it is.
pub fn value_label<'a>(key: &str, value: &'a str, lang: Lang) -> &'a str {
    let label = match key {
        "technique" => Technique::from_name(value).map(|v| v.label(lang)),
        "bias_mode" => BiasMode::from_name(value).map(|v| v.label(lang)),
        "pcf_kernel" => Kernel::from_name(value).map(|v| v.label(lang)),
        "depth_storage" => DepthStorage::from_name(value).map(|v| v.label(lang)),
        _ => None,
    };
    label.unwrap_or(value)
}

fn key_hint(lang: Lang, key: &str) -> String {
    crate::i18n::fill(lang, "scene key `{}` (lessons and --set use it)", &[&key])
}

pub fn show(state: &mut AppState, ui: &mut Ui) {
    let lang = state.lang;
    let tr = move |en: &'static str| translate(lang, en);
    let mut changed = false;
    let s = &mut state.scene.shadow;
    ui.heading(tr("Technique"));
    changed |= combo(
        lang,
        ui,
        tr("technique"),
        &mut s.technique,
        Technique::ALL,
        Technique::label,
        Some("technique"),
    );
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

    ui.separator();
    ui.heading(tr("Bias"));
    changed |=
        combo(lang, ui, tr("bias mode"), &mut s.bias_mode, BiasMode::ALL, BiasMode::label, Some("bias_mode"));
    changed |= ui
        .add(Slider::new(&mut s.bias, 0.0..=0.05).logarithmic(true).text(tr("bias (NDC depth)")))
        .on_hover_text(key_hint(lang, "bias"))
        .changed();
    changed |= ui
        .add(Slider::new(&mut s.slope_bias, 0.0..=0.2).logarithmic(true).text(tr("slope bias (NDC)")))
        .on_hover_text(key_hint(lang, "slope_bias"))
        .changed();
    changed |= ui
        .add(Slider::new(&mut s.adaptive_c, 0.0..=8.0).text(tr("adaptive c (× half texel)")))
        .on_hover_text(key_hint(lang, "adaptive_c"))
        .changed();
    changed |= ui
        .add(Slider::new(&mut s.normal_offset_texels, 0.0..=4.0).text(tr("normal offset (texels)")))
        .on_hover_text(key_hint(lang, "normal_offset_texels"))
        .changed();
    changed |= ui
        .add(Slider::new(&mut s.depth_bias_constant, 0..=20000).text(tr("hardware bias (depth units)")))
        .on_hover_text(key_hint(lang, "depth_bias_constant"))
        .changed();
    changed |= ui
        .add(Slider::new(&mut s.depth_bias_slope, -4.0..=8.0).text(tr("hardware slope bias")))
        .on_hover_text(key_hint(lang, "depth_bias_slope"))
        .changed();
    changed |= ui
        .checkbox(&mut s.cull_front_faces, tr("cull front faces in the shadow pass"))
        .on_hover_text(key_hint(lang, "cull_front_faces"))
        .changed();
    changed |= ui
        .checkbox(&mut s.clamp_outside, tr("outside the light frustum = lit"))
        .on_hover_text(key_hint(lang, "clamp_outside"))
        .changed();
    changed |= combo(
        lang,
        ui,
        tr("depth storage"),
        &mut s.depth_storage,
        DepthStorage::ALL,
        DepthStorage::label,
        Some("depth_storage"),
    );

    ui.separator();
    ui.heading(tr("PCF"));
    changed |=
        combo(lang, ui, tr("kernel"), &mut s.pcf_kernel, Kernel::ALL, Kernel::label, Some("pcf_kernel"));
    changed |= ui
        .add(Slider::new(&mut s.samples, 1..=128).text(tr("samples")))
        .on_hover_text(key_hint(lang, "samples"))
        .changed();
    if s.pcf_kernel == Kernel::Grid {
        let side = crate::shadow::kernels::grid_side(s.samples);
        ui.small(crate::i18n::fill(lang, "grid uses {}×{} = {} taps", &[&side, &side, &(side * side)]));
    }
    changed |= ui
        .add(Slider::new(&mut s.radius_texels, 0.0..=32.0).text(tr("radius (texels)")))
        .on_hover_text(key_hint(lang, "radius_texels"))
        .changed();
    changed |= ui
        .checkbox(&mut s.rotate_per_pixel, tr("rotate the pattern per pixel"))
        .on_hover_text(key_hint(lang, "rotate_per_pixel"))
        .changed();
    changed |=
        ui.add(egui::DragValue::new(&mut s.noise_seed).prefix(format!("{} ", tr("noise seed")))).changed();

    ui.separator();
    ui.heading(tr("PCSS"));
    changed |= ui
        .add(Slider::new(&mut s.blocker_samples, 1..=128).text(tr("blocker samples")))
        .on_hover_text(key_hint(lang, "blocker_samples"))
        .changed();
    changed |= ui
        .add(Slider::new(&mut s.min_filter_radius_texels, 0.0..=16.0).text(tr("min filter radius (texels)")))
        .on_hover_text(key_hint(lang, "min_filter_radius_texels"))
        .changed();
    changed |= ui
        .add(Slider::new(&mut s.search_radius_scale, 0.25..=4.0).text(tr("search radius (× light cone)")))
        .on_hover_text(key_hint(lang, "search_radius_scale"))
        .changed();
    changed |= ui
        .checkbox(&mut s.ortho_near_factor, tr("near / d on orthographic maps (NVIDIA's factor)"))
        .on_hover_text(key_hint(lang, "ortho_near_factor"))
        .changed();
    ui.separator();
    ui.heading(tr("VSM"));
    changed |= ui
        .add(
            Slider::new(&mut s.vsm_min_variance, 0.0..=1e-3)
                .logarithmic(true)
                .text(tr("VSM min variance (NDC²)")),
        )
        .on_hover_text(key_hint(lang, "vsm_min_variance"))
        .changed();
    changed |= ui
        .add(Slider::new(&mut s.vsm_bleed_reduction, 0.0..=0.95).text(tr("VSM bleed reduction")))
        .on_hover_text(key_hint(lang, "vsm_bleed_reduction"))
        .changed();
    ui.separator();
    changed |= ui
        .add(
            Slider::new(&mut s.reference_samples, 1..=1024)
                .logarithmic(true)
                .text(tr("ground-truth samples")),
        )
        .on_hover_text(key_hint(lang, "reference_samples"))
        .changed();

    ui.separator();
    changed |= lights(state, ui);

    ui.separator();
    ui.heading(tr("Camera"));
    if let Projection::Perspective { fov_deg } = &mut state.scene.camera.projection {
        changed |= ui.add(Slider::new(fov_deg, 10.0..=120.0).text(tr("field of view (°)"))).changed();
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
    for (label, key, point) in [
        ("position", "light.N.position", &mut light.position),
        ("target", "light.N.target", &mut light.target),
    ] {
        ui.horizontal(|ui| {
            let name = ui.label(tr(label)).on_hover_text(key_hint(lang, key));
            for (axis, prefix) in ["x ", "y ", "z "].into_iter().enumerate() {
                let value = egui::DragValue::new(&mut point[axis]).speed(0.5).max_decimals(2).prefix(prefix);
                changed |= ui.add(value).labelled_by(name.id).changed();
            }
        });
    }
    let mut size = light.shadow_map_size;
    egui::ComboBox::from_label(tr("shadow map (texels)")).selected_text(format!("{size}²")).show_ui(
        ui,
        |ui| {
            for option in [256u32, 512, 1024, 2048, 4096, 8192] {
                ui.selectable_value(&mut size, option, format!("{option}²"));
            }
        },
    );
    if size != light.shadow_map_size {
        light.shadow_map_size = size;
        changed = true;
    }
    match &mut light.kind {
        LightKind::Directional { extent_world } => {
            ui.label(tr("directional light, orthographic map"));
            changed |= ui
                .add(Slider::new(extent_world, 1.0..=300.0).text(tr("half-width (world units)")))
                .on_hover_text(key_hint(lang, "light.N.extent"))
                .changed();
        }
        LightKind::Spot { fov_deg } => {
            ui.label(tr("spot light, perspective map"));
            changed |= ui.add(Slider::new(fov_deg, 5.0..=150.0).text(tr("field of view (°)"))).changed();
        }
    }
    let far = light.far;
    changed |= ui
        .add(Slider::new(&mut light.near, 0.01..=far * 0.9).logarithmic(true).text(tr("near (world units)")))
        .on_hover_text(key_hint(lang, "light.N.near"))
        .changed();
    let near = light.near;
    changed |= ui
        .add(Slider::new(&mut light.far, near * 1.1..=2000.0).logarithmic(true).text(tr("far (world units)")))
        .on_hover_text(key_hint(lang, "light.N.far"))
        .changed();
    let directional = light.is_orthographic();
    match &mut light.size {
        LightSize::Width { width_world } => {
            let slider = ui
                .add(Slider::new(width_world, 0.0..=40.0).text(tr("light width (world units)")))
                .on_hover_text(key_hint(lang, "light.N.width"));
            #[cfg(feature = "test-hooks")]
            super::hooks::set_landmark(ui.ctx(), super::hooks::LANDMARK_LIGHT_WIDTH, slider.rect);
            changed |= slider.changed();
            if directional && ui.small_button(tr("use an angular diameter instead")).clicked() {
                light.size = LightSize::AngularDiameter { angular_diameter_deg: 0.53 };
                changed = true;
            }
        }
        LightSize::AngularDiameter { angular_diameter_deg } => {
            changed |= ui
                .add(Slider::new(angular_diameter_deg, 0.0..=20.0).text(tr("angular diameter (°)")))
                .on_hover_text(key_hint(lang, "light.N.angular_diameter_deg"))
                .changed();
            if ui.small_button(tr("use a width instead")).clicked() {
                light.size = LightSize::Width { width_world: 2.0 };
                changed = true;
            }
        }
    }
    changed |= ui
        .add(Slider::new(&mut light.intensity, 0.0..=4.0).text(tr("intensity")))
        .on_hover_text(key_hint(lang, "light.N.intensity"))
        .changed();
    changed |= ui
        .add(Slider::new(&mut light.orbit_deg_per_s, -180.0..=180.0).text(tr("orbit (°/s)")))
        .on_hover_text(key_hint(lang, "light.N.orbit_deg_per_s"))
        .changed();
    changed
}

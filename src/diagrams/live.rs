//! Diagram inputs from a live scene: the light's frustum and size model, the shadow settings,
//! and — when a pixel was probed — the probe's depths, radii and every sample it took.
//!
//! Without a probe the per-pixel values fall back to what the scene alone determines (the
//! receiver at the light's target, no blockers, the kernel's pattern with unknown results), so
//! a diagram never shows numbers from another scene.

use glam::{Vec2, Vec3};

use super::{DiagramInputs, LightTopView, ShadowViewsPlot};
use crate::probe::LightProbe;
use crate::scene::{BiasMode, LightKind, LightSize, Scene, Technique};
use crate::shadow::{self, LightViewGpu, ShadowParamsGpu, kernels};

/// Objects flatter than this fraction of their width are receivers (floors), not drawn in the
/// top view: a floor would be one disc covering the whole picture.
const FLAT_RATIO: f32 = 0.02;

/// Build every field of [`DiagramInputs`] for light `light_index` of `scene` at `time_s`.
///
/// `probe` is that light's entry of a [`crate::probe::ProbeReport`] and `normal` the report's
/// surface normal. The light angle is taken from the probe's N·L (exact for spot lights, whose
/// direction varies over the surface), else from `normal` and the light's axis, else from the
/// light's axis and the +Y floor. The PCF samples are the probe's filter taps turned back into
/// unit-disk offsets, `(tap_uv - probe_uv) / filter_radius_uv`, with a tap counted as blocked
/// when less than half of it is lit; without a probe they are the scene's kernel pattern and
/// `sample_blocked` is empty (no results to show). `picture_aspect` is the width / height of the
/// camera picture the renderer fitted its cascades to (the probe's frame where there is a probe),
/// so the shadow-views diagram draws the cascades the probe read.
pub fn inputs_from_scene(
    scene: &Scene,
    light_index: usize,
    time_s: f32,
    probe: Option<&LightProbe>,
    normal: Option<[f32; 3]>,
    picture_aspect: f32,
) -> DiagramInputs {
    let mut out = DiagramInputs {
        lights: top_views(scene, time_s),
        objects_xz: objects_xz(scene, time_s),
        camera_xz: [scene.camera.position.x, scene.camera.position.z],
        clamp_outside: scene.shadow.clamp_outside,
        cull_front_faces: scene.shadow.cull_front_faces,
        receiver_plane: scene.shadow.bias_mode == BiasMode::ReceiverPlane,
        // Only a VSM probe fills it; the diagram marks its example as one.
        vsm: None,
        shadow_views: shadow_views(scene, light_index, time_s, probe, picture_aspect),
        ..DiagramInputs::default()
    };
    let shadow = &scene.shadow;
    out.technique = shadow.technique;
    out.normal_offset_texels = shadow.normal_offset_texels;
    let Some(light) = scene.lights.get(light_index) else {
        // No light: nothing is shadowed.
        out.blocker_depth_linear = None;
        out.penumbra_width_world = 0.0;
        out.visibility = 1.0;
        out.blockers_found = 0;
        out.pcf_samples = Vec::new();
        out.sample_blocked = Vec::new();
        return out;
    };

    out.shadow_map_size_texels = light.shadow_map_size;
    out.frustum_width_world = light.frustum_width_world();
    out.light_near = light.near;
    out.light_far = light.far;
    out.orthographic = light.is_orthographic();
    (out.light_width_world, out.light_angular_diameter_deg) = match light.size {
        LightSize::Width { width_world } => (Some(width_world), None),
        LightSize::AngularDiameter { angular_diameter_deg } => (None, Some(angular_diameter_deg)),
    };

    let axis = light.direction_at(time_s);
    let to_light = -axis;
    let n_dot_l = match (probe, normal) {
        (Some(p), _) => p.n_dot_l,
        (None, Some(n)) => Vec3::from(n).normalize_or(Vec3::Y).dot(to_light),
        (None, None) => Vec3::Y.dot(to_light),
    };
    out.light_angle_deg = n_dot_l.clamp(-1.0, 1.0).acos().to_degrees();

    let map = light.shadow_map_size.max(1) as f32;
    match probe {
        Some(p) => {
            out.bias_ndc = p.bias_ndc;
            out.receiver_depth_linear = p.receiver_depth_linear;
            out.stored_depth_linear = p.stored_depth_linear;
            out.blocker_depth_linear = match shadow.technique {
                Technique::Pcss | Technique::Vssm => p.avg_blocker_depth_linear,
                // No blocker search: the blocker is the surface stored in the probe's texel,
                // when it is in front of the receiver.
                _ => {
                    (p.stored_depth_ndc < p.receiver_depth_ndc - p.bias_ndc).then_some(p.stored_depth_linear)
                }
            };
            out.penumbra_width_world = p.penumbra_width_world;
            out.search_radius_texels = p.blocker_search_radius_texels;
            out.filter_radius_texels = p.filter_radius_texels;
            let centre = Vec2::from(p.shadow_map_uv);
            let in_texel = centre * map - (centre * map).floor();
            out.probe_in_texel = in_texel.to_array();
            let filter: Vec<_> = p.taps.iter().filter(|t| t.kind == "filter").collect();
            out.pcf_samples = filter
                .iter()
                .map(|t| {
                    if p.filter_radius_uv > 0.0 {
                        ((Vec2::from(t.uv) - centre) / p.filter_radius_uv).to_array()
                    } else {
                        [0.0, 0.0]
                    }
                })
                .collect();
            out.sample_blocked = filter.iter().map(|t| t.value < 0.5).collect();
            out.blockers_found = p.blockers_found;
            out.blocker_samples = p.blocker_samples;
            out.visibility = p.visibility_twin;
            // The twin's rule, part by part (the probe's `inside_light_frustum` is both).
            out.outside_map = shadow::outside_map(Vec2::from(p.shadow_map_uv));
            out.outside_depth = shadow::outside_depth(p.receiver_depth_ndc);
            out.stored_depth_rgba8_error_ndc = p.stored_depth_rgba8_error_ndc;
            out.vsm = p.vsm.as_ref().map(|v| super::VsmPlot {
                histogram_range_ndc: v.histogram_range_ndc,
                histogram: v.histogram.clone(),
                mean_ndc: v.mean_depth_ndc,
                variance_ndc2: v.variance_ndc2,
                min_variance_ndc2: v.min_variance_ndc2,
                tested_ndc: v.tested_depth_ndc,
                chebyshev_bound: v.chebyshev_bound,
                visibility: v.visibility,
                true_lit_fraction: v.true_lit_fraction,
                plane_lit_fraction: v.plane_lit_fraction,
                bleed_reduction: v.bleed_reduction,
                filter_radius_texels: p.filter_radius_texels,
            });
        }
        None => {
            // The receiver at the light's target, lit, with the scene's own parameters.
            let d = (light.target - light.position_at(time_s)).dot(axis).clamp(light.near, light.far);
            out.receiver_depth_linear = d;
            out.stored_depth_linear = d;
            out.blocker_depth_linear = None;
            out.penumbra_width_world = 0.0;
            // The twin's formulas for a lit receiver there (no blockers: PCSS's filter is its
            // minimum), with the light and parameters a render of this scene would use.
            let light_gpu = LightViewGpu::single(light, time_s, light.shadow_map_size.max(1));
            let params = ShadowParamsGpu::new(shadow);
            let no_blockers =
                shadow::Penumbra { width_world: 0.0, filter_radius_texels: params.min_filter_radius_texels };
            out.filter_radius_texels = shadow::filter_radius_texels(&params, Some(&no_blockers));
            out.search_radius_texels = if searches_blockers(shadow.technique) {
                // On the light's axis: the centre of its map (of a cube's face).
                let axis_uv = Vec2::splat(0.5);
                shadow::blocker_search_radius_uv(&light_gpu.light, &light_gpu.view, &params, d, axis_uv) * map
            } else {
                0.0
            };
            let coord = shadow::ShadowCoord { depth_linear: d, n_dot_l, ..Default::default() };
            out.bias_ndc =
                shadow::receiver_bias_ndc(&light_gpu.view, &params, &coord, out.filter_radius_texels);
            let seed = kernels::pixel_seed((0, 0), shadow.noise_seed, false);
            out.pcf_samples = match shadow.technique {
                Technique::None | Technique::Hard | Technique::Vsm | Technique::Vssm => vec![[0.0, 0.0]],
                _ => kernels::kernel_points(shadow.pcf_kernel, shadow.samples, seed)
                    .iter()
                    .map(|p| p.to_array())
                    .collect(),
            };
            out.sample_blocked = Vec::new();
            out.blockers_found = 0;
            out.blocker_samples =
                kernels::filter_taps(shadow::search_kernel(shadow.pcf_kernel), shadow.blocker_samples);
            out.visibility = 1.0;
        }
    }
    out
}

/// The light's views for the shadow-views diagram: a lamp's cube, else its cascades (one for a
/// light with one map) fitted to the camera as a picture of `picture_aspect` sees it, as the
/// renderer fits them (`shadow::frame_lights`).
fn shadow_views(
    scene: &Scene,
    light_index: usize,
    time_s: f32,
    probe: Option<&LightProbe>,
    picture_aspect: f32,
) -> ShadowViewsPlot {
    let Some(light) = scene.lights.get(light_index) else {
        return ShadowViewsPlot::Cascades {
            splits_world: vec![scene.camera.near, scene.camera.far],
            widths_world: Vec::new(),
            one_map_width_world: 0.0,
            lambda: 0.0,
            probe_cascade: None,
            selection: Default::default(),
            read_world: Vec::new(),
        };
    };
    if light.stores_distance() {
        let p = light.position_at(time_s);
        let probe_face = probe
            .and_then(|l| l.cube_face.as_deref())
            .and_then(|name| crate::probe::CUBE_FACE_NAMES.iter().position(|n| *n == name));
        return ShadowViewsPlot::Cube { lamp_xz: [p.x, p.z], probe_face };
    }
    let one_map_width_world = light.frustum_width_world();
    if !light.cascades.is_cascaded() || !light.is_orthographic() {
        return ShadowViewsPlot::Cascades {
            splits_world: vec![scene.camera.near, scene.camera.far],
            widths_world: vec![one_map_width_world],
            one_map_width_world,
            lambda: light.cascades.lambda,
            probe_cascade: probe.map(|_| 0),
            selection: light.cascades.selection,
            read_world: vec![Some([scene.camera.near, scene.camera.far])],
        };
    }
    let fits = shadow::cascades::fit_cascades(light, &scene.camera, picture_aspect, time_s);
    let mut splits_world: Vec<f32> = fits.iter().map(|f| f.split_world.0).collect();
    splits_world.extend(fits.last().map(|f| f.split_world.1));
    // Where each is read: the renderer's own views and its choice of cascade, along the axis.
    let (lights, views) = shadow::frame_lights(scene, picture_aspect, time_s, light.shadow_map_size);
    let (from, to) =
        (splits_world.first().copied().unwrap_or(0.0), splits_world.last().copied().unwrap_or(0.0));
    let read_world = lights
        .get(light_index)
        .map(|l| super::cascade_reads::read_along_view_axis(l, &views, &scene.camera, from, to))
        .unwrap_or_default();
    ShadowViewsPlot::Cascades {
        splits_world,
        widths_world: fits.iter().map(|f| f.width_world).collect(),
        one_map_width_world,
        lambda: light.cascades.lambda,
        probe_cascade: probe.and_then(|l| l.cascade.as_ref()).map(|c| c.index),
        selection: light.cascades.selection,
        read_world,
    }
}

/// PCSS and VSSM search for blockers and size their filter from the penumbra.
fn searches_blockers(technique: Technique) -> bool {
    matches!(technique, Technique::Pcss | Technique::Vssm)
}

/// Every light seen from above at `time_s`.
fn top_views(scene: &Scene, time_s: f32) -> Vec<LightTopView> {
    scene
        .lights
        .iter()
        .map(|l| {
            let p = l.position_at(time_s);
            let half_width_world = match l.kind {
                LightKind::Directional { extent_world } => extent_world,
                LightKind::Spot { fov_deg } => (0.5 * fov_deg.to_radians()).tan() * (l.target - p).length(),
                // The face towards the target, 90° wide.
                LightKind::Point => (l.target - p).length(),
            };
            LightTopView {
                position_xz: [p.x, p.z],
                target_xz: [l.target.x, l.target.z],
                half_width_world,
                spot: !l.is_orthographic(),
                color_rgb: l.color.to_array(),
            }
        })
        .collect()
}

/// World-space centre and radius (half the larger horizontal extent) of every object that is
/// not flat, from its mesh bounds at `time_s`.
fn objects_xz(scene: &Scene, time_s: f32) -> Vec<([f32; 2], f32)> {
    scene
        .objects
        .iter()
        .filter_map(|object| {
            let (lo, hi) = object.world_bounds(time_s);
            let size = hi - lo;
            let radius = 0.5 * size.x.max(size.z);
            let flat = size.y <= FLAT_RATIO * size.x.max(size.z);
            (radius.is_finite() && !flat).then(|| {
                let c = (lo + hi) * 0.5;
                ([c.x, c.z], radius)
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::probe::TapReport;
    use crate::scene::parse_scene_str;
    use std::path::Path;

    /// The lessons' frames (960x540, `lessons::PROBE_FRAME`).
    const LESSON_ASPECT: f32 = 16.0 / 9.0;

    #[test]
    fn the_cascades_drawn_are_the_ones_the_renderer_fits_at_the_pictures_aspect() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/sun_avenue.toml");
        let scene = crate::scene::load_scene(&path, &[]).expect("sun_avenue");
        let map_size = scene.lights[0].shadow_map_size as f32;
        // A wide panel, the lessons' 16:9, and a tall narrow one.
        for aspect in [2.4, LESSON_ASPECT, 0.8] {
            let ShadowViewsPlot::Cascades { widths_world, .. } =
                inputs_from_scene(&scene, 0, 0.0, None, None, aspect).shadow_views
            else {
                panic!("a sun's cascades are drawn as cascades");
            };
            let (lights, views) = crate::shadow::frame_lights(&scene, aspect, 0.0, 1024);
            let first = lights[0].first_view as usize;
            let rendered = &views[first..first + lights[0].view_count as usize];
            assert_eq!(widths_world.len(), rendered.len(), "aspect {aspect}");
            for (drawn, view) in widths_world.iter().zip(rendered) {
                // The width the probe reports, and its texel (width / map size), agree exactly.
                assert_eq!(*drawn, view.frustum_width_world, "aspect {aspect}");
                assert_eq!(
                    drawn / map_size,
                    view.frustum_width_world / view.map_size_texels,
                    "aspect {aspect}"
                );
            }
        }
        // The aspect matters: the slices of a tall picture see less to the sides.
        let width_at = |aspect| match inputs_from_scene(&scene, 0, 0.0, None, None, aspect).shadow_views {
            ShadowViewsPlot::Cascades { widths_world, .. } => widths_world[3],
            ShadowViewsPlot::Cube { .. } => f32::NAN,
        };
        assert!(width_at(2.4) > width_at(0.8) * 1.05, "{} vs {}", width_at(2.4), width_at(0.8));
    }

    const SCENE: &str = r#"
[camera]
position = [30.0, 20.0, 40.0]
target = [0.0, 0.0, 0.0]

[[object]]
name = "floor"
mesh = "plane"
scale = [50.0, 1.0, 50.0]

[[object]]
name = "ball"
mesh = "sphere"
translate = [4.0, 5.0, -2.0]
scale = 3.0

[[light]]
kind = "directional"
position = [0.0, 50.0, 0.0]
target = [0.0, 0.0, 0.0]
extent = 30.0
near = 1.0
far = 101.0
shadow_map_size = 1024
angular_diameter_deg = 2.0

[[light]]
kind = "spot"
position = [20.0, 30.0, 0.0]
target = [0.0, 0.0, 0.0]
fov_deg = 60.0
near = 5.0
far = 100.0
shadow_map_size = 512
width = 3.0

[shadow]
technique = "pcf"
samples = 16
radius_texels = 4.0
normal_offset_texels = 0.5
"#;

    fn scene(overrides: &[(&str, &str)]) -> Scene {
        let o: Vec<(String, String)> =
            overrides.iter().map(|(k, v)| (k.to_string(), v.to_string())).collect();
        parse_scene_str(SCENE, Path::new("."), "test.toml", &o).expect("scene")
    }

    fn probe() -> LightProbe {
        let uv = [0.5, 0.5];
        let r = 4.0 / 1024.0;
        LightProbe {
            light: 0,
            shadow_view: 0,
            cube_face: None,
            cascade: None,
            shadow_map_uv: uv,
            shadow_map_texel: [512, 512],
            inside_light_frustum: true,
            n_dot_l: 0.5,
            receiver_depth_ndc: 0.49,
            receiver_depth_linear: 50.0,
            stored_depth_ndc: 0.4,
            stored_depth_linear: 41.0,
            bias_ndc: 0.001,
            receiver_plane_depth_per_texel_world: None,
            stored_depth_rgba8_error_ndc: None,
            vsm: None,
            vssm: None,
            blocker_search_radius_uv: 0.0,
            blocker_search_radius_texels: 0.0,
            blockers_found: 0,
            blocker_samples: 16,
            avg_blocker_depth_linear: None,
            penumbra_width_world: 0.0,
            filter_radius_uv: r,
            filter_radius_texels: 4.0,
            filter_samples: 2,
            visibility_gpu: 0.5,
            visibility_twin: 0.5,
            visibility_reference: None,
            taps: vec![
                TapReport { kind: "blocker-search".into(), uv: [0.1, 0.1], value: 1.0 },
                TapReport { kind: "filter".into(), uv: [0.5 + r, 0.5], value: 1.0 },
                TapReport { kind: "filter".into(), uv: [0.5, 0.5 - 0.5 * r], value: 0.0 },
            ],
        }
    }

    #[test]
    fn light_models_and_frustum_come_from_the_scene() {
        let s = scene(&[]);
        let sun = inputs_from_scene(&s, 0, 0.0, None, None, LESSON_ASPECT);
        assert!(sun.orthographic);
        assert_eq!(sun.shadow_map_size_texels, 1024);
        assert_eq!(sun.frustum_width_world, 60.0);
        assert_eq!((sun.light_near, sun.light_far), (1.0, 101.0));
        assert_eq!(sun.light_width_world, None);
        assert_eq!(sun.light_angular_diameter_deg, Some(2.0));
        assert_eq!(sun.normal_offset_texels, 0.5);
        // Straight down onto the floor.
        assert!(sun.light_angle_deg.abs() < 1e-3, "{}", sun.light_angle_deg);
        assert_eq!(sun.receiver_depth_linear, 50.0);

        let spot = inputs_from_scene(&s, 1, 0.0, None, None, LESSON_ASPECT);
        assert!(!spot.orthographic);
        assert_eq!(spot.shadow_map_size_texels, 512);
        assert_eq!(spot.light_width_world, Some(3.0));
        assert_eq!(spot.light_angular_diameter_deg, None);
        let w = 2.0 * 5.0 * (30f32).to_radians().tan();
        assert!((spot.frustum_width_world - w).abs() < 1e-4);
        // PCF without a probe: the kernel's pattern, results unknown.
        assert_eq!(spot.pcf_samples.len(), 16);
        assert!(spot.sample_blocked.is_empty());
        assert_eq!(spot.filter_radius_texels, 4.0);
        assert_eq!(spot.visibility, 1.0);
    }

    #[test]
    fn top_view_has_every_light_and_the_solid_objects() {
        let s = scene(&[]);
        let inp = inputs_from_scene(&s, 0, 0.0, None, None, LESSON_ASPECT);
        assert_eq!(inp.lights.len(), 2);
        assert!(!inp.lights[0].spot && inp.lights[1].spot);
        assert_eq!(inp.lights[0].half_width_world, 30.0);
        assert_eq!(inp.lights[1].position_xz, [20.0, 0.0]);
        let spot_half = (30f32).to_radians().tan() * (20f32 * 20.0 + 30.0 * 30.0).sqrt();
        assert!((inp.lights[1].half_width_world - spot_half).abs() < 1e-3);
        // The floor is flat and left out; the ball is at its place with its radius.
        assert_eq!(inp.objects_xz.len(), 1);
        let ([x, z], r) = inp.objects_xz[0];
        assert!((x - 4.0).abs() < 1e-3 && (z + 2.0).abs() < 1e-3, "{x},{z}");
        // The unit sphere has radius 0.5.
        assert!((r - 1.5).abs() < 0.05, "{r}");
        assert_eq!(inp.camera_xz, [30.0, 40.0]);
    }

    #[test]
    fn lights_orbit_with_time() {
        let s = scene(&[("light.1.orbit_deg_per_s", "90")]);
        let inp = inputs_from_scene(&s, 1, 1.0, None, None, LESSON_ASPECT);
        let [x, z] = inp.lights[1].position_xz;
        // A quarter turn about +Y: (20, 0) goes to (0, -20).
        assert!(x.abs() < 1e-3 && (z + 20.0).abs() < 1e-3, "{x},{z}");
    }

    #[test]
    fn probe_values_and_taps_become_the_diagram_numbers() {
        let s = scene(&[]);
        let p = probe();
        let inp = inputs_from_scene(&s, 0, 0.0, Some(&p), Some([0.0, 1.0, 0.0]), LESSON_ASPECT);
        assert!((inp.light_angle_deg - 60.0).abs() < 1e-3);
        assert_eq!(inp.receiver_depth_linear, 50.0);
        assert_eq!(inp.stored_depth_linear, 41.0);
        assert_eq!(inp.bias_ndc, 0.001);
        // PCF: the blocker is the stored surface, in front of the receiver.
        assert_eq!(inp.blocker_depth_linear, Some(41.0));
        assert_eq!(inp.pcf_samples.len(), 2);
        assert!((inp.pcf_samples[0][0] - 1.0).abs() < 1e-3 && inp.pcf_samples[0][1].abs() < 1e-3);
        assert!((inp.pcf_samples[1][1] + 0.5).abs() < 1e-3);
        assert_eq!(inp.sample_blocked, vec![false, true]);
        assert_eq!(inp.visibility, 0.5);
        assert_eq!(inp.blocker_samples, 16);
    }

    /// Off the map, past the depth range, or both: the twin's rule part by part, in step with
    /// the probe's `inside_light_frustum`; and the RGBA8 error and the technique come along.
    #[test]
    fn where_the_probe_lies_and_how_its_depth_was_stored_come_along() {
        let s = scene(&[]);
        let mut p = probe();
        let parts = |p: &LightProbe| {
            let inp = inputs_from_scene(&s, 0, 0.0, Some(p), None, LESSON_ASPECT);
            assert_eq!(inp.outside_frustum(), !p.inside_light_frustum, "{:?}", p.shadow_map_uv);
            (inp.outside_map, inp.outside_depth)
        };
        assert_eq!(parts(&p), (false, false));
        p.inside_light_frustum = false;
        p.shadow_map_uv = [1.3029855, 0.19428691];
        p.receiver_depth_ndc = 0.9643481;
        assert_eq!(parts(&p), (true, false));
        p.shadow_map_uv = [0.90604186, -0.49404275];
        p.receiver_depth_ndc = 1.1761581;
        assert_eq!(parts(&p), (true, true));
        p.shadow_map_uv = [0.5, 0.5];
        assert_eq!(parts(&p), (false, true));
        // NaN is outside, as in the shader.
        p.shadow_map_uv = [f32::NAN, 0.5];
        p.receiver_depth_ndc = 0.5;
        assert_eq!(parts(&p), (true, false));

        p.stored_depth_rgba8_error_ndc = Some(-0.0018);
        let inp = inputs_from_scene(&s, 0, 0.0, Some(&p), None, LESSON_ASPECT);
        assert_eq!(inp.stored_depth_rgba8_error_ndc, Some(-0.0018));
        assert_eq!(inp.technique, Technique::Pcf);
        let hard = inputs_from_scene(&scene(&[("technique", "hard")]), 0, 0.0, None, None, LESSON_ASPECT);
        assert_eq!((hard.technique, hard.outside_frustum()), (Technique::Hard, false));
    }

    #[test]
    fn normal_gives_the_angle_without_a_probe() {
        let s = scene(&[]);
        let n = [0.0, 1.0, 1.0];
        let inp = inputs_from_scene(&s, 0, 0.0, None, Some(n), LESSON_ASPECT);
        assert!((inp.light_angle_deg - 45.0).abs() < 1e-3, "{}", inp.light_angle_deg);
    }

    #[test]
    fn pcss_without_blockers_has_no_blocker_depth() {
        let s = scene(&[("technique", "pcss")]);
        let mut p = probe();
        p.avg_blocker_depth_linear = None;
        let inp = inputs_from_scene(&s, 0, 0.0, Some(&p), None, LESSON_ASPECT);
        assert_eq!(inp.blocker_depth_linear, None);
        p.avg_blocker_depth_linear = Some(30.0);
        p.blockers_found = 5;
        let inp = inputs_from_scene(&s, 0, 0.0, Some(&p), None, LESSON_ASPECT);
        assert_eq!(inp.blocker_depth_linear, Some(30.0));
        assert_eq!(inp.blockers_found, 5);
    }

    #[test]
    fn hard_shadows_have_one_centred_sample() {
        let s = scene(&[("technique", "hard")]);
        let inp = inputs_from_scene(&s, 0, 0.0, None, None, LESSON_ASPECT);
        assert_eq!(inp.pcf_samples, vec![[0.0, 0.0]]);
        assert_eq!(inp.filter_radius_texels, 0.0);
    }

    #[test]
    fn a_scene_without_lights_is_unshadowed() {
        let no_lights = SCENE.split("[[light]]").next().unwrap_or_default().to_string() + "\n[shadow]\n";
        let s = parse_scene_str(&no_lights, Path::new("."), "t.toml", &[]).expect("scene");
        let inp = inputs_from_scene(&s, 0, 0.0, None, None, LESSON_ASPECT);
        assert!(inp.lights.is_empty());
        assert_eq!(inp.visibility, 1.0);
        assert!(inp.pcf_samples.is_empty());
    }
}

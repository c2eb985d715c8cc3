//! The app driven the way a user drives it (egui_kittest on the wgpu renderer): layout
//! snapshots per technique, a click that pins the probe (checked against `shadowlab probe`),
//! a parameter change that changes the image, a bad scene that keeps the old one, and lesson
//! stepping with the arrow keys.

use egui_kittest::kittest::{NodeT, Queryable};
use egui_kittest::{Harness, SnapshotOptions};
use shadowlab::i18n::Lang;
use shadowlab::lessons::live::{self, Verdict};
use shadowlab::probe::ProbeReport;
use shadowlab::ui::{ProbeAt, Settings, ShadowlabApp, Source, app_for_test};

fn harness() -> Harness<'static, ShadowlabApp> {
    harness_sized([1400.0, 820.0])
}

fn harness_sized(size: [f32; 2]) -> Harness<'static, ShadowlabApp> {
    harness_with(size, Settings { show_timings: false, ..Settings::default() })
}

fn harness_with(size: [f32; 2], settings: Settings) -> Harness<'static, ShadowlabApp> {
    let mut setup = egui_kittest::wgpu::default_wgpu_setup();
    if let eframe::egui_wgpu::WgpuSetup::CreateNew(create) = setup {
        setup = eframe::egui_wgpu::WgpuSetup::CreateNew(shadowlab::ui::configure_wgpu(create));
    }
    let mut harness = Harness::builder()
        .with_size(size)
        .wgpu_setup(setup)
        .build_eframe(move |cc| app_for_test(cc, settings.clone()));
    settle(&mut harness);
    assert!(
        harness.state().camera_image().is_some(),
        "the app has no GPU view ({:?}): these tests need a Vulkan adapter (apt-get install mesa-vulkan-drivers)",
        harness.state().gpu_problem()
    );
    harness
}

/// Step frames until the render worker has delivered everything asked for (the app never waits
/// for the GPU itself, so a test waits here instead).
fn settle(h: &mut Harness<'_, ShadowlabApp>) {
    let start = std::time::Instant::now();
    loop {
        h.step();
        if !h.state().render_pending() {
            // One more frame shows what arrived.
            h.step();
            return;
        }
        assert!(
            start.elapsed() < std::time::Duration::from_secs(300),
            "the render worker did not finish ({:?})",
            h.state().gpu_problem()
        );
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
}

fn snapshot_options() -> SnapshotOptions {
    // Software rasterisers round a little differently from run to run of the driver version.
    SnapshotOptions::new().threshold(2.0).max_failed_pixels(2000)
}

#[test]
fn layout_snapshots_per_technique() {
    let mut results = egui_kittest::SnapshotResults::new();
    for technique in ["hard", "pcf", "pcss"] {
        let mut h = harness();
        h.state_mut().scene.shadow.technique =
            shadowlab::scene::Technique::from_name(technique).expect("technique");
        h.state_mut().mark_dirty();
        settle(&mut h);
        h.snapshot_options(format!("app_games202_{technique}"), &snapshot_options());
        results.extend(h.take_snapshot_results());
    }
}

fn camera_view_rect(h: &Harness<'_, ShadowlabApp>) -> egui::Rect {
    // The camera view fills the left part of the central panel, below the top bar; find it from
    // the inspector's right edge and the shadow-map heading.
    let map = h.get_by_label("Shadow map").rect();
    let inspector_right = h.get_by_label("Technique").rect().left() + 290.0;
    egui::Rect::from_min_max(
        egui::pos2(inspector_right + 20.0, map.top() + 10.0),
        egui::pos2(map.left() - 20.0, map.top() + 400.0),
    )
}

#[test]
fn clicking_the_camera_view_pins_a_probe_matching_the_cli() {
    let mut h = harness();
    let view = camera_view_rect(&h);
    let target = egui::pos2(view.left() + view.width() * 0.55, view.top() + view.height() * 0.6);
    h.hover_at(target);
    h.run_steps(1);
    h.event(egui::Event::PointerButton {
        pos: target,
        button: egui::PointerButton::Primary,
        pressed: true,
        modifiers: Default::default(),
    });
    h.run_steps(1);
    h.event(egui::Event::PointerButton {
        pos: target,
        button: egui::PointerButton::Primary,
        pressed: false,
        modifiers: Default::default(),
    });
    settle(&mut h);
    let report = h.state().probe_report().cloned().expect("a click pins the probe");
    assert!(report.hit, "the probe should land on the floor or a model");
    // The inspector shows the probe's numbers.
    h.get_by_label("visibility (CPU twin)");

    let output = std::process::Command::new(env!("CARGO_BIN_EXE_shadowlab"))
        .args(["probe", "--scene", "assets/scenes/games202.toml", "--no-reference"])
        .args(["--pixel", &format!("{},{}", report.pixel[0], report.pixel[1])])
        .args(["--size", &format!("{}x{}", report.size[0], report.size[1])])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .output()
        .expect("run shadowlab probe");
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let cli: serde_json::Value = serde_json::from_slice(&output.stdout).expect("probe JSON");
    let app_light = &report.lights[0];
    let cli_light = &cli["lights"][0];
    let close = |key: &str, app: f32| {
        let cli = cli_light[key].as_f64().unwrap_or(f64::NAN) as f32;
        assert!((cli - app).abs() < 1e-4, "{key}: app {app} vs CLI {cli}");
    };
    close("visibility_twin", app_light.visibility_twin);
    close("visibility_gpu", app_light.visibility_gpu);
    close("receiver_depth_ndc", app_light.receiver_depth_ndc);
    close("stored_depth_ndc", app_light.stored_depth_ndc);
    close("penumbra_width_world", app_light.penumbra_width_world);
    assert_eq!(cli_light["blockers_found"].as_u64(), Some(u64::from(app_light.blockers_found)));
}

#[test]
fn changing_a_parameter_changes_the_image() {
    let mut h = harness();
    let before = h.state().camera_image().expect("image");
    h.get_by_label("rotate the pattern per pixel").click();
    settle(&mut h);
    assert!(!h.state().scene.shadow.rotate_per_pixel, "the checkbox should turn rotation off");
    let after = h.state().camera_image().expect("image");
    assert_eq!(before.dimensions(), after.dimensions());
    let changed = before.pixels().zip(after.pixels()).filter(|(a, b)| a != b).count();
    assert!(changed > 100, "only {changed} pixels changed");
}

/// A scene or a lesson may set a value past the span a slider covers (the loader takes the whole
/// range of its row in src/scene/parameters): the inspector keeps it as it was given.
#[test]
fn a_value_beyond_a_sliders_span_is_kept_as_the_scene_gave_it() {
    let mut h = harness();
    h.state_mut().scene.lights[0].intensity = 10.0;
    h.state_mut().scene.shadow.radius_texels = 40.0;
    h.state_mut().scene.shadow.depth_bias_constant = -100;
    h.state_mut().mark_dirty();
    settle(&mut h);
    let state = h.state();
    assert_eq!(state.scene.lights[0].intensity, 10.0, "the intensity slider spans 0..=4");
    assert_eq!(state.scene.shadow.radius_texels, 40.0, "the radius slider spans 0..=32");
    assert_eq!(state.scene.shadow.depth_bias_constant, -100, "the hardware bias slider spans 0..=20000");
}

#[test]
fn a_malformed_scene_shows_the_error_and_keeps_the_old_scene() {
    let mut h = harness();
    let objects_before = h.state().scene.objects.len();
    let dir = tempfile::tempdir().expect("temp dir");
    let bad = dir.path().join("broken.toml");
    std::fs::write(&bad, "[camera]\nposition = [1, 2, 3]\n[shadow]\ntechnique = \"blurry\"\n")
        .expect("write");
    h.get_by_label("file").click();
    h.run_steps(1);
    h.get_by_label("file").type_text(&bad.display().to_string());
    h.run_steps(1);
    h.get_by_label("Open").click();
    settle(&mut h);
    let error = h.state().error.clone().expect("an error is shown").to_string();
    assert!(error.contains("broken.toml") && error.contains("technique"), "{error}");
    h.get_by_label_contains("broken.toml");
    h.get_by_label_contains("could not open the scene");
    // The headline in the reader's language; the details stay as the command line prints them.
    h.state_mut().lang = Lang::Zh;
    h.run_steps(2);
    h.get_by_label_contains("无法打开场景");
    h.state_mut().lang = Lang::En;
    assert_eq!(h.state().scene.objects.len(), objects_before, "the old scene stays");
    assert!(h.state().camera_image().is_some());
}

#[test]
fn arrow_keys_step_through_a_lesson_and_the_panels_follow() {
    let mut h = harness();
    h.key_press(egui::Key::ArrowRight);
    settle(&mut h);
    let first = h
        .state()
        .current_step()
        .map(|(l, s, i)| (l.id.clone(), s.title.en.clone(), i))
        .expect("a lesson step");
    assert_eq!(first.2, 0);
    h.get_by_label(&first.1);
    assert!(matches!(h.state().source, Source::Lesson { lesson: 0, step: 0 }));
    h.key_press(egui::Key::ArrowRight);
    settle(&mut h);
    let second = h.state().current_step().map(|(_, s, i)| (s.clone(), i)).expect("step 2");
    assert_eq!(second.1, 1);
    h.get_by_label(&second.0.title.en);
    assert_eq!(h.state().overlays, second.0.overlays, "the step's overlays are shown");
    if let Some(diagram) = second.0.diagram {
        assert_eq!(h.state().diagram, diagram, "the step's diagram is drawn");
    }
    h.key_press(egui::Key::ArrowLeft);
    settle(&mut h);
    assert!(matches!(h.state().source, Source::Lesson { lesson: 0, step: 0 }));
    h.get_by_label(&first.1);
}

#[test]
fn a_step_shows_only_the_panels_it_names() {
    let mut h = harness();
    let pcss = h.state().lessons.iter().position(|l| l.id == "pcss").expect("the pcss lesson");
    let steps = h.state().lessons[pcss].steps.clone();
    let without_map = steps
        .iter()
        .position(|s| !s.panels.contains(&shadowlab::lessons::Panel::ShadowMap))
        .expect("a pcss step without the shadow map");
    let with_map = steps
        .iter()
        .position(|s| s.panels.contains(&shadowlab::lessons::Panel::ShadowMap))
        .expect("a pcss step with the shadow map");
    h.state_mut().go_to_step(pcss, without_map);
    settle(&mut h);
    assert!(h.query_by_label("Shadow map").is_none(), "step {} names no shadow map", without_map + 1);
    h.state_mut().go_to_step(pcss, with_map);
    settle(&mut h);
    h.get_by_label("Shadow map");
    // "show every panel" brings the map back on any step.
    h.state_mut().go_to_step(pcss, without_map);
    settle(&mut h);
    h.get_by_label("show every panel").click();
    settle(&mut h);
    h.get_by_label("Shadow map");
}

#[test]
fn the_ab_split_renders_its_second_technique_at_once() {
    let mut h = harness();
    h.get_by_label("A/B split against").click();
    settle(&mut h);
    let a = h.state().camera_image().expect("A side");
    let b = h.state().camera_image_b().expect("the B side is rendered as soon as the split is on");
    assert_eq!(a.dimensions(), b.dimensions());
    // PCSS against hard shadows: the soft edges differ.
    let differing = a.pixels().zip(b.pixels()).filter(|(p, q)| p != q).count();
    assert!(differing > 100, "A and B look the same ({differing} pixels differ)");
}

#[test]
fn opening_an_obj_builds_a_scene_around_it() {
    let mut h = harness();
    let obj = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/obj/blender_export.obj");
    h.get_by_label("file").click();
    h.run_steps(1);
    h.get_by_label("file").type_text(&obj.display().to_string());
    h.run_steps(1);
    h.get_by_label("Open").click();
    settle(&mut h);
    let app = h.state();
    assert!(app.error.is_none(), "{:?}", app.error);
    assert_eq!(app.scene.objects.len(), 2, "a floor and the model");
    assert_eq!(app.scene.objects[1].name, "blender_export.obj");
    assert_eq!(app.scene.lights.len(), 1);
    assert!(app.camera_image().is_some());
    // The light's frustum is fitted to the model: it holds the model (scaled to 10 units) and
    // the shadow its top casts on the floor, and not much more.
    let light = &app.scene.lights[0];
    let shadowlab::scene::LightKind::Directional { extent_world } = light.kind else { panic!("directional") };
    let clip = light.clip_from_world(0.0);
    let to_floor = -(light.target - light.position).normalize();
    for object in &app.scene.objects[1..] {
        let (lo, hi) = object.mesh.bounds();
        for corner in 0..8 {
            let pick = |bit: u32, a: f32, b: f32| if corner & bit == 0 { a } else { b };
            let local = glam::Vec3::new(pick(1, lo.x, hi.x), pick(2, lo.y, hi.y), pick(4, lo.z, hi.z));
            let world = object.world_from_object(0.0).transform_point3(local);
            let shadow_tip = world - to_floor * (world.y / to_floor.y);
            for p in [world, shadow_tip] {
                let ndc = clip.project_point3(p);
                assert!(
                    ndc.x.abs() <= 1.0 && ndc.y.abs() <= 1.0,
                    "{p} is outside the light's frustum ({ndc})"
                );
            }
        }
    }
    assert!(extent_world < 16.0, "a 10-unit model needs no {extent_world}-unit half-width");
}

#[test]
fn the_ui_does_not_wait_for_a_render() {
    let mut h = harness();
    let before = h.state().camera_image().expect("image");
    h.state_mut().scene.shadow.technique = shadowlab::scene::Technique::Hard;
    h.state_mut().mark_dirty();
    // One UI frame: the render is asked for, not waited for; the last image stays on screen.
    h.step();
    assert!(h.state().render_pending(), "the new frame should still be rendering");
    assert_eq!(h.state().camera_image().as_ref(), Some(&before), "the last finished image stays shown");
    settle(&mut h);
    let after = h.state().camera_image().expect("image");
    let changed = before.pixels().zip(after.pixels()).filter(|(a, b)| a != b).count();
    assert!(changed > 100, "hard shadows should look different from PCSS ({changed} pixels)");
}

#[test]
fn dragging_a_slider_previews_at_half_resolution_and_refines_on_release() {
    let mut h = harness();
    let full = h.state().shown_size();
    let label = "light width (world units)";
    let slider = egui::accesskit::Role::Slider;
    let slider_node =
        |h: &Harness<'_, ShadowlabApp>| h.query_all_by_role_and_label(slider, label).next().map(|n| n.rect());
    assert!(slider_node(&h).is_some(), "the inspector shows the '{label}' slider");
    if let Some(node) = h.query_all_by_role_and_label(slider, label).next() {
        node.scroll_to_me();
    }
    // Scrolling animates over a few frames.
    h.run_steps(30);
    settle(&mut h);
    let slider = slider_node(&h).expect("slider");
    let from = slider.left_center() + egui::vec2(10.0, 0.0);
    h.hover_at(from);
    h.run_steps(1);
    h.drag_at(from);
    h.run_steps(1);
    let mut saw_preview = false;
    for i in 0..600 {
        h.hover_at(from + egui::vec2(20.0 + (i % 40) as f32, 0.0));
        h.step();
        if h.state().showing_preview() {
            saw_preview = true;
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    assert!(saw_preview, "a preview should arrive while the slider is dragged");
    let preview = h.state().shown_size();
    // Half the width and height, or less where previews are slow (down to a quarter).
    let fits = |d: u32| preview == ((full.0 / d).max(1), (full.1 / d).max(1));
    assert!(fits(2) || fits(3) || fits(4), "previews render at 1/2..1/4 resolution: {preview:?} of {full:?}");
    h.drop_at(from + egui::vec2(30.0, 0.0));
    settle(&mut h);
    assert!(!h.state().showing_preview(), "the full-quality frame replaces the preview on release");
    assert_eq!(h.state().shown_size(), full);
}

#[test]
fn the_ground_truth_fills_in_batch_by_batch() {
    let mut h = harness();
    h.state_mut().scene.shadow.reference_samples = 256;
    h.state_mut().overlays = vec![shadowlab::views::overlays::Overlay::Error];
    h.state_mut().mark_dirty();
    let mut partial = None;
    for _ in 0..6000 {
        h.step();
        if let Some((done, total)) = h.state().reference_progress()
            && done > 0
            && done < total
        {
            partial = Some((done, total));
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    let (done, total) = partial.expect("the ground truth should show partial progress");
    assert_eq!(total, 256);
    assert!(done < total);
    settle(&mut h);
    assert_eq!(h.state().reference_progress(), Some((256, 256)));
}

/// `shadowlab probe --lesson ID --step N`, with the ground truth where `with_reference`, parsed.
fn cli_probe(lesson: &str, step: usize, with_reference: bool) -> ProbeReport {
    let reference = if with_reference { None } else { Some("--no-reference") };
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_shadowlab"))
        .args(["probe", "--lesson", lesson, "--step", &step.to_string()])
        .args(reference)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .output()
        .expect("run shadowlab probe");
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    serde_json::from_slice(&output.stdout).expect("probe JSON")
}

#[test]
fn every_lesson_step_quotes_the_probe_on_screen_in_both_languages_at_two_window_sizes() {
    let lessons = shadowlab::lessons::load_all(&shadowlab::lessons::default_dir()).expect("lessons");
    // With the ground truth where the step quotes it (the app works it out there too).
    let quotes_truth =
        |s: &shadowlab::lessons::Step| s.quotes(live::Namespace::Probe, "visibility_reference");
    let cli: Vec<Vec<Option<ProbeReport>>> = lessons
        .iter()
        .map(|l| {
            let steps = l.steps.iter().enumerate();
            steps.map(|(i, s)| s.probe.map(|_| cli_probe(&l.id, i + 1, quotes_truth(s)))).collect()
        })
        .collect();
    for size in [[1600.0, 900.0], [1280.0, 720.0]] {
        let mut h = harness_sized(size);
        for (li, lesson) in lessons.iter().enumerate() {
            for (si, step) in lesson.steps.iter().enumerate() {
                let what = format!("{} step {} at {}x{}", lesson.id, si + 1, size[0], size[1]);
                h.state_mut().go_to_step(li, si);
                if step.play {
                    // Paused at the step's own time: the moment the text and the CLI describe.
                    h.state_mut().playing = false;
                    h.state_mut().time_s = step.time_s;
                    h.state_mut().mark_dirty();
                }
                settle(&mut h);
                let Some(expected) = &cli[li][si] else { continue };
                // The app probes the lesson's own frame: its numbers are the CLI's, whatever the
                // shape of its camera view.
                let report = h.state().probe_report().cloned().unwrap_or_else(|| panic!("{what}: no probe"));
                assert_eq!(&report, expected, "{what}: the app's probe differs from `shadowlab probe`");
                if let Some(verdict) = step.expect {
                    assert_eq!(Verdict::of(report.lights[step.light].visibility_gpu), verdict, "{what}");
                }
                for lang in [Lang::En, Lang::Zh] {
                    h.state_mut().lang = lang;
                    h.run_steps(2);
                    let sources = h.state().live_sources();
                    let (text, filled) = live::fill(step.text.get(lang), sources, step.light, lang);
                    assert!(filled.iter().all(|f| f.text != live::NO_VALUE), "{what} ({lang:?}): {text}");
                    // The lesson panel shows exactly this text: every quoted number is the probe's.
                    h.get_by_label(&text);
                }
                h.state_mut().lang = Lang::En;
            }
        }
    }
}

#[test]
fn a_student_probe_says_so_and_one_click_brings_back_the_lessons() {
    let mut h = harness();
    let lessons = &h.state().lessons;
    let lesson = lessons.iter().position(|l| l.id == "pcss").expect("the PCSS lesson");
    let step = lessons[lesson].steps[0].clone();
    h.state_mut().go_to_step(lesson, 0);
    settle(&mut h);
    assert!(h.query_by_label("Back to the lesson's probe").is_none(), "the lesson's own probe needs no note");
    // A probe of the student's own (a click in the view sets this).
    h.state_mut().probe_at = Some(ProbeAt::View(0.3, 0.7));
    h.state_mut().mark_dirty();
    settle(&mut h);
    h.get_by_label(
        "The numbers above are read at your probe; the sentences around them describe the lesson's.",
    );
    h.get_by_label("Back to the lesson's probe").click();
    settle(&mut h);
    let [x, y] = step.probe.expect("the step names a probe");
    assert_eq!(h.state().probe_at, Some(ProbeAt::LessonFrame(x, y)));
    assert_eq!(h.state().probe_report().map(|r| r.pixel), Some([x, y]));
    let text = step.text_filled(Lang::En, h.state().probe_report());
    h.get_by_label(&text);
}

/// A label's text (AccessKit keeps it as the node's value).
fn label_text(node: &egui_kittest::Node<'_>) -> Option<String> {
    node.accesskit_node().value().map(|v| v.to_string())
}

/// The ground truth at the probe, as the probe panel shows it: "0.4766 (256 samples)".
fn panel_ground_truth(h: &Harness<'_, ShadowlabApp>) -> Option<f32> {
    h.query_all_by_label_contains(" samples)")
        .filter_map(|n| label_text(&n))
        .find_map(|text| text.split(' ').next().and_then(|v| v.parse().ok()))
}

/// Lesson 4's "against the ground truth" step quotes the ground truth at its probe: the probe
/// panel counts the samples as they are averaged, then shows the value, the CLI's, and the text
/// quotes it and the view's mean error.
#[test]
fn the_ground_truth_step_shows_the_ground_truth_at_the_probe() {
    let mut h = harness_sized([1600.0, 900.0]);
    let lesson = h.state().lessons.iter().position(|l| l.id == "pcss").expect("lesson 4");
    let steps = &h.state().lessons[lesson].steps;
    let index =
        steps.iter().position(|s| s.title.en.starts_with("Against the ground truth")).expect("the step");
    let step = steps[index].clone();
    assert!(step.quotes(live::Namespace::Probe, "visibility_reference"), "the step quotes the ground truth");
    h.state_mut().go_to_step(lesson, index);
    // The panel counts the samples on the way ("12 / 256 samples…"), then shows the value.
    let mut counted = None;
    let start = std::time::Instant::now();
    while panel_ground_truth(&h).is_none() {
        h.step();
        if counted.is_none()
            && let Some(node) = h.query_all_by_label_contains(" / 256 samples…").next()
        {
            counted = label_text(&node);
        }
        assert!(start.elapsed() < std::time::Duration::from_secs(300), "no ground truth in the probe panel");
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    let counted = counted.expect("the panel should count the samples as they are averaged");
    let done: u32 = counted.split(' ').next().and_then(|n| n.parse().ok()).expect("a count");
    assert!(done < 256, "{counted}");
    let shown = panel_ground_truth(&h).expect("shown");
    let cli = cli_probe("pcss", index + 1, true).lights[step.light]
        .visibility_reference
        .expect("the CLI's ground truth");
    assert!((shown - cli).abs() < 0.02, "the panel shows {shown}, `shadowlab probe` {cli}");
    settle(&mut h);
    let report = h.state().probe_report().cloned().expect("the probe");
    let app = report.lights[step.light].visibility_reference.expect("the app's ground truth");
    assert!((app - cli).abs() < 1e-6, "the same pixel and samples as the CLI: {app} vs {cli}");
    // The text quotes it, and the view's mean error as the error legend gives it.
    let legend = h.state().legend_lines();
    let mae: f32 = legend
        .iter()
        .find_map(|l| l.strip_prefix("mean absolute error: "))
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("no mean error in the legend: {legend:?}"));
    let text = step.text_filled(Lang::En, h.state().live_sources());
    assert!(text.contains(&format!("({app:.2} at the probe)")), "{text}");
    let quoted: f32 = text
        .split_once("over this view is ")
        .and_then(|(_, rest)| rest.get(..5))
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("no mean error in the text: {text}"));
    assert!((quoted - mae).abs() <= 0.0005 + 1e-5, "the text says {quoted}, the legend {mae}");
    h.get_by_label(&text);
    // In Chinese too.
    h.state_mut().lang = Lang::Zh;
    h.run_steps(2);
    assert!(
        h.query_all_by_label(&format!("{app:.4}（256 个样本）")).next().is_some(),
        "the panel in Chinese"
    );
    h.get_by_label(&step.text_filled(Lang::Zh, h.state().live_sources()));
}

/// Where the text does not quote it, the probe panel works the ground truth out on a button,
/// and keeps it while the probe stays.
#[test]
fn the_probe_panel_works_the_ground_truth_out_on_demand() {
    let mut h = harness_sized([1600.0, 900.0]);
    let lesson = h.state().lessons.iter().position(|l| l.id == "pcss").expect("lesson 4");
    h.state_mut().go_to_step(lesson, 0);
    settle(&mut h);
    assert!(panel_ground_truth(&h).is_none(), "no ground truth until asked for");
    let light = h.state().selected_light;
    assert_eq!(h.state().probe_report().and_then(|r| r.lights[light].visibility_reference), None);
    // The inspector's probe panel and the lesson panel's both have it; the lesson panel's,
    // scrolled into view, is pressed.
    h.query_all_by_label("work it out").last().expect("the button").scroll_to_me();
    h.run_steps(30);
    h.query_all_by_label("work it out").last().expect("the button").click();
    settle(&mut h);
    let shown = panel_ground_truth(&h).expect("the ground truth after the button");
    let cli = cli_probe("pcss", 1, true).lights[light].visibility_reference.expect("the CLI's");
    assert!((shown - cli).abs() < 0.02, "the panel shows {shown}, `shadowlab probe` {cli}");
    // A new setting works it out again for the same probe; a new step forgets the request.
    h.state_mut().scene.shadow.samples = 16;
    h.state_mut().mark_dirty();
    settle(&mut h);
    assert!(panel_ground_truth(&h).is_some(), "the ground truth follows the settings");
    h.state_mut().go_to_step(lesson, 2);
    settle(&mut h);
    assert!(panel_ground_truth(&h).is_none(), "a step that does not quote it starts without it");
    assert!(h.query_all_by_label("work it out").next().is_some());
}

#[test]
fn a_step_sets_the_view_and_the_view_selector_changes_it() {
    let mut h = harness();
    let lesson = h.state().lessons.iter().position(|l| l.id == "hard-shadows").expect("lesson 1");
    // Step 2 says "black in this visibility view": the camera panel must show that view.
    h.state_mut().go_to_step(lesson, 1);
    settle(&mut h);
    assert_eq!(h.state().camera_panel_view(), shadowlab::views::View::Visibility);
    h.get_by_value("view: visibility").click();
    h.run_steps(2);
    h.get_by_label("blockers").click();
    settle(&mut h);
    assert_eq!(h.state().camera_panel_view(), shadowlab::views::View::Blockers);
    h.get_by_value("view: blockers");
    // Opening a scene starts from the shaded view again.
    h.state_mut()
        .open(std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/assets/scenes/contact.toml")));
    settle(&mut h);
    assert_eq!(h.state().camera_panel_view(), shadowlab::views::View::Final);
    assert!(
        h.state().probe_at.is_none() && h.state().overlays.is_empty(),
        "a new scene keeps no probe or overlay"
    );
}

/// Text a Chinese reader may see in Latin letters: units and acronyms. (Views, diagrams,
/// techniques, kernels and bias modes are shown by their Chinese labels: see the next test.)
fn allowed_in_chinese(word: &str) -> bool {
    // "screenshots" is the screenshot folder's default path; x, y and z name coordinates.
    let fixed = [
        "shadowlab",
        "English",
        "NDC",
        "uv",
        "GPU",
        "CPU",
        "ms",
        "PCF",
        "PCSS",
        "A",
        "B",
        "F",
        "S",
        "R",
        "N",
        "L",
        "x",
        "y",
        "z",
        "s",
        "screenshots",
        "Resize",
        "panel",
    ];
    // A student's shader's function names (findBlocker, useShadowMap): code, named as written.
    let camel_case = word.chars().next().is_some_and(|c| c.is_ascii_lowercase())
        && word.chars().any(|c| c.is_ascii_uppercase());
    fixed.contains(&word)
        // Identifiers and file names: `light.0.width`, games202.toml, blocker-radius.
        || word.contains(['_', '-', '.']) || word.chars().any(|c| c.is_ascii_digit())
        || camel_case
}

#[test]
fn in_chinese_every_panel_label_is_chinese() {
    let mut h = harness_sized([1600.0, 900.0]);
    h.state_mut().lang = Lang::Zh;
    // The shortcut help is open throughout (it floats over the panels).
    h.state_mut().show_help = true;
    let mut english = std::collections::BTreeSet::new();
    let lessons = h.state().lessons.len();
    let mut places = vec![None];
    for l in 0..lessons {
        places.extend((0..h.state().lessons[l].steps.len()).map(|s| Some((l, s))));
    }
    for place in places {
        if let Some((l, s)) = place {
            h.state_mut().go_to_step(l, s);
            h.state_mut().playing = false;
        }
        settle(&mut h);
        h.run_steps(2);
        for node in h.root().children_recursive() {
            let a = node.accesskit_node();
            for text in [a.label(), a.value()].into_iter().flatten() {
                // egui's own accessibility names for resize handles and close buttons: never drawn.
                if text.starts_with("Resize ") || text == "Close window" {
                    continue;
                }
                // Han characters, or CJK punctuation (a wrapped line may hold only "）。").
                let cjk = text.chars().any(|c| {
                    ('\u{4e00}'..='\u{9fff}').contains(&c)
                        || ('\u{3000}'..='\u{303f}').contains(&c)
                        || ('\u{ff00}'..='\u{ffef}').contains(&c)
                });
                let words = text.split(|c: char| !(c.is_ascii_alphanumeric() || "_-.".contains(c)));
                if !cjk
                    && words
                        .filter(|w| w.chars().any(|c| c.is_ascii_alphabetic()))
                        .any(|w| !allowed_in_chinese(w))
                {
                    english.insert(text);
                }
            }
        }
    }
    assert!(english.is_empty(), "English left in the Chinese UI (add it to src/i18n/ui_zh.rs): {english:#?}");
}

/// Latin words that stay Latin in a Chinese shadow-mapping course: the acronyms of the techniques
/// (PCF, PCSS, VSM, VSSM) and of NDC and RGBA8, as Chinese textbooks and GAMES202 write them.
/// "English" is the language picker naming English in its own script.
const LATIN_IN_CHINESE_LABELS: [&str; 7] = ["PCF", "PCSS", "VSM", "VSSM", "NDC", "RGBA8", "English"];

/// The ASCII words of two letters or more in `text` that a Chinese reader should not meet in a
/// view name, diagram tab, combo-box value or object name: everything but the acronyms above and
/// the names of scene files (the scene picker lists files).
fn latin_words(text: &str) -> Vec<&str> {
    text.split(|c: char| !(c.is_ascii_alphanumeric() || "_-.".contains(c)))
        .filter(|w| w.chars().filter(|c| c.is_ascii_alphabetic()).count() >= 2)
        .filter(|w| !LATIN_IN_CHINESE_LABELS.contains(w) && !w.ends_with(".toml"))
        .collect()
}

/// In Chinese, the names that files and the command line use in English are shown translated:
/// the camera panel's view menu, the diagram tabs, the values of every combo box (technique,
/// bias mode, depth storage, kernel...), the object under the probe and the Apply tooltips,
/// over a few lesson steps with each combo box opened in turn.
#[test]
fn in_chinese_views_diagrams_settings_and_objects_have_chinese_names() {
    use egui::accesskit::Role;
    use shadowlab::scene::{BiasMode, DepthStorage, Kernel, Technique};
    let mut h = harness_sized([1600.0, 900.0]);
    h.state_mut().lang = Lang::Zh;
    let mut english = std::collections::BTreeSet::new();
    // Every text looked at: the test fails if the walk missed a name it should have met.
    let mut seen = std::collections::BTreeSet::new();
    let mut objects = std::collections::BTreeSet::new();
    let check = |what: &str, text: &str, english: &mut std::collections::BTreeSet<String>| {
        if !latin_words(text).is_empty() {
            english.insert(format!("{what}: {text}"));
        }
    };
    // Tabs and menu options are toggle buttons named by their text; a combo box shows its value
    // (its name is its label or tooltip).
    let named = |h: &Harness<'_, ShadowlabApp>| -> Vec<(String, String)> {
        let mut out = Vec::new();
        for node in h.root().children_recursive() {
            let a = node.accesskit_node();
            let shown = match a.role() {
                Role::ComboBox => a.value().map(|v| ("combo box", v)),
                Role::Button if a.toggled().is_some() => a.label().map(|l| ("tab or option", l)),
                _ => None,
            };
            out.extend(shown.map(|(what, text)| (what.to_string(), text)));
        }
        out
    };
    // Steps probing the floor and a box, with a view, a technique and a bias mode to Apply.
    for (id, step) in [("hard-shadows", 1), ("bias", 2), ("pcss", 3), ("vsm", 2)] {
        let lesson = h.state().lessons.iter().position(|l| l.id == id).expect("lesson");
        h.state_mut().go_to_step(lesson, step);
        settle(&mut h);
        h.run_steps(2);
        let at = format!("{id} step {}", step + 1);
        for (what, text) in named(&h) {
            check(&format!("{at}, {what}"), &text, &mut english);
            seen.insert(text);
        }
        // Open each combo box (the view menu among them) and read its options.
        let combos = h.query_all_by_role(Role::ComboBox).count();
        assert!(combos >= 6, "{at}: only {combos} combo boxes");
        for i in 0..combos {
            h.query_all_by_role(Role::ComboBox).nth(i).expect("combo box").click_accesskit();
            h.run_steps(2);
            for (what, text) in named(&h) {
                check(&format!("{at}, combo box {i} open, {what}"), &text, &mut english);
                seen.insert(text);
            }
            h.key_press(egui::Key::Escape);
            h.run_steps(2);
        }
        // The surface under the probe: "像素 x,y，位于 地面".
        for node in h.root().children_recursive() {
            let a = node.accesskit_node();
            for text in [a.label(), a.value()].into_iter().flatten() {
                if let Some((_, object)) = text.split_once("，位于 ") {
                    check(&format!("{at}, probe"), object, &mut english);
                    objects.insert(object.to_string());
                }
            }
        }
        // What each Apply button sets, as its tooltip lists it ("视图 = 着色画面").
        for b in 0..h.query_all_by_label("应用").count() {
            h.query_all_by_label("应用").nth(b).expect("Apply").hover();
            h.run_steps(60);
            let mut tooltip = false;
            for node in h.root().children_recursive() {
                let a = node.accesskit_node();
                for text in [a.label(), a.value()].into_iter().flatten() {
                    if text.starts_with(shadowlab::i18n::tr(Lang::Zh, "set what this prompt says")) {
                        tooltip = true;
                        for line in text.lines().skip(1) {
                            let value = line.split_once(" = ").map_or(line, |(_, v)| v);
                            check(&format!("{at}, Apply tooltip"), value, &mut english);
                            seen.insert(value.to_string());
                        }
                    }
                }
            }
            assert!(tooltip, "{at}: no tooltip on Apply button {}", b + 1);
            h.hover_at(egui::pos2(1.0, 450.0));
            h.run_steps(2);
        }
    }
    assert!(english.is_empty(), "English names left in the Chinese app: {english:#?}");
    // The walk met every view, diagram and setting by its Chinese name, and named the surfaces.
    let labels = shadowlab::views::View::ALL
        .iter()
        .map(|v| v.label(Lang::Zh))
        .chain(shadowlab::diagrams::DiagramKind::ALL.iter().map(|d| d.label(Lang::Zh)))
        .chain(Technique::ALL.iter().map(|t| t.label(Lang::Zh)))
        .chain(BiasMode::ALL.iter().map(|b| b.label(Lang::Zh)))
        .chain(Kernel::ALL.iter().map(|k| k.label(Lang::Zh)))
        .chain(DepthStorage::ALL.iter().map(|d| d.label(Lang::Zh)));
    for label in labels {
        assert!(seen.iter().any(|t| t.contains(label)), "`{label}` never shown: {seen:#?}");
    }
    for tip in ["自适应", "着色画面", "PCF 滤波"] {
        assert!(seen.contains(tip), "no Apply tooltip says `{tip}`");
    }
    assert_eq!(objects, ["地面", "箱子"].map(String::from).into(), "the surfaces under the probes");
}

#[test]
fn the_ab_divider_follows_a_fast_drag_that_started_on_it() {
    let mut h = harness();
    h.state_mut().ab =
        Some(shadowlab::ui::AbSplit { b: shadowlab::scene::Technique::Hard, divider: 0.5, grabbed: false });
    h.state_mut().mark_dirty();
    settle(&mut h);
    let view = shadowlab::ui::landmark(&h.ctx, shadowlab::ui::LANDMARK_CAMERA_VIEW).expect("the camera view");
    let camera = *h.state().camera();
    let start = egui::pos2(view.center().x, view.center().y);
    // Press on the divider, then one fast move far past the grab margin, then release.
    let end = start + egui::vec2(-0.3 * view.width(), 40.0);
    h.hover_at(start);
    h.run_steps(1);
    let button = |pos, pressed| egui::Event::PointerButton {
        pos,
        button: egui::PointerButton::Primary,
        pressed,
        modifiers: Default::default(),
    };
    h.event(button(start, true));
    h.run_steps(1);
    for k in 1..=3 {
        h.event(egui::Event::PointerMoved(start + (end - start) * (k as f32 / 3.0)));
        h.run_steps(1);
    }
    h.event(button(end, false));
    settle(&mut h);
    let divider = h.state().ab.as_ref().expect("A/B still on").divider;
    assert!((divider - 0.2).abs() < 0.02, "the divider should follow the pointer to 0.2 ({divider})");
    assert_eq!(*h.state().camera(), camera, "dragging the divider must not orbit the camera");
}

#[test]
fn a_screenshot_saves_what_the_panels_show_under_an_absolute_path() {
    let mut h = harness();
    // A relative folder, as a user may type it: the app must say where the files really went.
    let relative = std::path::PathBuf::from(format!("target/test-screenshots-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&relative);
    h.state_mut().settings.screenshot_dir = relative.clone();
    let lesson = h.state().lessons.iter().position(|l| l.id == "pcss").expect("the PCSS lesson");
    h.state_mut().go_to_step(lesson, 0);
    settle(&mut h);
    // Let the layout settle too (the lesson panel's scroll bar), then render at that size.
    h.run_steps(3);
    settle(&mut h);
    h.get_by_label("Screenshot").click();
    for _ in 0..4 {
        h.run_steps(1);
    }
    let status = h.state().status.clone();
    let absolute = std::path::absolute(&relative).expect("absolute");
    assert!(status.contains(&absolute.display().to_string()), "status: {status}");
    let camera = image::open(absolute.join("shot-001-camera.png")).expect("the camera view PNG").to_rgba8();
    let shown = h.state().camera_image().expect("the camera view");
    assert_eq!(camera.dimensions(), shown.dimensions());
    // The PNG carries the penumbra overlay and the probe's ring, as the panel does.
    let ring = camera.pixels().filter(|p| p.0 == [255, 210, 0, 255]).count();
    assert!(ring > 20, "the probe marker is missing ({ring} marker pixels)");
    let differs = camera.pixels().zip(shown.pixels()).filter(|(a, b)| a != b).count();
    assert!(differs > 1000, "the overlay is missing ({differs} pixels differ from the bare render)");
    assert!(
        absolute.join("shot-001-window.png").exists() && absolute.join("shot-001-shadow-map.png").exists()
    );
    let _ = std::fs::remove_dir_all(&relative);
}

#[test]
fn lessons_are_picked_from_their_own_list_first_in_the_top_bar_and_on_start() {
    let mut h = harness();
    let titles: Vec<String> = h.state().lessons.iter().map(|l| l.title.en.clone()).collect();
    // The start list (the window shows it on a first start).
    h.state_mut().show_lesson_list = true;
    h.run_steps(2);
    h.get_by_label(&format!("4. {}", titles[3])).click();
    settle(&mut h);
    assert_eq!(h.state().source, Source::Lesson { lesson: 3, step: 0 });
    assert!(!h.state().show_lesson_list, "the list closes once a lesson is chosen");
    // The lesson picker in the top bar.
    h.get_by_label("lesson").click();
    h.run_steps(2);
    h.get_by_label(&format!("2. {}", titles[1])).click();
    settle(&mut h);
    assert_eq!(h.state().source, Source::Lesson { lesson: 1, step: 0 });
}

#[test]
fn f5_presents_the_views_diagram_and_lesson_text_alone_and_esc_returns() {
    let mut h = harness_sized([1600.0, 900.0]);
    let lesson = h.state().lessons.iter().position(|l| l.id == "pcss").expect("the PCSS lesson");
    h.state_mut().go_to_step(lesson, 1);
    settle(&mut h);
    let normal_view = shadowlab::ui::landmark(&h.ctx, shadowlab::ui::LANDMARK_CAMERA_VIEW).expect("view");
    let key = |h: &mut Harness<'_, ShadowlabApp>, key| {
        h.event(egui::Event::Key {
            key,
            physical_key: None,
            pressed: true,
            repeat: false,
            modifiers: Default::default(),
        });
        h.run_steps(2);
    };
    key(&mut h, egui::Key::F5);
    settle(&mut h);
    assert!(h.state().present);
    assert!(h.query_by_label("Technique").is_none(), "the inspector is hidden");
    assert!(h.query_by_label("Screenshot").is_none(), "the top bar is hidden");
    h.get_by_label("F5 or Esc: leave present mode");
    let step = h.state().current_step().map(|(_, s, _)| s.clone()).expect("step");
    h.get_by_label(&step.text_filled(shadowlab::i18n::Lang::En, h.state().probe_report()));
    let present_view = shadowlab::ui::landmark(&h.ctx, shadowlab::ui::LANDMARK_CAMERA_VIEW).expect("view");
    assert!(present_view.width() > normal_view.width() * 1.1, "{present_view:?} vs {normal_view:?}");
    h.get_by_label("Shadow map");
    key(&mut h, egui::Key::Escape);
    assert!(!h.state().present);
    h.get_by_label("Technique");
}

#[test]
fn a_small_window_keeps_a_usable_camera_view_even_with_large_saved_panels() {
    let mut setup = egui_kittest::wgpu::default_wgpu_setup();
    if let eframe::egui_wgpu::WgpuSetup::CreateNew(create) = setup {
        setup = eframe::egui_wgpu::WgpuSetup::CreateNew(shadowlab::ui::configure_wgpu(create));
    }
    // Panel sizes saved from a large window.
    let settings = Settings {
        show_timings: false,
        inspector_width: 700.0,
        diagram_height: 600.0,
        ..Settings::default()
    };
    let mut h = Harness::builder()
        .with_size([800.0, 500.0])
        .wgpu_setup(setup)
        .build_eframe(move |cc| app_for_test(cc, settings.clone()));
    settle(&mut h);
    let view = shadowlab::ui::landmark(&h.ctx, shadowlab::ui::LANDMARK_CAMERA_VIEW).expect("the camera view");
    assert!(
        view.width() >= 0.3 * 800.0 && view.height() >= 0.25 * 500.0,
        "camera view {view:?} in an 800x500 window"
    );
}

#[test]
fn at_1600x900_diagram_text_is_at_least_14_points_in_both_layouts_and_languages() {
    let mut h = harness_sized([1600.0, 900.0]);
    let lesson = h.state().lessons.iter().position(|l| l.id == "pcss").expect("the PCSS lesson");
    h.state_mut().go_to_step(lesson, 0);
    settle(&mut h);
    assert!(h.state().panel_visible(shadowlab::lessons::Panel::Diagram));
    for lang in [shadowlab::i18n::Lang::En, shadowlab::i18n::Lang::Zh] {
        for present in [false, true] {
            h.state_mut().lang = lang;
            h.state_mut().present = present;
            settle(&mut h);
            h.run_steps(2);
            let smallest = h.state().smallest_diagram_text_pt().expect("a diagram is drawn");
            assert!(smallest >= 14.0, "{lang:?}, present {present}: diagram text of {smallest:.1} pt");
        }
    }
}

#[test]
fn every_try_this_apply_button_sets_what_its_prompt_says() {
    let mut h = harness_sized([1600.0, 1000.0]);
    let lessons = h.state().lessons.clone();
    let mut pressed = 0;
    for (l, lesson) in lessons.iter().enumerate() {
        for (s, step) in lesson.steps.iter().enumerate() {
            h.state_mut().go_to_step(l, s);
            h.run_steps(2);
            let applying: Vec<usize> =
                (0..step.try_this.len()).filter(|&j| step.try_this[j].applies_anything()).collect();
            assert_eq!(h.query_all_by_label("Apply").count(), applying.len(), "{} step {}", lesson.id, s + 1);
            for (button, &j) in applying.iter().enumerate() {
                let at = format!("{} step {} try_this {}", lesson.id, s + 1, j + 1);
                let prompt = &step.try_this[j];
                let camera = h.state().scene.camera;
                h.query_all_by_label("Apply").nth(button).expect("the Apply button").click();
                h.run_steps(2);
                pressed += 1;
                let expected = step.scene_with_try_this(j).expect("the prompt's scene");
                let app = h.state();
                assert_eq!(app.applied_try_this, Some(j), "{at}");
                assert_eq!(format!("{:?}", app.scene.shadow), format!("{:?}", expected.shadow), "{at}");
                assert_eq!(format!("{:?}", app.scene.lights), format!("{:?}", expected.lights), "{at}");
                assert_eq!(app.scene.camera, camera, "{at}: the student's camera is kept");
                assert_eq!(app.time_s, prompt.time_s.unwrap_or(step.time_s), "{at}");
                assert_eq!(app.view, prompt.view.unwrap_or(step.view), "{at}");
                // Every control the prompt names is on screen for the student to move.
                for key in prompt.overrides.iter().map(|o| &o.key) {
                    if let Some(n) = key.strip_prefix("light.").and_then(|k| k.split('.').next()) {
                        h.state_mut().selected_light = n.parse().expect("light index");
                        h.run_steps(2);
                    }
                    let label = shadowlab::ui::control_label(key).expect("a control");
                    assert!(
                        h.query_all_by_label_contains(label).next().is_some(),
                        "{at}: no `{label}` control on screen"
                    );
                }
            }
            if !applying.is_empty() {
                h.get_by_label("Back to the step's settings").click();
                h.run_steps(2);
                let own = step.scene().expect("the step's scene");
                assert_eq!(format!("{:?}", h.state().scene.lights), format!("{:?}", own.lights));
                assert_eq!(format!("{:?}", h.state().scene.shadow), format!("{:?}", own.shadow));
                assert_eq!(h.state().applied_try_this, None);
            }
        }
    }
    assert!(pressed >= 30, "only {pressed} Apply buttons pressed");
}

/// A lamp's map panel as a student meets it: the six cube faces unfolded into a 4 x 3 picture,
/// and a click on the floor in the torus's shadow pins a probe that names the face it read (the
/// lamp's -X face, the second of its views), its stored distance nearer than the floor's.
#[test]
fn a_point_lights_map_panel_unfolds_its_cube_and_the_probe_names_the_face() {
    let mut h = harness();
    h.state_mut()
        .open(std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/assets/scenes/point_lamp.toml")));
    settle(&mut h);
    let map = shadowlab::ui::landmark(&h.ctx, shadowlab::ui::LANDMARK_SHADOW_MAP).expect("the map picture");
    assert!((map.height() / map.width() - 0.75).abs() < 0.01, "a 4 x 3 cross: {map:?}");
    // The floor in the torus's shadow, a third of the way across and two thirds down.
    let view = camera_view_rect(&h);
    let target = egui::pos2(view.left() + view.width() * 0.3125, view.top() + view.height() * 0.667);
    h.hover_at(target);
    h.run_steps(1);
    for pressed in [true, false] {
        h.event(egui::Event::PointerButton {
            pos: target,
            button: egui::PointerButton::Primary,
            pressed,
            modifiers: Default::default(),
        });
        h.run_steps(1);
    }
    settle(&mut h);
    let report = h.state().probe_report().cloned().expect("a click pins the probe");
    assert_eq!(report.object.as_deref(), Some("floor"), "{report:#?}");
    let light = &report.lights[0];
    assert_eq!(light.cube_face.as_deref(), Some("-X"), "{light:#?}");
    assert_eq!(light.shadow_view, 1);
    assert!(light.stored_depth_linear < light.receiver_depth_linear - 1.0, "{light:#?}");
}

/// The texel-density view picked from the view menu: its legend gives the scale with its unit
/// and the densities on screen, in the language shown, and a map twice as large on a side has
/// twice the density.
#[test]
fn the_view_menu_shows_the_texel_density_and_a_larger_map_doubles_it() {
    let mut h = harness();
    h.state_mut()
        .open(std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/assets/scenes/contact.toml")));
    settle(&mut h);
    h.get_by_value("view: final").click();
    h.run_steps(2);
    h.get_by_label("texel-density").click();
    settle(&mut h);
    assert_eq!(h.state().camera_panel_view(), shadowlab::views::View::TexelDensity);
    let median = |legends: &[String]| -> f64 {
        let line =
            legends.iter().find_map(|l| l.strip_prefix("on screen: ")).expect("the densities on screen");
        line.rsplit_once("median ").and_then(|(_, m)| m.parse().ok()).expect("a median")
    };
    let legends = h.state().legend_lines();
    assert!(legends[0].starts_with("texel density: 0.0625 .. 16 map texels per pixel"), "{legends:?}");
    let before = median(&legends);
    h.state_mut().lang = Lang::Zh;
    h.run_steps(2);
    let legends = h.state().legend_lines();
    assert!(legends[0].starts_with("纹素密度：0.0625 .. 16 贴图纹素/像素"), "{legends:?}");
    h.state_mut().lang = Lang::En;
    h.state_mut().scene.lights[0].shadow_map_size *= 2;
    h.state_mut().mark_dirty();
    settle(&mut h);
    let after = median(&h.state().legend_lines());
    assert!((after / before - 2.0).abs() < 0.01, "{before} then {after}");
}

/// The cascade-index view picked from the view menu on the avenue: its legend names the sun's
/// four cascades by their colours, in the language shown.
#[test]
fn the_view_menu_shows_the_cascade_index_of_the_avenue() {
    let mut h = harness();
    h.state_mut()
        .open(std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/assets/scenes/sun_avenue.toml")));
    settle(&mut h);
    h.get_by_value("view: final").click();
    h.run_steps(2);
    h.get_by_label("cascade-index").click();
    settle(&mut h);
    assert_eq!(h.state().camera_panel_view(), shadowlab::views::View::CascadeIndex);
    let legends = h.state().legend_lines();
    assert!(legends[0].starts_with("cascade index: which of the light's 4 shadow maps"), "{legends:?}");
    assert_eq!(legends[1], "orange: cascade 1, sky blue: cascade 2, green: cascade 3, yellow: cascade 4");
    h.state_mut().lang = Lang::Zh;
    h.run_steps(2);
    let legends = h.state().legend_lines();
    assert!(legends[0].starts_with("级联序号：每个像素读取光源 4 张阴影贴图中的哪一张"), "{legends:?}");
    assert_eq!(legends[1], "橙色：级联 1，天蓝：级联 2，绿色：级联 3，黄色：级联 4");
}

/// Lesson 6 as a student meets it: the bleeding overlay and its legend on the two-slab scene, the
/// probe's Chebyshev rows, then the moments view picked from the view menu, and what it says
/// once the technique has no moments.
#[test]
fn the_vsm_lesson_shows_light_bleeding_and_the_view_menu_shows_the_moments() {
    let mut h = harness();
    let lesson = h.state().lessons.iter().position(|l| l.id == "vsm").expect("lesson 6");
    h.state_mut().go_to_step(lesson, 2);
    settle(&mut h);
    let legends = h.state().legend_lines();
    assert!(legends.iter().any(|l| l.starts_with("magenta stripes: light bleeding")), "{legends:?}");
    let overlay = h.state().overlay_image().expect("the bleeding overlay");
    let magenta = overlay.pixels().filter(|p| p[0] == 255 && p[1] == 0 && p[2] == 200 && p[3] > 0).count();
    assert!(magenta > 500, "only {magenta} magenta overlay pixels");
    // A new language writes the legends again.
    h.state_mut().lang = Lang::Zh;
    h.run_steps(2);
    let legends = h.state().legend_lines();
    assert!(legends.iter().any(|l| l.starts_with("品红条纹：漏光")), "{legends:?}");
    h.state_mut().lang = Lang::En;
    h.run_steps(2);
    assert!(
        h.query_all_by_label("Chebyshev bound / true share").count() > 0,
        "no Chebyshev row in the probe"
    );
    h.get_by_value("view: final").click();
    h.run_steps(2);
    h.get_by_label("moments").click();
    settle(&mut h);
    assert_eq!(h.state().camera_panel_view(), shadowlab::views::View::Moments);
    let legends = h.state().legend_lines();
    assert!(
        legends.iter().any(|l| l.starts_with("VSM moments, level 3 (each texel averages 8x8")),
        "{legends:?}"
    );
    h.state_mut().scene.shadow.technique = shadowlab::scene::Technique::Pcf;
    h.state_mut().mark_dirty();
    settle(&mut h);
    let legends = h.state().legend_lines();
    assert!(legends.iter().any(|l| l == "the moments view needs the vsm or vssm technique"), "{legends:?}");
    // The moments view is of the light's map: the camera picture's overlays stay off it.
    assert!(!legends.iter().any(|l| l.contains("only VSM and VSSM")), "{legends:?}");
}

/// What `shadowlab FILE`, `--lesson ID --step N` and `--lang zh` open, as the window shows it:
/// a scene, a model on a floor, a shipped lesson at a step, in Chinese.
#[test]
fn the_command_line_opens_a_scene_a_model_or_a_lesson_in_a_language() {
    use shadowlab::ui::launch::resolve;
    let mut h = harness();
    let repo = |p: &str| format!("{}/{p}", env!("CARGO_MANIFEST_DIR"));
    let bleeding = repo("assets/scenes/bleeding.toml");
    h.state_mut().apply_launch(resolve(Some(&bleeding), None, None, None).expect("a scene"));
    settle(&mut h);
    assert!(h.state().scene.objects.iter().any(|o| o.name == "high slab"), "bleeding.toml is open");
    assert!(h.state().current_step().is_none());
    let obj = repo("tests/data/obj/blender_export.obj");
    h.state_mut().apply_launch(resolve(Some(&obj), None, None, None).expect("a model"));
    settle(&mut h);
    assert!(h.state().scene.objects.len() >= 2, "the model stands on a floor");
    let launch = resolve(None, Some("vsm"), Some(4), Some(Lang::Zh)).expect("a lesson");
    h.state_mut().apply_launch(launch);
    settle(&mut h);
    let (lesson, step, index) = h.state().current_step().expect("a lesson step");
    assert_eq!((lesson.id.as_str(), index), ("vsm", 3));
    assert_eq!(h.state().lang, Lang::Zh);
    h.get_by_label(&step.title.zh);
}

/// A scene opened from a path comes back from the scene picker's "recent" list.
#[test]
fn a_scene_opened_from_a_path_is_listed_under_recent_and_opens_from_there() {
    let mut h = harness();
    let dir = tempfile::tempdir().expect("temporary folder");
    let mine = dir.path().join("my_slabs.toml");
    let contact = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/contact.toml");
    std::fs::write(&mine, std::fs::read_to_string(&contact).expect("contact.toml")).expect("write");
    h.get_by_label("file").click();
    h.run_steps(1);
    h.get_by_label("file").type_text(&mine.display().to_string());
    h.run_steps(1);
    h.get_by_label("Open").click();
    settle(&mut h);
    assert_eq!(h.state().settings.recent_files.first(), Some(&mine));
    // Another scene from the picker, then the recent one again.
    h.get_by_value("my_slabs.toml").click();
    h.run_steps(2);
    h.get_by_label("games202.toml").click();
    settle(&mut h);
    assert!(h.state().scene.path.as_deref().is_some_and(|p| p.ends_with("games202.toml")));
    h.get_by_value("games202.toml").click();
    h.run_steps(2);
    h.get_by_label("recent");
    h.get_by_label("my_slabs.toml").click();
    settle(&mut h);
    assert_eq!(h.state().scene.path.as_deref(), Some(mine.as_path()));
    // The shipped scenes are not repeated among the recent files.
    assert_eq!(h.state().settings.recent_files, vec![mine]);
}

/// Browse… asks the desktop for its Open dialog; where there is none (no session bus, no
/// xdg-desktop-portal, as here) the app says so and hands the path box the keyboard.
#[test]
fn browse_without_a_dialog_service_points_at_the_path_box() {
    let mut h = harness();
    h.get_by_label("Browse…").click();
    // The click lands on the next frame; the answer comes from the dialog's own thread.
    let start = std::time::Instant::now();
    while h.state().browsing() || h.state().status.is_empty() {
        h.step();
        assert!(start.elapsed() < std::time::Duration::from_secs(60), "the dialog never answered");
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
    h.run_steps(2);
    assert!(h.state().status.starts_with("no file dialog on this desktop"), "{}", h.state().status);
    assert!(h.get_by_label("file").is_focused(), "the path box has the keyboard");
    // The box then opens a lesson by its id, as the command line does.
    h.get_by_label("file").type_text("vsm");
    h.run_steps(1);
    h.get_by_label("Open").click();
    settle(&mut h);
    let (lesson, _, index) = h.state().current_step().expect("a lesson step");
    assert_eq!((lesson.id.as_str(), index), ("vsm", 0));
}

/// (lesson, step) of every step of every lesson, in order.
fn every_step(h: &Harness<'_, ShadowlabApp>) -> Vec<(usize, usize)> {
    let lessons = &h.state().lessons;
    lessons.iter().enumerate().flat_map(|(l, lesson)| (0..lesson.steps.len()).map(move |s| (l, s))).collect()
}

fn lesson_index(h: &Harness<'_, ShadowlabApp>, id: &str) -> usize {
    h.state().lessons.iter().position(|l| l.id == id).unwrap_or_else(|| panic!("no lesson {id}"))
}

#[test]
fn a_light_space_view_carries_none_of_the_camera_views_marks() {
    let mut h = harness_sized([1600.0, 900.0]);
    // Lesson 5 step 1: the shadow-map view with the light-frustum overlay and a probe; lesson 4
    // step 2 with the map picked: the blocker-search heatmap overlay and a probe.
    let multi = lesson_index(&h, "multi-light");
    let pcss = lesson_index(&h, "pcss");
    for (lesson, step, pick_map) in [(multi, 0, false), (pcss, 1, true)] {
        h.state_mut().go_to_step(lesson, step);
        if pick_map {
            h.state_mut().view = shadowlab::views::View::ShadowMap;
            h.state_mut().mark_dirty();
        }
        settle(&mut h);
        assert!(!h.state().overlays.is_empty(), "the step has overlays on");
        let painted = h.state().camera_paint().clone();
        assert_eq!(painted.view, Some(shadowlab::views::View::ShadowMap), "step {}", step + 1);
        assert!(!painted.overlay, "an overlay of the camera's picture over the map (step {})", step + 1);
        assert!(!painted.frusta, "light frusta drawn over the map (step {})", step + 1);
        assert_eq!(painted.probe_crosshair, None, "the camera's probe crosshair on the map");
        // The probe is marked where it is in the map: at its texel, inside the picture.
        assert_eq!(painted.probe_texel.len(), 1, "the probe's texel is circled on the map");
        assert!(painted.picture.contains(painted.probe_texel[0]));
        // And no legend of the camera's overlays under it.
        assert_eq!(h.state().legend_lines(), Vec::<String>::new(), "step {}", step + 1);
    }
    // Back on the final view, the same step's marks are drawn.
    h.state_mut().view = shadowlab::views::View::Final;
    h.state_mut().mark_dirty();
    settle(&mut h);
    let painted = h.state().camera_paint().clone();
    assert!(painted.overlay && painted.probe_crosshair.is_some(), "{painted:?}");
}

#[test]
fn every_steps_frame_is_shown_whole_at_classroom_sizes() {
    let (fw, fh) = shadowlab::lessons::PROBE_FRAME;
    let frame_aspect = fw as f32 / fh as f32;
    for size in [[1280.0, 720.0], [1600.0, 900.0]] {
        let mut h = harness_sized(size);
        let steps = every_step(&h);
        for (l, s) in steps {
            h.state_mut().go_to_step(l, s);
            h.run_steps(2);
            let painted = h.state().camera_paint().clone();
            let name = format!("{} step {} at {size:?}", h.state().lessons[l].id, s + 1);
            let picture = painted.picture;
            // Letterboxed: the frame's shape, inside the panel, never cropped to the panel's.
            assert!(
                (picture.width() / picture.height() - frame_aspect).abs() < 0.01,
                "{name}: the frame is shown {picture:?}, not 16:9"
            );
            assert!(
                painted.area.expand(0.5).contains_rect(picture),
                "{name}: {picture:?} outside {:?}",
                painted.area
            );
            assert!(picture.width() >= 320.0, "{name}: the frame is only {} points wide", picture.width());
        }
        // What is rendered has the frame's shape too.
        settle(&mut h);
        let (w, h_px) = h.state().shown_size();
        assert!((w as f32 / h_px as f32 - frame_aspect).abs() < 0.01, "rendered at {w}x{h_px}");
    }
}

#[test]
fn the_lesson_text_says_when_the_settings_are_no_longer_the_steps() {
    let mut h = harness();
    let pcss = lesson_index(&h, "pcss");
    h.state_mut().go_to_step(pcss, 1);
    settle(&mut h);
    assert!(h.state().changed_from_step().is_empty());
    assert!(h.query_by_label_contains("You changed the step's settings").is_none());
    h.state_mut().scene.shadow.technique = shadowlab::scene::Technique::Hard;
    h.state_mut().mark_dirty();
    settle(&mut h);
    assert_eq!(h.state().changed_from_step(), vec!["shadow settings"]);
    h.get_by_label_contains("You changed the step's settings");
    h.get_by_label("Back to the step's settings").click();
    settle(&mut h);
    assert!(h.state().changed_from_step().is_empty());
    assert!(h.query_by_label_contains("You changed the step's settings").is_none());
}

#[test]
fn playback_left_running_loops_over_the_time_range() {
    let mut h = harness();
    let multi = lesson_index(&h, "multi-light");
    h.state_mut().go_to_step(multi, 3);
    settle(&mut h);
    let end = shadowlab::ui::PLAYBACK_RANGE_S;
    h.state_mut().time_s = end - 1.0;
    h.state_mut().speed = 10.0;
    h.state_mut().playing = true;
    // Play past the end of the range: time comes round to the start and keeps moving.
    let frames_before = h.state().frames_shown();
    let mut wrapped = false;
    let mut last = h.state().time_s;
    for _ in 0..400 {
        h.step();
        std::thread::sleep(std::time::Duration::from_millis(20));
        let t = h.state().time_s;
        assert!((0.0..end).contains(&t), "time {t} outside 0..{end}");
        wrapped |= t < last;
        last = t;
        if wrapped && t > 2.0 {
            break;
        }
    }
    assert!(wrapped && last > 2.0, "playback did not come round (time {last})");
    assert!(h.state().playing, "playback stopped");
    h.state_mut().playing = false;
    settle(&mut h);
    assert!(h.state().frames_shown() > frames_before + 1, "the views stopped refreshing");
}

#[test]
fn the_ab_split_compares_shaded_pictures_whatever_the_view() {
    let mut h = harness();
    h.state_mut().view = shadowlab::views::View::Penumbra;
    h.state_mut().scene.shadow.technique = shadowlab::scene::Technique::Pcss;
    h.get_by_label("A/B split against").click();
    settle(&mut h);
    // Both sides shaded (one heatmap beside one shaded picture compares nothing), and it says so.
    assert_eq!(h.state().camera_panel_view(), shadowlab::views::View::Final);
    assert!(h.state().camera_image_b().is_some(), "side B is rendered");
    // Its labels stay clear of the view selector.
    let painted = h.state().camera_paint().clone();
    assert!(
        painted.legend.iter().any(|l| l.contains("the A/B split compares the shaded pictures")),
        "{painted:?}"
    );
    assert_eq!(painted.ab_labels.len(), 2);
    for label in &painted.ab_labels {
        assert!(!label.intersects(painted.selector), "{label:?} under the selector {:?}", painted.selector);
    }
    // Off again, the chosen view returns.
    h.get_by_label("A/B split against").click();
    settle(&mut h);
    assert_eq!(h.state().camera_panel_view(), shadowlab::views::View::Penumbra);
}

/// A long error and a long "saved …" message share the status bar's left with the timings at
/// its right: each is cut with an ellipsis short of the timings, at two window sizes and in
/// both languages, and hovering the error shows its whole text once.
#[test]
fn long_status_messages_stop_short_of_the_timings_and_show_once_on_hover() {
    let detail = format!(
        "{}/lessons/my-homework/scenes/a-scene-with-a-rather-long-name.toml: line 12: key \
         `shadow.technique`: expected one of hard, pcf, pcss, vsm, vssm, found \"blurry\" (did you mean pcss?)",
        env!("CARGO_MANIFEST_DIR")
    );
    let saved = format!(
        "saved {0}/shot-001-window.png, {0}/shot-001-camera.png, {0}/shot-001-shadow-map.png",
        std::env::temp_dir().join("shadowlab-screenshots-of-a-long-lesson").display()
    );
    for size in [[1280.0, 720.0], [1600.0, 900.0]] {
        let mut h = harness_with(size, Settings { show_timings: true, ..Settings::default() });
        for lang in [Lang::En, Lang::Zh] {
            let app = h.state_mut();
            app.lang = lang;
            app.error = Some(shadowlab::ui::AppError::new("could not open the scene", &detail));
            app.status = saved.clone();
            h.run_steps(3);
            let case = format!("{lang:?} at {}x{}", size[0], size[1]);
            let shown = h.state().shown_size();
            let resolution = format!("{}x{}", shown.0, shown.1);
            let timings: Vec<egui::Rect> =
                h.query_all_by_label_contains(&resolution).map(|n| n.rect()).collect();
            assert_eq!(timings.len(), 1, "{case}: one timings label naming {resolution}");
            let timings = timings[0];
            assert!(timings.right() <= size[0] && timings.left() > size[0] * 0.3, "{case}: {timings:?}");
            let error = h.get_by_label_contains(&detail).rect();
            let status = h.get_by_label(&saved).rect();
            let dismiss = h.get_by_label(shadowlab::i18n::tr(lang, "dismiss")).rect();
            for (what, rect) in [("error", error), ("dismiss", dismiss), ("saved message", status)] {
                assert!(
                    rect.right() <= timings.left() && rect.width() > 0.0,
                    "{case}: the {what} ({rect:?}) runs under the timings ({timings:?})"
                );
                assert!((rect.center().y - timings.center().y).abs() < 4.0, "{case}: {what} {rect:?}");
            }
            // Hovering either shows its whole text in a tooltip, once (egui shows one only for a
            // cut text, so this also says both were cut).
            for (what, text, rect) in [("error", &detail, error), ("saved message", &saved, status)] {
                let count = |h: &Harness<'_, ShadowlabApp>| h.query_all_by_label_contains(text).count();
                assert_eq!(count(&h), 1, "{case}: the {what} before hovering");
                h.hover_at(rect.center());
                h.run_steps(4);
                assert_eq!(count(&h), 2, "{case}: the {what} in the bar and once in its tooltip");
            }
            h.hover_at(egui::pos2(size[0] * 0.5, size[1] * 0.5));
            h.run_steps(4);
        }
    }
}

/// Every step in both languages, in normal and present mode, as PNGs to look at
/// (`target/tmp/walk/`): `cargo test --release --test app -- --ignored walk_every_step`.
#[test]
#[ignore = "writes pictures of every step for a person to look at"]
fn walk_every_step_to_pictures() {
    let out = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("walk");
    let mut h = harness_sized([1600.0, 900.0]);
    let steps = every_step(&h);
    for lang in [Lang::En, Lang::Zh] {
        for present in [false, true] {
            let dir = out.join(format!("{}{}", lang.code(), if present { "-present" } else { "" }));
            std::fs::create_dir_all(&dir).expect("create the folder");
            for &(l, s) in &steps {
                h.state_mut().lang = lang;
                h.state_mut().present = present;
                h.state_mut().go_to_step(l, s);
                settle(&mut h);
                h.run_steps(3);
                let id = h.state().lessons[l].id.clone();
                let image = h.render().expect("render the window");
                image.save(dir.join(format!("{id}-{}.png", s + 1))).expect("write the picture");
            }
        }
    }
}

#[test]
fn a_page_without_webgpu_says_why_in_place_of_the_views_in_both_languages() {
    use shadowlab::browser::NoWebGpu;
    let mut h = harness();
    h.state_mut().without_webgpu(NoWebGpu::Missing);
    h.run_steps(2);
    h.get_by_label_contains("need WebGPU");
    h.get_by_label(NoWebGpu::Missing.reason());
    h.get_by_label_contains(
        "Chrome or Edge 113 or later, Safari 26 or later, Firefox 141 or later on Windows",
    );
    assert!(!h.state().render_pending(), "nothing is rendered without a renderer");
    h.state_mut().lang = Lang::Zh;
    h.run_steps(2);
    h.get_by_label("相机视图和阴影贴图需要 WebGPU");
    h.get_by_label("这个浏览器没有 WebGPU，或者把它关掉了。");
    assert!(h.query_by_label_contains("need WebGPU").is_none(), "English left on screen");
    // The lessons still open and show their text.
    let lesson = h.state().lessons.iter().position(|l| l.id == "pcss").expect("the PCSS lesson");
    h.state_mut().go_to_step(lesson, 0);
    h.run_steps(2);
    h.get_by_label_contains("相机视图和阴影贴图需要 WebGPU");
    let title = h.state().lessons[lesson].steps[0].title.zh.clone();
    h.get_by_label_contains(&title);
}

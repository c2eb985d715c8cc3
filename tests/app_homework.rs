//! Checking a homework in the app, as a student does: the shader's path typed into the path box
//! and opened, its picture in the camera view and the findings in the homework panel; an edit
//! saved in their editor checked again; in Chinese, the findings in Chinese.

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use shadowlab::i18n::Lang;
use shadowlab::ui::{Settings, ShadowlabApp, app_for_test};
use std::path::Path;

#[path = "../src/homework/submission/tests/writer.rs"]
#[allow(dead_code)]
mod zip_writer;

fn harness() -> Harness<'static, ShadowlabApp> {
    let mut setup = egui_kittest::wgpu::default_wgpu_setup();
    if let eframe::egui_wgpu::WgpuSetup::CreateNew(create) = setup {
        setup = eframe::egui_wgpu::WgpuSetup::CreateNew(shadowlab::ui::configure_wgpu(create));
    }
    let settings = Settings { show_timings: false, ..Settings::default() };
    Harness::builder()
        .with_size([1600.0, 900.0])
        .wgpu_setup(setup)
        .build_eframe(move |cc| app_for_test(cc, settings.clone()))
}

/// Step frames until the homework's check of its current program is in.
fn settle_check(h: &mut Harness<'_, ShadowlabApp>) {
    let start = std::time::Instant::now();
    loop {
        h.step();
        let checked = h.state().homework.as_ref().is_some_and(|hw| hw.checked());
        if checked && !h.state().render_pending() {
            h.run_steps(2);
            return;
        }
        let problem = h.state().homework.as_ref().and_then(|hw| hw.gpu_error.clone());
        assert!(problem.is_none(), "the check failed: {problem:?}");
        assert!(start.elapsed() < std::time::Duration::from_secs(300), "the check did not come");
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
}

/// Types `path` into the path box, opens it and waits for its check, as a student does.
fn open_and_check(h: &mut Harness<'_, ShadowlabApp>, path: &Path) {
    h.get_by_label("file").click();
    h.run_steps(1);
    h.get_by_label("file").type_text(&path.display().to_string());
    h.run_steps(1);
    h.get_by_label("Open").click();
    settle_check(h);
}

fn finding_ids(h: &Harness<'_, ShadowlabApp>) -> Vec<&'static str> {
    let homework = h.state().homework.as_ref().expect("a homework");
    homework.outcome.as_ref().expect("a check").report.findings.iter().map(|f| f.id).collect()
}

fn example(name: &str) -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/homework").join(name))
        .expect("the example")
}

#[test]
fn a_shader_typed_into_the_path_box_shows_its_findings_and_an_edit_is_checked_again() {
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let shader = scratch.path().join("phongFragment.glsl");
    std::fs::write(&shader, example("phongFragment_nan_blocker.glsl")).expect("write");
    let mut h = harness();
    open_and_check(&mut h, &shader);
    assert!(h.state().error.is_none(), "{:?}", h.state().error);
    assert_eq!(finding_ids(&h), ["nan_blocker_depth"]);
    // The panel names the finding and links its lesson step.
    h.get_by_label("nan_blocker_depth");
    // The student fixes it in their editor; the app notices and checks again, camera kept.
    let camera = h.state().scene.camera;
    std::thread::sleep(std::time::Duration::from_millis(20));
    std::fs::write(&shader, example("phongFragment.glsl")).expect("write");
    let start = std::time::Instant::now();
    while h.state().homework.as_ref().is_some_and(|hw| hw.reloads == 0) {
        h.step();
        std::thread::sleep(std::time::Duration::from_millis(20));
        assert!(start.elapsed() < std::time::Duration::from_secs(30), "the edit was not noticed");
    }
    settle_check(&mut h);
    assert_eq!(finding_ids(&h), Vec::<&str>::new());
    assert_eq!(h.state().scene.camera, camera);
    h.get_by_label("No findings: your shadows match the ground truth.");
    // Each picture the selector offers can be shown.
    for label in [
        "your shader, map cleared to white",
        "difference",
        "ground truth",
        "your visibility",
        "shadowlab's",
        "your shader",
    ] {
        h.get_by_label(label).click();
        h.run_steps(2);
    }
    assert_eq!(
        h.state().homework.as_ref().map(|hw| hw.picture),
        Some(shadowlab::app::homework::HomeworkPicture::Student)
    );
    // A finding's link opens the lesson step that teaches it.
    std::fs::write(&shader, example("phongFragment_tiny_light.glsl")).expect("write");
    let start = std::time::Instant::now();
    while h.state().homework.as_ref().is_some_and(|hw| hw.reloads < 2) {
        h.step();
        std::thread::sleep(std::time::Duration::from_millis(20));
        assert!(start.elapsed() < std::time::Duration::from_secs(30), "the edit was not noticed");
    }
    settle_check(&mut h);
    assert_eq!(finding_ids(&h), ["no_penumbra"]);
    let link =
        h.get_all_by(|n| n.label().is_some_and(|l| l.starts_with("→ "))).next().expect("a lesson link");
    link.click();
    h.run_steps(2);
    let (lesson, _, step) = h.state().current_step().expect("a lesson step");
    assert_eq!((lesson.id.as_str(), step + 1), ("pcss", 5));
}

#[test]
fn in_chinese_the_findings_are_explained_in_chinese() {
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let shader = scratch.path().join("phongFragment.glsl");
    std::fs::write(&shader, example("phongFragment_light_size_world.glsl")).expect("write");
    let mut h = harness();
    h.state_mut().lang = Lang::Zh;
    h.state_mut().open_any(&shader);
    settle_check(&mut h);
    let homework = h.state().homework.as_ref().expect("a homework");
    let report = &homework.outcome.as_ref().expect("a check").report;
    assert_eq!(report.findings.len(), 2);
    for f in &report.findings {
        assert!(f.explanation.chars().any(|c| ('\u{4e00}'..='\u{9fff}').contains(&c)), "{}", f.explanation);
    }
    h.get_by_label("你的作业");
}

/// A page's drop: the shader's bytes handed over, not a path. The panel says it is not watched
/// (there is no disk copy to watch) and shows the findings as for a file.
#[test]
fn a_shader_handed_over_as_bytes_is_checked_and_the_panel_says_it_is_not_watched() {
    let mut h = harness();
    let dropped = vec![shadowlab::files::hand_over(
        "phongFragment.glsl",
        example("phongFragment_nan_blocker.glsl").as_bytes(),
    )];
    h.state_mut().open_files(&dropped);
    settle_check(&mut h);
    assert_eq!(finding_ids(&h), ["nan_blocker_depth"]);
    h.get_by_label_contains("not watched: after an edit, drop the file again");
    assert!(h.query_by_label_contains("watching the file").is_none());
}

/// Wait until the homework was read again after a change on disk (`reloads` past `before`).
fn await_reload(h: &mut Harness<'_, ShadowlabApp>, before: u64) {
    let start = std::time::Instant::now();
    while h.state().homework.as_ref().is_some_and(|hw| hw.reloads <= before) {
        h.step();
        std::thread::sleep(std::time::Duration::from_millis(20));
        assert!(start.elapsed() < std::time::Duration::from_secs(30), "the edit was not noticed");
    }
}

/// The student's homework folder opened from the path box: checked with the light their
/// DirectionalLight.js builds (the panel says where it came from), and their light script
/// watched like their shader: fixed in their editor, it is checked again.
#[test]
fn a_homework_folder_is_checked_with_the_students_own_light_and_its_script_is_watched() {
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let folder = scratch.path().join("alice");
    let shader = folder.join("homework1/src/shaders/phongShader/phongFragment.glsl");
    let light = folder.join("homework1/src/lights/DirectionalLight.js");
    for (path, name) in [(&shader, "phongFragment.glsl"), (&light, "DirectionalLight_narrow.js")] {
        std::fs::create_dir_all(path.parent().expect("a parent")).expect("folders");
        std::fs::write(path, example(name)).expect("write");
    }
    let mut h = harness();
    open_and_check(&mut h, &folder);
    assert!(h.state().error.is_none(), "{:?}", h.state().error);
    assert_eq!(finding_ids(&h), ["light_frustum_clips"]);
    h.get_by_label("alice");
    h.get_by_label_contains("light from DirectionalLight.js:");
    h.get_by_label_contains("your penumbrae behave as a light");
    h.get_by_label_contains(", 50 wide");
    // The student widens their light's box; the app notices the script and checks again.
    std::thread::sleep(std::time::Duration::from_millis(20));
    std::fs::write(&light, example("DirectionalLight.js")).expect("write");
    await_reload(&mut h, 0);
    settle_check(&mut h);
    assert_eq!(finding_ids(&h), Vec::<&str>::new());
    h.get_by_label_contains(", 200 wide");
    let width = h
        .state()
        .homework
        .as_ref()
        .and_then(|hw| hw.outcome.as_ref()?.report.light_width.as_ref()?.implied_light_width_world);
    assert!(width.is_some_and(|w| (2.5..5.0).contains(&w)), "{width:?}");
}

/// A page's drop of a zip: the submission's bytes handed over, its files found inside, its light
/// used; a folder or zip with no homework in it keeps what is shown and says why.
#[test]
fn a_zip_handed_over_is_checked_and_one_without_a_homework_is_refused() {
    let mut h = harness();
    let zip = zip_writer::build(&[
        zip_writer::deflated(
            "bob/homework1/src/shaders/phongShader/phongFragment.glsl",
            example("phongFragment_nan_blocker.glsl").as_bytes(),
        ),
        zip_writer::deflated(
            "bob/homework1/src/lights/DirectionalLight.js",
            example("DirectionalLight.js").as_bytes(),
        ),
    ]);
    let dropped = vec![shadowlab::files::hand_over("bob.zip", &zip)];
    h.state_mut().open_files(&dropped);
    settle_check(&mut h);
    assert_eq!(finding_ids(&h), ["nan_blocker_depth"]);
    let from = h
        .state()
        .homework
        .as_ref()
        .and_then(|hw| Some(hw.outcome.as_ref()?.report.light.as_ref()?.from.clone()));
    assert!(from.as_deref().is_some_and(|f| f.contains("DirectionalLight.js")), "{from:?}");
    h.get_by_label("bob");
    // A zip with no homework in it: an error naming it, bob's check still on screen.
    let empty = zip_writer::build(&[zip_writer::spec("notes.txt", b"no homework here")]);
    let dropped = vec![shadowlab::files::hand_over("empty.zip", &empty)];
    h.state_mut().open_files(&dropped);
    h.run_steps(2);
    let error = h.state().error.as_ref().map(|e| format!("{e:?}"));
    assert!(error.as_deref().is_some_and(|e| e.contains("empty.zip")), "{error:?}");
    assert_eq!(finding_ids(&h), ["nan_blocker_depth"]);
}

/// The bonus in the app: a page with two lights lists both in the panel; choosing the second
/// checks it (its own matrices, its own findings), and its animation's times are offered.
#[test]
fn each_light_of_the_page_is_checked_when_chosen_in_the_panel() {
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let folder = scratch.path().join("bea");
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let engine = std::fs::read_to_string(root.join("assets/homework/framework/src/engine.js"))
        .expect("the framework's engine.js")
        .replace(
            "    renderer.addLight(directionLight);",
            "    renderer.addLight(directionLight);
    const highLight = new DirectionalLight(2500, [1, 1, 1], [0, 420, 1], focalPoint, lightUp, true, renderer.gl);
    renderer.addLight(highLight);",
        )
        .replace(
            "        renderer.render();",
            "        renderer.render();\n        highLight.lightPos = [Math.sin(Date.now() * 0.001), 420, 1];",
        );
    for (path, text) in [
        ("homework1/src/shaders/phongShader/phongFragment.glsl", example("phongFragment.glsl")),
        ("homework1/src/lights/DirectionalLight.js", example("DirectionalLight.js")),
        ("homework1/src/engine.js", engine),
    ] {
        let to = folder.join(path);
        std::fs::create_dir_all(to.parent().expect("a parent")).expect("folders");
        std::fs::write(to, text).expect("write");
    }
    let mut h = harness();
    open_and_check(&mut h, &folder);
    let checked_position = |h: &Harness<'_, ShadowlabApp>| {
        h.state().homework.as_ref().and_then(|hw| Some(hw.outcome.as_ref()?.report.light.as_ref()?.position))
    };
    assert_eq!(checked_position(&h), Some([0.0, 80.0, 80.0]));
    h.get_by_label("the page's lights: the check is of the one chosen");
    // The high light (far 400 leaves the floor out of its map), chosen by a click.
    h.get_by_label_contains("2 DirectionalLight (engine.js:").click();
    h.run_steps(1);
    settle_check(&mut h);
    let position = checked_position(&h).expect("a light");
    assert!((position[1] - 420.0).abs() < 1e-3, "{position:?}");
    assert!(finding_ids(&h).contains(&"light_frustum_clips"), "{:?}", finding_ids(&h));
    // Its animation moves it: the times the check looks again at are offered, and one is checked.
    h.get_by_label("1.0 s").click();
    h.run_steps(1);
    settle_check(&mut h);
    let position = checked_position(&h).expect("a light");
    let t = (1.0f32 * 60.0).ceil() / 60.0;
    assert!((position[0] - t.sin()).abs() < 1e-3, "{position:?}");
}

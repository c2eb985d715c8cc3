//! A class of homeworks in the app, as a TA opens it: the class folder typed into the path box,
//! checked in the background, then the findings ranked by how many students have them and the
//! students; a student's name opens their homework, and the homework panel leads back. The class
//! report folder opens again at once.

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use shadowlab::i18n::Lang;
use shadowlab::ui::{Settings, ShadowlabApp, app_for_test};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

fn harness() -> Harness<'static, ShadowlabApp> {
    harness_at([1600.0, 900.0], Lang::En)
}

fn harness_at(size: [f32; 2], lang: Lang) -> Harness<'static, ShadowlabApp> {
    let mut setup = egui_kittest::wgpu::default_wgpu_setup();
    if let eframe::egui_wgpu::WgpuSetup::CreateNew(create) = setup {
        setup = eframe::egui_wgpu::WgpuSetup::CreateNew(shadowlab::ui::configure_wgpu(create));
    }
    let settings = Settings { show_timings: false, lang, ..Settings::default() };
    let mut h = Harness::builder()
        .with_size(size)
        .wgpu_setup(setup)
        .build_eframe(move |cc| app_for_test(cc, settings.clone()));
    // The class is checked by the program itself (the test binary is not it).
    h.state_mut().class_checker = Some(PathBuf::from(env!("CARGO_BIN_EXE_shadowlab")));
    h
}

/// A finding as a student reads it: its id, its figures by name, its explanation.
type Said = (String, Vec<(String, Option<f64>)>, String);

fn example(name: &str) -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/homework").join(name))
        .expect("the example")
}

/// A student's homework folder in the framework's layout, with `shader` as their phongFragment.
fn student(class: &Path, name: &str, shader: &str) {
    let path = class.join(name).join("homework1/src/shaders/phongShader/phongFragment.glsl");
    std::fs::create_dir_all(path.parent().expect("a parent")).expect("folders");
    std::fs::write(path, example(shader)).expect("write");
}

fn open(h: &mut Harness<'_, ShadowlabApp>, path: &Path) {
    h.get_by_label("file").click();
    h.run_steps(1);
    h.get_by_label("file").type_text(&path.display().to_string());
    h.run_steps(1);
    h.get_by_label("Open").click();
    h.run_steps(1);
}

/// Step frames until the class check has ended.
fn settle_class(h: &mut Harness<'_, ShadowlabApp>) {
    let start = Instant::now();
    while h.state().class.as_ref().is_some_and(|c| c.running()) {
        h.step();
        assert!(start.elapsed() < Duration::from_secs(600), "the class check did not end");
        std::thread::sleep(Duration::from_millis(50));
    }
    h.run_steps(2);
}

/// Step frames until the open homework's check is in.
fn settle_check(h: &mut Harness<'_, ShadowlabApp>) {
    let start = Instant::now();
    while !h.state().homework.as_ref().is_some_and(|hw| hw.checked()) || h.state().render_pending() {
        h.step();
        assert!(start.elapsed() < Duration::from_secs(300), "the check did not come");
        std::thread::sleep(Duration::from_millis(10));
    }
    h.run_steps(2);
}

#[test]
fn a_class_folder_opens_as_its_ranked_findings_and_each_student_is_a_click_away() {
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let class = scratch.path().join("class-2026");
    student(&class, "alice", "phongFragment.glsl");
    student(&class, "bob", "phongFragment_receiver_blocker.glsl");
    let mut h = harness();
    open(&mut h, &class);
    assert!(h.state().error.is_none(), "{:?}", h.state().error);
    assert!(h.state().homework.is_none(), "a class is not opened as one homework");
    h.get_by_label("Class");
    settle_class(&mut h);
    let state = h.state().class.as_ref().expect("the class");
    assert_eq!(state.error, None);
    let names: Vec<&str> = state.rows.iter().map(|r| r.name.as_str()).collect();
    assert_eq!(names, ["alice", "bob"]);
    let ranked: Vec<(&str, usize)> = state.ranked.iter().map(|r| (r.id.as_str(), r.students.len())).collect();
    assert_eq!(ranked, [("receiver_counts_as_blocker", 1)]);
    let out = state.out.clone();
    assert!(out.join("index.html").is_file() && out.join("class.json").is_file());
    // Ranked above, and in bob's row below.
    assert_eq!(h.get_all_by_label("receiver_counts_as_blocker").count(), 2);
    h.get_by_label_contains("2 submissions: 2 checked");
    h.get_by_label("no findings");

    // bob's name under the finding opens his homework, checked in the app.
    let bob = h.get_all_by_label("bob").next().expect("bob's name");
    bob.click();
    h.run_steps(1);
    settle_check(&mut h);
    let homework = h.state().homework.as_ref().expect("bob's homework");
    assert_eq!(homework.path, class.join("bob"));
    let outcome = homework.outcome.as_ref().expect("a check");
    let found: Vec<&str> = outcome.report.findings.iter().map(|f| f.id).collect();
    assert_eq!(found, ["receiver_counts_as_blocker"]);
    // The same findings, with the same numbers, as the command line's check of the same folder
    // (the class report's): judged at the command line's size whatever the panel's, the
    // pictures shown scaled into the panel.
    let class_row = &h.state().class.as_ref().expect("the class").rows[1];
    let by_cli = class_row.report.as_ref().expect("bob's report");
    let said_by_cli: Vec<Said> = by_cli
        .findings
        .iter()
        .map(|f| {
            (f.id.clone(), f.figures.iter().map(|(k, v)| (k.clone(), *v)).collect(), f.explanation.clone())
        })
        .collect();
    let said_in_app: Vec<Said> = outcome
        .report
        .findings
        .iter()
        .map(|f| {
            let figures =
                f.figures.iter().map(|(k, v)| (k.to_string(), v.is_finite().then_some(*v))).collect();
            (f.id.to_string(), figures, f.explanation.clone())
        })
        .collect();
    assert_eq!(said_in_app, said_by_cli);
    assert_eq!((outcome.student.width, outcome.student.height), shadowlab::homework::CHECK_SIZE);
    h.get_by_label("Your homework");

    // The homework panel leads back to the class.
    h.get_by_label_contains("← class class-2026 (2 submissions)").click();
    h.run_steps(2);
    h.get_by_label("Findings across the class");

    // The class report folder opens again at once, nothing checked.
    let mut h = harness();
    open(&mut h, &out);
    let state = h.state().class.as_ref().expect("the class report");
    assert!(!state.running());
    assert_eq!(state.rows.len(), 2);
    h.run_steps(2);
    assert_eq!(h.get_all_by_label("receiver_counts_as_blocker").count(), 2);
}

#[test]
fn a_class_folder_without_submissions_is_refused_and_the_scene_kept() {
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let empty = scratch.path().join("empty");
    std::fs::create_dir_all(&empty).expect("folder");
    let mut h = harness();
    let scene = h.state().scene.path.clone();
    open(&mut h, &empty);
    assert!(h.state().class.is_none());
    let error = h.state().error.as_ref().expect("an error");
    assert!(error.to_string().contains("empty"), "{error}");
    assert_eq!(h.state().scene.path, scene);
}

/// On a classroom laptop's screen, in Chinese, each finding id in the students' list stays whole
/// (the list breaks between ids, never inside one).
#[test]
fn finding_ids_stay_whole_in_the_students_list_on_a_small_screen() {
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let class = scratch.path().join("class-2026");
    student(&class, "alice", "phongFragment_divided_by_blockers.glsl");
    student(&class, "bob_with_a_long_name", "phongFragment_light_size_world.glsl");
    let mut h = harness_at([1366.0, 768.0], Lang::En);
    open(&mut h, &class);
    settle_class(&mut h);
    h.state_mut().lang = Lang::Zh;
    h.run_steps(3);
    let ids: Vec<String> = h
        .state()
        .class
        .as_ref()
        .expect("the class")
        .rows
        .iter()
        .flat_map(|r| r.report.iter().flat_map(|report| report.findings.iter().map(|f| f.id.clone())))
        .collect();
    assert!(ids.len() >= 4, "two findings each: {ids:?}");
    let row_height = h.get_all_by_label("alice").map(|n| n.rect().height()).fold(f32::INFINITY, f32::min);
    for id in &ids {
        for label in h.get_all_by_label(id) {
            let rect = label.rect();
            assert!(rect.height() < 1.5 * row_height, "{id} wraps: {rect:?} (a row is {row_height})");
        }
    }
}

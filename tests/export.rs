//! `shadowlab export` run as a process: the files it writes, their sizes, the two languages,
//! determinism, and the checks that stop it before anything is written.

mod common;

use common::Run;
use shadowlab::export::slide::SlideLayout;
use shadowlab::lessons;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;
use tempfile::TempDir;

const LESSON: &str = "hard-shadows";

fn shadowlab(args: &[&str]) -> Run {
    common::run(common::shadowlab_command().args(args))
}

/// Export `LESSON` in `lang` at `size` into a new temporary folder.
fn export(lang: &str, size: &str) -> (TempDir, PathBuf) {
    let tmp = tempfile::tempdir().expect("temporary folder");
    let out = tmp.path().join("slides");
    let out_arg = out.display().to_string();
    let run = shadowlab(&["export", "--lesson", LESSON, "--lang", lang, "--size", size, "--out", &out_arg]);
    assert_eq!(run.code, Some(0), "export failed:\n{run}");
    assert!(run.stdout.contains("index.html"), "the summary names the index:\n{run}");
    assert!(run.stderr.contains(&format!("[1/{}] {LESSON} step 1/", steps())), "progress on stderr:\n{run}");
    assert!(!run.stderr.contains("was shortened"), "every title, caption and probe value fits:\n{run}");
    (tmp, out)
}

/// The English export at 960x540, shared by the tests that only read it.
fn english() -> &'static Path {
    static EN: OnceLock<(TempDir, PathBuf)> = OnceLock::new();
    &EN.get_or_init(|| export("en", "960x540")).1
}

fn steps() -> usize {
    let all = lessons::load_all(&lessons::default_dir()).expect("the shipped lessons load");
    lessons::find(&all, LESSON).expect("the lesson exists").steps.len()
}

/// Every file under `dir`, as relative paths with `/`.
fn files(dir: &Path) -> BTreeSet<String> {
    fn walk(root: &Path, dir: &Path, out: &mut BTreeSet<String>) {
        for entry in std::fs::read_dir(dir).expect("read folder") {
            let path = entry.expect("entry").path();
            if path.is_dir() {
                walk(root, &path, out);
            } else {
                let rel = path.strip_prefix(root).expect("inside root");
                out.insert(
                    rel.components().map(|c| c.as_os_str().to_string_lossy()).collect::<Vec<_>>().join("/"),
                );
            }
        }
    }
    let mut out = BTreeSet::new();
    walk(dir, dir, &mut out);
    out
}

fn slide_names(n: usize) -> Vec<String> {
    (1..=n).map(|i| format!("{LESSON}/step-{i:02}-slide.png")).collect()
}

fn decode(path: &Path) -> image::RgbaImage {
    image::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display())).to_rgba8()
}

#[test]
fn one_lesson_gives_four_pngs_per_step_and_an_index() {
    let out = english();
    let n = steps();
    let mut expected: BTreeSet<String> = ["index.html".to_string()].into();
    for i in 1..=n {
        for what in ["camera", "shadow-map", "diagram", "slide"] {
            expected.insert(format!("{LESSON}/step-{i:02}-{what}.png"));
        }
    }
    assert_eq!(files(out), expected);

    let layout = SlideLayout::new(960, 540);
    for i in 1..=n {
        let size = |what: &str| {
            let img = decode(&out.join(format!("{LESSON}/step-{i:02}-{what}.png")));
            (img.width(), img.height())
        };
        assert_eq!(size("slide"), (960, 540));
        assert_eq!(size("camera"), (layout.camera.w, layout.camera.h));
        assert_eq!(size("shadow-map"), (layout.shadow_map.w, layout.shadow_map.h));
        assert_eq!(size("diagram"), (layout.diagram.w, layout.diagram.h));
    }
}

#[test]
fn the_index_shows_every_slide_in_order() {
    let html = std::fs::read_to_string(english().join("index.html")).expect("index.html");
    assert!(html.contains("<html lang=\"en\">"));
    let mut last = 0;
    for name in slide_names(steps()) {
        let at = html.find(&format!("src=\"{name}\"")).unwrap_or_else(|| panic!("index lacks {name}"));
        assert!(at > last, "{name} out of order");
        last = at;
    }
    for what in ["camera", "shadow-map", "diagram"] {
        assert!(html.contains(&format!("href=\"{LESSON}/step-01-{what}.png\"")));
    }
    assert!(html.contains("ArrowRight"), "keyboard navigation");
}

#[test]
fn chinese_slides_differ_from_english_ones() {
    let (_tmp, zh) = export("zh", "960x540");
    let html = std::fs::read_to_string(zh.join("index.html")).expect("index.html");
    assert!(html.contains("lang=\"zh-Hans\""));
    for name in slide_names(steps()) {
        let (a, b) = (decode(&english().join(&name)), decode(&zh.join(&name)));
        assert_eq!(a.dimensions(), b.dimensions());
        let differing = a.pixels().zip(b.pixels()).filter(|(p, q)| p != q).count();
        assert!(differing > 1000, "{name}: only {differing} pixels differ between en and zh");
    }
    // The diagrams are drawn in Chinese, on their own and on the slide.
    let d = SlideLayout::new(960, 540).diagram;
    for i in 1..=steps() {
        let name = format!("{LESSON}/step-{i:02}-diagram.png");
        let (a, b) = (decode(&english().join(&name)), decode(&zh.join(&name)));
        let differing = a.pixels().zip(b.pixels()).filter(|(p, q)| p != q).count();
        assert!(differing > 500, "{name}: only {differing} pixels differ between en and zh");
        let slide = format!("{LESSON}/step-{i:02}-slide.png");
        let (a, b) = (decode(&english().join(&slide)), decode(&zh.join(&slide)));
        let region =
            |img: &image::RgbaImage| image::imageops::crop_imm(img, d.x, d.y, d.w, d.h).to_image().into_raw();
        assert_ne!(region(&a), region(&b), "{slide}: the diagram on the slide is not translated");
    }
    // The pictures themselves do not depend on the language.
    let camera = format!("{LESSON}/step-01-camera.png");
    assert_eq!(std::fs::read(english().join(&camera)).ok(), std::fs::read(zh.join(&camera)).ok());
}

/// A slide's probe panel names the surface in the slide's language (the scene's `name_zh`), and
/// its caption names the view as the Chinese app's view menu does.
#[test]
fn slides_name_the_probed_surface_and_the_view_in_the_slides_language() {
    use shadowlab::i18n::Lang;
    use shadowlab::views::View;
    let all = lessons::load_all(&lessons::default_dir()).expect("the shipped lessons load");
    let lesson = lessons::find(&all, LESSON).expect("the lesson exists");
    // Step 2 probes the floor behind the big bunny.
    let scene = lesson.steps[1].scene().expect("the step's scene");
    let (_ctx, mut renderer) = common::gpu();
    for (lang, surface) in [(Lang::En, "floor"), (Lang::Zh, "地面")] {
        let pictures =
            shadowlab::export::step::render_step(&mut renderer, lesson, 1, &scene, (320, 180), lang)
                .expect("the step renders");
        assert_eq!(pictures.probe_object.as_deref(), Some(surface), "{lang:?}");
    }
    use shadowlab::export::slide::view_label;
    for view in View::ALL {
        assert_eq!(view_label(view, Lang::Zh), view.label(Lang::Zh));
    }
    assert_eq!(view_label(View::Final, Lang::En), "shaded", "English captions keep their own words");
}

#[test]
fn exporting_twice_gives_identical_files() {
    let (_a, first) = export("en", "640x360");
    let (_b, second) = export("en", "640x360");
    let names = files(&first);
    assert_eq!(names, files(&second));
    for name in &names {
        let (x, y) = (std::fs::read(first.join(name)), std::fs::read(second.join(name)));
        assert!(x.expect("read") == y.expect("read"), "{name} differs between two exports");
    }
}

/// Exit code 2 with one `shadowlab: ` line mentioning every needle, nothing on stdout.
#[track_caller]
fn assert_bad_input(run: &Run, needles: &[&str]) {
    assert_eq!(run.code, Some(2), "bad input exits with 2:\n{run}");
    assert!(!run.stderr.contains("panicked"), "panicked:\n{run}");
    for needle in needles {
        assert!(run.stderr.contains(needle), "stderr should mention {needle:?}:\n{run}");
    }
    assert!(run.stdout.is_empty(), "nothing on stdout:\n{run}");
}

#[test]
fn a_malformed_lesson_stops_everything_before_writing() {
    let tmp = tempfile::tempdir().expect("temporary folder");
    let lessons = tmp.path().join("lessons");
    std::fs::create_dir(&lessons).expect("mkdir");
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/games202.toml");
    let good = format!(
        "id = \"good\"\norder = 1\ntitle = {{ en = \"Good\", zh = \"好\" }}\n\
         summary = {{ en = \"s\", zh = \"s\" }}\n\
         [[step]]\ntitle = {{ en = \"t\", zh = \"t\" }}\ntext = {{ en = \"x\", zh = \"x\" }}\nscene = '{}'\n",
        scene.display()
    );
    std::fs::write(lessons.join("01_good.toml"), good).expect("write");
    // The Chinese title is missing.
    let broken =
        "id = \"broken\"\norder = 2\ntitle = { en = \"Broken\" }\nsummary = { en = \"s\", zh = \"s\" }\n";
    std::fs::write(lessons.join("02_broken.toml"), broken).expect("write");
    let out = tmp.path().join("slides");
    let (dir_arg, out_arg) = (lessons.display().to_string(), out.display().to_string());
    // Even exporting only the good lesson stops: every lesson is checked first.
    let run = shadowlab(&["export", "--lessons-dir", &dir_arg, "--lesson", "good", "--out", &out_arg]);
    assert_bad_input(&run, &["02_broken.toml"]);
    assert_eq!(run.stderr.lines().count(), 1, "one line:\n{run}");
    assert!(!out.exists(), "nothing may be written");
}

#[test]
fn an_unknown_lesson_lists_the_lessons() {
    let tmp = tempfile::tempdir().expect("temporary folder");
    let out = tmp.path().join("slides");
    let run = shadowlab(&["export", "--lesson", "no-such-lesson", "--out", &out.display().to_string()]);
    assert_bad_input(&run, &["no-such-lesson", LESSON]);
    assert!(!out.exists());
}

#[test]
fn an_unknown_language_is_refused() {
    let tmp = tempfile::tempdir().expect("temporary folder");
    let out = tmp.path().join("slides");
    let run = shadowlab(&["export", "--lang", "fr", "--out", &out.display().to_string()]);
    assert_bad_input(&run, &["fr", "--lang"]);
    assert!(!out.exists());
}

#[test]
fn an_output_that_is_a_file_is_refused() {
    let tmp = tempfile::tempdir().expect("temporary folder");
    let out = tmp.path().join("slides");
    std::fs::write(&out, "keep me").expect("write");
    let run = shadowlab(&["export", "--lesson", LESSON, "--out", &out.display().to_string()]);
    assert_bad_input(&run, &["not a folder"]);
    assert_eq!(std::fs::read_to_string(&out).ok().as_deref(), Some("keep me"));
}

#[test]
fn a_slide_too_small_to_read_is_refused() {
    let tmp = tempfile::tempdir().expect("temporary folder");
    let out = tmp.path().join("slides");
    let run = shadowlab(&["export", "--size", "320x180", "--out", &out.display().to_string()]);
    assert_bad_input(&run, &["--size"]);
    assert!(!out.exists());
}

#[test]
fn a_steps_overlays_are_on_its_camera_picture() {
    // Hard-shadows step 4 names the outside-the-frustum tint and the frustum wireframe. Its
    // camera picture carries both, as the app shows them.
    let dir = english().join(LESSON);
    let outside = decode(&dir.join("step-04-camera.png"));
    let frame = |p: &image::Rgba<u8>| {
        let [r, g, b, _] = p.0;
        r > 230 && (180..=220).contains(&g) && b < 110
    };
    let frame_pixels = outside.pixels().filter(|p| frame(p)).count();
    assert!(frame_pixels > 100, "no frustum wireframe on the slide's camera picture ({frame_pixels} pixels)");
    // The orange tint over the floor outside the frustum: warm pixels far from grey.
    let orange =
        outside.pixels().filter(|p| p[0] > p[2].saturating_add(60) && p[1] > p[2].saturating_add(20)).count();
    assert!(orange > 5000, "no outside-the-frustum tint ({orange} orange pixels)");
}

/// The slide of lesson 4's "against the ground truth" step: its text quotes the ground truth at
/// the probe and the mean error of the camera panel the slide shows, in both languages, with no
/// "…" left (the slides render deterministically, so nothing is still being worked out).
#[test]
fn a_slide_fills_the_ground_truth_and_the_mean_error_it_shows() {
    use shadowlab::i18n::Lang;
    use shadowlab::lessons::live;
    let (_ctx, mut renderer) = common::gpu();
    let all = lessons::load_all(&lessons::default_dir()).expect("the shipped lessons load");
    let lesson = lessons::find(&all, "pcss").expect("lesson 4");
    let index =
        lesson.steps.iter().position(|s| s.title.en.starts_with("Against the ground truth")).expect("step");
    let step = &lesson.steps[index];
    let scene = step.scene().expect("the step's scene");
    let layout = SlideLayout::new(960, 540);
    let size = (layout.camera.w, layout.camera.h);
    let pictures = shadowlab::export::step::render_step(&mut renderer, lesson, index, &scene, size, Lang::En)
        .expect("the step renders");
    let report = pictures.probe.as_ref().expect("the probe");
    let truth = report.lights[step.light].visibility_reference.expect("the ground truth at the probe");
    let mae = pictures.frame.mean_abs_error.expect("the error view's mean error");
    // The number the camera panel's legend prints, at the panel's size.
    let summary = pictures.camera_summary.as_deref().unwrap_or_default();
    assert!(summary.contains(&format!("mean absolute error: {mae:.5}")), "{summary}");
    for lang in [Lang::En, Lang::Zh] {
        let text = step.text_filled(lang, pictures.live());
        assert!(!text.contains(live::NO_VALUE), "{lang:?}: {text}");
        assert!(text.contains(&format!("{truth:.2}")), "{lang:?}: no ground truth {truth:.2} in {text}");
        assert!(text.contains(&format!("{mae:.3}")), "{lang:?}: no mean error {mae:.3} in {text}");
    }
    // A probe alone leaves the frame's number pending.
    assert!(step.text_filled(Lang::En, pictures.probe.as_ref()).contains(live::NO_VALUE));
}

#[test]
fn chinese_text_no_font_holds_is_refused_naming_the_characters() {
    let tmp = tempfile::tempdir().expect("temporary folder");
    let lessons = tmp.path().join("lessons");
    std::fs::create_dir(&lessons).expect("mkdir");
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/games202.toml");
    // Tibetan: neither the UI fonts nor a CJK font (system or built in) has it.
    let lesson = format!(
        "id = \"tibetan\"\norder = 1\ntitle = {{ en = \"T\", zh = \"阴影 ཀཁ\" }}\n\
         summary = {{ en = \"s\", zh = \"s\" }}\n\
         [[step]]\ntitle = {{ en = \"t\", zh = \"t\" }}\ntext = {{ en = \"x\", zh = \"x\" }}\nscene = '{}'\n",
        scene.display()
    );
    std::fs::write(lessons.join("01_tibetan.toml"), lesson).expect("write");
    let out = tmp.path().join("slides");
    let (dir_arg, out_arg) = (lessons.display().to_string(), out.display().to_string());
    let run = shadowlab(&["export", "--lessons-dir", &dir_arg, "--lang", "zh", "--out", &out_arg]);
    assert_bad_input(&run, &["ཀཁ", "fonts-noto-cjk"]);
    assert!(!run.stderr.contains('阴'), "only what no font has is named:\n{run}");
    assert!(!out.exists(), "nothing may be written");
}

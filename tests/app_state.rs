//! The app's state driven as the window drives it, without a window, a GPU or threads: what each
//! action (open, step, apply a "Try this", reset, play) leaves the state showing.

use shadowlab::app::{AppState, PLAYBACK_RANGE_S, ProbeAt, Settings, Source, launch};
use shadowlab::i18n::Lang;
use shadowlab::scene::Technique;
use std::path::Path;

fn fresh() -> AppState {
    AppState::new(Settings::default())
}

fn lesson_index(state: &AppState, id: &str) -> usize {
    state.lessons.iter().position(|l| l.id == id).unwrap_or_else(|| panic!("no lesson {id}"))
}

#[test]
fn a_fresh_state_shows_the_default_scene_with_every_lesson_loaded() {
    let state = fresh();
    assert!(state.error.is_none(), "{:?}", state.error);
    assert!(matches!(&state.source, Source::Scene(p) if p.ends_with("games202.toml")), "{:?}", state.source);
    assert!(state.lessons.len() >= 6, "{} lessons", state.lessons.len());
    assert!(state.current_step().is_none());
    assert!(state.dirty, "the first frame is still to be rendered");
}

#[test]
fn a_lesson_step_sets_what_its_file_says() {
    let mut state = fresh();
    let lesson = lesson_index(&state, "hard-shadows");
    state.go_to_step(lesson, 0);
    let (l, step, index) = state.current_step().expect("in a lesson");
    assert_eq!((l.id.as_str(), index), ("hard-shadows", 0));
    let (view, overlays, probe, time_s) = (step.view, step.overlays.clone(), step.probe, step.time_s);
    assert_eq!(state.view, view);
    assert_eq!(state.overlays, overlays);
    assert_eq!(state.probe_at, probe.map(|[x, y]| ProbeAt::LessonFrame(x, y)));
    assert_eq!(state.time_s, time_s);
    assert_eq!(state.scene.shadow.technique, Technique::Hard, "the step's `set` is applied");
    assert_eq!(state.settings.last_lesson, Some(("hard-shadows".to_string(), 0)), "remembered for next time");
    assert!(state.changed_from_step().is_empty(), "{:?}", state.changed_from_step());
}

#[test]
fn try_this_changes_the_settings_and_back_to_the_step_undoes_it() {
    let mut state = fresh();
    let lesson = lesson_index(&state, "hard-shadows");
    state.go_to_step(lesson, 0);
    let before = state.scene.lights[0].shadow_map_size;
    state.apply_try_this(1);
    assert_eq!(state.applied_try_this, Some(1));
    assert_eq!(state.scene.lights[0].shadow_map_size, 256, "was {before}");
    assert_eq!(state.changed_from_step(), vec!["lights"]);
    state.back_to_step_settings();
    assert_eq!(state.scene.lights[0].shadow_map_size, before);
    assert!(state.changed_from_step().is_empty());
    assert_eq!(state.applied_try_this, None);
}

#[test]
fn stepping_walks_every_step_of_every_lesson_and_stops_at_both_ends() {
    let mut state = fresh();
    state.step_lesson(1);
    assert!(matches!(state.source, Source::Lesson { lesson: 0, step: 0 }), "{:?}", state.source);
    let total: usize = state.lessons.iter().map(|l| l.steps.len()).sum();
    let mut seen = 1;
    loop {
        let before = state.source.clone();
        state.step_lesson(1);
        if state.source == before {
            break;
        }
        assert!(state.error.is_none(), "{:?} at {:?}", state.error, state.source);
        seen += 1;
    }
    assert_eq!(seen, total, "every step once");
    for _ in 0..total + 3 {
        state.step_lesson(-1);
    }
    assert!(matches!(state.source, Source::Lesson { lesson: 0, step: 0 }), "{:?}", state.source);
}

#[test]
fn a_bad_file_keeps_the_last_good_scene_and_says_why() {
    let mut state = fresh();
    let good = state.scene.clone();
    let bad = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/scenes/missing_mesh.toml");
    state.open(&bad);
    let error = state.error.clone().expect("an error");
    assert!(error.detail.contains("no_such_mesh.obj"), "names the file it could not read: {error}");
    assert_eq!(state.scene.objects.len(), good.objects.len(), "the last good scene stays");
    assert_eq!(state.scene.path, good.path);
    // A good one clears it.
    state.open(&Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/scenes/minimal.toml"));
    assert!(state.error.is_none(), "{:?}", state.error);
    assert_eq!(state.scenes_opened, 1);
}

#[test]
fn playback_loops_over_the_time_range_and_a_stall_does_not_jump_it() {
    let mut state = fresh();
    let start = PLAYBACK_RANGE_S - 0.1;
    state.time_s = start;
    state.dirty = false;
    state.advance_playback(0.3);
    assert_eq!(state.time_s, start, "paused: nothing moves");
    assert!(!state.dirty);
    state.playing = true;
    state.advance_playback(0.3);
    assert!((state.time_s - 0.2).abs() < 1e-4, "wrapped to {}", state.time_s);
    assert!(state.dirty, "a new frame is due");
    state.advance_playback(30.0);
    assert!((state.time_s - 0.7).abs() < 1e-4, "a 30 s stall moves half a second: {}", state.time_s);
}

#[test]
fn a_launch_opens_the_lesson_step_in_the_language_asked_for() {
    let mut state = fresh();
    let wanted = launch::resolve(None, Some("pcss"), Some(3), Some(Lang::Zh)).expect("resolves");
    state.apply_launch(wanted);
    assert_eq!(state.lang, Lang::Zh);
    let (lesson, _, step) = state.current_step().expect("in a lesson");
    assert_eq!((lesson.id.as_str(), step), ("pcss", 2));
    assert!(launch::resolve(None, Some("pcss"), Some(99), None).is_err(), "no step 99");
}

/// A student's shader opens on the homework scene from the path box, a drop or the command line;
/// an edit on disk is read again (the last version that compiled stays while one does not), and
/// opening a scene closes it.
#[test]
fn a_homework_shader_opens_reloads_on_change_and_keeps_its_last_good_version() {
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let shader = scratch.path().join("phongFragment.glsl");
    let correct = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/homework/phongFragment.glsl"),
    )
    .expect("the example");
    std::fs::write(&shader, &correct).expect("write");
    let launch =
        launch::resolve(Some(&shader.display().to_string()), None, None, None).expect("a shader opens");
    let mut state = fresh();
    state.apply_launch(launch);
    assert!(state.error.is_none(), "{:?}", state.error);
    assert!(
        matches!(&state.source, Source::Scene(p) if p.ends_with("homework_check.toml")),
        "{:?}",
        state.source
    );
    let homework = state.homework.as_ref().expect("the homework is open");
    assert!(homework.error.is_none(), "{:?}", homework.error);
    assert!(homework.program.is_some());
    let first = homework.generation;

    // Nothing changed on disk: nothing read again.
    assert!(!state.reload_homework_if_changed());
    // The student saves a broken version: its error, on their own line; the program stays.
    let broken = correct.replacen("  float depthSum = 0.0;", "  float depthSum = 0.0 +;", 1);
    let line = broken.lines().position(|l| l.contains("0.0 +;")).expect("the line") + 1;
    std::thread::sleep(std::time::Duration::from_millis(20));
    std::fs::write(&shader, &broken).expect("write");
    assert!(state.reload_homework_if_changed());
    let homework = state.homework.as_ref().expect("still open");
    let error = homework.error.as_ref().expect("the error");
    assert_eq!(error.line(), Some(line), "{error}");
    assert!(error.to_string().starts_with(&format!("phongFragment.glsl:{line}: ")), "{error}");
    assert_eq!(homework.generation, first, "the last good program stays");
    assert!(homework.program.is_some());
    // Fixed again: a new program.
    std::thread::sleep(std::time::Duration::from_millis(20));
    std::fs::write(&shader, &correct).expect("write");
    assert!(state.reload_homework_if_changed());
    let homework = state.homework.as_ref().expect("still open");
    assert!(homework.error.is_none());
    assert_eq!(homework.generation, first + 1);
    assert_eq!(homework.reloads, 2);

    // A scene closes it.
    state.open(&Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/contact.toml"));
    assert!(state.homework.is_none());
    // A shader path typed into the path box opens it again.
    state.open_any(&shader);
    assert!(state.homework.is_some());
    // A missing one says so and keeps what is open.
    state.open_any(&scratch.path().join("missing.glsl"));
    assert!(state.homework.is_some());
}

#[test]
fn a_link_opens_its_lesson_step_in_its_language_and_the_address_follows_the_student() {
    use shadowlab::app::link;
    let mut state = fresh();
    state.show_lesson_list = true;
    let (wanted, problems) = link::parse("?lesson=pcss&step=3&lang=zh");
    assert!(problems.is_empty(), "{problems:?}");
    state.follow_link(&wanted, problems);
    assert!(state.error.is_none(), "{:?}", state.error);
    let (lesson, _, step) = state.current_step().expect("in a lesson");
    assert_eq!((lesson.id.as_str(), step), ("pcss", 2));
    assert_eq!(state.lang, Lang::Zh);
    assert!(!state.show_lesson_list, "a link opens its place, not the list");
    assert_eq!(state.link(), "lesson=pcss&step=3&lang=zh");

    // The student walks on and changes the technique: the address says so.
    state.step_lesson(1);
    state.scene.shadow.technique = Technique::Pcf;
    assert_eq!(state.link(), "lesson=pcss&step=4&technique=pcf&lang=zh");
    // A lesson by number, a scene with a technique; each round-trips.
    for query in ["lesson=2&step=1&lang=en", "scene=contact&technique=pcf&lang=en"] {
        let mut other = fresh();
        let (wanted, problems) = link::parse(query);
        other.follow_link(&wanted, problems);
        assert!(other.error.is_none(), "{query}: {:?}", other.error);
        let expected = query.replace("lesson=2", "lesson=bias");
        assert_eq!(other.link(), expected, "{query}");
    }
    let mut scene = fresh();
    let (wanted, _) = link::parse("scene=contact&technique=pcf");
    scene.follow_link(&wanted, Vec::new());
    assert!(matches!(&scene.source, Source::Scene(p) if p.ends_with("contact.toml")), "{:?}", scene.source);
    assert_eq!(scene.scene.shadow.technique, Technique::Pcf);
}

#[test]
fn a_bad_link_says_what_it_could_not_follow_in_one_line_and_applies_the_rest() {
    use shadowlab::app::link;
    let cases: [(&str, &str); 7] = [
        ("lesson=nope", "no lesson `nope`"),
        ("lesson=pcss&step=99", "has steps 1 to"),
        ("scene=../../etc/passwd", "no scene `../../etc/passwd` (scenes: acne, "),
        ("technique=fancy", "no technique `fancy` (techniques: "),
        ("lang=fr", "no language `fr`"),
        ("step=2", "`step` needs a lesson"),
        ("colour=red", "unknown part `colour`"),
    ];
    for (query, said) in cases {
        let mut state = fresh();
        let before = state.scene.clone();
        let (wanted, problems) = link::parse(&format!("?{query}&lang=zh"));
        state.follow_link(&wanted, problems);
        let error = state.error.as_ref().map(|e| e.to_string()).unwrap_or_default();
        assert!(error.contains(said), "{query}: {error}");
        assert!(!error.contains('\n'), "{query}: one line: {error}");
        assert_eq!(state.lang, Lang::Zh, "{query}: the language still applies");
        if !query.starts_with("lesson") {
            assert_eq!(state.scene.objects.len(), before.objects.len(), "{query}: the scene stays");
        }
    }
    // Escapes are read as a browser writes them; the page's backend is kept, not a problem.
    let (wanted, problems) = link::parse("?lesson=multi%2Dlight&backend=webgl2&lang=z%68");
    assert!(problems.is_empty(), "{problems:?}");
    assert_eq!((wanted.lesson.as_deref(), wanted.lang), (Some("multi-light"), Some(Lang::Zh)));
    assert_eq!(link::kept_parts("?lesson=pcss&backend=webgl2"), "&backend=webgl2");
}

#[test]
fn files_handed_over_as_bytes_open_as_a_page_opens_them_and_are_not_remembered() {
    use shadowlab::files::hand_over;
    // A student drops their shader with the light pass's and a stray texture: the camera pass's
    // shader is the one opened.
    let shader =
        std::fs::read(Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/homework/phongFragment.glsl"))
            .expect("the example");
    let dropped = vec![
        hand_over("shadowFragment.glsl", b"void main() {}"),
        hand_over("C:\\Users\\me\\Desktop\\phongFragment.glsl", &shader),
        hand_over("wood.png", &[0u8; 4]),
    ];
    let main = shadowlab::app::main_file(&dropped).expect("one to open");
    assert_eq!(main, Path::new("handed-over/phongFragment.glsl"), "named by the file, not the sender's path");
    let mut state = fresh();
    // A first start offers the lessons; a file dropped on it is what the student chose instead.
    state.show_lesson_list = true;
    state.open_files(&dropped);
    assert!(!state.show_lesson_list, "the lesson list closes");
    let homework = state.homework.as_ref().expect("the homework opened");
    assert_eq!(homework.path, main);
    assert_eq!(homework.shadow_fragment.as_deref(), Some(Path::new("handed-over/shadowFragment.glsl")));
    assert!(homework.error.is_none(), "{:?}", homework.error);
    assert!(homework.program.is_some(), "it compiled from the bytes handed over");
    assert!(state.settings.recent_files.is_empty(), "{:?}", state.settings.recent_files);
    // Nothing to watch: the bytes do not change on a disk.
    assert!(!state.reload_homework_if_changed());

    // A scene handed over opens; a broken one keeps the last good scene and names the file.
    let scene = std::fs::read(Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/contact.toml"))
        .expect("a scene");
    let path = hand_over("my scene.toml", &scene);
    state.open_any(&path);
    assert!(state.error.is_none(), "{:?}", state.error);
    assert_eq!(state.source, Source::Scene(path.clone()));
    assert!(state.settings.last_scene.is_none(), "a handed-over scene is not reopened next time");
    let broken = hand_over("broken.toml", b"[camera\nfov = ");
    state.open_any(&broken);
    let error = state.error.as_ref().map(|e| e.to_string()).unwrap_or_default();
    assert!(error.contains("broken.toml"), "{error}");
    assert_eq!(state.source, Source::Scene(path), "the last good scene stays");
}

//! The shipped lessons: they load, they are complete in both languages, every step renders, and
//! malformed lesson files are rejected with an error naming the file, the line and the key.

mod common;

use shadowlab::lessons::live::{self, Namespace, Verdict};
use shadowlab::lessons::{self, Lang, Lesson, LessonError, Text};
use shadowlab::probe::ProbeReport;
use shadowlab::views::{View, render_view};
use std::collections::HashSet;
use std::path::PathBuf;

/// Size the render test uses; probes are given in a 960x540 frame.
const RENDER_SIZE: (u32, u32) = (160, 90);

fn shipped() -> Vec<Lesson> {
    lessons::load_all(&lessons::default_dir())
        .unwrap_or_else(|e| panic!("the shipped lessons must load: {e}"))
}

fn check_text(text: &Text, what: &str) {
    assert!(!text.en.trim().is_empty(), "{what}: English text is empty");
    assert!(!text.zh.trim().is_empty(), "{what}: Chinese text is empty");
}

#[test]
fn every_lesson_loads_with_unique_ids_and_orders() {
    let lessons = shipped();
    assert_eq!(lessons.len(), 6, "expected 6 lessons, found {}", lessons.len());
    let ids: HashSet<&str> = lessons.iter().map(|l| l.id.as_str()).collect();
    assert_eq!(ids.len(), lessons.len(), "lesson ids must be unique");
    let orders: Vec<u32> = lessons.iter().map(|l| l.order).collect();
    assert_eq!(orders, vec![1, 2, 3, 4, 5, 6], "lessons must be ordered 1..6");
    let expected = ["hard-shadows", "bias", "pcf", "pcss", "multi-light", "vsm"];
    let found: Vec<&str> = lessons.iter().map(|l| l.id.as_str()).collect();
    assert_eq!(found, expected);
}

#[test]
fn every_lesson_has_three_to_eight_steps() {
    // A lesson is one sitting of a class: PCSS, with its three steps and their pitfalls, is the
    // longest.
    for lesson in shipped() {
        let n = lesson.steps.len();
        assert!((3..=8).contains(&n), "{}: {n} steps, expected 3 to 8", lesson.id);
    }
}

#[test]
fn every_text_is_given_in_both_languages() {
    for lesson in shipped() {
        check_text(&lesson.title, &format!("{} title", lesson.id));
        check_text(&lesson.summary, &format!("{} summary", lesson.id));
        for (i, step) in lesson.steps.iter().enumerate() {
            let at = format!("{} step {}", lesson.id, i + 1);
            check_text(&step.title, &format!("{at} title"));
            check_text(&step.text, &format!("{at} text"));
            assert!(
                (1..=2).contains(&step.try_this.len()),
                "{at}: {} try_this prompts, expected 1 or 2",
                step.try_this.len()
            );
            for (j, prompt) in step.try_this.iter().enumerate() {
                check_text(&prompt.text, &format!("{at} try_this {}", j + 1));
            }
        }
    }
}

#[test]
fn every_probe_lies_inside_the_frame() {
    for lesson in shipped() {
        for (i, step) in lesson.steps.iter().enumerate() {
            let [x, y] = step.probe.unwrap_or_else(|| panic!("{} step {}: no probe pixel", lesson.id, i + 1));
            assert!(x < 960 && y < 540, "{} step {}: probe {x},{y} outside 960x540", lesson.id, i + 1);
        }
    }
}

#[test]
fn every_step_scene_loads_and_names_an_existing_light() {
    for lesson in shipped() {
        for (i, step) in lesson.steps.iter().enumerate() {
            let scene = step.scene().unwrap_or_else(|e| panic!("{} step {}: {e}", lesson.id, i + 1));
            assert!(
                step.light < scene.lights.len(),
                "{} step {}: light {} but the scene has {}",
                lesson.id,
                i + 1,
                step.light,
                scene.lights.len()
            );
            assert!(step.time_s.is_finite() && step.time_s >= 0.0, "{} step {}: bad time", lesson.id, i + 1);
        }
    }
}

/// Variance of the luminance, in 8-bit levels squared.
fn luminance_variance(image: &image::RgbaImage) -> f64 {
    let values: Vec<f64> = image
        .pixels()
        .map(|p| 0.2126 * f64::from(p[0]) + 0.7152 * f64::from(p[1]) + 0.0722 * f64::from(p[2]))
        .collect();
    let n = values.len().max(1) as f64;
    let mean = values.iter().sum::<f64>() / n;
    values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n
}

#[test]
fn every_step_renders_its_view_and_a_final_image_that_is_not_blank() {
    let lessons = shipped();
    let (_ctx, mut renderer) = common::gpu();
    for lesson in &lessons {
        for (i, step) in lesson.steps.iter().enumerate() {
            let at = format!("{} step {}", lesson.id, i + 1);
            let scene = step.scene().unwrap_or_else(|e| panic!("{at}: {e}"));
            let (image, _) =
                render_view(&mut renderer, &scene, step.view, step.light, step.time_s, RENDER_SIZE, Lang::En)
                    .unwrap_or_else(|e| panic!("{at}: view {} failed: {e}", step.view.name()));
            assert!(image.width() > 0 && image.height() > 0, "{at}: empty {} image", step.view.name());
            let (final_image, _) = render_view(
                &mut renderer,
                &scene,
                View::Final,
                step.light,
                step.time_s,
                RENDER_SIZE,
                Lang::En,
            )
            .unwrap_or_else(|e| panic!("{at}: final view failed: {e}"));
            assert_eq!(final_image.dimensions(), RENDER_SIZE, "{at}: final image size");
            let variance = luminance_variance(&final_image);
            assert!(variance > 25.0, "{at}: the final image is blank (luminance variance {variance:.2})");
        }
    }
}

// ------------------------------------------------------------------ malformed lessons

fn data_file(name: &str) -> PathBuf {
    common::repo_path(&format!("tests/data/lessons/{name}"))
}

/// 1-based line of the first line containing `needle`.
fn line_of(path: &std::path::Path, needle: &str) -> usize {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    text.lines()
        .position(|l| l.contains(needle))
        .map(|i| i + 1)
        .unwrap_or_else(|| panic!("{}: no line contains {needle:?}", path.display()))
}

/// Load a malformed lesson and return its error message; it must name the file and `line`.
fn error_of(name: &str, line: usize) -> String {
    let path = data_file(name);
    let error: LessonError = match lessons::load_lesson(&path) {
        Ok(_) => panic!("{name}: a malformed lesson was accepted"),
        Err(e) => e,
    };
    let message = error.to_string();
    assert!(message.contains(name), "{name}: the error does not name the file: {message}");
    assert!(
        message.contains(&format!(":{line}:")),
        "{name}: the error does not point at line {line}: {message}"
    );
    message
}

#[test]
fn unknown_key_in_a_step_names_file_line_and_key() {
    let line = line_of(&data_file("unknown_step_key.toml"), "tittle =");
    let message = error_of("unknown_step_key.toml", line);
    assert!(message.contains("tittle"), "{message}");
}

#[test]
fn missing_chinese_text_names_file_line_and_key() {
    let line = line_of(&data_file("missing_zh.toml"), "text = ");
    let message = error_of("missing_zh.toml", line);
    assert!(message.contains("zh"), "{message}");
}

#[test]
fn unknown_diagram_names_file_line_and_id() {
    let line = line_of(&data_file("unknown_diagram.toml"), "diagram = ");
    let message = error_of("unknown_diagram.toml", line);
    assert!(message.contains("two-passes"), "{message}");
    assert!(message.contains("diagram"), "{message}");
}

#[test]
fn unknown_overlay_names_file_line_and_value() {
    let line = line_of(&data_file("unknown_overlay.toml"), "overlays = ");
    let message = error_of("unknown_overlay.toml", line);
    assert!(message.contains("shadow-rays"), "{message}");
}

/// The part of a control's label before its unit: “light width” of “light width (world units)”.
fn short_label(label: &str) -> &str {
    let en = label.split(" (").next().unwrap_or(label);
    en.split('（').next().unwrap_or(en)
}

#[test]
fn try_this_prompts_name_the_apps_controls_and_apply_what_they_say() {
    let mut applied = 0;
    for lesson in shipped() {
        for (i, step) in lesson.steps.iter().enumerate() {
            for (j, prompt) in step.try_this.iter().enumerate() {
                let at = format!("{} step {} try_this {}", lesson.id, i + 1, j + 1);
                let (en, zh) = (&prompt.text.en, &prompt.text.zh);
                // No command-line syntax: the student is in the app.
                for text in [en, zh] {
                    assert!(
                        !text.contains('`') && !text.contains("--"),
                        "{at}: command-line syntax in {text:?}"
                    );
                }
                for (key, value) in &prompt.overrides {
                    let label = shadowlab::ui::control_label(key)
                        .unwrap_or_else(|| panic!("{at}: `{key}` has no control in the app"));
                    let en_name = format!("“{}”", short_label(label));
                    let zh_name = format!("「{}」", short_label(shadowlab::i18n::tr(Lang::Zh, label)));
                    assert!(en.contains(&en_name), "{at}: the English text does not name {en_name}: {en}");
                    assert!(zh.contains(&zh_name), "{at}: the Chinese text does not name {zh_name}: {zh}");
                    let value = value.trim_matches('"');
                    assert!(
                        en.contains(value) && zh.contains(value),
                        "{at}: the text does not say {key} = {value}"
                    );
                }
                if let Some(t) = prompt.time_s {
                    assert!(
                        en.contains("“time”") && zh.contains("「时间」"),
                        "{at}: the time control is not named"
                    );
                    assert!(en.contains(&t.to_string()), "{at}: the text does not say time {t}");
                }
                if let Some(view) = prompt.view {
                    assert!(
                        en.contains(view.name()) && zh.contains(view.name()),
                        "{at}: view {} not named",
                        view.name()
                    );
                }
                // The Apply button's scene loads.
                step.scene_with_try_this(j).unwrap_or_else(|e| panic!("{at}: {e}"));
                applied += usize::from(prompt.applies_anything());
            }
        }
    }
    assert!(applied >= 30, "only {applied} prompts have an Apply button");
}

#[test]
fn a_bad_key_in_a_try_this_prompt_names_file_line_and_key() {
    let line = line_of(&data_file("bad_try_this_key.toml"), "radius_texel");
    let message = error_of("bad_try_this_key.toml", line);
    assert!(message.contains("radius_texel"), "{message}");
    assert!(message.contains("try_this 1"), "{message}");
}

#[test]
fn bad_override_key_names_file_line_and_key() {
    let line = line_of(&data_file("bad_set_key.toml"), "set = ");
    let message = error_of("bad_set_key.toml", line);
    assert!(message.contains("techniqe"), "{message}");
}

#[test]
fn missing_scene_file_names_file_line_and_scene() {
    let line = line_of(&data_file("missing_scene.toml"), "scene = ");
    let message = error_of("missing_scene.toml", line);
    assert!(message.contains("no_such_scene.toml"), "{message}");
}

#[test]
fn probe_outside_the_frame_names_file_line_and_probe() {
    // `probe` carries no span of its own, so the error points at the step it belongs to.
    let line = line_of(&data_file("probe_outside.toml"), "[[step]]");
    let message = error_of("probe_outside.toml", line);
    assert!(message.contains("probe 960,100"), "{message}");
}

#[test]
fn malformed_lessons_are_not_picked_up_with_the_shipped_ones() {
    let error = lessons::load_all(&common::repo_path("tests/data/lessons"))
        .err()
        .unwrap_or_else(|| panic!("loading the malformed lessons as a folder must fail"));
    assert!(error.to_string().contains("tests/data/lessons"), "{error}");
}

#[test]
fn unknown_probe_placeholder_names_file_line_and_placeholder() {
    // Text carries no span of its own either: the error points at the step.
    let line = line_of(&data_file("unknown_placeholder.toml"), "[[step]]");
    let message = error_of("unknown_placeholder.toml", line);
    assert!(message.contains("{probe.receiver_distance:.2}"), "{message}");
    assert!(message.contains("receiver_depth_world"), "the error lists the names there are: {message}");
}

/// `shadowlab probe --lesson ID --step N`, parsed: the lesson's own frame, with the ground truth
/// where `with_reference`.
fn cli_probe(lesson: &str, step: usize, with_reference: bool) -> ProbeReport {
    let mut command = std::process::Command::new(env!("CARGO_BIN_EXE_shadowlab"));
    command.args(["probe", "--lesson", lesson, "--step", &step.to_string()]);
    if !with_reference {
        command.arg("--no-reference");
    }
    let output = command.env("XDG_RUNTIME_DIR", std::env::temp_dir()).output().expect("run shadowlab probe");
    let what = format!("{lesson} step {step}");
    assert!(output.status.success(), "{what}: {}", String::from_utf8_lossy(&output.stderr));
    serde_json::from_slice(&output.stdout).unwrap_or_else(|e| panic!("{what}: probe JSON: {e}"))
}

/// What `shadowlab render --lesson ID --step N` says of the step's view in the lesson's own
/// frame: its mean absolute error against the ground truth, where the view gives one.
fn cli_frame_values(lesson: &str, step: usize) -> live::FrameValues {
    let dir = tempfile::tempdir().expect("temporary folder");
    let out = dir.path().join("view.png");
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_shadowlab"))
        .args(["render", "--lesson", lesson, "--step", &step.to_string(), "--out"])
        .arg(&out)
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .output()
        .expect("run shadowlab render");
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success(), "{lesson} step {step}: {}", String::from_utf8_lossy(&output.stderr));
    let mean_abs_error = stdout
        .lines()
        .find_map(|l| l.strip_prefix("mean absolute error:"))
        .map(|v| v.trim().parse().unwrap_or_else(|e| panic!("{lesson} step {step}: {v:?}: {e}")));
    live::FrameValues { mean_abs_error }
}

#[test]
fn every_claimed_verdict_and_quoted_number_holds_at_the_cli_probe() {
    // `shadowlab probe --lesson ID --step N` (the lesson's own frame) must find what the text says,
    // and `shadowlab render` must give every frame number the text quotes.
    for lesson in shipped() {
        for (i, step) in lesson.steps.iter().enumerate() {
            let quotes = step.texts().any(|t| t.contains("{probe."));
            let quotes_frame = step.texts().any(|t| t.contains("{frame."));
            if step.expect.is_none() && !quotes && !quotes_frame {
                continue;
            }
            let what = format!("{} step {}", lesson.id, i + 1);
            let with_reference = step.quotes(Namespace::Probe, "visibility_reference");
            let report = cli_probe(&lesson.id, i + 1, with_reference);
            assert!(report.hit, "{what}: the lesson's probe finds no surface");
            if let Some(expected) = step.expect {
                let visibility = report.lights[step.light].visibility_gpu;
                assert_eq!(Verdict::of(visibility), expected, "{what}: visibility {visibility}");
            }
            let frame = if quotes_frame { cli_frame_values(&lesson.id, i + 1) } else { Default::default() };
            let sources = live::Sources { probe: Some(&report), frame };
            // Every quoted number has a value there (no "…" on a slide or in the app), and each
            // is the report's value as rounded in the text.
            for lang in [Lang::En, Lang::Zh] {
                let texts = [&step.text].into_iter().chain(step.try_this.iter().map(|t| &t.text));
                for text in texts.map(|t| t.get(lang)) {
                    let (filled_text, filled) = live::fill(text, sources, step.light, lang);
                    for f in &filled {
                        assert_ne!(
                            f.text,
                            live::NO_VALUE,
                            "{what} ({lang:?}): {} has no value",
                            f.placeholder.name
                        );
                        assert!(filled_text.contains(&f.text));
                    }
                }
            }
        }
    }
}

#[test]
fn the_steps_that_quote_the_ground_truth_ask_for_it_on_their_own_light() {
    let lessons = shipped();
    let pcss = lessons::find(&lessons, "pcss").expect("the PCSS lesson");
    let quoting: Vec<usize> = (0..pcss.steps.len())
        .filter(|&i| pcss.steps[i].quotes(Namespace::Probe, "visibility_reference"))
        .map(|i| i + 1)
        .collect();
    assert_eq!(quoting, [2, 4, 5, 8], "the PCSS steps that quote the ground truth");
    for i in quoting {
        assert_eq!(pcss.steps[i - 1].quoted_lights("visibility_reference"), [pcss.steps[i - 1].light]);
    }
    assert!(pcss.steps[7].quotes(Namespace::Frame, "mean_abs_error"));
    assert!(!pcss.steps[0].quotes(Namespace::Probe, "visibility_reference"));
    assert_eq!(pcss.steps[0].quoted_lights("visibility_reference"), Vec::<usize>::new());
}

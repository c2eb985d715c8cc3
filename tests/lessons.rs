//! The shipped lessons: they load, they are complete in both languages, every step renders, and
//! malformed lesson files are rejected with an error naming the file, the line and the key.

mod common;

use shadowlab::i18n::Lang;
use shadowlab::lessons::live::{self, Namespace, Verdict};
use shadowlab::lessons::{self, Lesson, LessonError, Text};
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

/// The lesson files in lessons/, sorted by name: what ships (src/built_in/list.rs), `.toml`.
fn shipped_lesson_files() -> Vec<PathBuf> {
    let dir = lessons::default_dir();
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|entry| entry.expect("a folder entry").path())
        .filter(|p| p.is_file() && p.extension().is_some_and(|e| e == "toml"))
        .filter(|p| p.file_name().is_some_and(|n| shadowlab::built_in::ships(&n.to_string_lossy())))
        .collect();
    paths.sort();
    paths
}

#[test]
fn every_lesson_file_loads_with_a_unique_id_in_the_order_of_the_file_names() {
    let files = shipped_lesson_files();
    assert!(!files.is_empty(), "no lessons in {}", lessons::default_dir().display());
    for file in &files {
        lessons::load_lesson(file).unwrap_or_else(|e| panic!("{e}"));
    }
    let lessons = shipped();
    let loaded: Vec<&std::path::Path> = lessons.iter().map(|l| l.path.as_path()).collect();
    assert_eq!(loaded.len(), files.len(), "every file is a lesson: {loaded:?}");
    let ids: HashSet<&str> = lessons.iter().map(|l| l.id.as_str()).collect();
    assert_eq!(ids.len(), lessons.len(), "lesson ids must be unique");
    // `--lesson N` and the lesson picker count from 1 in `order`; the folder lists them so too.
    let orders: Vec<u32> = lessons.iter().map(|l| l.order).collect();
    let expected: Vec<u32> = (1..=lessons.len() as u32).collect();
    assert_eq!(orders, expected, "lessons must be ordered 1..={}", lessons.len());
    let by_name: Vec<&std::path::Path> = files.iter().map(|p| p.as_path()).collect();
    assert_eq!(loaded, by_name, "the file names sort as the lessons' `order` does");
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

#[cfg(unix)]
#[test]
fn a_lesson_path_that_is_not_a_regular_file_is_refused_at_once() {
    // /dev/zero never ends: reading it whole hung until the memory ran out.
    let message = lessons::load_lesson(std::path::Path::new("/dev/zero")).expect_err("a device").to_string();
    assert!(message.starts_with("/dev/zero: ") && message.contains("not a regular file"), "{message}");
    assert_eq!(message.lines().count(), 1, "{message}");
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
                for o in &prompt.overrides {
                    let (key, value) = (&o.key, o.value_text());
                    let label = shadowlab::ui::control_label(key)
                        .unwrap_or_else(|| panic!("{at}: `{key}` has no control in the app"));
                    let en_name = format!("“{}”", short_label(label));
                    let zh_name = format!("「{}」", short_label(shadowlab::i18n::tr(Lang::Zh, label)));
                    assert!(en.contains(&en_name), "{at}: the English text does not name {en_name}: {en}");
                    assert!(zh.contains(&zh_name), "{at}: the Chinese text does not name {zh_name}: {zh}");
                    let value = value.as_str();
                    // A value the inspector shows by a label (a technique, kernel...) is named by
                    // the label the student sees in the combo box.
                    let zh_value = shadowlab::ui::value_label(key, value, Lang::Zh);
                    let zh_value =
                        if zh_value == value { value.to_string() } else { format!("「{zh_value}」") };
                    assert!(
                        en.contains(value) && zh.contains(&zh_value),
                        "{at}: the text does not say {key} = {value} ({zh_value})"
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
                    let zh_view = format!("「{}」", view.label(Lang::Zh));
                    assert!(
                        en.contains(view.name()) && zh.contains(&zh_view),
                        "{at}: view {} not named (in Chinese {zh_view})",
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

/// Chinese text names a view, technique, bias mode, kernel or depth storage by the label the
/// app shows for it (「着色画面」视图), not by its file name (「final」), which the Chinese app
/// never shows.
#[test]
fn chinese_text_names_views_and_settings_as_the_chinese_app_shows_them() {
    use shadowlab::scene::{BiasMode, DepthStorage, Kernel, Technique};
    let names: Vec<&str> = shadowlab::views::View::ALL
        .iter()
        .map(|v| v.name())
        .chain(Technique::ALL.iter().map(|t| t.name()))
        .chain(BiasMode::ALL.iter().map(|b| b.name()))
        .chain(Kernel::ALL.iter().map(|k| k.name()))
        .chain(DepthStorage::ALL.iter().map(|d| d.name()))
        .collect();
    for lesson in shipped() {
        let steps = lesson.steps.iter().enumerate();
        let texts = steps.flat_map(|(i, s)| {
            let tries = s.try_this.iter().map(move |t| (format!("step {} try_this", i + 1), &t.text.zh));
            [(format!("step {}", i + 1), &s.text.zh)].into_iter().chain(tries)
        });
        for (at, zh) in texts {
            for name in &names {
                for quoted in [format!("「{name}」"), format!("\"{name}\""), format!("“{name}”")] {
                    assert!(!zh.contains(&quoted), "{} {at}: {quoted} in Chinese: {zh}", lesson.id);
                }
            }
        }
    }
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
fn a_step_that_plays_cannot_state_what_its_probe_shows() {
    // The picture moves on from `time`, so a claim about that moment is soon false.
    let line = line_of(&data_file("playing_probe.toml"), "[[step]]");
    let message = error_of("playing_probe.toml", line);
    assert!(message.contains("play = true"), "{message}");
}

#[test]
fn no_shipped_step_plays_by_itself_while_its_text_describes_one_moment() {
    for lesson in lessons::load_all(&common::repo_path("lessons")).expect("lessons") {
        for (i, step) in lesson.steps.iter().enumerate() {
            if step.play {
                // Said in the text, so the class knows the picture will move.
                let says_so = step.text.en.contains("playing") && step.text.zh.contains("播放");
                assert!(says_so, "{} step {}: plays without saying so", lesson.id, i + 1);
                assert!(step.probe.is_none(), "{} step {}: plays with a probe", lesson.id, i + 1);
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

// ------------------------------------------------------------------ fixed figures

/// A decimal number written in digits in a step's text (outside its placeholders), and the
/// sentence it stands in.
struct Fixed {
    number: String,
    sentence: String,
}

/// The decimal numbers of `text` (`0.27`, `-0.0018`, `4.15`; not `N.L`, `0..1` or `256²`),
/// placeholders left out, each with its sentence (ended by `. `, `; `, `。` or `；`).
fn fixed_decimals(text: &str) -> Vec<Fixed> {
    let mut plain = String::new();
    let mut at = 0;
    for p in live::placeholders(text).expect("the loader checked them") {
        plain.push_str(&text[at..p.span.start]);
        plain.push_str("{}");
        at = p.span.end;
    }
    plain.push_str(&text[at..]);
    let mut sentences = vec![String::new()];
    let chars: Vec<char> = plain.chars().collect();
    for (i, &c) in chars.iter().enumerate() {
        sentences.last_mut().expect("one").push(c);
        let next = chars.get(i + 1).copied();
        let ends =
            matches!(c, '。' | '；') || (matches!(c, '.' | ';') && next.is_none_or(char::is_whitespace));
        if ends {
            sentences.push(String::new());
        }
    }
    let mut out = Vec::new();
    for sentence in sentences {
        let chars: Vec<char> = sentence.chars().collect();
        let mut i = 0;
        while i < chars.len() {
            let starts = chars[i].is_ascii_digit()
                && (i == 0 || !(chars[i - 1].is_alphanumeric() || matches!(chars[i - 1], '.' | '_')));
            if !starts {
                i += 1;
                continue;
            }
            let mut j = i;
            while j < chars.len() && chars[j].is_ascii_digit() {
                j += 1;
            }
            let decimal = j + 1 < chars.len() && chars[j] == '.' && chars[j + 1].is_ascii_digit();
            if !decimal {
                i = j;
                continue;
            }
            j += 1;
            while j < chars.len() && chars[j].is_ascii_digit() {
                j += 1;
            }
            // A version or a path (1.2.3, 0.5.x) is not a number.
            let version = |j: usize| chars[j] == '.' && chars.get(j + 1).is_some_and(char::is_ascii_digit);
            let ends_clean =
                j == chars.len() || !(chars[j].is_alphanumeric() || chars[j] == '_' || version(j));
            let negative = i >= 1 && chars[i - 1] == '-' && (i == 1 || !chars[i - 2].is_alphanumeric());
            if ends_clean {
                let start = if negative { i - 1 } else { i };
                out.push(Fixed {
                    number: chars[start..j].iter().collect(),
                    sentence: sentence.trim().to_string(),
                });
            }
            i = j;
        }
    }
    out
}

/// The sentence says what the probe, the ground truth or the mean error is.
fn names_a_measured_value(sentence: &str) -> bool {
    let lower = sentence.to_lowercase();
    ["probe", "ground truth", "truth", "reference", "mean error", "mean absolute error"]
        .iter()
        .any(|k| lower.contains(k))
        || ["探针", "真实", "真值", "平均绝对误差", "平均误差"].iter().any(|k| sentence.contains(k))
}

/// Every number in `text` (integers too, exponents kept).
fn numbers_in(text: &str) -> Vec<f64> {
    text.split(|c: char| !(c.is_ascii_digit() || matches!(c, '.' | '-' | 'e')))
        .filter_map(|w| w.trim_matches(|c| c == '.' || c == 'e').parse().ok())
        .collect()
}

/// Constants a step's text may write down, each with the arithmetic or the reason that gives
/// it, where the scene and the step's settings do not hold it as it is: (lesson, step, value,
/// why). Add to it only what no probe or frame computes.
const DERIVED: &[(&str, usize, f64, &str)] = &[
    ("bias", 1, 80.0 / 1024.0, "a texel of the 80-unit frustum on a 1024² map"),
    ("bias", 1, 0.4, "the depth that texel spans on the floor, 0.078 / tan(11°)"),
    ("bias", 5, 80.0 / 2048.0, "A, half a texel of the 80-unit frustum on a 2048² map"),
    ("bias", 5, 1.5 * 4.0 * 80.0 / 2048.0, "c * A with c = 1.5 and the radius's factor 4"),
    ("pcf", 2, 2.0 / 512.0 * 120.0, "2 texels of the 120-unit frustum on a 512² map"),
    ("pcf", 5, 0.25, "1 of 4 taps lit"),
    ("pcf", 5, 0.75, "3 of 4 taps lit"),
    ("pcss", 5, 28.0, "W_near = 2 * 20 * tan(35°), the spot light's near-plane width"),
    ("more-maps", 4, 220.0 / 1024.0, "a texel of the 220-unit square (extent 110) on a 1024² map"),
];

/// Numbers any text may write: a half, and the ends of 0..1 (in formulas and code).
const UNIVERSAL: [f64; 3] = [0.0, 0.5, 1.0];

/// The numbers the step documents: its scene's (the file, and the scene as loaded with the
/// step's settings, defaults included), the values its own `set` and its prompts' `set` give,
/// and its entries in [`DERIVED`].
fn documented_constants(lesson: &Lesson, index: usize) -> Vec<f64> {
    let step = &lesson.steps[index];
    let mut out = UNIVERSAL.to_vec();
    fn walk(value: &toml::Value, out: &mut Vec<f64>) {
        match value {
            toml::Value::Integer(i) => out.push(*i as f64),
            toml::Value::Float(f) => out.push(*f),
            toml::Value::Array(items) => items.iter().for_each(|v| walk(v, out)),
            toml::Value::Table(table) => table.values().for_each(|v| walk(v, out)),
            _ => {}
        }
    }
    let file = std::fs::read_to_string(&step.scene_path).expect("the scene file");
    walk(&file.parse::<toml::Table>().expect("scene TOML").into(), &mut out);
    let scene = step.scene().expect("the step's scene");
    out.extend(numbers_in(&format!("{:?} {:?} {:?}", scene.shadow, scene.lights, scene.camera)));
    let prompts = step.try_this.iter().flat_map(|t| &t.overrides);
    for o in step.overrides.iter().chain(prompts) {
        out.extend(numbers_in(&o.value_text()));
    }
    out.extend(DERIVED.iter().filter(|d| d.0 == lesson.id && d.1 == index + 1).map(|d| d.2));
    out
}

/// `number` as written is `value` rounded to as many decimals.
fn shows(number: &str, value: f64) -> bool {
    let decimals = number.split_once('.').map_or(0, |(_, d)| d.len());
    format!("{value:.decimals$}") == number
        || (value == 0.0 && number.trim_start_matches('-') == format!("{value:.decimals$}"))
}

/// Significant digits of a number as written: 2 for 0.27 and -0.0018, 3 for 4.15, 1 for 0.004.
fn significant_digits(number: &str) -> usize {
    number.trim_start_matches(['-', '0', '.']).chars().filter(char::is_ascii_digit).count()
}

/// Every value a placeholder could quote from `report`, for each light, at full precision.
fn probe_values(report: &ProbeReport) -> Vec<(String, f64)> {
    let mut out = Vec::new();
    for l in &report.lights {
        for name in live::probe_names() {
            let text = format!("{{probe.light{}.{name}:.6}}", l.light);
            if let (_, filled) = live::fill(&text, Some(report), l.light, Lang::En)
                && let Some(value) = filled[0].value
            {
                out.push((format!("light {} {name}", l.light), value));
            }
        }
    }
    out
}

/// The check that would have caught "against the ground truth's 0.27", "about 0.008" and
/// "ground truth is 0.53": a figure the probe or the frame computes, written into the text at
/// the settings it was read with, goes stale the moment a student moves a slider (or the
/// renderer changes), while a placeholder follows. Over every step of every lesson, English
/// and Chinese, explanation and prompts:
///
/// 1. In a sentence that names the probe, the ground truth (truth, reference) or the mean
///    error, every fixed decimal number must be one of the step's documented constants (its
///    scene and settings, the values its prompts set, a half, 0 and 1, or an entry of
///    [`DERIVED`] with its arithmetic).
/// 2. Anywhere in the text, a fixed decimal number of two significant digits or more that
///    equals, rounded as written, a value the CLI probe reports at the step (any quantity a
///    placeholder can name, any light) and is not a documented constant is a probe value written
///    down. (A one-digit figure, 0.2 or 0.004, matches some probe value by chance too often to
///    tell; rule 1 still holds it.)
///
/// What it cannot see: numbers written in words ("about sixfold"); integers (tap counts, texel
/// sizes, bench timings in ms); figures read off a heatmap's or the shadow map's colour bar, or
/// any other frame number no placeholder reads (rule 2 compares with the probe only; such a
/// figure is caught only in a sentence of rule 1); outcomes a prompt promises after its change
/// (they are read at other settings than the step's probe) unless the sentence names the probe;
/// a stale figure in a sentence that names none of the above and matches no probe value; and
/// whether the arithmetic behind a [`DERIVED`] entry is right.
#[test]
fn no_fixed_figure_stands_where_the_probe_or_the_frame_computes_one() {
    let mut found = Vec::new();
    for lesson in shipped() {
        for (i, step) in lesson.steps.iter().enumerate() {
            let at = format!("{} step {}", lesson.id, i + 1);
            let constants = documented_constants(&lesson, i);
            let documented = |number: &str| constants.iter().any(|&c| shows(number, c) || shows(number, -c));
            let probe = step.probe.map(|_| probe_values(&cli_probe(&lesson.id, i + 1, false)));
            for text in step.texts() {
                for fixed in fixed_decimals(text) {
                    if documented(&fixed.number) {
                        continue;
                    }
                    if names_a_measured_value(&fixed.sentence) {
                        found.push(format!(
                            "{at}: {} is fixed in a sentence about the probe, the ground truth or the mean \
                             error (quote it with a placeholder, or document the constant in DERIVED): {}",
                            fixed.number, fixed.sentence
                        ));
                        continue;
                    }
                    if significant_digits(&fixed.number) < 2 {
                        continue;
                    }
                    let same = probe.iter().flatten().find(|(_, v)| shows(&fixed.number, *v));
                    if let Some((name, value)) = same {
                        found.push(format!(
                            "{at}: {} is what the probe gives for {name} ({value}): quote it live: {}",
                            fixed.number, fixed.sentence
                        ));
                    }
                }
            }
        }
    }
    assert!(found.is_empty(), "fixed figures where the text should quote live values:\n{}", found.join("\n"));
}

#[test]
fn fixed_decimals_are_found_with_their_sentences() {
    let text = "The probe reads {probe.visibility:.2} against 0.27; N.L is 0.19 over 0..1. \
                Off by -0.0018 NDC, 256² texels, v1.2.3 and x_0.5 are not numbers. 真实值是 0.48。下一句 3.5";
    let found: Vec<(String, String)> =
        fixed_decimals(text).into_iter().map(|f| (f.number, f.sentence)).collect();
    let numbers: Vec<&str> = found.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(numbers, ["0.27", "0.19", "-0.0018", "0.48", "3.5"]);
    assert_eq!(found[0].1, "The probe reads {} against 0.27;");
    assert!(names_a_measured_value(&found[0].1));
    assert!(!names_a_measured_value(&found[1].1), "{}", found[1].1);
    assert!(names_a_measured_value(&found[3].1) && !names_a_measured_value(&found[4].1));
    assert!(shows("0.27", 0.26953125) && shows("-0.0018", -0.00181) && !shows("0.27", 0.275_01));
    let digits: Vec<usize> =
        ["0.27", "-0.0018", "4.15", "0.004", "28.0", "0.50"].map(significant_digits).into();
    assert_eq!(digits, [2, 2, 3, 1, 3, 2]);
}

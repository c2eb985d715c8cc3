//! `shadowlab homework --class` as a TA runs it: the binary as a process over a class made here
//! from the project's own examples (a folder, a zip, a shader that does not compile, a hostile
//! zip), then again (what is done is skipped), with --force, after one student's file changed;
//! a check that takes too long stopped at --timeout; bad input refused with nothing written.

mod common;
#[path = "../src/homework/submission/tests/writer.rs"]
#[allow(dead_code)]
mod zip_writer;

use common::{Run, repo_path};
use std::path::{Path, PathBuf};
use std::time::{Duration, SystemTime};

/// Small enough to be quick.
const SIZE: &str = "240x135";
const SHADER_AT: &str = "homework1/src/shaders/phongShader/phongFragment.glsl";

fn shadowlab<S: AsRef<std::ffi::OsStr>>(args: &[S]) -> Run {
    common::run(common::shadowlab_command().args(args))
}

fn example(name: &str) -> String {
    std::fs::read_to_string(repo_path("assets/homework").join(name)).expect("an example shader")
}

/// A zip of `entries` (name, bytes), stored without compression.
fn zip(entries: &[(&str, &[u8])]) -> Vec<u8> {
    let specs: Vec<zip_writer::Spec> =
        entries.iter().map(|(name, data)| zip_writer::spec(name, data)).collect();
    zip_writer::build(&specs)
}

fn student_folder(class: &Path, name: &str, shader: &str) -> PathBuf {
    let file = class.join(name).join(SHADER_AT);
    std::fs::create_dir_all(file.parent().expect("a parent")).expect("the student's folders");
    std::fs::write(&file, shader).expect("the student's shader");
    file
}

/// alice: the correct solution (a folder); bob: findBlocker's 0 / 0 (a zip); carol: a shader
/// that does not compile; dave: a zip with an entry outside itself. A hidden entry is no student.
fn class_of_four(class: &Path) -> PathBuf {
    let alice = student_folder(class, "alice", &example("phongFragment.glsl"));
    let nan = example("phongFragment_nan_blocker.glsl");
    let bob = zip(&[(&format!("bob/{SHADER_AT}"), nan.as_bytes())]);
    std::fs::write(class.join("bob.zip"), bob).expect("bob.zip");
    let broken = example("phongFragment.glsl").replacen("float findBlocker", "floot findBlocker", 1);
    student_folder(class, "carol", &broken);
    std::fs::write(class.join("dave.zip"), zip(&[("../evil.glsl", b"void main() {}")])).expect("dave.zip");
    std::fs::create_dir_all(class.join(".hidden")).expect("a hidden folder");
    alice
}

fn check_class(class: &Path, out: &Path, extra: &[&str]) -> Run {
    let (class, out) = (class.display().to_string(), out.display().to_string());
    let mut args = vec!["homework", "--class", &class, "--out", &out, "--size", SIZE];
    args.extend_from_slice(extra);
    let run = shadowlab(&args);
    assert_eq!(run.code, Some(0), "{run}");
    run
}

/// grades.csv as records of fields (RFC 4180).
fn csv(out: &Path) -> Vec<Vec<String>> {
    let text = std::fs::read_to_string(out.join("grades.csv")).expect("grades.csv");
    let text = text.strip_prefix('\u{feff}').unwrap_or(&text);
    let (mut rows, mut row, mut field, mut quoted) = (Vec::new(), Vec::new(), String::new(), false);
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        match (quoted, c) {
            (true, '"') if chars.peek() == Some(&'"') => {
                chars.next();
                field.push('"');
            }
            (true, '"') => quoted = false,
            (true, c) => field.push(c),
            (false, '"') => quoted = true,
            (false, ',') => row.push(std::mem::take(&mut field)),
            (false, '\r') => {}
            (false, '\n') => {
                row.push(std::mem::take(&mut field));
                rows.push(std::mem::take(&mut row));
            }
            (false, c) => field.push(c),
        }
    }
    rows
}

/// Each student's section of a page: (its heading's text, the pictures it links).
fn sections(html: &str) -> Vec<(String, Vec<String>)> {
    html.split("<section class=\"student\"")
        .skip(1)
        .map(|section| {
            let section = section.split("</section>").next().unwrap_or_default();
            let heading =
                section.split("<h3>").nth(1).and_then(|h| h.split(" <span").next()).unwrap_or_default();
            let pictures = section
                .split("src=\"")
                .skip(1)
                .filter_map(|s| s.split('"').next())
                .map(str::to_string)
                .collect();
            (heading.to_string(), pictures)
        })
        .collect()
}

#[test]
fn a_class_is_checked_reported_and_checked_again_only_where_it_changed() {
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let (class, out) = (scratch.path().join("class"), scratch.path().join("report"));
    let alice = class_of_four(&class);

    let run = check_class(&class, &out, &[]);
    assert!(run.stdout.contains("4 submissions: 2 checked, 1 did not compile, 1 refused"), "{run}");
    assert!(run.stdout.contains("4 submissions in ") && run.stdout.contains(" per minute"), "{run}");
    for line in
        ["[1/4] alice: checked", "[2/4] bob: checked", "[3/4] carol: did not compile", "[4/4] dave: refused"]
    {
        assert!(run.stderr.contains(line), "{line}: {run}");
    }
    assert!(!scratch.path().join("evil.glsl").exists() && !class.join("evil.glsl").exists());

    let rows = csv(&out);
    assert_eq!(rows.len(), 5, "a header and a row per student: {rows:?}");
    let column = |name: &str| rows[0].iter().position(|h| h == name).unwrap_or_else(|| panic!("{name}"));
    let (status, message) = (column("status"), column("message"));
    let names: Vec<(&str, &str)> = rows[1..].iter().map(|r| (r[0].as_str(), r[status].as_str())).collect();
    assert_eq!(
        names,
        [("alice", "checked"), ("bob", "checked"), ("carol", "did not compile"), ("dave", "refused")]
    );
    assert!(rows.iter().all(|r| r.len() == rows[0].len()), "{rows:?}");
    assert_eq!(rows[1][column("mistakes")], "0");
    assert_eq!(rows[2][column("nan_blocker_depth")], "1", "{rows:?}");
    assert_eq!(rows[1][column("visibility function")], "PCSS");
    assert!(
        rows[3][message].contains("phongFragment.glsl:") && rows[3][message].contains("floot"),
        "{rows:?}"
    );
    assert!(rows[4][message].contains("../evil.glsl"), "{rows:?}");

    let en = std::fs::read_to_string(out.join("index.html")).expect("index.html");
    let zh = std::fs::read_to_string(out.join("index_zh.html")).expect("index_zh.html");
    assert!(en.contains("href=\"index_zh.html\"") && zh.contains("href=\"index.html\""));
    // The ranked list: bob's NaN, one student of four.
    let ranked = en.split("<tr id=\"finding-nan_blocker_depth\">").nth(1).expect("nan_blocker_depth ranked");
    let ranked = ranked.split("</tr>").next().unwrap_or_default();
    assert!(ranked.contains("<td class=\"n\">1</td><td class=\"n\">25%</td>"), "{ranked}");
    assert!(
        ranked.contains("lesson pcss, step 3") && ranked.contains("href=\"#student-2\">bob</a>"),
        "{ranked}"
    );
    assert!(!en.contains("<script") && !en.contains("http"), "static, nothing from elsewhere");
    for english in [
        "Class report",
        "Findings across the class",
        "share of the class",
        "did not compile",
        "refused",
        "their picture",
        "lesson pcss",
        "latent",
        "findBlocker returns NaN",
    ] {
        assert!(!zh.contains(english), "`{english}` on the Chinese page");
    }
    assert!(zh.contains("课程 pcss，第 3 步") && zh.contains("错误"));
    for page in [&en, &zh] {
        let sections = sections(page);
        let headings: Vec<&str> = sections.iter().map(|(h, _)| h.as_str()).collect();
        assert_eq!(headings, ["alice", "bob", "carol", "dave"]);
        for (name, pictures) in &sections {
            let expected = if ["alice", "bob"].contains(&name.as_str()) { 4 } else { 0 };
            assert_eq!(pictures.len(), expected, "{name}: {pictures:?}");
            for picture in pictures {
                assert!(picture.starts_with(&format!("{name}/")), "{picture}");
                assert!(out.join(picture).is_file(), "{picture} is linked but missing");
            }
        }
    }

    // Again: everything is done and unchanged.
    let again = check_class(&class, &out, &[]);
    assert!(again.stdout.contains("skipped 4 already checked"), "{again}");
    assert!(!again.stderr.contains("[1/"), "{again}");
    assert_eq!(csv(&out), rows, "the same report from what was remembered");
    // --force checks all four again.
    let forced = check_class(&class, &out, &["--force"]);
    assert!(!forced.stdout.contains("skipped") && forced.stdout.contains("4 submissions in "), "{forced}");
    assert!(forced.stderr.contains("[4/4]"), "{forced}");
    // A file touched: only its student is checked again.
    let later = SystemTime::now() + Duration::from_secs(60);
    let file = std::fs::File::options().write(true).open(&alice).expect("alice's shader");
    file.set_times(std::fs::FileTimes::new().set_modified(later)).expect("touch");
    let touched = check_class(&class, &out, &[]);
    assert!(touched.stdout.contains("skipped 3 already checked"), "{touched}");
    assert!(touched.stderr.contains("[1/1] alice: checked"), "{touched}");
    assert_eq!(csv(&out), rows);
}

#[test]
fn a_check_that_takes_too_long_is_stopped_and_the_class_report_still_written() {
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let (class, out) = (scratch.path().join("class"), scratch.path().join("report"));
    student_folder(&class, "alice", &example("phongFragment.glsl"));
    let broken = example("phongFragment.glsl").replacen("float findBlocker", "floot findBlocker", 1);
    student_folder(&class, "carol", &broken);
    // A check at 960x540 takes seconds on any machine this runs on: well past one.
    let (class_arg, out_arg) = (class.display().to_string(), out.display().to_string());
    let args = [
        "homework",
        "--class",
        &class_arg,
        "--out",
        &out_arg,
        "--size",
        "960x540",
        "--timeout",
        "1",
        "--jobs",
        "2",
    ];
    let run = shadowlab(&args);
    assert_eq!(run.code, Some(0), "{run}");
    let rows = csv(&out);
    let status = rows[0].iter().position(|h| h == "status").expect("status");
    assert_eq!(rows[1][0], "alice");
    assert_eq!(rows[1][status], "timed out", "{rows:?}");
    assert_eq!(rows[2][status], "did not compile", "{rows:?}");
    assert!(run.stdout.contains("1 did not compile, 1 timed out"), "{run}");
    assert!(!out.join("alice/checked.json").exists(), "a stopped check is not done");
    let en = std::fs::read_to_string(out.join("index.html")).expect("index.html");
    assert!(en.contains("timed out") && en.contains("--timeout"), "{en}");
}

#[test]
fn bad_input_is_one_line_exit_2_and_nothing_written() {
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let out = scratch.path().join("report");
    let out_arg = out.display().to_string();
    let empty = scratch.path().join("empty");
    std::fs::create_dir_all(empty.join(".git")).expect("an empty class");
    std::fs::write(empty.join("notes.txt"), "not a submission").expect("a file");
    let a_file = scratch.path().join("a_file");
    std::fs::write(&a_file, "x").expect("a file");
    let missing = scratch.path().join("missing").display().to_string();
    let (empty, a_file) = (empty.display().to_string(), a_file.display().to_string());
    for (args, says) in [
        (vec!["homework", "--class", &missing, "--out", &out_arg], "does not exist"),
        (vec!["homework", "--class", &a_file, "--out", &out_arg], "is not a folder"),
        (vec!["homework", "--class", &empty, "--out", &out_arg], "no submissions"),
        (vec!["homework", "--class", &empty, "--out", &a_file], "is a file"),
    ] {
        let run = shadowlab(&args);
        assert_eq!(run.code, Some(2), "{args:?}: {run}");
        assert_eq!(run.stderr.lines().count(), 1, "{args:?}: {run}");
        assert!(run.stderr.contains(says), "{args:?}: {run}");
        assert!(!out.exists(), "{args:?} wrote {}", out.display());
    }
    // --class and a PATH, or the class options without --class: the command line says no.
    for args in [
        vec!["homework", "x.glsl", "--class", &empty, "--out", &out_arg],
        vec!["homework", "x.glsl", "--out", &out_arg, "--jobs", "2"],
        vec!["homework", "--class", &empty, "--out", &out_arg, "--timeout", "0"],
    ] {
        let run = shadowlab(&args);
        assert_eq!(run.code, Some(2), "{args:?}: {run}");
        assert!(!out.exists());
    }
}

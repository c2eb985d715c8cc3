//! Tests with small trees and archives made on the spot (never real students' code).

mod folders;
mod fuzz;
mod hostile;
mod writer;
mod zips;

use super::*;
use std::path::Path;

/// The framework's six files under `prefix` ("" or "x/"), each text naming its own path.
pub fn framework(prefix: &str) -> Vec<(String, Vec<u8>)> {
    [
        "src/shaders/phongShader/phongFragment.glsl",
        "src/shaders/phongShader/phongVertex.glsl",
        "src/shaders/shadowShader/shadowFragment.glsl",
        "src/shaders/shadowShader/shadowVertex.glsl",
        "src/lights/DirectionalLight.js",
        "src/engine.js",
    ]
    .iter()
    .map(|p| file(&format!("{prefix}{p}")))
    .collect()
}

/// A file whose text is `// <path>\n`, so a test sees which copy was chosen.
pub fn file(path: &str) -> (String, Vec<u8>) {
    (path.to_owned(), format!("// {path}\n").into_bytes())
}

pub fn write_tree(root: &Path, files: &[(String, Vec<u8>)]) {
    for (path, bytes) in files {
        let full = root.join(path);
        if let Some(parent) = full.parent() {
            fs::create_dir_all(parent).expect("create folders");
        }
        fs::write(full, bytes).expect("write file");
    }
}

/// Path and text of every file found, in `SubmissionFiles` order.
pub fn found_paths(sub: &Submission) -> Vec<Option<String>> {
    let f = &sub.files;
    [
        Some(&f.phong_fragment),
        f.phong_vertex.as_ref(),
        f.shadow_fragment.as_ref(),
        f.shadow_vertex.as_ref(),
        f.light_script.as_ref(),
        f.engine.as_ref(),
    ]
    .into_iter()
    .map(|found| {
        found.map(|found| {
            assert_eq!(found.text, format!("// {}\n", found.path), "text belongs to its path");
            found.path.clone()
        })
    })
    .collect()
}

/// The paths `framework(prefix)` puts its files at.
pub fn framework_paths(prefix: &str) -> Vec<Option<String>> {
    framework(prefix).into_iter().map(|(p, _)| Some(p)).collect()
}

/// A folder holding `files`, returned with its temp dir (kept alive by the caller).
pub fn folder(name: &str, files: &[(String, Vec<u8>)]) -> (tempfile::TempDir, std::path::PathBuf) {
    let dir = tempfile::tempdir().expect("temp dir");
    let root = dir.path().join(name);
    fs::create_dir_all(&root).expect("root");
    write_tree(&root, files);
    (dir, root)
}

/// Checks a refusal: an error naming `archive`, on one line, saying `expected`.
pub fn assert_refused(result: Result<Submission, SubmissionError>, archive: &str, expected: &str) {
    let err = match result {
        Ok(sub) => panic!("expected a refusal saying {expected:?}, got {sub:?}"),
        Err(err) => err,
    };
    let line = err.to_string();
    assert!(!line.contains('\n') && !line.contains('\r'), "one line: {line:?}");
    assert!(line.starts_with(&format!("{archive}: ")), "names the archive: {line}");
    assert!(line.contains(expected), "{line:?} should say {expected:?}");
}

#[test]
fn class_members_lists_folders_and_zips() {
    let dir = tempfile::tempdir().expect("temp dir");
    let d = dir.path();
    for sub in ["carol", "alice", ".hidden", "alice/inner", "__MACOSX/alice"] {
        fs::create_dir_all(d.join(sub)).expect("dir");
    }
    for f in ["bob.zip", "dave.ZIP", "notes.txt", ".DS_Store", ".secret.zip"] {
        fs::write(d.join(f), b"x").expect("file");
    }
    let names: Vec<String> = class_members(d)
        .expect("listed")
        .iter()
        .map(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default())
        .collect();
    assert_eq!(names, ["alice", "bob.zip", "carol", "dave.ZIP"]);
    let missing = class_members(&d.join("nope")).expect_err("no such folder");
    assert!(missing.to_string().contains("nope"));
}

#[test]
fn errors_stay_on_one_line() {
    let err = SubmissionError::new("a\nb", "bad\r\nthing");
    assert_eq!(err.to_string(), "a\\nb: bad\\r\\nthing");
}

#[test]
fn suffix_is_stripped_ignoring_case() {
    assert_eq!(strip_suffix("Alice.ZIP", ".zip"), "Alice");
    assert_eq!(strip_suffix("zip", ".zip"), "zip");
    assert_eq!(strip_suffix("é.zip", ".zip"), "é");
    assert_eq!(strip_suffix("ééé", ".zip"), "ééé");
}

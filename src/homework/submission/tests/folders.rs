//! Folder submissions in the layouts students hand in.

use super::*;

fn read(root: &Path) -> Submission {
    read_path(root, Limits::default()).expect("readable submission")
}

#[test]
fn framework_layout() {
    let (_dir, root) = folder("alice", &framework("homework1/"));
    let sub = read(&root);
    assert_eq!(sub.name, "alice");
    assert_eq!(found_paths(&sub), framework_paths("homework1/"));
    assert!(sub.notes.is_empty(), "{:?}", sub.notes);
}

#[test]
fn without_homework1_level_or_src() {
    let (_dir, root) = folder("bob", &framework(""));
    assert_eq!(found_paths(&read(&root)), framework_paths(""));
    let flat: Vec<_> = ["phongFragment.glsl", "phongVertex.glsl", "DirectionalLight.js", "engine.js"]
        .iter()
        .map(|p| file(p))
        .collect();
    let (_dir, root) = folder("flat", &flat);
    let paths = found_paths(&read(&root));
    assert_eq!(paths[0].as_deref(), Some("phongFragment.glsl"));
    assert_eq!(paths[2], None);
    assert_eq!(paths[5].as_deref(), Some("engine.js"));
}

#[test]
fn repo_root_above() {
    let mut files = framework("GAMES202-master/homework1/");
    files.push(file("GAMES202-master/README.md"));
    let (_dir, root) = folder("carol", &files);
    assert_eq!(found_paths(&read(&root)), framework_paths("GAMES202-master/homework1/"));
}

#[test]
fn homework2_beside_loses() {
    let mut files = framework("homework1/");
    files.extend(framework("homework2/"));
    files.push(file("hw3/phongFragment.glsl"));
    let (_dir, root) = folder("dave", &files);
    let sub = read(&root);
    assert_eq!(found_paths(&sub), framework_paths("homework1/"));
    let note = sub.notes.iter().find(|n| n.starts_with("phongFragment.glsl:")).expect("a note");
    assert!(
        note.contains("chose homework1/src/shaders/phongShader/phongFragment.glsl over homework2/src/shaders/phongShader/phongFragment.glsl (names another homework)"),
        "{note}"
    );
    assert!(note.contains("hw3/phongFragment.glsl (names another homework)"), "{note}");
    assert_eq!(sub.notes.len(), 6, "one note per file with several candidates: {:?}", sub.notes);
}

#[test]
fn backup_copy_loses_even_when_shallower() {
    let mut files = framework("");
    files.push(file("old/phongShader/phongFragment.glsl"));
    files.push(file("src - Copy/shaders/phongShader/phongFragment.glsl"));
    let (_dir, root) = folder("erin", &files);
    let sub = read(&root);
    assert_eq!(found_paths(&sub), framework_paths(""));
    assert!(
        sub.notes.iter().any(|n| n.contains("old/phongShader/phongFragment.glsl (in a backup-like folder)")),
        "{:?}",
        sub.notes
    );
}

#[test]
fn others_come_from_the_chosen_homework_root() {
    let mut files = vec![file("hw1/phongFragment.glsl"), file("hw1/engine.js")];
    files.extend(framework("hw2/"));
    let (_dir, root) = folder("frank", &files);
    let sub = read(&root);
    let paths = found_paths(&sub);
    // Homework 1's flat copy wins over homework 2's framework-shaped one ...
    assert_eq!(paths[0].as_deref(), Some("hw1/phongFragment.glsl"));
    // ... and the rest follow it into hw1 where it has them.
    assert_eq!(paths[5].as_deref(), Some("hw1/engine.js"));

    let files = vec![
        file("hw1/shaders/phongShader/phongFragment.glsl"),
        file("hw1/engine.js"),
        file("other/src/engine.js"),
        file("hw1/shadowShader/shadowFragment.glsl"),
        file("hw1/shaders/phongShader/backup/shadowFragment.glsl"),
    ];
    let (_dir, root) = folder("gina", &files);
    let sub = read(&root);
    let paths = found_paths(&sub);
    assert_eq!(paths[5].as_deref(), Some("hw1/engine.js"));
    assert_eq!(paths[2].as_deref(), Some("hw1/shadowShader/shadowFragment.glsl"));
    assert!(
        sub.notes
            .iter()
            .any(|n| n.contains("other/src/engine.js (farther from the chosen phongFragment.glsl)")),
        "{:?}",
        sub.notes
    );
}

#[test]
fn only_phong_fragment() {
    let (_dir, root) = folder("hank", &[file("PhongFragment.GLSL")]);
    let sub = read(&root);
    assert_eq!(found_paths(&sub), [Some("PhongFragment.GLSL".to_owned()), None, None, None, None, None]);
}

#[test]
fn glsl_path_directly() {
    let (_dir, root) = folder("ivy", &[file("ivy_phong.glsl")]);
    let sub = read_path(&root.join("ivy_phong.glsl"), Limits::default()).expect("a lone shader");
    assert_eq!(sub.name, "ivy_phong");
    assert_eq!(sub.files.phong_fragment.text, "// ivy_phong.glsl\n");
    assert_eq!(sub.files.engine, None);
    assert_eq!(sub.notes, ["read ivy_phong.glsl as the phongFragment.glsl"]);
    let err = read_path(&root.join("missing.glsl"), Limits::default()).expect_err("missing");
    assert!(err.to_string().contains("missing.glsl: cannot be read"), "{err}");
}

#[test]
fn bom_is_stripped_and_bad_utf8_is_located() {
    let bom = [b"\xEF\xBB\xBFvoid main() {}\n".as_slice()].concat();
    let (_dir, root) = folder("jay", &[("phongFragment.glsl".to_owned(), bom)]);
    assert_eq!(read(&root).files.phong_fragment.text, "void main() {}\n");

    let bad = b"\xEF\xBB\xBFok\n\xFF".to_vec();
    let (_dir, root) = folder("kim", &[("phongFragment.glsl".to_owned(), bad)]);
    let err = read_path(&root, Limits::default()).expect_err("not UTF-8");
    assert!(err.path.ends_with("kim/phongFragment.glsl"), "{err}");
    assert!(err.message.contains("not UTF-8 text (invalid byte at offset 6)"), "{err}");
}

#[test]
fn too_large_file_is_refused() {
    let big = vec![b' '; 2000];
    let (_dir, root) = folder("lou", &[("phongFragment.glsl".to_owned(), big)]);
    let limits = Limits { file_bytes: 1000, ..Limits::default() };
    let err = read_path(&root, limits).expect_err("too large");
    assert!(err.to_string().contains("phongFragment.glsl: is over the limit of 1000 bytes"), "{err}");
}

#[test]
fn tool_folders_are_not_looked_in() {
    let files = [
        file("node_modules/x/phongFragment.glsl"),
        file(".git/phongFragment.glsl"),
        file("__MACOSX/phongFragment.glsl"),
        file("src/._phongFragment.glsl"),
        file("src/main.js"),
    ];
    let (_dir, root) = folder("max", &files);
    let err = read_path(&root, Limits::default()).expect_err("nothing usable");
    assert!(err.to_string().ends_with("max: no phongFragment.glsl in it (looked in 1 file)"), "{err}");
}

#[test]
fn depth_and_entry_limits() {
    let deep = format!("{}phongFragment.glsl", "d/".repeat(30));
    let (_dir, root) = folder("ned", &[file(&deep)]);
    let err = read_path(&root, Limits::default()).expect_err("too deep");
    assert!(err.message.contains("is nested deeper than 24 folders"), "{err}");

    let files: Vec<_> = (0..30).map(|i| file(&format!("f{i}.txt"))).collect();
    let (_dir, root) = folder("oli", &files);
    let limits = Limits { folder_entries: 10, ..Limits::default() };
    let err = read_path(&root, limits).expect_err("too many");
    assert!(err.message.contains("has more than 10 files and folders"), "{err}");
}

#[cfg(unix)]
#[test]
fn symlinks_are_skipped() {
    use std::os::unix::fs::symlink;
    let outside = tempfile::tempdir().expect("temp dir");
    fs::write(outside.path().join("secret.glsl"), b"// secret\n").expect("outside file");
    let mut files = framework("homework1/");
    files.push(file("homework1/notes.txt"));
    let (_dir, root) = folder("pat", &files);
    symlink(&root, root.join("homework1/loop")).expect("loop");
    symlink(outside.path().join("secret.glsl"), root.join("phongFragment.glsl")).expect("link out");
    symlink(outside.path(), root.join("outside")).expect("dir link out");
    let sub = read(&root);
    assert_eq!(found_paths(&sub), framework_paths("homework1/"));
    for link in ["homework1/loop", "phongFragment.glsl", "outside"] {
        assert!(sub.notes.contains(&format!("skipped {link} (a symlink)")), "{:?}", sub.notes);
    }
}

#[test]
fn dropped_files() {
    let mut files = framework("alice/homework1/");
    files.push(file("alice/__MACOSX/._phongFragment.glsl"));
    let sub = from_files("alice", files, Limits::default()).expect("dropped folder");
    assert_eq!(sub.name, "alice");
    assert_eq!(found_paths(&sub), framework_paths("alice/homework1/"));

    let err = from_files("eve", vec![file("../phongFragment.glsl")], Limits::default()).expect_err("escape");
    assert_eq!(err.to_string(), "eve: entry ../phongFragment.glsl would land outside the submission");
    let bad = vec![("phongFragment.glsl".to_owned(), vec![b'a', 0xC3])];
    let err = from_files("eve", bad, Limits::default()).expect_err("bad text");
    assert_eq!(err.to_string(), "eve/phongFragment.glsl: is not UTF-8 text (invalid byte at offset 1)");
}

/// A class folder given as one homework: its students' homeworks rank level, told apart only by
/// their names, so it is refused with a pointer to `--class` rather than checked as its first
/// student. A student's own spare copies (another homework's folder, a backup) still rank lower.
#[test]
fn homeworks_side_by_side_are_a_class_not_one_homework() {
    let mut files = framework("alice/homework1/");
    files.extend(framework("bob/homework1/"));
    files.extend(framework("carol/homework1/"));
    let (_dir, root) = folder("class", &files);
    let error = read_path(&root, Limits::default()).expect_err("a class, not a homework");
    assert!(
        error.message.contains("holds 3 homeworks side by side (alice/, bob/, carol/)")
            && error.message.contains("--class"),
        "{error}"
    );
    let mut files = framework("homework1/");
    files.extend(framework("homework1_backup/"));
    let (_dir, root) = folder("erin", &files);
    assert_eq!(found_paths(&read(&root)), framework_paths("homework1/"));
}

#[test]
fn an_es_module_port_is_refused_naming_its_first_import() {
    let files = vec![
        (
            "src/engine.js".to_string(),
            b"// a bundler's entry\nimport * as THREE from 'three';\nexport function main() {}\n".to_vec(),
        ),
        (
            "src/materials/PhongMaterial.js".to_string(),
            b"import fragmentShader from '../shaders/phong/fragment.glsl?raw';\n".to_vec(),
        ),
        file("src/shaders/phong/fragment.glsl"),
    ];
    let (_dir, root) = folder("erin", &files);
    let err = read_path(&root, Limits::default()).expect_err("not the framework's scripts");
    let shown = err.to_string();
    assert!(
        shown.ends_with("erin: src/engine.js:2: an ES-module port of the framework (`import ... from`, its shaders imported as strings): the check runs the framework's classic scripts only, so it does not judge this submission"),
        "{shown}"
    );
}

//! Zip submissions in the layouts students hand in.

use super::writer::{Spec, build, deflated, spec};
use super::*;

fn specs(files: &[(String, Vec<u8>)], deflate: bool) -> Vec<Spec> {
    files.iter().map(|(p, b)| if deflate { deflated(p, b) } else { spec(p, b) }).collect()
}

fn read(bytes: &[u8]) -> Submission {
    read_zip_bytes("class/alice.zip", bytes, Limits::default()).expect("readable zip")
}

#[test]
fn layouts_stored_and_deflated() {
    for deflate in [false, true] {
        for prefix in ["homework1/", "", "alice/GAMES202/homework1/"] {
            let zip = build(&specs(&framework(prefix), deflate));
            let sub = read(&zip);
            assert_eq!(sub.name, "alice");
            assert_eq!(found_paths(&sub), framework_paths(prefix), "{prefix} deflate={deflate}");
        }
    }
}

#[test]
fn zip_from_disk_matches_folder() {
    let mut files = framework("homework1/");
    files.extend(framework("homework2/"));
    let (_dir, root) = folder("bob", &files);
    let from_folder = read_path(&root, Limits::default()).expect("folder");
    let zip_path = root.with_file_name("bob.ZIP");
    fs::write(&zip_path, build(&specs(&files, true))).expect("zip written");
    let from_zip = read_path(&zip_path, Limits::default()).expect("zip");
    assert_eq!(from_zip, from_folder);
}

#[test]
fn macosx_junk_and_directories() {
    let mut all = vec![spec("homework1/", b""), spec("__MACOSX/", b"")];
    all.extend(specs(&framework("homework1/"), true));
    all.push(spec("__MACOSX/homework1/src/shaders/phongShader/._phongFragment.glsl", b"\x00\x05\x16\x07"));
    all.push(spec("homework1/src/shaders/phongShader/._phongVertex.glsl", b"\x00\x05\x16\x07"));
    all.push(spec("homework1/.DS_Store", b"junk"));
    let sub = read(&build(&all));
    assert_eq!(found_paths(&sub), framework_paths("homework1/"));
    assert!(
        sub.notes.contains(
            &"skipped __MACOSX/homework1/src/shaders/phongShader/._phongFragment.glsl (macOS metadata)"
                .to_owned()
        ),
        "{:?}",
        sub.notes
    );
}

#[test]
fn backslash_names() {
    let files: Vec<Spec> =
        framework("homework1/").iter().map(|(p, b)| deflated(&p.replace('/', "\\"), b)).collect();
    let sub = read(&build(&files));
    assert_eq!(found_paths(&sub), framework_paths("homework1/"));
}

#[test]
fn data_descriptors() {
    let files: Vec<Spec> = framework("hw1/")
        .iter()
        .enumerate()
        .map(|(i, (p, b))| Spec { descriptor: true, deflate: i % 2 == 0, ..spec(p, b) })
        .collect();
    assert_eq!(found_paths(&read(&build(&files))), framework_paths("hw1/"));
}

#[test]
fn name_encodings() {
    // CP437 without the UTF-8 flag: non-ASCII bytes become '?'.
    let cp437 = Spec {
        name: b"caf\x82/phongFragment.glsl".to_vec(),
        data: b"// caf?/phongFragment.glsl\n".to_vec(),
        ..Spec::default()
    };
    let sub = read(&build(&[cp437]));
    assert_eq!(sub.files.phong_fragment.path, "caf?/phongFragment.glsl");
    // UTF-8 with the flag, and without it (as macOS writes).
    for flags in [0x800, 0] {
        let utf8 = Spec { flags, ..spec("作业1/phongShader/phongFragment.glsl", b"// 1\n") };
        let other = spec("作业2/phongShader/phongFragment.glsl", b"// 2\n");
        let sub = read(&build(&[other, utf8]));
        assert_eq!(sub.files.phong_fragment.path, "作业1/phongShader/phongFragment.glsl");
    }
}

#[test]
fn nested_zip_is_ignored() {
    let inner = build(&specs(&framework("homework1/"), true));
    let mut outer = specs(&framework("homework1/"), true);
    outer.push(spec("homework1.zip", &inner));
    let sub = read(&build(&outer));
    assert_eq!(found_paths(&sub), framework_paths("homework1/"));
    assert!(
        sub.notes
            .contains(&"ignored homework1.zip (an archive inside the submission is not opened)".to_owned()),
        "{:?}",
        sub.notes
    );

    let only = build(&[spec("submission.zip", &inner), spec("readme.txt", b"hi")]);
    let err = read_zip_bytes("class/alice.zip", &only, Limits::default()).expect_err("nothing usable");
    assert_eq!(
        err.to_string(),
        "class/alice.zip: no phongFragment.glsl in it (looked in 2 files; it holds submission.zip, which is not opened)"
    );
}

#[test]
fn unused_odd_entries_do_not_matter() {
    // An entry in a method we cannot read is fine while nobody needs it.
    let mut files = specs(&framework("homework1/"), false);
    files.push(Spec { method: Some(14), ..spec("homework1/lib/three.min.js", b"lzma?") });
    assert_eq!(found_paths(&read(&build(&files))), framework_paths("homework1/"));
}

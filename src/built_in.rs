//! The lessons, scenes, meshes and textures shadowlab ships, as bytes built into the binary: the
//! copy an installed binary unpacks (`shipped.rs`) and the files a page reads (`files.rs`).
//! `build.rs` finds them in the folders `list.rs` names, so a file dropped into one ships.

mod list;

pub use list::{SHIPPED_DIRS, SHIPPED_FILES, ships};

// `FILES`: every file of the shipped folders and the shipped files, as `build.rs` found them.
include!(concat!(env!("OUT_DIR"), "/shipped_files.rs"));

/// `path` as a key of [`FILES`]: `.` left out, `..` taken back, `\` read as `/`.
fn key(path: &std::path::Path) -> String {
    let mut parts: Vec<String> = Vec::new();
    for part in path.to_string_lossy().split(['/', '\\']) {
        match part {
            "" | "." => {}
            ".." => {
                parts.pop();
            }
            part => parts.push(part.to_owned()),
        }
    }
    parts.join("/")
}

/// The built-in bytes of the shipped file at `path` (relative to the checkout), if there is one.
pub fn file(path: &std::path::Path) -> Option<&'static [u8]> {
    let key = key(path);
    FILES.iter().find(|(p, _)| *p == key).map(|(_, bytes)| *bytes)
}

/// `path` names a shipped folder (one holding built-in files, directly or below).
pub fn is_folder(path: &std::path::Path) -> bool {
    let key = key(path);
    key.is_empty()
        || FILES.iter().any(|(p, _)| p.strip_prefix(key.as_str()).is_some_and(|rest| rest.starts_with('/')))
}

/// The built-in files directly in the folder `path`, by their paths.
pub fn files_in(path: &std::path::Path) -> Vec<std::path::PathBuf> {
    let key = key(path);
    FILES
        .iter()
        .filter_map(|(p, _)| {
            let rest =
                if key.is_empty() { Some(*p) } else { p.strip_prefix(key.as_str())?.strip_prefix('/') };
            rest.filter(|rest| !rest.contains('/')).map(|_| std::path::PathBuf::from(p))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::{Path, PathBuf};

    #[test]
    fn shipped_files_are_found_by_relative_paths_with_dots() {
        let bias = std::fs::read(Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons/02_bias.toml"));
        assert_eq!(file(Path::new("lessons/02_bias.toml")), bias.ok().as_deref());
        assert!(file(Path::new("./assets/scenes/../meshes/bunny.obj")).is_some());
        assert!(file(Path::new("assets/meshes")).is_none());
        assert!(file(Path::new("Cargo.toml")).is_none());
        assert!(is_folder(Path::new("assets/homework/")) && is_folder(Path::new("assets")));
        assert!(!is_folder(Path::new("assets/home")) && !is_folder(Path::new("lessons/02_bias.toml")));
        let textures = files_in(Path::new("assets/textures"));
        assert_eq!(textures, vec![PathBuf::from("assets/textures/checker.png")]);
        let homework = files_in(Path::new("assets/homework"));
        let on_disk = std::fs::read_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/homework"))
            .expect("the homework folder")
            .flatten()
            .filter(|e| e.path().is_file() && ships(&e.file_name().to_string_lossy()))
            .count();
        assert_eq!(homework.len(), on_disk, "{homework:?}");
        assert!(homework.iter().all(|p| p.parent() == Some(Path::new("assets/homework"))));
    }
}

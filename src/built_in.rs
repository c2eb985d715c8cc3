//! The lessons, scenes, meshes and textures shadowlab ships, as bytes built into the binary: the
//! copy an installed binary unpacks (`shipped.rs`) and the files a page reads (`files.rs`).

macro_rules! shipped_files {
    ($($path:literal),* $(,)?) => {
        /// Every shipped file, by its path relative to the checkout, with its bytes.
        pub const FILES: &[(&str, &[u8])] =
            &[$(($path, include_bytes!(concat!(env!("CARGO_MANIFEST_DIR"), "/", $path)))),*];
    };
}

shipped_files![
    "lessons/01_hard_shadows.toml",
    "lessons/02_bias.toml",
    "lessons/03_pcf.toml",
    "lessons/04_pcss.toml",
    "lessons/05_multi_light.toml",
    "lessons/06_vsm.toml",
    "lessons/07_homework.toml",
    "assets/README.md",
    "assets/meshes/bunny.obj",
    "assets/meshes/floor.mtl",
    "assets/meshes/floor.obj",
    "assets/scenes/acne.toml",
    "assets/scenes/bleeding.toml",
    "assets/scenes/contact.toml",
    "assets/scenes/games202.toml",
    "assets/scenes/homework.toml",
    "assets/scenes/homework_check.toml",
    "assets/homework/README.md",
    "assets/homework/DirectionalLight.js",
    "assets/homework/DirectionalLight_narrow.js",
    "assets/homework/DirectionalLight_no_model.js",
    "assets/homework/phongFragment.glsl",
    "assets/homework/phongFragment_bias_too_large.glsl",
    "assets/homework/phongFragment_constant_filter.glsl",
    "assets/homework/phongFragment_divided_twice.glsl",
    "assets/homework/phongFragment_light_size_world.glsl",
    "assets/homework/phongFragment_nan_blocker.glsl",
    "assets/homework/phongFragment_ndc_coordinates.glsl",
    "assets/homework/phongFragment_no_bias.glsl",
    "assets/homework/phongFragment_no_bias_hidden.glsl",
    "assets/homework/phongFragment_random_walk.glsl",
    "assets/homework/phongFragment_receiver_blocker.glsl",
    "assets/homework/phongFragment_search_radius.glsl",
    "assets/homework/phongFragment_tiny_light.glsl",
    "assets/homework/phongFragment_undivided.glsl",
    "assets/homework/phongFragment_zero_blocker.glsl",
    "assets/homework/phongFragment_divided_by_blockers.glsl",
    "assets/homework/shadowFragment_255.glsl",
    "assets/homework/shadowFragment_carry.glsl",
    "assets/homework/framework/phongVertex.glsl",
    "assets/homework/framework/shadowFragment.glsl",
    "assets/homework/framework/shadowVertex.glsl",
    "assets/scenes/lesson_bias_cull.toml",
    "assets/scenes/lesson_pcss_sun.toml",
    "assets/scenes/multi_light.toml",
    "assets/textures/checker.png",
];

/// Folders whose files ship (the test that keeps [`FILES`] complete walks them).
pub const SHIPPED_DIRS: [&str; 6] = [
    "lessons",
    "assets/meshes",
    "assets/scenes",
    "assets/textures",
    "assets/homework",
    "assets/homework/framework",
];

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
        assert_eq!(file(Path::new("lessons/02_bias.toml")), Some(FILES[1].1));
        assert!(file(Path::new("./assets/scenes/../meshes/bunny.obj")).is_some());
        assert!(file(Path::new("assets/meshes")).is_none());
        assert!(file(Path::new("Cargo.toml")).is_none());
        assert!(is_folder(Path::new("assets/homework/")) && is_folder(Path::new("assets")));
        assert!(!is_folder(Path::new("assets/home")) && !is_folder(Path::new("lessons/02_bias.toml")));
        let textures = files_in(Path::new("assets/textures"));
        assert_eq!(textures, vec![PathBuf::from("assets/textures/checker.png")]);
        assert_eq!(files_in(Path::new("assets/homework")).len(), 22);
    }
}

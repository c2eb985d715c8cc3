//! The lessons, scenes, meshes and textures shadowlab ships. They are read from disk where they
//! are found (the working folder, beside the executable, the checkout it was built from); an
//! installed binary whose checkout is gone unpacks the copy built into it, once, into the user's
//! data folder, and reads them there. Loaders stay path-based either way: a lesson names its
//! scene and a scene its meshes by relative paths, which hold in the unpacked folder too.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// Set to 1 to use the copy built into the binary even where files are found on disk.
pub const BUILT_IN_ENV: &str = "SHADOWLAB_BUILT_IN_DATA";

pub use crate::built_in::{FILES, SHIPPED_DIRS, SHIPPED_FILES};

/// A shipped file or folder, found from any working folder: relative to the working folder
/// first, then beside the executable (and up to three folders above it, which covers
/// `target/release/`), then in the source tree it was built from, then in the unpacked built-in
/// copy. In a page, `relative` itself: the built-in copy's name for it.
pub fn shipped_path(relative: &str) -> PathBuf {
    // A page has no disk: its files are the copy built in, by their relative paths (`files.rs`).
    if cfg!(target_arch = "wasm32") {
        return PathBuf::from(relative);
    }
    let source_tree = Path::new(env!("CARGO_MANIFEST_DIR")).join(relative);
    if !use_built_in() {
        let beside_exe: Vec<PathBuf> = std::env::current_exe()
            .map(|exe| exe.ancestors().skip(1).take(4).map(|dir| dir.join(relative)).collect())
            .unwrap_or_default();
        let mut on_disk =
            std::iter::once(PathBuf::from(relative)).chain(beside_exe).chain([source_tree.clone()]);
        if let Some(found) = on_disk.find(|p| p.exists()) {
            return found;
        }
    }
    match built_in_root() {
        Some(root) => root.join(relative),
        // Forced to the copy and it cannot be unpacked: the bare path, which fails to load
        // with its name, rather than files from disk the user asked not to read.
        None if use_built_in() => PathBuf::from(relative),
        // Otherwise the error names the source-tree path.
        None => source_tree,
    }
}

fn use_built_in() -> bool {
    std::env::var(BUILT_IN_ENV).is_ok_and(|v| v == "1")
}

/// The folder the built-in copy is unpacked into (once per process), named by a hash of its
/// contents so that another version never reads a stale copy; `None` when it cannot be written.
pub fn built_in_root() -> Option<PathBuf> {
    static ROOT: OnceLock<Option<PathBuf>> = OnceLock::new();
    ROOT.get_or_init(|| {
        let root = data_home()?.join("shadowlab").join(format!("shipped-{:016x}", content_hash()));
        match unpack(&root) {
            Ok(()) => Some(root),
            Err(e) => {
                eprintln!("shadowlab: cannot unpack the built-in lessons and assets: {e}");
                None
            }
        }
    })
    .clone()
}

/// `$XDG_DATA_HOME`, else `~/.local/share` (a relative path counts as unset, as the XDG base
/// directory rules say).
fn data_home() -> Option<PathBuf> {
    let from = |var: &str| std::env::var_os(var).map(PathBuf::from).filter(|p| p.is_absolute());
    from("XDG_DATA_HOME").or_else(|| from("HOME").map(|home| home.join(".local/share")))
}

/// FNV-1a over every path and its bytes.
fn content_hash() -> u64 {
    let mut h = crate::files::Fnv1a::new();
    for (path, bytes) in FILES {
        h.add(path.as_bytes());
        h.add(&[0]);
        h.add(bytes);
    }
    h.value()
}

/// Writes every file that is missing or differs, each atomically (a crash leaves no half file):
/// the copy is the binary's, and an edited file is restored on the next start.
fn unpack(root: &Path) -> Result<(), String> {
    for (relative, bytes) in FILES {
        let path = root.join(relative);
        if std::fs::read(&path).is_ok_and(|on_disk| on_disk == *bytes) {
            continue;
        }
        let folder = path.parent().unwrap_or(root);
        std::fs::create_dir_all(folder).map_err(|e| format!("{}: {e}", folder.display()))?;
        crate::files::write_atomic(&path, bytes).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What `build.rs` built in is every shipped file as it is on disk, sorted, and no junk.
    #[test]
    fn the_built_in_copy_holds_every_shipped_file_as_it_is_on_disk() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let mut on_disk: Vec<String> = SHIPPED_FILES.iter().map(|f| f.to_string()).collect();
        for dir in SHIPPED_DIRS {
            for entry in std::fs::read_dir(root.join(dir)).expect("a shipped folder") {
                let entry = entry.expect("an entry");
                if entry.file_type().expect("a file type").is_dir() {
                    continue; // shipped folders are listed on their own
                }
                let name = entry.file_name().to_string_lossy().into_owned();
                if crate::built_in::ships(&name) {
                    on_disk.push(format!("{dir}/{name}"));
                }
            }
        }
        on_disk.sort();
        let built_in: Vec<String> = FILES.iter().map(|(p, _)| p.to_string()).collect();
        assert_eq!(built_in, on_disk);
        for (path, bytes) in FILES {
            assert_eq!(std::fs::read(root.join(path)).expect("readable").as_slice(), *bytes, "{path}");
        }
    }

    #[test]
    fn editor_junk_and_hidden_files_do_not_ship() {
        use crate::built_in::ships;
        for name in ["04_pcss.toml", "bunny.obj", "README.md", "phongFragment_no_bias.glsl"] {
            assert!(ships(name), "{name}");
        }
        for name in
            [".04_pcss.toml.swp", ".DS_Store", "04_pcss.toml~", "#04_pcss.toml#", "a.toml.bak", "a.orig"]
        {
            assert!(!ships(name), "{name}");
        }
    }

    #[test]
    fn unpacking_writes_every_file_and_repairs_a_changed_one() {
        let dir = tempfile::tempdir().expect("temp dir");
        let root = dir.path().join("shipped");
        unpack(&root).expect("unpack");
        for (path, bytes) in FILES {
            assert_eq!(std::fs::read(root.join(path)).expect("unpacked").as_slice(), *bytes, "{path}");
        }
        let edited = root.join(FILES[0].0);
        std::fs::write(&edited, "edited").expect("edit");
        unpack(&root).expect("unpack again");
        assert_eq!(std::fs::read(&edited).expect("repaired").as_slice(), FILES[0].1);
    }
}

//! Which files ship: read by `build.rs`, which builds every one of them into the binary, and by
//! the tests that hold the built-in copy to the folders.

/// Folders whose files ship, each read on its own (not the folders below it).
pub const SHIPPED_DIRS: [&str; 6] = [
    "lessons",
    "assets/meshes",
    "assets/scenes",
    "assets/textures",
    "assets/homework",
    "assets/homework/framework",
];

/// Files that ship from folders that do not (`assets/` also holds the font and the tools).
pub const SHIPPED_FILES: [&str; 1] = ["assets/README.md"];

/// A file of a shipped folder ships unless it is hidden or an editor's backup, swap or lock file.
pub fn ships(name: &str) -> bool {
    let junk = name.starts_with('.')
        || name.starts_with('#')
        || name.ends_with('~')
        || [".swp", ".swo", ".bak", ".orig", ".rej", ".tmp"].iter().any(|ext| name.ends_with(ext));
    !name.is_empty() && !junk
}

//! shadowlab: learn real-time shadows — shadow mapping, bias, PCF and PCSS — with a CPU twin
//! of every shader function and a ground truth to compare against.

pub mod cli;
pub mod diagrams;
pub mod export;
pub mod i18n;
pub mod lessons;
pub mod probe;
pub mod reference;
pub mod render;
pub mod scene;
pub mod shadow;
pub mod ui;
pub mod views;

use std::path::{Path, PathBuf};

/// A file shipped with shadowlab (scenes, lessons), found from any working folder: relative to
/// the working folder first, then beside the executable (and up to three folders above it, which
/// covers `target/release/`), then in the source tree it was built from.
pub fn shipped_path(relative: &str) -> PathBuf {
    let local = PathBuf::from(relative);
    if local.exists() {
        return local;
    }
    if let Ok(exe) = std::env::current_exe() {
        for dir in exe.ancestors().skip(1).take(4) {
            let candidate = dir.join(relative);
            if candidate.exists() {
                return candidate;
            }
        }
    }
    Path::new(env!("CARGO_MANIFEST_DIR")).join(relative)
}

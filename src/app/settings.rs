//! What the app remembers between runs (eframe storage).

use crate::i18n::Lang;
use crate::views::overlays::Overlay;
use serde::{Deserialize, Serialize};
use std::path::PathBuf;

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(default)]
pub struct Settings {
    pub last_scene: Option<PathBuf>,
    /// Scenes and models opened from a path (the box, a drop, the command line), newest first.
    pub recent_files: Vec<PathBuf>,
    /// Lesson id and step index.
    pub last_lesson: Option<(String, usize)>,
    pub overlays: Vec<Overlay>,
    pub lang: Lang,
    /// Fraction of the view area given to the camera view (the shadow map gets the rest).
    pub split: f32,
    pub inspector_width: f32,
    pub diagram_height: f32,
    pub screenshot_dir: PathBuf,
    pub show_kernel_plot: bool,
    /// Frame and pass times in the status bar (off for reproducible screenshots).
    pub show_timings: bool,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            last_scene: None,
            recent_files: Vec::new(),
            last_lesson: None,
            overlays: Vec::new(),
            lang: Lang::En,
            split: 0.62,
            inspector_width: 300.0,
            diagram_height: 300.0,
            screenshot_dir: PathBuf::from("screenshots"),
            show_kernel_plot: true,
            show_timings: true,
        }
    }
}

pub const STORAGE_KEY: &str = "shadowlab-settings";

/// How many recent files the scene picker lists.
pub const RECENT_FILES: usize = 8;

impl Settings {
    /// Put `path` first among the recent files (once, at most `RECENT_FILES` kept), kept as a
    /// canonical path, so it opens from any folder and is never listed twice.
    pub fn remember_file(&mut self, path: &std::path::Path) {
        // Bytes handed over (a page's dropped file) do not outlive the session.
        if crate::files::is_handed_over(path) {
            return;
        }
        let path = std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf());
        self.recent_files.retain(|p| *p != path);
        self.recent_files.insert(0, path);
        self.recent_files.truncate(RECENT_FILES);
    }
}

//! Screenshots: the window as egui painted it, and each view as rendered, as PNGs.

use super::ShadowlabApp;
use std::path::PathBuf;

impl ShadowlabApp {
    pub fn request_screenshot(&mut self, ctx: &egui::Context) {
        let slot = self.screenshot.clone();
        ctx.request_screenshot(move |image| {
            if let Ok(mut s) = slot.lock() {
                *s = Some(image);
            }
        });
        self.screenshot_pending = true;
        self.status = super::strings::tr(self.lang, "taking a screenshot...").into();
    }

    /// Save a finished window screenshot and each viewport as PNGs.
    pub(super) fn save_screenshot_if_ready(&mut self) {
        let image = match self.screenshot.lock() {
            Ok(mut slot) => slot.take(),
            Err(_) => None,
        };
        let Some(window) = image else { return };
        self.screenshot_pending = false;
        match self.save_screenshot(&window) {
            Ok(paths) => {
                let names: Vec<String> = paths.iter().map(|p| p.display().to_string()).collect();
                self.status = format!("{} {}", super::strings::tr(self.lang, "saved"), names.join(", "));
            }
            Err(e) => self.error = Some(e),
        }
    }

    pub(super) fn save_screenshot(&mut self, window: &egui::ColorImage) -> Result<Vec<PathBuf>, String> {
        let dir = self.settings.screenshot_dir.clone();
        std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        let n = (1..10_000).find(|n| !dir.join(format!("shot-{n:03}-window.png")).exists()).unwrap_or(0);
        let mut written = Vec::new();
        let [w, h] = window.size;
        let bytes: Vec<u8> = window.pixels.iter().flat_map(|c| c.to_srgba_unmultiplied()).collect();
        let mut images = Vec::new();
        if let Some(img) = image::RgbaImage::from_raw(w as u32, h as u32, bytes) {
            images.push(("window", img));
        }
        if let Some(img) = &self.shown.color {
            images.push(("camera", img.clone()));
        }
        if let Some((map, light)) = self.view_state.map() {
            images.push(("shadow-map", crate::views::shadow_map_image(map, light).0));
        }
        for (what, img) in images {
            let path = dir.join(format!("shot-{n:03}-{what}.png"));
            crate::export::write_png(&path, &img).map_err(|e| e.to_string())?;
            written.push(path);
        }
        Ok(written)
    }
}

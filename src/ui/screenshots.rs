//! Screenshots: the window as egui painted it, and each view as rendered, as PNGs: written to
//! the screenshot folder on the desktop, handed to the browser as downloads in a page.

use super::ShadowlabApp;
use crate::views::View;

impl ShadowlabApp {
    pub fn request_screenshot(&mut self, ctx: &egui::Context) {
        let slot = self.screenshot.clone();
        ctx.request_screenshot(move |image| {
            if let Ok(mut s) = slot.lock() {
                *s = Some(image);
            }
        });
        self.screenshot_pending = true;
        self.state.status = crate::i18n::tr(self.state.lang, "taking a screenshot...").into();
    }

    /// Save a finished window screenshot and each viewport as PNGs.
    pub(super) fn save_screenshot_if_ready(&mut self) {
        let image = match self.screenshot.lock() {
            Ok(mut slot) => slot.take(),
            Err(_) => None,
        };
        let Some(window) = image else { return };
        self.screenshot_pending = false;
        let done = if cfg!(target_arch = "wasm32") { "downloaded" } else { "saved" };
        match self.save_screenshot(&window) {
            Ok(names) => {
                self.state.status =
                    format!("{} {}", crate::i18n::tr(self.state.lang, done), names.join(", "));
            }
            Err(e) => self.state.error = Some(super::AppError::new("could not save the screenshot", e)),
        }
    }

    /// The camera panel as drawn: the view shown, its overlays and the probe's marker.
    fn camera_picture(&self) -> Option<image::RgbaImage> {
        let mut picture = match self.camera_panel_view() {
            View::Final | View::ShadowMap => self.render.shown.color.clone()?,
            _ => self.camera_panel.view_picture()?.clone(),
        };
        let (w, h) = picture.dimensions();
        if let Some(overlay) =
            self.camera_panel.overlay_picture().filter(|_| !self.render.shown.overlays_stale())
        {
            crate::views::overlays::blend_onto(&mut picture, overlay);
        }
        if let Some((fx, fy)) = super::camera_marks::probe_fraction(&self.state, w as f32 / h.max(1) as f32) {
            // The marker as on screen: a yellow ring of radius 7 and 2 px wide.
            let (cx, cy) = (fx * w as f32, fy * h as f32);
            let span = |c: f32, size: u32| (c - 9.0).max(0.0) as u32..((c + 9.0).max(0.0) as u32).min(size);
            for y in span(cy, h) {
                for x in span(cx, w) {
                    let d = ((x as f32 + 0.5 - cx).powi(2) + (y as f32 + 0.5 - cy).powi(2)).sqrt();
                    if (d - 7.0).abs() <= 1.0 {
                        picture.put_pixel(x, y, image::Rgba([255, 210, 0, 255]));
                    }
                }
            }
        }
        Some(picture)
    }

    /// The screenshot's pictures by what they show: the window, the camera view, the shadow map.
    fn screenshot_pictures(&self, window: &egui::ColorImage) -> Vec<(&'static str, image::RgbaImage)> {
        let [w, h] = window.size;
        let bytes: Vec<u8> = window.pixels.iter().flat_map(|c| c.to_srgba_unmultiplied()).collect();
        let mut images = Vec::new();
        if let Some(img) = image::RgbaImage::from_raw(w as u32, h as u32, bytes) {
            images.push(("window", img));
        }
        if let Some(img) = self.camera_picture() {
            images.push(("camera", img));
        }
        if let Some(map) = &self.render.shown.map {
            images.push(("shadow-map", crate::views::shadow_map_image(&map.depth, &map.view).0));
        }
        images
    }

    /// Write the pictures as `shot-NNN-*.png` to the screenshot folder; their absolute paths.
    #[cfg(not(target_arch = "wasm32"))]
    pub(super) fn save_screenshot(&mut self, window: &egui::ColorImage) -> Result<Vec<String>, String> {
        // Reported and written as an absolute path: the working directory is nobody's business.
        let dir = std::path::absolute(&self.state.settings.screenshot_dir)
            .map_err(|e| format!("{}: {e}", self.state.settings.screenshot_dir.display()))?;
        std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        let n = (1..10_000).find(|n| !dir.join(format!("shot-{n:03}-window.png")).exists()).unwrap_or(0);
        let mut written = Vec::new();
        for (what, img) in self.screenshot_pictures(window) {
            let path = dir.join(format!("shot-{n:03}-{what}.png"));
            crate::export::write_png(&path, &img).map_err(|e| e.to_string())?;
            written.push(path.display().to_string());
        }
        Ok(written)
    }

    /// Hand the pictures to the browser as downloads named `shot-NNN-*.png` (numbered from 1
    /// in each visit; a browser renames a name it already has); their names.
    #[cfg(target_arch = "wasm32")]
    pub(super) fn save_screenshot(&mut self, window: &egui::ColorImage) -> Result<Vec<String>, String> {
        static SHOTS: std::sync::atomic::AtomicU32 = std::sync::atomic::AtomicU32::new(1);
        let n = SHOTS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let mut downloaded = Vec::new();
        for (what, img) in self.screenshot_pictures(window) {
            let name = format!("shot-{n:03}-{what}.png");
            let png =
                crate::export::encode_png(&img, std::path::Path::new(&name)).map_err(|e| e.to_string())?;
            crate::browser::download(&name, "image/png", &png)?;
            downloaded.push(name);
        }
        Ok(downloaded)
    }
}

//! The app's GPU side: a Renderer on eframe's device, with its colour target registered as an
//! egui texture (the same render path as the CLI and the tests).

use crate::render::{FrameRequest, RenderError, Renderer};
use crate::scene::Scene;
use eframe::egui_wgpu;

pub struct ViewGpu {
    render_state: egui_wgpu::RenderState,
    pub renderer: Renderer,
    texture: Option<(egui::TextureId, (u32, u32))>,
}

impl ViewGpu {
    pub fn new(render_state: &egui_wgpu::RenderState) -> Result<Self, RenderError> {
        let renderer = Renderer::new(&render_state.device, &render_state.queue)?;
        Ok(Self { render_state: render_state.clone(), renderer, texture: None })
    }

    /// Render and make sure egui shows the new colour target.
    pub fn render(&mut self, scene: &Scene, request: &FrameRequest) -> Result<(), RenderError> {
        self.renderer.render(scene, request)?;
        if request.final_color {
            self.sync_texture(request.size);
        }
        Ok(())
    }

    fn sync_texture(&mut self, size: (u32, u32)) {
        let Some(texture) = self.renderer.color_texture() else { return };
        let view = texture.create_view(&Default::default());
        let device = &self.render_state.device;
        let mut egui_renderer = self.render_state.renderer.write();
        match self.texture {
            Some((id, old)) if old == size => {
                // Same target: egui already samples it; nothing to do.
                let _ = id;
            }
            Some((id, _)) => {
                egui_renderer.update_egui_texture_from_wgpu_texture(
                    device,
                    &view,
                    wgpu::FilterMode::Linear,
                    id,
                );
                self.texture = Some((id, size));
            }
            None => {
                let id = egui_renderer.register_native_texture(device, &view, wgpu::FilterMode::Linear);
                self.texture = Some((id, size));
            }
        }
    }

    /// The egui texture showing the last rendered camera view, and its size in pixels.
    pub fn texture(&self) -> Option<(egui::TextureId, (u32, u32))> {
        self.texture
    }
}

//! What a render is asked for and what it drew: the request, and the lights and parameters
//! exactly as the GPU saw them (everything downstream of a render reads these, never the scene).

use crate::shadow::{LightGpu, LightViewGpu, ShadowParamsGpu, ShadowViewGpu};

/// What to render for one frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameRequest {
    pub time_s: f32,
    /// Camera view size, pixels.
    pub size: (u32, u32),
    /// The light the analysis outputs (visibility, PCSS terms) describe.
    pub selected_light: usize,
    pub final_color: bool,
    pub analysis: bool,
    /// Record GPU timestamps (where the adapter supports them).
    pub timestamps: bool,
    /// Shade only this pixel of the camera passes (a scissor): the probe reads no other, and a
    /// full PCSS analysis pass to read one pixel would cost as much as the frame.
    pub only_pixel: Option<(u32, u32)>,
}

impl Default for FrameRequest {
    fn default() -> Self {
        Self {
            time_s: 0.0,
            size: (960, 540),
            selected_light: 0,
            final_color: true,
            analysis: true,
            timestamps: false,
            only_pixel: None,
        }
    }
}

/// What one `render` drew: the request, and the lights, their shadow views and the parameters
/// exactly as the GPU saw them (the CPU twin and the probe use these).
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    pub request: FrameRequest,
    pub lights: Vec<LightGpu>,
    /// Every light's shadow views (`LightGpu::first_view` and `view_count` index them).
    pub views: Vec<ShadowViewGpu>,
    pub params: ShadowParamsGpu,
    /// The still textured objects' albedo came from the view's cache (the camera, the size and
    /// those objects were as in the frame before), not from sampling their textures again.
    pub albedo_from_cache: bool,
    /// The shadow maps were kept from an earlier frame: nothing they depend on had changed.
    pub shadow_maps_kept: bool,
    /// The VSM moments were rebuilt this frame.
    pub moments_built: bool,
}

impl Frame {
    /// The shadow view a light's map pictures and probe read first (each light owns at least one),
    /// with its index in `views`.
    pub fn first_view_of(&self, light: usize) -> Option<(usize, &ShadowViewGpu)> {
        let (index, _) = crate::shadow::gpu::first_view_of(&self.lights, &self.views, light)?;
        Some((index, &self.views[index]))
    }

    /// Every shadow view light `light` owns (a point light: its six cube faces), with the first's
    /// index in `views`.
    pub fn views_of(&self, light: usize) -> Option<(usize, &[ShadowViewGpu])> {
        let l = self.lights.get(light)?;
        let first = l.first_view as usize;
        Some((first, self.views.get(first..first + l.view_count as usize)?))
    }

    /// Index into `views` of light `light`'s view that covers `world_pos` (a point light: the
    /// cube face towards it): the one its lookups there read.
    pub fn view_covering(&self, light: usize, world_pos: glam::Vec3) -> Option<usize> {
        Some(crate::shadow::view_covering(self.lights.get(light)?, &self.views, world_pos))
    }

    /// Light `light` with its first view: what the twin of one of its lookups needs.
    pub fn light_view(&self, light: usize) -> Option<LightViewGpu> {
        crate::shadow::gpu::first_view_of(&self.lights, &self.views, light).map(|(_, lv)| lv)
    }
}

//! Pass 1 (shaders/shadow_pass.wgsl): each light's depth from its own view, into one layer of
//! the shadow-map array. Re-rendered whenever a light, an object or the shadow pipeline has
//! changed (every frame while lights orbit and objects spin; not while a slider that only the
//! camera pass reads is dragged).

use super::gpu_types::DYNAMIC_STRIDE;
use super::scene_gpu::SceneGpu;
use super::targets::ShadowMaps;
use super::timing::Timer;
use crate::scene::Scene;

/// Record one depth pass per light: clear to far (1.0), draw every object. `view_group` holds
/// the lights' view matrices at DYNAMIC_STRIDE apart. The passes begin span 0 of `timer`, and
/// end it unless the VSM moments built from the maps do (`ends_span`).
#[allow(clippy::too_many_arguments)]
pub fn encode(
    encoder: &mut wgpu::CommandEncoder,
    scene: &Scene,
    scene_gpu: &SceneGpu,
    maps: &ShadowMaps,
    pipeline: &wgpu::RenderPipeline,
    view_group: &wgpu::BindGroup,
    timer: Option<&Timer>,
    ends_span: bool,
) {
    let layers = scene.lights.len().max(1);
    for layer in 0..layers {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("shadow pass"),
            color_attachments: &[],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &maps.layer_views[layer],
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: timer
                .and_then(|t| t.span_writes(0, layer == 0, ends_span && layer + 1 == layers)),
            occlusion_query_set: None,
            multiview_mask: None,
        });
        // A scene without lights still clears its one layer (the shaders bind the array).
        if let Some(light) = scene.lights.get(layer) {
            let size = light.shadow_map_size as f32;
            pass.set_viewport(0.0, 0.0, size, size, 0.0, 1.0);
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, view_group, &[(layer as u64 * DYNAMIC_STRIDE) as u32]);
            scene_gpu.draw(&mut pass, 1);
        }
    }
}

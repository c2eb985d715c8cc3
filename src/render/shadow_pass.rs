//! Pass 1 (shaders/shadow_pass.wgsl): each shadow view's depth (a light owns one or more), into
//! the view's layer of the shadow-map array. Re-rendered whenever a light, an object or the shadow pipeline has
//! changed (every frame while lights orbit and objects spin; not while a slider that only the
//! camera pass reads is dragged).

use super::gpu_types::DYNAMIC_STRIDE;
use super::scene_gpu::SceneGpu;
use super::targets::ShadowMaps;
use super::timing::Timer;
use crate::shadow::ShadowViewGpu;

/// The shadow pass's pipelines: projected depth, and for cube faces (where the frame has any)
/// the distance to the light.
#[derive(Clone, Copy)]
pub struct Pipelines<'a> {
    pub projected: &'a wgpu::RenderPipeline,
    pub distance: Option<&'a wgpu::RenderPipeline>,
}

impl<'a> Pipelines<'a> {
    fn for_view(&self, view: &ShadowViewGpu) -> &'a wgpu::RenderPipeline {
        match self.distance {
            Some(distance) if view.cube == 1 => distance,
            _ => self.projected,
        }
    }
}

/// Record one depth pass per shadow view: clear to far (1.0), draw every object. `view_group`
/// holds the views at DYNAMIC_STRIDE apart, in the order of `views`. The passes begin span 0 of `timer`, and
/// end it unless the VSM moments built from the maps do (`ends_span`).
#[allow(clippy::too_many_arguments)]
pub fn encode(
    encoder: &mut wgpu::CommandEncoder,
    views: &[ShadowViewGpu],
    scene_gpu: &SceneGpu,
    maps: &ShadowMaps,
    pipelines: Pipelines<'_>,
    view_group: &wgpu::BindGroup,
    timer: Option<&Timer>,
    ends_span: bool,
) {
    // A frame without views still clears layer 0 (the shaders bind the array).
    let passes = views.len().max(1);
    for pass_index in 0..passes {
        let view = views.get(pass_index);
        let layer = view.map_or(0, |v| v.layer as usize);
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
                .and_then(|t| t.span_writes(0, pass_index == 0, ends_span && pass_index + 1 == passes)),
            occlusion_query_set: None,
            multiview_mask: None,
        });
        if let Some(view) = view {
            let size = view.map_size_texels;
            pass.set_viewport(0.0, 0.0, size, size, 0.0, 1.0);
            pass.set_pipeline(pipelines.for_view(view));
            pass.set_bind_group(0, view_group, &[(pass_index as u64 * DYNAMIC_STRIDE) as u32]);
            scene_gpu.draw(&mut pass, 1);
        }
    }
}

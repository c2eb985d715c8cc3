//! Pass 2 (shaders/camera.wgsl): the camera view. When the view's albedo cache needs filling,
//! the still textured objects' texture values first; then a depth pre-pass, so that the shading
//! runs once per visible pixel however much geometry overlaps it; then the shaded colour and,
//! when asked, the float analysis targets of the selected light.

use super::scene_gpu::SceneGpu;
use super::targets::ViewTargets;
use super::timing::Timer;
use super::{BACKGROUND, FrameRequest};
use crate::scene::Scene;

/// The pipelines and bind groups the camera passes draw with.
pub struct CameraPasses<'a> {
    pub depth_only: &'a wgpu::RenderPipeline,
    /// The colour pass, present when the request wants the picture.
    pub shaded: Option<&'a wgpu::RenderPipeline>,
    /// `shaded` writes the analysis targets too (after the colour).
    pub shaded_writes_analysis: bool,
    /// Run the depth pre-pass (the shaded pipelines were built to test against it); without
    /// it the one shaded pass clears depth and keeps the nearest fragment itself.
    pub depth_prepass: bool,
    /// Present when the still textured objects read the view's albedo cache: `shaded` with
    /// ALBEDO_FROM_CACHE, which draws those objects (`shaded` draws the rest).
    pub shaded_from_cache: Option<&'a wgpu::RenderPipeline>,
    /// An analysis-only pass, present when the request wants the analysis without the picture.
    pub analysis: Option<&'a wgpu::RenderPipeline>,
    /// Present when the view's albedo cache is to be filled before the other passes.
    pub fill_albedo_cache: Option<&'a wgpu::RenderPipeline>,
    pub frame_group: &'a wgpu::BindGroup,
    pub lights_group: &'a wgpu::BindGroup,
    /// Group 3 while the cache itself is the pass's target.
    pub albedo_placeholder: &'a wgpu::BindGroup,
}

impl CameraPasses<'_> {
    /// Record the passes `request` asks for; they make span 1 of `timer`.
    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        request: &FrameRequest,
        targets: &ViewTargets,
        scene: &Scene,
        scene_gpu: &SceneGpu,
        timer: Option<&Timer>,
    ) {
        let (width, height) = targets.size;
        // A probe reads one pixel: shade only that one.
        let scissor = |pass: &mut wgpu::RenderPass<'_>| {
            if let Some((x, y)) = request.only_pixel {
                pass.set_scissor_rect(x.min(width - 1), y.min(height - 1), 1, 1);
            }
        };
        let shaded: Vec<(&wgpu::RenderPipeline, bool)> =
            [self.shaded.map(|p| (p, true)), self.analysis.map(|p| (p, false))]
                .into_iter()
                .flatten()
                .collect();
        if let Some(pipeline) = self.fill_albedo_cache {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("albedo cache"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &targets.albedo_cache.view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &targets.depth_view,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Discard,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: timer.and_then(|t| t.span_writes(1, true, false)),
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, self.frame_group, &[]);
            pass.set_bind_group(1, self.lights_group, &[]);
            pass.set_bind_group(3, self.albedo_placeholder, &[]);
            scene_gpu.draw_cacheable_albedo(&mut pass, 2, scene, true);
        }
        let first = self.fill_albedo_cache.is_none();
        if self.depth_prepass {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("camera depth pre-pass"),
                color_attachments: &[],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &targets.depth_view,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: timer.and_then(|t| t.span_writes(1, first, shaded.is_empty())),
                occlusion_query_set: None,
                multiview_mask: None,
            });
            scissor(&mut pass);
            pass.set_pipeline(self.depth_only);
            pass.set_bind_group(0, self.frame_group, &[]);
            pass.set_bind_group(1, self.lights_group, &[]);
            pass.set_bind_group(3, &targets.albedo_cache.bind_group, &[]);
            scene_gpu.draw(&mut pass, 2);
        }
        for (index, (pipeline, is_final)) in shaded.iter().enumerate() {
            let attachment = |view, clear| {
                Some(wgpu::RenderPassColorAttachment {
                    view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations { load: wgpu::LoadOp::Clear(clear), store: wgpu::StoreOp::Store },
                })
            };
            let analysis =
                targets.analysis_views.iter().map(|view| attachment(view, wgpu::Color::TRANSPARENT));
            let color_attachments: Vec<_> = match (*is_final, self.shaded_writes_analysis) {
                (true, true) => {
                    std::iter::once(attachment(&targets.color_view, BACKGROUND)).chain(analysis).collect()
                }
                (true, false) => vec![attachment(&targets.color_view, BACKGROUND)],
                (false, _) => analysis.collect(),
            };
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some(if *is_final { "camera pass" } else { "analysis pass" }),
                color_attachments: &color_attachments,
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &targets.depth_view,
                    depth_ops: Some(wgpu::Operations {
                        load: if self.depth_prepass { wgpu::LoadOp::Load } else { wgpu::LoadOp::Clear(1.0) },
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: timer.and_then(|t| {
                    t.span_writes(1, first && !self.depth_prepass && index == 0, index + 1 == shaded.len())
                }),
                occlusion_query_set: None,
                multiview_mask: None,
            });
            scissor(&mut pass);
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, self.frame_group, &[]);
            pass.set_bind_group(1, self.lights_group, &[]);
            pass.set_bind_group(3, &targets.albedo_cache.bind_group, &[]);
            match self.shaded_from_cache.filter(|_| *is_final) {
                Some(from_cache) => {
                    scene_gpu.draw_cacheable_albedo(&mut pass, 2, scene, false);
                    pass.set_pipeline(from_cache);
                    scene_gpu.draw_cacheable_albedo(&mut pass, 2, scene, true);
                }
                None => scene_gpu.draw(&mut pass, 2),
            }
        }
    }
}

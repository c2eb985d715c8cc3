//! Ground truth on the GPU: for each light sample, render a hard shadow map and add the hard
//! visibility of every camera pixel (from the analysis pass's positions and normals).

use super::gpu_types::{DYNAMIC_STRIDE, ReferenceInfoGpu, ShadowViewGpu};
use super::pipelines::ShadowPipelineKey;
use super::readback::{self, Readback};
use super::targets::ShadowMaps;
use super::{RenderError, Renderer, shadow_view_group};
use crate::reference;
use crate::scene::Scene;
use crate::shadow::{LightGpu, ShadowParamsGpu};

/// Samples recorded per command buffer (keeps a submission's size bounded).
const BATCH: usize = 32;

/// Called after each batch of a progressive ground truth with (samples done, samples in all,
/// the average so far); returning false stops the accumulation.
pub type ReferenceProgress<'a> = &'a mut dyn FnMut(u32, u32, &[f32]) -> bool;

impl Renderer {
    /// Have `ticker` told (samples done, samples in all) after each batch of every ground truth
    /// this renderer accumulates; each batch is then waited for, so the count is what the GPU
    /// has done.
    pub fn set_reference_ticker(&mut self, ticker: Option<Box<dyn FnMut(u32, u32) + Send>>) {
        self.reference_ticker = ticker;
    }

    /// Ground-truth visibility of light `light_index` at every pixel of the last frame (which
    /// must have rendered the analysis targets), averaged over `scene.shadow.reference_samples`
    /// hard shadows from points (width model) or directions (angular model) over the light.
    /// Pixels with no surface get 1.
    pub fn render_reference(&mut self, scene: &Scene, light_index: usize) -> Result<Vec<f32>, RenderError> {
        let done = self.guarded(|r| r.render_reference_unguarded(scene, light_index, BATCH, BATCH, None))?;
        done.ok_or_else(|| RenderError::Usage("the ground truth was stopped".into()))
    }

    /// The same ground truth, read back after every batch (`first_batch` samples, doubling up to
    /// `max_batch`) and handed to `progress`; None where `progress` stopped it.
    pub fn render_reference_progressive(
        &mut self,
        scene: &Scene,
        light_index: usize,
        first_batch: usize,
        max_batch: usize,
        progress: ReferenceProgress<'_>,
    ) -> Result<Option<Vec<f32>>, RenderError> {
        self.guarded(|r| {
            r.render_reference_unguarded(scene, light_index, first_batch, max_batch, Some(progress))
        })
    }

    fn render_reference_unguarded(
        &mut self,
        scene: &Scene,
        light_index: usize,
        first_batch: usize,
        max_batch: usize,
        mut progress: Option<ReferenceProgress<'_>>,
    ) -> Result<Option<Vec<f32>>, RenderError> {
        let request = self
            .last_frame
            .as_ref()
            .map(|f| f.request)
            .filter(|r| r.analysis)
            .ok_or_else(|| RenderError::Usage("render the analysis pass before the reference".into()))?;
        let light = scene.lights.get(light_index).ok_or_else(|| {
            RenderError::Usage(format!(
                "light {light_index} does not exist (the scene has {})",
                scene.lights.len()
            ))
        })?;
        let samples: Vec<LightGpu> =
            reference::sample_lights(light, request.time_s, scene.shadow.reference_samples as usize);
        let device = self.device.clone();
        let (width, height) = request.size;
        let pixels = u64::from(width) * u64::from(height);

        let maps = ShadowMaps::new(&device, light.shadow_map_size, 1);
        let dynamic_buffer = |label: &str| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: DYNAMIC_STRIDE * samples.len() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let light_buffer = dynamic_buffer("reference lights");
        let view_buffer = dynamic_buffer("reference views");
        for (i, sample) in samples.iter().enumerate() {
            let offset = i as u64 * DYNAMIC_STRIDE;
            self.queue.write_buffer(&light_buffer, offset, bytemuck::bytes_of(sample));
            let view = ShadowViewGpu { clip_from_world: sample.clip_from_world };
            self.queue.write_buffer(&view_buffer, offset, bytemuck::bytes_of(&view));
        }
        let accumulated = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("reference sum"),
            size: pixels * 4,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let info = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("reference info"),
            size: std::mem::size_of::<ReferenceInfoGpu>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let info_gpu = ReferenceInfoGpu { width, height, weight: 1.0 / samples.len() as f32, _pad: 0 };
        self.queue.write_buffer(&info, 0, bytemuck::bytes_of(&info_gpu));
        let params = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("reference params"),
            size: std::mem::size_of::<ShadowParamsGpu>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let params_gpu = ShadowParamsGpu::new(&reference::reference_settings(&scene.shadow));
        self.queue.write_buffer(&params, 0, bytemuck::bytes_of(&params_gpu));
        let targets = self.targets()?;
        let io_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("reference io"),
            layout: &self.layouts.reference_io,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(&targets.analysis_views[1]),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&targets.analysis_views[2]),
                },
                wgpu::BindGroupEntry { binding: 2, resource: accumulated.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 3, resource: info.as_entire_binding() },
            ],
        });
        let light_group = self.shadow_inputs_group(
            &self.layouts.reference_light,
            wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                buffer: &light_buffer,
                offset: 0,
                size: std::num::NonZeroU64::new(std::mem::size_of::<LightGpu>() as u64),
            }),
            &params,
            &maps,
            None,
        );
        let view_group = shadow_view_group(&device, &self.layouts, &view_buffer);
        // The reference's own shadow pass: no hardware bias and no culling, whatever the user
        // set, so their effects show up as error rather than being copied into the truth.
        let key =
            ShadowPipelineKey { depth_bias_constant: 0, depth_bias_slope_bits: 0, cull_front_faces: false };
        let shadow_pipeline = self.pipelines.shadow(&device, key).clone();
        let scene_gpu =
            self.scene_gpu.as_ref().ok_or_else(|| RenderError::Usage("no scene uploaded".into()))?;

        let hit: Vec<bool> = self.hits_readback()?.wait(&device)?;
        // Sums hold weight 1/N per sample: after k of N samples the average is sum * N / k.
        let finish = |sums: &[f32], done: usize| -> Vec<f32> {
            let scale = samples.len() as f32 / done.max(1) as f32;
            sums.iter()
                .zip(&hit)
                .map(|(&v, &hit)| if hit { (v * scale).clamp(0.0, 1.0) } else { 1.0 })
                .collect()
        };
        let read_sums = |encoder: wgpu::CommandEncoder| -> Result<Vec<f32>, RenderError> {
            let sums = Readback::buffer(&device, &self.queue, encoder, &accumulated, pixels * 4, |mapped| {
                Ok(mapped.rows().flat_map(readback::f32s).collect())
            });
            sums.wait(&device)
        };

        if let Some(tick) = self.reference_ticker.as_mut() {
            tick(0, samples.len() as u32);
        }
        let mut encoder = device.create_command_encoder(&Default::default());
        encoder.clear_buffer(&accumulated, 0, None);
        let mut batch = if progress.is_some() { first_batch.max(1) } else { max_batch.max(1) };
        let mut batch_end = batch;
        for (i, _) in samples.iter().enumerate() {
            let offset = (i as u64 * DYNAMIC_STRIDE) as u32;
            {
                let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some("reference shadow pass"),
                    color_attachments: &[],
                    depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                        view: &maps.layer_views[0],
                        depth_ops: Some(wgpu::Operations {
                            load: wgpu::LoadOp::Clear(1.0),
                            store: wgpu::StoreOp::Store,
                        }),
                        stencil_ops: None,
                    }),
                    timestamp_writes: None,
                    occlusion_query_set: None,
                    multiview_mask: None,
                });
                pass.set_pipeline(&shadow_pipeline);
                pass.set_bind_group(0, &view_group, &[offset]);
                scene_gpu.draw(&mut pass, 1);
            }
            {
                let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some("reference accumulate"),
                    timestamp_writes: None,
                });
                pass.set_pipeline(&self.pipelines.reference);
                pass.set_bind_group(0, &io_group, &[]);
                pass.set_bind_group(1, &light_group, &[offset]);
                pass.dispatch_workgroups(width.div_ceil(8), height.div_ceil(8), 1);
            }
            let done = i + 1;
            if done == batch_end && done < samples.len() {
                let finished =
                    std::mem::replace(&mut encoder, device.create_command_encoder(&Default::default()));
                match progress.as_mut() {
                    Some(report) => {
                        let sums = read_sums(finished)?;
                        if !report(done as u32, samples.len() as u32, &finish(&sums, done)) {
                            return Ok(None);
                        }
                    }
                    None => {
                        self.queue.submit([finished.finish()]);
                        if let Some(tick) = self.reference_ticker.as_mut() {
                            let _ = self.device.poll(wgpu::PollType::wait_indefinitely());
                            tick(done as u32, samples.len() as u32);
                        }
                    }
                }
                batch = (batch * 2).min(max_batch.max(1));
                batch_end = done + batch;
            }
        }
        let result = finish(&read_sums(encoder)?, samples.len());
        if let Some(tick) = self.reference_ticker.as_mut() {
            tick(samples.len() as u32, samples.len() as u32);
        }
        if let Some(report) = progress.as_mut() {
            report(samples.len() as u32, samples.len() as u32, &result);
        }
        Ok(Some(result))
    }
}

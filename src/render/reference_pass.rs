//! Ground truth on the GPU: for each light sample, render a hard shadow map and add the hard
//! visibility of every camera pixel (from the analysis pass's positions and normals). A
//! [`GroundTruth`] is one under way, a batch of samples at a time: a caller that cannot wait for
//! the GPU (a browser's frame) submits a batch, returns, and collects its sums on a later call.

use super::gpu_types::{DYNAMIC_STRIDE, ReferenceInfoGpu};
use super::readback::{self, GpuWait, Readback};
use super::targets::ShadowMaps;
use super::targets::ShadowPipelineKey;
use super::{RenderError, Renderer, shadow_view_group};
use crate::reference;
use crate::scene::Scene;
use crate::shadow::{LightViewGpu, ShadowParamsGpu};

/// Samples recorded per command buffer where only the finished average is read (keeps a
/// submission's size bounded).
const BATCH: usize = 32;

/// Called after each batch of a progressive ground truth with (samples done, samples in all,
/// the average so far); returning false stops the accumulation.
pub type ReferenceProgress<'a> = &'a mut dyn FnMut(u32, u32, &[f32]) -> bool;

/// How a ground truth's samples are split into submissions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Batches {
    /// Samples in the first batch; each later one doubles, up to `max`.
    pub first: usize,
    pub max: usize,
    /// Read the sums back after every batch (a partial average each), not only after the last.
    pub read_each: bool,
}

impl Batches {
    /// Batches of `first` samples doubling up to `max`, each read back.
    pub fn progressive(first: usize, max: usize) -> Self {
        Self { first: first.max(1), max: max.max(1), read_each: true }
    }

    /// Only the finished average read back.
    pub fn whole() -> Self {
        Self { first: BATCH, max: BATCH, read_each: false }
    }
}

/// The average after a batch: `done` of `total` samples, per pixel of the frame.
#[derive(Clone, Debug, PartialEq)]
pub struct GroundTruthProgress {
    pub done: u32,
    pub total: u32,
    pub values: Vec<f32>,
}

impl GroundTruthProgress {
    pub fn finished(&self) -> bool {
        self.done == self.total
    }
}

/// A ground truth under way over the frame that was last rendered when it started: its GPU
/// resources, the samples recorded so far and the read-back of their sums. The renderer it came
/// from must render nothing else until it is finished (its batches draw the uploaded scene).
pub struct GroundTruth {
    samples: usize,
    /// Shadow views each sample renders (a point light's six faces, else one).
    views_per_sample: usize,
    /// Pixels of the frame, one sum each.
    pixels: u64,
    size: (u32, u32),
    batches: Batches,
    /// Samples in the next batch.
    batch: usize,
    /// Samples recorded so far.
    recorded: usize,
    maps: ShadowMaps,
    accumulated: wgpu::Buffer,
    io_group: wgpu::BindGroup,
    light_group: wgpu::BindGroup,
    view_group: wgpu::BindGroup,
    shadow_pipeline: wgpu::RenderPipeline,
    /// The scene upload the batches draw.
    scene_upload: u64,
    /// Which pixels hit a surface (the others are 1): on their way until the first sums come.
    hits: Vec<bool>,
    hits_coming: Option<Readback<Vec<bool>>>,
    /// The sums of the last batch submitted, on their way.
    sums_coming: Option<Readback<Vec<f32>>>,
}

impl GroundTruth {
    /// Sums hold weight 1/N per sample: after k of N samples the average is sum * N / k.
    fn average(&self, sums: &[f32]) -> Vec<f32> {
        let scale = self.samples as f32 / self.recorded.max(1) as f32;
        sums.iter()
            .zip(&self.hits)
            .map(|(&v, &hit)| if hit { (v * scale).clamp(0.0, 1.0) } else { 1.0 })
            .collect()
    }
}

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
        let mut truth = self.start_ground_truth(scene, light_index, Batches::whole())?;
        Ok(self.wait_ground_truth(&mut truth)?.values)
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
        let batches = Batches::progressive(first_batch, max_batch);
        let mut truth = self.start_ground_truth(scene, light_index, batches)?;
        loop {
            let step = self.wait_ground_truth(&mut truth)?;
            let go_on = progress(step.done, step.total, &step.values);
            if step.finished() {
                return Ok(Some(step.values));
            }
            if !go_on {
                return Ok(None);
            }
            self.next_ground_truth_batch(&mut truth)?;
        }
    }

    /// Start light `light_index`'s ground truth over the last frame (which must have rendered
    /// the analysis targets): its first batch is submitted here (with `Batches::whole`, all of
    /// it). Collect each batch with `ground_truth_progress`, then ask for the next.
    pub fn start_ground_truth(
        &mut self,
        scene: &Scene,
        light_index: usize,
        batches: Batches,
    ) -> Result<GroundTruth, RenderError> {
        self.guarded(|r| {
            let mut truth = r.prepare_ground_truth(scene, light_index, batches)?;
            if let Some(tick) = r.reference_ticker.as_mut() {
                tick(0, truth.samples as u32);
            }
            r.submit_batches(&mut truth)?;
            Ok(truth)
        })
    }

    /// Record and submit the ground truth's next batch, once the last one's sums have been
    /// collected.
    pub fn next_ground_truth_batch(&mut self, truth: &mut GroundTruth) -> Result<(), RenderError> {
        self.guarded(|r| r.submit_batches(truth))
    }

    /// The average after the batch submitted last, once its sums have arrived (None before;
    /// `GpuWait::Block` waits for them).
    pub fn ground_truth_progress(
        &mut self,
        truth: &mut GroundTruth,
        wait: GpuWait,
    ) -> Result<Option<GroundTruthProgress>, RenderError> {
        let sums = truth
            .sums_coming
            .take()
            .ok_or_else(|| RenderError::Usage("no batch of the ground truth is on its way".into()))?;
        if !sums.arrived(&self.device, wait)? {
            truth.sums_coming = Some(sums);
            return Ok(None);
        }
        if let Some(hits) = truth.hits_coming.take() {
            if !hits.arrived(&self.device, wait)? {
                (truth.hits_coming, truth.sums_coming) = (Some(hits), Some(sums));
                return Ok(None);
            }
            truth.hits = hits.finish()?;
        }
        let values = truth.average(&sums.finish()?);
        let (done, total) = (truth.recorded as u32, truth.samples as u32);
        if done == total
            && let Some(tick) = self.reference_ticker.as_mut()
        {
            tick(total, total);
        }
        Ok(Some(GroundTruthProgress { done, total, values }))
    }

    /// `ground_truth_progress`, waited for.
    fn wait_ground_truth(&mut self, truth: &mut GroundTruth) -> Result<GroundTruthProgress, RenderError> {
        self.ground_truth_progress(truth, GpuWait::Block)?
            .ok_or_else(|| RenderError::Readback("the ground truth's sums did not arrive".into()))
    }

    /// The ground truth's samples, lights and bind groups, on the last frame's analysis targets.
    fn prepare_ground_truth(
        &mut self,
        scene: &Scene,
        light_index: usize,
        batches: Batches,
    ) -> Result<GroundTruth, RenderError> {
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
        let samples: Vec<LightViewGpu> =
            reference::sample_lights(light, request.time_s, scene.shadow.reference_samples as usize);
        let device = self.device.clone();
        let (width, height) = request.size;
        let pixels = u64::from(width) * u64::from(height);

        // Each sample's views (a point light's six faces) into layers 0.., one after the other.
        let views_per_sample = samples.first().map_or(1, |s| reference::sample_views(light, s).len());
        let maps = ShadowMaps::new(&device, light.shadow_map_size, views_per_sample as u32);
        let dynamic_buffer = |label: &str, count: usize, usage: wgpu::BufferUsages| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: DYNAMIC_STRIDE * count as u64,
                usage: usage | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        // The accumulating dispatch reads its sample from storage (layouts::LightBinding).
        let light_buffer = dynamic_buffer("reference lights", samples.len(), wgpu::BufferUsages::STORAGE);
        let view_buffer =
            dynamic_buffer("reference views", samples.len() * views_per_sample, wgpu::BufferUsages::UNIFORM);
        for (i, sample) in samples.iter().enumerate() {
            let offset = i as u64 * DYNAMIC_STRIDE;
            self.queue.write_buffer(&light_buffer, offset, bytemuck::bytes_of(sample));
            for (v, view) in reference::sample_views(light, sample).iter().enumerate() {
                let offset = (i * views_per_sample + v) as u64 * DYNAMIC_STRIDE;
                self.queue.write_buffer(&view_buffer, offset, bytemuck::bytes_of(view));
            }
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
                size: std::num::NonZeroU64::new(std::mem::size_of::<LightViewGpu>() as u64),
            }),
            &params,
            &maps,
            None,
        );
        let view_group = shadow_view_group(&device, &self.layouts, &view_buffer);
        // The reference's own shadow pass: no hardware bias and no culling, whatever the user
        // set, so their effects show up as error rather than being copied into the truth.
        let key = ShadowPipelineKey {
            depth_bias_constant: 0,
            depth_bias_slope_bits: 0,
            cull_front_faces: false,
            stores_distance: light.stores_distance(),
        };
        let shadow_pipeline = self.pipelines.shadow(&device, key).clone();
        let scene_upload =
            self.scene_gpu.as_ref().ok_or_else(|| RenderError::Usage("no scene uploaded".into()))?.generation;
        Ok(GroundTruth {
            samples: samples.len(),
            views_per_sample,
            pixels,
            size: (width, height),
            batches,
            batch: batches.first,
            recorded: 0,
            maps,
            accumulated,
            io_group,
            light_group,
            view_group,
            shadow_pipeline,
            scene_upload,
            hits: Vec::new(),
            hits_coming: Some(self.hits_readback()?),
            sums_coming: None,
        })
    }

    /// Record the next batch and submit it with its sums' read-back; where only the finished
    /// average is read (`Batches::read_each` false), every batch up to the last.
    fn submit_batches(&mut self, truth: &mut GroundTruth) -> Result<(), RenderError> {
        if truth.sums_coming.is_some() || truth.recorded >= truth.samples {
            return Err(RenderError::Usage("the ground truth has no batch to submit now".into()));
        }
        let scene_gpu = self.scene_gpu.as_ref().filter(|s| s.generation == truth.scene_upload);
        let scene_gpu = scene_gpu
            .ok_or_else(|| RenderError::Usage("the scene changed under a ground truth in progress".into()))?;
        let (width, height) = truth.size;
        loop {
            let mut encoder = self.device.create_command_encoder(&Default::default());
            if truth.recorded == 0 {
                encoder.clear_buffer(&truth.accumulated, 0, None);
            }
            let end = (truth.recorded + truth.batch).min(truth.samples);
            for i in truth.recorded..end {
                let offset = (i as u64 * DYNAMIC_STRIDE) as u32;
                for v in 0..truth.views_per_sample {
                    let view_offset = ((i * truth.views_per_sample + v) as u64 * DYNAMIC_STRIDE) as u32;
                    let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                        label: Some("reference shadow pass"),
                        color_attachments: &[],
                        depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                            view: &truth.maps.layer_views[v],
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
                    pass.set_pipeline(&truth.shadow_pipeline);
                    pass.set_bind_group(0, &truth.view_group, &[view_offset]);
                    scene_gpu.draw(&mut pass, 1);
                }
                let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some("reference accumulate"),
                    timestamp_writes: None,
                });
                pass.set_pipeline(&self.pipelines.reference);
                pass.set_bind_group(0, &truth.io_group, &[]);
                pass.set_bind_group(1, &truth.light_group, &[offset]);
                pass.dispatch_workgroups(width.div_ceil(8), height.div_ceil(8), 1);
            }
            truth.recorded = end;
            truth.batch = (truth.batch * 2).min(truth.batches.max);
            if end == truth.samples || truth.batches.read_each {
                let sums = Readback::buffer(
                    &self.device,
                    &self.queue,
                    encoder,
                    &truth.accumulated,
                    truth.pixels * 4,
                    |mapped| Ok(mapped.rows().flat_map(readback::f32s).collect()),
                );
                truth.sums_coming = Some(sums);
                return Ok(());
            }
            self.queue.submit([encoder.finish()]);
            if let Some(tick) = self.reference_ticker.as_mut() {
                // The count is what the GPU has done, not what was recorded.
                let _ = GpuWait::Block.poll(&self.device);
                tick(end as u32, truth.samples as u32);
            }
        }
    }
}

//! The renderers a scheduler owns and the stages of a job (image, maps, details, ground truths),
//! the same whichever scheduler runs them. A stage never waits for the GPU unless told to: it
//! submits its work and returns, and the next call collects the read-backs once they are there
//! (`GpuWait::Poll`, a page's frames) or waits for them (`GpuWait::Block`, the render thread).

use super::details::DetailsComing;
use super::keys::{MapKey, ReferenceKey};
use super::maps::MapsComing;
use super::truths::{ProbeTruths, ViewTruth};
use super::{RenderEvent, RenderJob, RenderOutput};
use crate::render::{Frame, FrameRequest, GpuWait, PassTimes, Readback, RenderError, Renderer};
use web_time::Instant;

/// Where a job is: the stage to run next, with the work it has under way.
pub(super) enum Stage {
    /// The image (and the A/B side) to render: what goes on screen first.
    Image,
    /// The image rendered, its bytes on their way.
    ImageComing(Box<ImageComing>),
    /// The shadow-map pictures, read one after another.
    Maps(Box<MapsComing>),
    /// The analysis the overlays draw and the probe, to start.
    Details,
    /// The analysis's read-backs and the probe under way.
    DetailsComing(Box<DetailsComing>),
    /// The ground truths at the probe (from the probe's frame, the last one rendered).
    ProbeReference(Box<ProbeTruths>),
    /// The homework check, where the job carries one (on renderers of its own, so the view's
    /// keeps its frame for the view's ground truth), a piece at a time.
    Homework,
    /// The view's ground truth, to start.
    ViewReference,
    /// The view's ground truth under way.
    ViewReferenceComing(Box<ViewTruth>),
    Done,
}

impl Stage {
    pub(super) fn is_done(&self) -> bool {
        matches!(self, Stage::Done)
    }
}

/// The worker's renderers: `a` for the view, `b` for the A/B split's right side (made on first use).
pub(super) struct Renderers {
    pub(super) device: wgpu::Device,
    queue: wgpu::Queue,
    pub(super) a: Renderer,
    b: Option<Renderer>,
    /// What the last map picture sent was drawn from.
    pub(super) last_map: Option<MapKey>,
    /// Ground truths at probes finished lately, newest last: what each depends on, the value at
    /// the probed pixel and the samples averaged.
    pub(super) probe_truths: Vec<(ReferenceKey, f32, u32)>,
    /// The view's last finished ground truth.
    pub(super) view_truth: Option<(ReferenceKey, Vec<f32>, u32)>,
    homework: super::homework::HomeworkRunner,
}

/// Renderers on a device of their own (the desktop: the device opens at once).
#[cfg(not(target_arch = "wasm32"))]
pub(super) fn open(adapter: &wgpu::Adapter) -> Result<Renderers, RenderError> {
    let descriptor = crate::render::device_descriptor(adapter, "shadowlab render worker");
    let (device, queue) = pollster::block_on(adapter.request_device(&descriptor))
        .map_err(|e| RenderError::Device(e.to_string()))?;
    open_on(device, queue)
}

/// Renderers on a device already open (a page's: a browser's adapter gives one device).
pub(super) fn open_on(device: wgpu::Device, queue: wgpu::Queue) -> Result<Renderers, RenderError> {
    let a = Renderer::new(&device, &queue)?;
    Ok(Renderers {
        device,
        queue,
        a,
        b: None,
        last_map: None,
        probe_truths: Vec::new(),
        view_truth: None,
        homework: Default::default(),
    })
}

/// The image's bytes on their way, with the frame the GPU rendered.
pub(super) struct ImageComing {
    frame: Frame,
    bytes: Readback<ImageBytes>,
}

/// The view's colour, the A/B side's and the passes' GPU times.
struct ImageBytes {
    color: image::RgbaImage,
    color_b: Option<image::RgbaImage>,
    pass_times: Option<PassTimes>,
}

impl Renderers {
    /// Block until the GPU has done everything submitted so far.
    pub(super) fn wait_for_gpu(&self) -> Result<(), RenderError> {
        GpuWait::Block.poll(&self.device)
    }

    /// Run `stage` of job `id`, telling `send` what it finished; returns the stage to run next
    /// (the same one where read-backs are still on their way). `cancelled` says a newer job is
    /// waiting (the details and ground truths are then moot); `wait` whether to wait for the GPU.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn run_stage(
        &mut self,
        id: u64,
        job: &RenderJob,
        stage: Stage,
        started: Instant,
        send: &mut dyn FnMut(RenderEvent),
        cancelled: &dyn Fn() -> bool,
        wait: GpuWait,
    ) -> Stage {
        let shows_image = matches!(stage, Stage::Image | Stage::ImageComing(_) | Stage::Maps(_));
        let next = match stage {
            Stage::Image => self.submit_image(job).map(|coming| Stage::ImageComing(Box::new(coming))),
            Stage::ImageComing(coming) => self.image_step(id, job, *coming, started, send, wait),
            Stage::Maps(maps) => self.maps_step(job, *maps, send, wait),
            // A newer request makes these details moot: it brings its own.
            Stage::Details if cancelled() => Ok(Stage::Done),
            Stage::Details => self.start_details(job).map(|d| Stage::DetailsComing(Box::new(d))),
            Stage::DetailsComing(details) => self.details_step(id, job, *details, started, send, wait),
            Stage::ProbeReference(truths) => self.probe_truths_step(id, job, *truths, send, cancelled, wait),
            Stage::Homework if cancelled() => Ok(Stage::Done),
            Stage::Homework => {
                let Some(homework) = &job.homework else { return Stage::ViewReference };
                let (size, time_s) = (job.request.size, job.request.time_s);
                let stepped =
                    self.homework.step(&self.device, &self.queue, homework, &job.scene, size, time_s, wait);
                match stepped.transpose() {
                    None => Ok(Stage::Homework),
                    Some(outcome) => {
                        send(RenderEvent::Homework { job: id, generation: homework.generation, outcome });
                        Ok(Stage::ViewReference)
                    }
                }
            }
            Stage::ViewReference if !(job.reference && job.analysis) || cancelled() => Ok(Stage::Done),
            Stage::ViewReference => self.start_view_truth(id, job, send),
            Stage::ViewReferenceComing(truth) => self.view_truth_step(id, *truth, send, cancelled, wait),
            Stage::Done => Ok(Stage::Done),
        };
        next.unwrap_or_else(|e| {
            if shows_image {
                // The views may not have what was last read back: read it all next time.
                self.last_map = None;
            }
            send(RenderEvent::Failed { job: id, message: e.to_string() });
            Stage::Done
        })
    }

    /// Render the job's image (and the A/B side) and submit their read-backs. The overlays'
    /// analysis comes from the same pass (one filtering, not two); the details read it back
    /// after the image is on its way.
    fn submit_image(&mut self, job: &RenderJob) -> Result<ImageComing, RenderError> {
        let request =
            FrameRequest { final_color: true, analysis: job.analysis, timestamps: true, ..job.request };
        let frame = self.a.render(&job.scene, &request)?;
        let times = self.a.pass_times_readback();
        let color = self.a.color_readback()?;
        let color_b = match job.technique_b {
            Some(technique) => {
                if self.b.is_none() {
                    self.b = Some(Renderer::new(&self.device, &self.queue)?);
                }
                let b = self.b.as_mut().ok_or_else(|| RenderError::Usage("no B renderer".into()))?;
                let mut scene_b = job.scene.clone();
                scene_b.shadow.technique = technique;
                b.render(&scene_b, &request)?;
                b.color_readback()?.map(|color| Ok(Some(color)))
            }
            None => Readback::ready(None),
        };
        let bytes = color
            .zip(color_b)
            .zip(times)
            .map(|((color, color_b), pass_times)| Ok(ImageBytes { color, color_b, pass_times }));
        Ok(ImageComing { frame, bytes })
    }

    /// Once the image is there: send it, and start on the maps.
    fn image_step(
        &mut self,
        id: u64,
        job: &RenderJob,
        coming: ImageComing,
        started: Instant,
        send: &mut dyn FnMut(RenderEvent),
        wait: GpuWait,
    ) -> Result<Stage, RenderError> {
        if !coming.bytes.arrived(&self.device, wait)? {
            return Ok(Stage::ImageComing(Box::new(coming)));
        }
        let ImageBytes { color, color_b, pass_times } = coming.bytes.finish()?;
        send(RenderEvent::Frame(Box::new(RenderOutput {
            job: id,
            preview: job.preview,
            size: coming.frame.request.size,
            color,
            color_b,
            lights: coming.frame.lights,
            views: coming.frame.views,
            params: coming.frame.params,
            details_follow: job.wants_details(),
            pass_times,
            render_ms: started.elapsed().as_secs_f64() * 1e3,
        })));
        let maps = self.maps_to_read(id, job);
        self.maps_step(job, maps, send, wait)
    }
}

impl RenderJob {
    /// The stage after the probe's: the homework check where there is one, then the view's
    /// ground truth.
    pub(super) fn after_probe(&self) -> Stage {
        if self.homework.is_some() { Stage::Homework } else { Stage::ViewReference }
    }

    /// A probe or overlays to work out after the image.
    pub(super) fn wants_details(&self) -> bool {
        !self.scene.lights.is_empty() && (self.probe.is_some() || self.analysis)
    }
}

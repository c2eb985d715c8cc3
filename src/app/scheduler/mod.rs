//! Render scheduling: the app asks for frames (`RenderJob`s) and hears back (`RenderEvent`s)
//! through a [`RenderScheduler`], which knows nothing of egui. Two of them: [`WorkerThread`]
//! renders on a thread and device of its own, so that a slow render never holds up the window
//! (native); [`FrameDriven`] renders on the caller's thread a step at a time, from the UI's frame
//! callback, and never waits for the GPU (what a browser, which has no threads to give and maps a
//! buffer only between frames, needs; tested natively too). Both run the same stages (`Stage`,
//! a file each, on the `Renderers` of `renderers.rs`): each submits its work and collects its
//! read-backs on a later call, waiting for them on the thread, asking after them in the frames.
//!
//! Newest request wins: requests still waiting when a render ends are dropped, all but the last;
//! a ground truth in progress stops at its next batch when a newer request arrives, and reports
//! its partial average after every batch so the view can show it filling in. The ground truth at
//! the probe comes first (the probe panel and the lesson text quote it), then the view's. Both are
//! kept: a job whose ground truth depends on nothing that changed gets it again at once.

mod details;
mod frame;
mod homework;
mod image_stage;
mod keys;
mod maps;
mod renderers;
#[cfg(not(target_arch = "wasm32"))]
mod thread;
mod truths;

pub use frame::FrameDriven;
pub use homework::HomeworkJob;
#[cfg(not(target_arch = "wasm32"))]
pub use thread::WorkerThread;

use details::DetailsComing;
use image_stage::ImageComing;
use maps::MapsComing;
use renderers::Renderers;
use truths::{ProbeTruths, ViewTruth};

use crate::probe::ProbeReport;
use crate::render::{Analysis, FrameRequest, GpuWait, PassTimes};
use crate::scene::{Scene, Technique};
use crate::shadow::{DepthImage, LightGpu, ShadowParamsGpu, ShadowViewGpu};
use std::time::Duration;
use web_time::Instant;

/// Something that renders the app's jobs and reports back. `submit` never waits for the GPU;
/// `poll` returns what has finished since the last call (a frame-driven scheduler does the next
/// piece of work there).
pub trait RenderScheduler {
    /// Queue a render; anything older that has not started is dropped. Returns the job's id.
    fn submit(&mut self, job: RenderJob) -> u64;
    /// Events that have arrived since the last call.
    fn poll(&mut self) -> Vec<RenderEvent>;
    /// A frame is being rendered (or waits to be).
    fn busy(&self) -> bool;
    /// How long the views have been waiting for a frame.
    fn waiting_for(&self) -> Option<Duration>;
    /// Work waits for the next `poll`: the caller should come back next frame, not only when
    /// woken (a frame-driven scheduler renders only when polled).
    fn needs_polling(&self) -> bool {
        false
    }
}

/// What the app wants rendered.
#[derive(Clone)]
pub struct RenderJob {
    pub scene: Scene,
    /// Time, size (the resolution rendered at) and the light the analysis describes.
    pub request: FrameRequest,
    /// Probe here (full-quality renders only).
    pub probe: Option<ProbeSpot>,
    /// Render the analysis targets of the selected light (the overlays need them).
    pub analysis: bool,
    /// Accumulate the ground truth of the selected light (needs `analysis`).
    pub reference: bool,
    /// Accumulate the ground truth at the probe for these lights (needs `probe`).
    pub probe_reference: Vec<usize>,
    /// Work out VSM's light bleeding for the selected light (needs `analysis`).
    pub bleeding: bool,
    /// Read back the level of the selected light's VSM moments the filter reads (needs
    /// `analysis`; VSM techniques only).
    pub moments: bool,
    /// The A/B split's right side: the same frame with this technique.
    pub technique_b: Option<Technique>,
    /// A small picture of every light's map (several lights, full quality).
    pub thumbnails: bool,
    /// A reduced-quality render while a value is being dragged.
    pub preview: bool,
    /// Texels per side of the shadow-map picture at most (the map is subsampled beyond).
    pub map_texels: u32,
    /// A student's homework to check beside the frame (full-quality renders only).
    pub homework: Option<HomeworkJob>,
}

/// A pixel to probe, in a frame of its own size: the view's, or a lesson's own frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProbeSpot {
    pub pixel: (u32, u32),
    pub frame: (u32, u32),
}

/// The selected light's shadow map (its first view's): the depths (for the hover readout and the
/// probe picture) and the picture shown, with the depth range of its colour bar (world units).
pub struct MapView {
    /// The map (a light with several: its first's; all are in `tiles`).
    pub depth: DepthImage,
    pub view: ShadowViewGpu,
    /// Which of the frame's shadow views it is (a light with several: its first).
    pub index: usize,
    /// A light with several maps (a point light's six faces, a sun's cascades): each map with
    /// its view, in view order (`image` tiles them by `MapsLayout`); empty for a light with one.
    pub tiles: Vec<(DepthImage, ShadowViewGpu)>,
    pub image: image::RgbaImage,
    pub range: (f32, f32),
}

/// One finished render.
pub struct RenderOutput {
    pub job: u64,
    pub preview: bool,
    /// The resolution the camera view was rendered at, pixels.
    pub size: (u32, u32),
    pub color: image::RgbaImage,
    pub color_b: Option<image::RgbaImage>,
    /// The lights, their shadow views and the shadow parameters as the GPU had them.
    pub lights: Vec<LightGpu>,
    pub views: Vec<ShadowViewGpu>,
    pub params: ShadowParamsGpu,
    /// A `Details` event for this job follows (the probe, the overlays' analysis).
    pub details_follow: bool,
    /// GPU time of the last frame's passes (where the adapter has timestamps).
    pub pass_times: Option<PassTimes>,
    /// Wall-clock time of the whole job (renders, read-backs, probe), milliseconds.
    pub render_ms: f64,
}

/// The shadow-map pictures of one frame, sent after its image.
pub struct Maps {
    pub job: u64,
    /// The selected light's map; None where it is the same as in the last frame sent (the views
    /// keep the picture they have).
    pub map: Option<MapView>,
    pub thumbnails: Vec<image::RgbaImage>,
}

/// The probe's report: None where no probe was asked for, Some(Err) where it failed.
pub type ProbeOutcome = Option<Result<ProbeReport, String>>;

/// What a full-quality frame adds after its image: the probe and the analysis the overlays draw.
pub struct Details {
    pub job: u64,
    pub probe: ProbeOutcome,
    pub analysis: Option<Analysis>,
    /// Wall-clock time of the whole job so far, milliseconds.
    pub render_ms: f64,
}

pub enum RenderEvent {
    /// The worker's device is ready (adapter description) or could not be opened.
    Ready(Result<String, String>),
    /// The image first: it goes on screen while the maps and the details are worked out.
    Frame(Box<RenderOutput>),
    Maps(Box<Maps>),
    Details(Box<Details>),
    /// The ground truth so far: `done` of `total` light samples averaged.
    Reference {
        job: u64,
        done: u32,
        total: u32,
        values: Vec<f32>,
    },
    /// The ground truth at the probe so far, for light `light`: `done` of `total` samples
    /// averaged at the probed pixel.
    ProbeReference {
        job: u64,
        light: usize,
        done: u32,
        total: u32,
        value: f32,
    },
    /// The homework check of `generation` (of the program the job carried), or why it failed.
    Homework {
        job: u64,
        generation: u64,
        /// Which of the page's lights the check was of (None: the first).
        page_light: Option<crate::homework::student_light::PageLight>,
        outcome: Result<std::sync::Arc<crate::homework::CheckOutcome>, String>,
    },
    Failed {
        job: u64,
        message: String,
    },
}

/// What a scheduler remembers of the jobs it was given: the newest submitted, the newest
/// finished, and since when the views wait (both schedulers keep the same books).
#[derive(Default)]
struct JobBook {
    latest: u64,
    finished: u64,
    submitted_at: Option<web_time::Instant>,
}

impl JobBook {
    fn submitted(&mut self, id: u64) {
        self.latest = id;
        self.submitted_at.get_or_insert_with(web_time::Instant::now);
    }

    /// Note what `events` finish.
    fn heard(&mut self, events: &[RenderEvent]) {
        for event in events {
            match event {
                // A frame arrived: the views are waiting only for the newer ones from now on.
                RenderEvent::Frame(_) => self.submitted_at = Some(web_time::Instant::now()),
                // The maps complete a job (its details, if any, follow).
                RenderEvent::Maps(maps) => self.finished = self.finished.max(maps.job),
                RenderEvent::Details(details) => self.finished = self.finished.max(details.job),
                RenderEvent::Failed { job, .. } => self.finished = self.finished.max(*job),
                _ => {}
            }
        }
        if !self.busy() {
            self.submitted_at = None;
        }
    }

    fn busy(&self) -> bool {
        self.finished < self.latest
    }

    fn waiting_for(&self) -> Option<Duration> {
        self.submitted_at.filter(|_| self.busy()).map(|t| t.elapsed())
    }
}

/// Where a job is: the stage to run next, with the work it has under way. A stage never waits
/// for the GPU unless told to: it submits its work and returns, and the next call collects the
/// read-backs once they are there (`GpuWait::Poll`, a page's frames) or waits for them
/// (`GpuWait::Block`, the render thread).
enum Stage {
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
    fn is_done(&self) -> bool {
        matches!(self, Stage::Done)
    }
}

impl Renderers {
    /// Run `stage` of job `id`, telling `send` what it finished; returns the stage to run next
    /// (the same one where read-backs are still on their way). `cancelled` says a newer job is
    /// waiting (the details and ground truths are then moot); `wait` whether to wait for the GPU.
    #[allow(clippy::too_many_arguments)]
    fn run_stage(
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
                // Judged at the size the command line judges at, whatever the panel's: the same
                // homework gets the same findings in the app and in a class report.
                let (size, time_s) = (crate::homework::CHECK_SIZE, job.request.time_s);
                let stepped =
                    self.homework.step(&self.device, &self.queue, homework, &job.scene, size, time_s, wait);
                match stepped.transpose() {
                    None => Ok(Stage::Homework),
                    Some(outcome) => {
                        let page_light = homework.page_light;
                        send(RenderEvent::Homework {
                            job: id,
                            generation: homework.generation,
                            page_light,
                            outcome,
                        });
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
}

impl RenderJob {
    /// The stage after the probe's: the homework check where there is one, then the view's
    /// ground truth.
    fn after_probe(&self) -> Stage {
        if self.homework.is_some() { Stage::Homework } else { Stage::ViewReference }
    }

    /// A probe or overlays to work out after the image.
    fn wants_details(&self) -> bool {
        !self.scene.lights.is_empty() && (self.probe.is_some() || self.analysis)
    }
}

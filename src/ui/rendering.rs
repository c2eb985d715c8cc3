//! Render scheduling: what the app asks the render worker for, and what it does with the answers.
//! The views always show the last finished frame; while a value is being dragged they ask for
//! previews (half resolution or less, PCSS with fewer taps) and refine once it is let go.

use super::{ProbeAt, ShadowlabApp};
use crate::app::scheduler::{HomeworkJob, ProbeSpot, RenderEvent, RenderJob, RenderOutput, RenderScheduler};
use crate::render::{Analysis, FrameRequest, PassTimes};
use crate::scene::Technique;
use crate::shadow::{DepthImage, LightGpu, LightViewGpu, ShadowParamsGpu, ShadowViewGpu};
use crate::views::View;
use crate::views::overlays::Overlay;
use std::time::Duration;
use web_time::Instant;

/// Show "rendering..." over a view that has waited this long for its frame.
pub const SLOW_RENDER: Duration = Duration::from_millis(150);
/// What a preview may take, milliseconds: the preview resolution adapts to keep views refreshing
/// about ten times a second (half the view's width and height, down to a quarter).
const PREVIEW_BUDGET_MS: f64 = 100.0;
const PREVIEW_DIVISOR_MIN: u32 = 2;
const PREVIEW_DIVISOR_MAX: u32 = 4;
/// PCSS taps (blocker search and filter, each) at most while dragging.
const PREVIEW_PCSS_SAMPLES: u32 = 16;
/// Texels per side of the shadow-map picture: enough for the panel, and every texel once zoomed.
const MAP_PICTURE_TEXELS: u32 = 1024;
const MAP_PICTURE_TEXELS_ZOOMED: u32 = 2048;

/// What the views show: the last finished render, as textures, with what it was rendered from.
#[derive(Default)]
pub struct Shown {
    pub camera: Option<egui::TextureHandle>,
    pub camera_b: Option<egui::TextureHandle>,
    pub color: Option<image::RgbaImage>,
    pub color_b: Option<image::RgbaImage>,
    /// The selected light's shadow map (the last one a scene with lights sent).
    pub map: Option<MapPicture>,
    /// One small picture per light (several lights only).
    pub thumbnails: Vec<egui::TextureHandle>,
    /// The overlays' analysis of the frame shown, once it came.
    pub analysis: Option<Analysis>,
    /// The lights and their shadow views as the GPU saw them in that frame.
    pub lights: Vec<LightGpu>,
    pub views: Vec<ShadowViewGpu>,
    /// The shadow parameters of that frame (the views read these, not the scene's newer ones).
    pub params: ShadowParamsGpu,
    /// Resolution it was rendered at, pixels.
    pub size: (u32, u32),
    pub preview: bool,
    pub pass_times: Option<PassTimes>,
    /// Wall-clock time of the job (renders, read-backs, probe), milliseconds.
    pub render_ms: f64,
    /// Ground truth in progress or done: (samples averaged, samples in all).
    pub reference_progress: Option<(u32, u32)>,
    /// The job whose probe report is shown.
    pub probe_job: Option<u64>,
    /// The job whose probe and analysis are still to come.
    pub details_pending: Option<u64>,
    /// Counts the changes to what is shown (the camera panel makes its pictures again after one).
    pub changes: u64,
}

/// The shadow map shown: its picture, its depths, the shadow view it was rendered from and its
/// linear depth range (world units).
pub struct MapPicture {
    pub texture: egui::TextureHandle,
    pub depth: DepthImage,
    pub view: ShadowViewGpu,
    /// Which of the frame's shadow views it is (a light with several: its first; `tiles` holds
    /// them all with their views, the picture tiled by `MapsLayout`).
    pub index: usize,
    pub tiles: Vec<(DepthImage, ShadowViewGpu)>,
    pub range: (f32, f32),
}

impl Shown {
    /// The view shows an image whose overlays are not worked out yet (a preview, or a full frame
    /// waiting for its details): they would be about other settings.
    pub fn overlays_stale(&self) -> bool {
        self.preview || self.details_pending.is_some()
    }

    /// Light `light` of the frame shown with its first shadow view (what the views of one light
    /// read).
    pub fn light_view(&self, light: usize) -> Option<LightViewGpu> {
        crate::shadow::gpu::first_view_of(&self.lights, &self.views, light).map(|(_, lv)| lv)
    }
}

/// A picture as egui takes it.
pub(super) fn color_image(image: &image::RgbaImage) -> egui::ColorImage {
    egui::ColorImage::from_rgba_unmultiplied(
        [image.width() as usize, image.height() as usize],
        image.as_raw(),
    )
}

/// What the last submitted job was, so that a preview is followed by a full-quality frame.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Submitted {
    pub job: u64,
    pub preview: bool,
    pub size: (u32, u32),
}

/// Rendering the views: the scheduler, what it sent, and what the views wait for.
pub(super) struct RenderSession {
    /// Renders the views (None where no GPU device could be had).
    pub(super) worker: Option<Box<dyn RenderScheduler>>,
    /// What the views show: the last finished render.
    pub(super) shown: Shown,
    /// The job the views wait for, and the newest one shown.
    pub(super) submitted: Submitted,
    pub(super) shown_job: u64,
    pub(super) frames_shown: u64,
    /// Why there is no GPU view (shown in place of the views).
    pub(super) gpu_error: Option<String>,
    /// The user is dragging in a view: render previews.
    pub(super) interacting: bool,
    /// Previews render at 1/preview_divisor of the view's width and height (2..=4, adapted to
    /// how long they take).
    pub(super) preview_divisor: u32,
}

impl RenderSession {
    pub(super) fn new(worker: Option<Box<dyn RenderScheduler>>, gpu_error: Option<String>) -> Self {
        Self {
            worker,
            shown: Shown::default(),
            submitted: Submitted::default(),
            shown_job: 0,
            frames_shown: 0,
            gpu_error,
            interacting: false,
            preview_divisor: PREVIEW_DIVISOR_MIN,
        }
    }
}

/// How often the homework's files are looked at for changes.
const HOMEWORK_WATCH_EVERY: std::time::Duration = std::time::Duration::from_millis(300);

impl ShadowlabApp {
    /// Look at the homework's files a few times a second; one saved in the student's editor is
    /// read again (and checked again with the next render). The camera, probe and view stay.
    pub(super) fn watch_homework(&mut self, ctx: &egui::Context) {
        if self.state.homework.is_none() {
            return;
        }
        let now = web_time::Instant::now();
        if self.homework_watched.is_some_and(|t| now - t < HOMEWORK_WATCH_EVERY) {
            ctx.request_repaint_after(HOMEWORK_WATCH_EVERY);
            return;
        }
        self.homework_watched = Some(now);
        self.state.reload_homework_if_changed();
        ctx.request_repaint_after(HOMEWORK_WATCH_EVERY);
    }

    /// Take the progress of a class check running in the background, and its report once it
    /// has ended.
    pub(super) fn watch_class(&mut self, ctx: &egui::Context) {
        let Some(class) = self.state.class.as_mut() else { return };
        class.poll();
        if class.running() {
            ctx.request_repaint_after(HOMEWORK_WATCH_EVERY);
        }
    }

    /// Take what the worker has finished; called once per UI frame.
    pub(super) fn receive_renders(&mut self, ctx: &egui::Context) {
        let Some(worker) = self.render.worker.as_mut() else { return };
        for event in worker.poll() {
            match event {
                RenderEvent::Ready(Ok(_)) => {}
                RenderEvent::Ready(Err(e)) => {
                    self.render.gpu_error = Some(e);
                    self.render.worker = None;
                    return;
                }
                RenderEvent::Frame(output) => self.show_output(ctx, *output),
                RenderEvent::Maps(maps) => self.show_maps(ctx, *maps),
                RenderEvent::Details(details) => self.show_details(*details),
                RenderEvent::Reference { job, done, total, values } => {
                    if job == self.render.submitted.job {
                        // The error legend's number, once the ground truth is all there.
                        self.state.mean_abs_error = self
                            .render
                            .shown
                            .analysis
                            .as_ref()
                            .filter(|a| done == total && a.shadow.len() == values.len())
                            .map(|a| crate::views::mean_abs_error(a, &values));
                        self.state.reference = Some(values);
                        self.render.shown.reference_progress = Some((done, total));
                        self.render.shown.changes += 1;
                    }
                }
                RenderEvent::ProbeReference { job, light, done, total, value } => {
                    if job == self.render.submitted.job && self.render.shown.probe_job == Some(job) {
                        self.show_probe_reference(light, done, total, value);
                    }
                }
                RenderEvent::Homework { job: _, generation, page_light, outcome } => {
                    if let Some(homework) = self.state.homework.as_mut() {
                        match outcome {
                            Ok(outcome) => {
                                homework.outcome = Some(outcome);
                                homework.outcome_generation = generation;
                                homework.outcome_light = page_light;
                                homework.gpu_error = None;
                            }
                            Err(message) => homework.gpu_error = Some(message),
                        }
                    }
                }
                RenderEvent::Failed { job, message } => {
                    if job == self.render.submitted.job {
                        self.render.shown.reference_progress = None;
                        self.state.probe_truth_progress.clear();
                        self.state.error = Some(super::AppError::new("rendering failed", message));
                    }
                }
            }
        }
    }

    fn show_output(&mut self, ctx: &egui::Context, out: RenderOutput) {
        // A frame older than the one shown (possible only across a worker restart) is dropped.
        if out.job < self.render.shown_job {
            return;
        }
        self.render.shown_job = out.job;
        self.render.frames_shown += 1;
        let filter = egui::TextureOptions::LINEAR;
        let upload = |slot: &mut Option<egui::TextureHandle>, name: &str, image: &image::RgbaImage| {
            let pixels = color_image(image);
            match slot {
                Some(handle) => handle.set(pixels, filter),
                None => *slot = Some(ctx.load_texture(name, pixels, filter)),
            }
        };
        upload(&mut self.render.shown.camera, "camera view", &out.color);
        match &out.color_b {
            Some(b) => upload(&mut self.render.shown.camera_b, "camera view B", b),
            None => self.render.shown.camera_b = None,
        }
        self.render.shown.color = Some(out.color);
        self.render.shown.color_b = out.color_b;
        self.render.shown.lights = out.lights;
        self.render.shown.views = out.views;
        self.render.shown.params = out.params;
        self.render.shown.size = out.size;
        self.render.shown.preview = out.preview;
        if out.preview {
            self.adapt_preview_size(out.render_ms);
        }
        self.render.shown.pass_times = out.pass_times;
        self.render.shown.render_ms = out.render_ms;
        if out.job == self.render.submitted.job {
            // The ground truths (progress since the job was asked for) follow with their events.
            self.state.mean_abs_error = None;
        }
        // The probe and the overlays' analysis follow in a `Details` event; until then the old
        // ones stay (and the overlays hide, being about other settings).
        self.render.shown.details_pending = out.details_follow.then_some(out.job);
        if !out.preview && !out.details_follow {
            // A full frame with no overlays on and no probe pinned.
            self.render.shown.analysis = None;
            if self.state.probe_at.is_none() {
                self.state.probe = None;
            }
        }
        self.render.shown.changes += 1;
    }

    /// The shadow-map pictures of the frame just shown.
    fn show_maps(&mut self, ctx: &egui::Context, maps: crate::app::scheduler::Maps) {
        if maps.job < self.render.shown_job {
            return;
        }
        if let Some(map) = maps.map {
            let texture =
                ctx.load_texture("shadow map", color_image(&map.image), egui::TextureOptions::NEAREST);
            let crate::app::scheduler::MapView { depth, view, index, tiles, range, .. } = map;
            self.render.shown.map = Some(MapPicture { texture, depth, view, index, tiles, range });
        }
        if !maps.thumbnails.is_empty() || self.render.shown.lights.len() < 2 {
            self.render.shown.thumbnails = maps
                .thumbnails
                .iter()
                .enumerate()
                .map(|(i, image)| {
                    let picture = color_image(image);
                    ctx.load_texture(format!("thumbnail {i}"), picture, egui::TextureOptions::LINEAR)
                })
                .collect();
        }
        self.render.shown.changes += 1;
    }

    fn show_details(&mut self, details: crate::app::scheduler::Details) {
        if self.render.shown.details_pending != Some(details.job) {
            return;
        }
        self.render.shown.details_pending = None;
        self.render.shown.render_ms = details.render_ms;
        self.render.shown.analysis = details.analysis;
        match details.probe {
            Some(Ok(report)) => {
                // No surface, no ground truth to wait for.
                if !report.hit {
                    self.state.probe_truth_progress.clear();
                }
                self.state.probe = Some(report);
                self.render.shown.probe_job = Some(details.job);
            }
            Some(Err(e)) => {
                self.state.probe = None;
                self.state.probe_truth_progress.clear();
                self.state.error = Some(super::AppError::new("the probe failed", e));
            }
            None if self.state.probe_at.is_none() => self.state.probe = None,
            None => {}
        }
        if self.state.focus_on_probe
            && let Some(p) = self.state.probe.as_ref().and_then(|p| p.world_position)
        {
            self.state.scene.camera.target = glam::Vec3::from(p);
            // The focused point now projects to the centre of the view, and so does the probe.
            self.state.probe_at = Some(ProbeAt::View(0.5, 0.5));
            self.state.focus_on_probe = false;
            self.state.mark_dirty();
        }
        self.render.shown.changes += 1;
    }

    /// The ground truth at the probe so far for `light`: its progress, and once complete, the
    /// value in the probe's report (where the panel and the lesson text read it).
    fn show_probe_reference(&mut self, light: usize, done: u32, total: u32, value: f32) {
        match self.state.probe_truth_progress.iter_mut().find(|(l, ..)| *l == light) {
            Some(progress) => *progress = (light, done, total),
            None => self.state.probe_truth_progress.push((light, done, total)),
        }
        if done == total
            && let Some(l) =
                self.state.probe.as_mut().and_then(|p| p.lights.iter_mut().find(|l| l.light == light))
        {
            l.visibility_reference = Some(value);
        }
    }

    /// Dynamic resolution for previews: a step smaller when one took well over the budget, a step
    /// larger when well under it (the gap between keeps it from hunting).
    fn adapt_preview_size(&mut self, render_ms: f64) {
        if render_ms > 1.4 * PREVIEW_BUDGET_MS && self.render.preview_divisor < PREVIEW_DIVISOR_MAX {
            self.render.preview_divisor += 1;
        } else if render_ms < 0.6 * PREVIEW_BUDGET_MS && self.render.preview_divisor > PREVIEW_DIVISOR_MIN {
            self.render.preview_divisor -= 1;
        }
    }

    /// Ask for a new frame where something changed; called once per frame with the camera
    /// view's size in pixels. Never waits for the GPU.
    pub(super) fn schedule_render(&mut self, view_size_px: (u32, u32)) {
        if self.render.worker.is_none() {
            return;
        }
        let preview = self.render.interacting;
        let d = self.render.preview_divisor;
        let size =
            if preview { ((view_size_px.0 / d).max(1), (view_size_px.1 / d).max(1)) } else { view_size_px };
        // A preview is followed by the full-quality frame once the drag ends.
        let refine = self.render.submitted.preview && !preview;
        let resized = self.render.submitted.size != size;
        if !(self.state.dirty || resized || refine || self.state.playing) {
            return;
        }
        if self.state.scene.lights.is_empty() {
            self.state.selected_light = 0;
        }
        let has_lights = !self.state.scene.lights.is_empty();
        let full_detail = !preview && !self.state.playing;
        let probe = self.state.probe_at.filter(|_| full_detail).map(|at| match at {
            ProbeAt::View(fx, fy) => ProbeSpot {
                pixel: (
                    ((fx * size.0 as f32) as u32).min(size.0 - 1),
                    ((fy * size.1 as f32) as u32).min(size.1 - 1),
                ),
                frame: size,
            },
            ProbeAt::LessonFrame(x, y) => ProbeSpot { pixel: (x, y), frame: crate::lessons::PROBE_FRAME },
        });
        // The analysis pass feeds the overlays only: skip it when none is on.
        let overlays_need_analysis = self.state.overlays.iter().any(|o| *o != Overlay::LightFrustum);
        let view_needs_analysis = !matches!(self.state.view, View::Final | View::ShadowMap);
        let analysis = full_detail && (overlays_need_analysis || view_needs_analysis) && has_lights;
        let mut scene = self.state.scene.clone();
        if preview && scene.shadow.technique == Technique::Pcss {
            scene.shadow.samples = scene.shadow.samples.min(PREVIEW_PCSS_SAMPLES);
            scene.shadow.blocker_samples = scene.shadow.blocker_samples.min(PREVIEW_PCSS_SAMPLES);
        }
        let job = RenderJob {
            scene,
            request: FrameRequest {
                time_s: self.state.time_s,
                size,
                selected_light: self.state.selected_light,
                final_color: true,
                analysis: false,
                timestamps: true,
                ..Default::default()
            },
            probe,
            analysis,
            reference: analysis
                && (self.state.overlays.iter().any(|o| o.needs_reference())
                    || self.state.view.needs_reference()),
            probe_reference: if probe.is_some() && has_lights {
                self.state.probe_truth_lights()
            } else {
                Vec::new()
            },
            moments: analysis && self.state.view == View::Moments,
            bleeding: analysis && self.state.overlays.contains(&Overlay::Bleeding),
            technique_b: self.state.ab.as_ref().map(|ab| ab.b),
            thumbnails: full_detail,
            homework: self.state.homework.as_ref().filter(|_| full_detail).and_then(|h| {
                let program = h.program.clone()?;
                Some(HomeworkJob {
                    program,
                    source: h.source.clone(),
                    generation: h.generation,
                    lang: self.state.lang,
                    page_light: h.page_light,
                })
            }),
            preview,
            map_texels: if self.map_panel.zoomed() { MAP_PICTURE_TEXELS_ZOOMED } else { MAP_PICTURE_TEXELS },
        };
        // Waiting for the ground truths from now on, until their last batch comes (a probe that
        // finds no surface and a failed job clear them).
        self.render.shown.reference_progress =
            job.reference.then_some((0, self.state.scene.shadow.reference_samples));
        self.state.probe_truth_progress =
            job.probe_reference.iter().map(|&l| (l, 0, self.state.scene.shadow.reference_samples)).collect();
        let Some(worker) = self.render.worker.as_mut() else { return };
        let id = worker.submit(job);
        self.render.submitted = Submitted { job: id, preview, size };
        self.state.dirty = false;
    }

    /// A render is waiting or in progress (or a ground truth is still accumulating).
    pub fn render_pending(&self) -> bool {
        let Some(worker) = self.render.worker.as_ref() else { return false };
        let reference_running =
            self.render.shown.reference_progress.is_some_and(|(done, total)| done < total);
        let probe_reference_running =
            self.state.probe_truth_progress.iter().any(|(_, done, total)| done < total);
        self.state.dirty
            || worker.busy()
            || reference_running
            || probe_reference_running
            || self.render.shown_job < self.render.submitted.job
            || self.render.shown.details_pending.is_some()
    }

    /// How many frames have reached the views (each a new image on screen).
    pub fn frames_shown(&self) -> u64 {
        self.render.frames_shown
    }

    /// The resolution the shown camera view was rendered at, pixels.
    pub fn shown_size(&self) -> (u32, u32) {
        self.render.shown.size
    }

    /// The ground truth shown so far: (samples averaged, samples in all).
    pub fn reference_progress(&self) -> Option<(u32, u32)> {
        self.render.shown.reference_progress
    }

    /// The views show a reduced-quality preview.
    pub fn showing_preview(&self) -> bool {
        self.render.shown.preview
    }

    /// The worker has been busy long enough to say so.
    pub fn render_is_slow(&self) -> Option<Duration> {
        self.render.worker.as_ref()?.waiting_for().filter(|d| *d >= SLOW_RENDER)
    }

    /// Scene time advances at wall-clock rate times the speed, however long frames take.
    pub(super) fn advance_time(&mut self, now: Instant) {
        let dt = self.last_tick.map_or(0.0, |t| now.duration_since(t).as_secs_f32());
        self.last_tick = Some(now);
        self.state.advance_playback(dt);
    }
}

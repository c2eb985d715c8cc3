//! The ground-truth stages: at the probe for each light the job asks for, then the view's, a
//! batch at a time (its partial average sent after each), or at once where the last one finished
//! depends on nothing that has changed since.

use super::keys::ReferenceKey;
use super::renderers::Renderers;
use super::{RenderEvent, RenderJob, Stage};
use crate::render::{Batches, FrameRequest, GpuWait, GroundTruth, RenderError};

/// Ground-truth samples in the first batch; each later batch doubles, up to `REFERENCE_BATCH_MAX`.
const REFERENCE_BATCH_FIRST: usize = 4;
const REFERENCE_BATCH_MAX: usize = 32;
/// Probes' ground truths kept.
const PROBE_TRUTHS_KEPT: usize = 16;

fn batches() -> Batches {
    Batches::progressive(REFERENCE_BATCH_FIRST, REFERENCE_BATCH_MAX)
}

/// The ground truths at the probe under way.
#[derive(Default)]
pub(super) struct ProbeTruths {
    /// Of the job's `probe_reference`, the next light to start.
    next: usize,
    /// The light under way, what its ground truth depends on, and it.
    running: Option<(usize, ReferenceKey, GroundTruth)>,
}

/// The view's ground truth under way, and what it depends on.
pub(super) struct ViewTruth {
    key: ReferenceKey,
    truth: GroundTruth,
}

impl Renderers {
    /// Collect the batch under way (sending the average at the probed pixel so far) and submit
    /// the next; once a light's is finished, start the next light's.
    pub(super) fn probe_truths_step(
        &mut self,
        id: u64,
        job: &RenderJob,
        mut truths: ProbeTruths,
        send: &mut dyn FnMut(RenderEvent),
        cancelled: &dyn Fn() -> bool,
        wait: GpuWait,
    ) -> Result<Stage, RenderError> {
        let Some(spot) = job.probe else { return Ok(job.after_probe()) };
        let index = (spot.pixel.1 * spot.frame.0 + spot.pixel.0) as usize;
        let mut send_value = |light, done, total, value| {
            send(RenderEvent::ProbeReference { job: id, light, done, total, value });
        };
        match truths.running.take() {
            Some((light, key, mut truth)) => {
                let Some(progress) = self.a.ground_truth_progress(&mut truth, wait)? else {
                    truths.running = Some((light, key, truth));
                    return Ok(Stage::ProbeReference(Box::new(truths)));
                };
                let value = progress.values.get(index).copied().unwrap_or(1.0);
                send_value(light, progress.done, progress.total, value);
                if !progress.finished() {
                    if cancelled() {
                        return Ok(Stage::Done);
                    }
                    self.a.next_ground_truth_batch(&mut truth)?;
                    truths.running = Some((light, key, truth));
                    return Ok(Stage::ProbeReference(Box::new(truths)));
                }
                // Finished (even where a newer job is waiting): keep it.
                if self.probe_truths.len() >= PROBE_TRUTHS_KEPT {
                    self.probe_truths.remove(0);
                }
                self.probe_truths.push((key, value, progress.total));
                if cancelled() {
                    return Ok(Stage::Done);
                }
            }
            None if cancelled() => return Ok(Stage::Done),
            None => {}
        }
        // It starts from the probe's own frame, which the probe has just rendered.
        let frame = FrameRequest { size: spot.frame, ..job.request };
        while let Some(&light) = job.probe_reference.get(truths.next) {
            truths.next += 1;
            if light >= job.scene.lights.len() {
                continue;
            }
            let key = ReferenceKey::new(&job.scene, &frame, Some(spot.pixel), light);
            if let Some((_, value, total)) = self.probe_truths.iter().find(|(k, ..)| *k == key) {
                send_value(light, *total, *total, *value);
                if cancelled() {
                    return Ok(Stage::Done);
                }
                continue;
            }
            let truth = self.a.start_ground_truth(&job.scene, light, batches())?;
            truths.running = Some((light, key, truth));
            return Ok(Stage::ProbeReference(Box::new(truths)));
        }
        Ok(job.after_probe())
    }

    /// Start the view's ground truth for the selected light (its analysis is drawn again where a
    /// probe rendered since), or send the last one where nothing it depends on has changed.
    pub(super) fn start_view_truth(
        &mut self,
        id: u64,
        job: &RenderJob,
        send: &mut dyn FnMut(RenderEvent),
    ) -> Result<Stage, RenderError> {
        let light = job.request.selected_light;
        let key = ReferenceKey::new(&job.scene, &job.request, None, light);
        if let Some((_, values, total)) = self.view_truth.as_ref().filter(|(k, ..)| *k == key) {
            let (done, total, values) = (*total, *total, values.clone());
            send(RenderEvent::Reference { job: id, done, total, values });
            return Ok(Stage::Done);
        }
        if job.probe.is_some() {
            let request =
                FrameRequest { final_color: false, analysis: true, timestamps: false, ..job.request };
            self.a.render(&job.scene, &request)?;
        }
        let truth = self.a.start_ground_truth(&job.scene, light, batches())?;
        Ok(Stage::ViewReferenceComing(Box::new(ViewTruth { key, truth })))
    }

    /// Collect the batch under way (sending the average so far) and submit the next.
    pub(super) fn view_truth_step(
        &mut self,
        id: u64,
        mut view: ViewTruth,
        send: &mut dyn FnMut(RenderEvent),
        cancelled: &dyn Fn() -> bool,
        wait: GpuWait,
    ) -> Result<Stage, RenderError> {
        let Some(progress) = self.a.ground_truth_progress(&mut view.truth, wait)? else {
            return Ok(Stage::ViewReferenceComing(Box::new(view)));
        };
        let (done, total) = (progress.done, progress.total);
        if progress.finished() {
            self.view_truth = Some((view.key, progress.values.clone(), total));
            send(RenderEvent::Reference { job: id, done, total, values: progress.values });
            return Ok(Stage::Done);
        }
        send(RenderEvent::Reference { job: id, done, total, values: progress.values });
        if cancelled() {
            return Ok(Stage::Done);
        }
        self.a.next_ground_truth_batch(&mut view.truth)?;
        Ok(Stage::ViewReferenceComing(Box::new(view)))
    }
}

//! The details stage: the selected light's analysis for the overlays (read back from the image's
//! own frame, with its moments and light bleeding where asked for), then the probe, a light at a
//! time (one pixel of the analysis pass per light, which leaves the probe's frame as the last one
//! rendered).

use super::renderers::Renderers;
use super::{Details, ProbeOutcome, RenderEvent, RenderJob, Stage};
use crate::probe::{Probed, Probing};
use crate::render::{Analysis, FrameRequest, GpuWait, Readback, RenderError};
use crate::views::overlays::bleeding_inputs_readback;
use web_time::Instant;

/// The details under way.
pub(super) struct DetailsComing {
    /// The overlays' analysis on its way; None where it was not asked for or has arrived.
    analysis_coming: Option<Readback<Analysis>>,
    analysis: Option<Analysis>,
    probe: ProbeProgress,
}

enum ProbeProgress {
    Running(Box<Probing>),
    Finished(ProbeOutcome),
}

impl Renderers {
    /// Submit the analysis's read-backs and start the probe.
    pub(super) fn start_details(&mut self, job: &RenderJob) -> Result<DetailsComing, RenderError> {
        let analysis_coming = if job.analysis { Some(self.analysis_readback(job)?) } else { None };
        let probe = match job.probe {
            Some(spot) => {
                let request = FrameRequest {
                    size: spot.frame,
                    final_color: false,
                    analysis: true,
                    timestamps: false,
                    ..job.request
                };
                match Probing::start(&mut self.a, &job.scene, &request, spot.pixel) {
                    Ok(probing) => ProbeProgress::Running(Box::new(probing)),
                    Err(e) => ProbeProgress::Finished(Some(Err(e.to_string()))),
                }
            }
            None => ProbeProgress::Finished(None),
        };
        Ok(DetailsComing { analysis_coming, analysis: None, probe })
    }

    /// The image frame's analysis, with the moments and the light bleeding where the job asks
    /// for them, on its way back.
    fn analysis_readback(&self, job: &RenderJob) -> Result<Readback<Analysis>, RenderError> {
        let light = job.request.selected_light;
        // Techniques without moments leave them out (the view says so); VSSM's radius varies
        // per pixel, so the view shows the level of the PCF radius and says which radius.
        let moments = match job.moments {
            true => match self.a.moments_for_radius_readback(light, job.scene.shadow.radius_texels) {
                Ok(level) => level.map(|level| Ok(Some(level))),
                Err(RenderError::Usage(_)) => Readback::ready(None),
                Err(e) => return Err(e),
            },
            false => Readback::ready(None),
        };
        let bleeding = match job.bleeding {
            true => bleeding_inputs_readback(&self.a, light)?,
            false => Readback::ready(None),
        };
        Ok(self.a.analysis_readback()?.zip(moments).zip(bleeding).map(
            |((mut analysis, moments), bleeding)| {
                analysis.moments = moments;
                analysis.bleeding = bleeding.map(|inputs| inputs.bleeding(&analysis));
                Ok(analysis)
            },
        ))
    }

    /// Take the analysis once it is there and advance the probe; once both are done, send the
    /// details.
    pub(super) fn details_step(
        &mut self,
        id: u64,
        job: &RenderJob,
        mut details: DetailsComing,
        started: Instant,
        send: &mut dyn FnMut(RenderEvent),
        wait: GpuWait,
    ) -> Result<Stage, RenderError> {
        if let Some(coming) = details.analysis_coming.take() {
            match coming.arrived(&self.device, wait)? {
                true => details.analysis = Some(coming.finish()?),
                false => details.analysis_coming = Some(coming),
            }
        }
        details.probe = match details.probe {
            ProbeProgress::Running(probing) => match probing.advance(&mut self.a, &job.scene, wait) {
                Ok(Probed::Waiting(probing)) => ProbeProgress::Running(probing),
                Ok(Probed::Done(report)) => ProbeProgress::Finished(Some(Ok(report))),
                Err(e) => ProbeProgress::Finished(Some(Err(e.to_string()))),
            },
            finished => finished,
        };
        let probe = match details.probe {
            ProbeProgress::Finished(probe) if details.analysis_coming.is_none() => probe,
            under_way => {
                details.probe = under_way;
                return Ok(Stage::DetailsComing(Box::new(details)));
            }
        };
        let probe_hit = matches!(&probe, Some(Ok(report)) if report.hit);
        send(RenderEvent::Details(Box::new(Details {
            job: id,
            probe,
            analysis: details.analysis,
            render_ms: started.elapsed().as_secs_f64() * 1e3,
        })));
        Ok(if probe_hit && !job.probe_reference.is_empty() {
            Stage::ProbeReference(Box::default())
        } else {
            job.after_probe()
        })
    }
}

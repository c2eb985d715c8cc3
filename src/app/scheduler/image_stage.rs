//! The image stage: the view's colour (and the A/B side's) rendered and read back, sent first;
//! the maps follow.

use super::renderers::Renderers;
use super::{RenderEvent, RenderJob, RenderOutput, Stage};
use crate::render::{Frame, FrameRequest, GpuWait, PassTimes, Readback, RenderError, Renderer};
use web_time::Instant;

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
    /// Render the job's image (and the A/B side) and submit their read-backs. The overlays'
    /// analysis comes from the same pass (one filtering, not two); the details read it back
    /// after the image is on its way.
    pub(super) fn submit_image(&mut self, job: &RenderJob) -> Result<ImageComing, RenderError> {
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
    pub(super) fn image_step(
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

//! The homework check as a scheduler runs it: the student's pipelines built once per program
//! (a reload makes a new one), shadowlab's comparison on a renderer of its own (the view's keeps
//! its frame for the probe and the ground truths), a piece at a time without waiting where the
//! scheduler polls, and the last outcome kept while nothing it depends on changes.

use crate::homework::student_light::{LightReport, PageLight, student_light_of};
use crate::homework::{
    CheckOutcome, CheckRun, FRAMEWORK_LIGHT_INTENSITY, HomeworkLight, HomeworkProgram, HomeworkRenderer,
    HomeworkRequest, HomeworkSource, MapKind, ShaderSource,
};
use crate::i18n::Lang;
use crate::render::{GpuWait, Renderer};
use crate::scene::{Camera, Light, Scene, ShadowSettings};
use std::sync::Arc;

/// A homework to check with a job: the program and its generation (which changes on a reload).
#[derive(Clone)]
pub struct HomeworkJob {
    pub program: Arc<HomeworkProgram>,
    /// The submission it was read from, whose light scripts build the light (None: the
    /// framework's light, as for a shader opened alone).
    pub source: Option<Arc<HomeworkSource>>,
    pub generation: u64,
    /// The language of the findings' explanations.
    pub lang: Lang,
    /// Which of the page's lights (and when in its animation) the check is of; None: the first.
    pub page_light: Option<PageLight>,
}

/// What a check's outcome depends on.
#[derive(Clone, Debug, PartialEq)]
struct CheckKey {
    generation: u64,
    lang: Lang,
    camera: Camera,
    lights: Vec<Light>,
    settings: ShadowSettings,
    objects: usize,
    size: (u32, u32),
    time_bits: u32,
    page_light: Option<PageLight>,
}

/// The homework's GPU side in a scheduler.
#[derive(Default)]
pub(super) struct HomeworkRunner {
    /// The pipelines of the program of this generation.
    pipelines: Option<(u64, HomeworkRenderer)>,
    /// shadowlab's side of the comparison (made on first use).
    comparison: Option<Renderer>,
    /// The check under way, what it depends on, and the light it draws with.
    running: Option<(CheckKey, CheckRun, Option<LightReport>)>,
    last: Option<(CheckKey, Arc<CheckOutcome>)>,
}

impl HomeworkRunner {
    /// Go on with the check of `job` at `size` and `time_s`: its outcome once there (the last
    /// one again where nothing it depends on changed), None while it is under way. A check of
    /// other settings under way is dropped. Errors are one line: a pipeline wgpu refuses, a
    /// failed render.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn step(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        job: &HomeworkJob,
        scene: &Scene,
        size: (u32, u32),
        time_s: f32,
        wait: GpuWait,
    ) -> Result<Option<Arc<CheckOutcome>>, String> {
        let key = CheckKey {
            generation: job.generation,
            lang: job.lang,
            camera: scene.camera,
            lights: scene.lights.clone(),
            settings: scene.shadow,
            objects: scene.objects.len(),
            size,
            time_bits: time_s.to_bits(),
            page_light: job.page_light,
        };
        if let Some((_, outcome)) = self.last.as_ref().filter(|(k, _)| *k == key) {
            return Ok(Some(outcome.clone()));
        }
        let comparison = match self.comparison.as_mut() {
            Some(r) => r,
            None => self.comparison.insert(Renderer::new(device, queue).map_err(|e| e.to_string())?),
        };
        let (run, light_report) = match &mut self.running {
            Some((k, run, light)) if *k == key => (run, light),
            slot => {
                let homework = match &mut self.pipelines {
                    Some((generation, renderer)) if *generation == job.generation => renderer,
                    pipelines => {
                        let renderer =
                            HomeworkRenderer::new(device, queue, &job.program).map_err(|e| e.to_string())?;
                        &mut pipelines.insert((job.generation, renderer)).1
                    }
                };
                // A browser says whether it took the student's pipelines a frame or two later.
                match homework.ready() {
                    std::task::Poll::Pending => return Ok(None),
                    std::task::Poll::Ready(Err(e)) => return Err(e.to_string()),
                    std::task::Poll::Ready(Ok(())) => {}
                }
                let request = HomeworkRequest { time_s, size, light: 0, map: MapKind::Framework };
                let shader: &ShaderSource = &job.program.files.phong_fragment;
                // The student's own light where their submission has its scripts (in the browser,
                // their page's Worker answers a frame or more later).
                let student = match job
                    .source
                    .as_deref()
                    .map(|source| student_light_of(source, scene, 0, time_s, job.page_light))
                {
                    Some(std::task::Poll::Pending) => return Ok(None),
                    Some(std::task::Poll::Ready(student)) => student,
                    None => None,
                };
                let run = match student {
                    Some(student) => {
                        if let Some(refused) = student.refused {
                            return Err(refused);
                        }
                        let run = CheckRun::start(
                            homework,
                            shader,
                            &student.scene,
                            &student.light,
                            &request,
                            job.lang,
                        );
                        (run.map_err(|e| e.to_string())?, Some(student.report))
                    }
                    None => {
                        let light = HomeworkLight::of_scene(scene, 0, time_s, FRAMEWORK_LIGHT_INTENSITY)
                            .ok_or_else(|| "the scene has no light".to_string())?;
                        let run = CheckRun::start(homework, shader, scene, &light, &request, job.lang);
                        (run.map_err(|e| e.to_string())?, None)
                    }
                };
                let (_, run, light) = slot.insert((key.clone(), run.0, run.1));
                (run, light)
            }
        };
        let stepped = run.step(comparison, wait).map_err(|e| e.to_string());
        match stepped {
            Ok(None) => Ok(None),
            Ok(Some(mut outcome)) => {
                outcome.report.set_light(light_report.take());
                self.running = None;
                let outcome = Arc::new(outcome);
                self.last = Some((key, outcome.clone()));
                Ok(Some(outcome))
            }
            Err(e) => {
                self.running = None;
                Err(e)
            }
        }
    }
}

//! A homework check that never waits for the GPU unless told to: each `step` collects what has
//! arrived and submits the next piece (the student's two pictures, then shadowlab's frame and its
//! analysis, then the ground truth), so a page's frames can drive it as the render thread does.

use super::check::{CheckInputs, check};
use super::session::{CheckOutcome, HomeworkReport};
use super::{HomeworkGpuError, HomeworkImages, HomeworkRenderer, HomeworkRequest, RECORDED_FUNCTIONS};
use crate::i18n::Lang;
use crate::render::{Analysis, Batches, FrameRequest, GpuWait, GroundTruth, Readback, Renderer};
use crate::scene::{Scene, Technique};

/// A check under way.
pub struct CheckRun {
    shader: String,
    scene: Scene,
    request: HomeworkRequest,
    lang: Lang,
    stage: Stage,
}

enum Stage {
    /// The student's shader over the framework's map and over a white one, on their way.
    Student(Readback<(HomeworkImages, HomeworkImages)>),
    /// shadowlab's frame with the compared technique, and its analysis, on their way.
    Shadowlab(Box<Compared>, Readback<(image::RgbaImage, Analysis)>),
    /// The ground truth of shadowlab's frame, a batch at a time.
    GroundTruth(Box<Compared>, Box<Shadowlab>, Box<GroundTruth>),
    /// Finished (or failed): nothing more to step.
    Over,
}

/// The student's side and what it is compared with.
struct Compared {
    student: HomeworkImages,
    white: HomeworkImages,
    /// Which of useShadowMap / PCF / PCSS `main` took its visibility from at most pixels (1..=3).
    function: Option<usize>,
    /// The scene with the technique of that function.
    scene: Scene,
}

/// shadowlab's side once read back.
struct Shadowlab {
    picture: image::RgbaImage,
    analysis: Analysis,
}

/// shadowlab's technique for the function `main` used (1 useShadowMap, 2 PCF, 3 PCSS).
fn technique_for(function: usize) -> Technique {
    match function {
        1 => Technique::Hard,
        2 => Technique::Pcf,
        _ => Technique::Pcss,
    }
}

impl CheckRun {
    /// Submit the student's two passes. `shader` names the fragment shader in the report.
    pub fn start(
        homework: &HomeworkRenderer,
        shader: &str,
        scene: &Scene,
        request: &HomeworkRequest,
        lang: Lang,
    ) -> Result<Self, HomeworkGpuError> {
        let student = homework.submit(scene, request)?;
        let white = homework.submit(scene, &HomeworkRequest { clear_map_white: true, ..*request })?;
        Ok(Self {
            shader: shader.to_owned(),
            scene: scene.clone(),
            request: *request,
            lang,
            stage: Stage::Student(student.zip(white)),
        })
    }

    /// Go on with the check on `renderer` (shadowlab's side, which must render nothing else
    /// until the check is over): the outcome once it is finished, None while work is under way.
    /// `GpuWait::Block` waits for each piece; `GpuWait::Poll` returns at once where it has not
    /// arrived.
    pub fn step(
        &mut self,
        renderer: &mut Renderer,
        wait: GpuWait,
    ) -> Result<Option<CheckOutcome>, HomeworkGpuError> {
        let stage = std::mem::replace(&mut self.stage, Stage::Over);
        let (next, outcome) = match stage {
            Stage::Student(images) => {
                if !images.arrived(renderer.device(), wait)? {
                    (Stage::Student(images), None)
                } else {
                    let (student, white) = images.finish()?;
                    let compared = self.compared(student, white);
                    let coming = self.submit_shadowlab(renderer, &compared.scene)?;
                    (Stage::Shadowlab(Box::new(compared), coming), None)
                }
            }
            Stage::Shadowlab(compared, coming) => {
                if !coming.arrived(renderer.device(), wait)? {
                    (Stage::Shadowlab(compared, coming), None)
                } else {
                    let (picture, analysis) = coming.finish()?;
                    let truth =
                        renderer.start_ground_truth(&compared.scene, self.request.light, Batches::whole())?;
                    (
                        Stage::GroundTruth(
                            compared,
                            Box::new(Shadowlab { picture, analysis }),
                            Box::new(truth),
                        ),
                        None,
                    )
                }
            }
            Stage::GroundTruth(compared, shadowlab, mut truth) => {
                match renderer.ground_truth_progress(&mut truth, wait)? {
                    None => (Stage::GroundTruth(compared, shadowlab, truth), None),
                    Some(progress) if !progress.finished() => {
                        renderer.next_ground_truth_batch(&mut truth)?;
                        (Stage::GroundTruth(compared, shadowlab, truth), None)
                    }
                    Some(progress) => {
                        (Stage::Over, Some(self.outcome(*compared, *shadowlab, progress.values)))
                    }
                }
            }
            Stage::Over => return Err(HomeworkGpuError("the check is already over".into())),
        };
        self.stage = next;
        Ok(outcome)
    }

    /// The function `main` used, by vote over the pixels, and the scene with its technique.
    fn compared(&self, student: HomeworkImages, white: HomeworkImages) -> Compared {
        let mut votes = [0u64; 4];
        for c in &student.calls {
            votes[(c[1] as usize).min(3)] += u64::from(c[3] != 0 && c[1] != 0);
        }
        let function = (1..=3).max_by_key(|&k| votes[k]).filter(|&k| votes[k] > 0);
        let mut scene = self.scene.clone();
        scene.shadow.technique = technique_for(function.unwrap_or(3));
        Compared { student, white, function, scene }
    }

    /// shadowlab's frame at the homework's settings, with its analysis; read-backs submitted.
    fn submit_shadowlab(
        &self,
        renderer: &mut Renderer,
        scene: &Scene,
    ) -> Result<Readback<(image::RgbaImage, Analysis)>, HomeworkGpuError> {
        let frame = FrameRequest {
            time_s: self.request.time_s,
            size: self.request.size,
            selected_light: self.request.light,
            final_color: true,
            analysis: true,
            timestamps: false,
            only_pixel: None,
        };
        renderer.render(scene, &frame)?;
        Ok(renderer.color_readback()?.zip(renderer.analysis_readback()?))
    }

    /// The figures and findings, from everything rendered.
    fn outcome(&self, compared: Compared, shadowlab: Shadowlab, ground_truth: Vec<f32>) -> CheckOutcome {
        let Compared { student, white, function, scene } = compared;
        let analysis = &shadowlab.analysis;
        let ran = student.ran_anywhere();
        let calls: Vec<&'static str> = RECORDED_FUNCTIONS
            .iter()
            .enumerate()
            .filter(|(k, _)| ran & (1 << k) != 0)
            .map(|(_, n)| *n)
            .collect();
        let shadowlab_visibility: Vec<f32> = analysis.shadow.iter().map(|s| s[0]).collect();
        let positions: Vec<Option<glam::Vec3>> = (0..analysis.position.len())
            .map(|i| analysis.hit(i).then(|| glam::Vec3::from_slice(&analysis.position[i][..3])))
            .collect();
        let toward_light = -self.scene.lights[self.request.light].direction_at(self.request.time_s);
        let facing: Vec<Option<f32>> = (0..analysis.shadow.len())
            .map(|i| {
                analysis.hit(i).then(|| {
                    glam::Vec3::from_slice(&analysis.normal[i][..3]).normalize_or_zero().dot(toward_light)
                })
            })
            .collect();
        let (figures, findings) = check(
            &CheckInputs {
                student: &student,
                student_white_map: &white,
                shadowlab: &shadowlab_visibility,
                ground_truth: &ground_truth,
                facing: &facing,
                visibility_function: function,
                positions: &positions,
            },
            self.lang,
        );
        let report = HomeworkReport {
            shader: self.shader.clone(),
            compiled: true,
            error: None,
            calls,
            visibility_function: function.map(|k| RECORDED_FUNCTIONS[k - 1]),
            compared_with: Some(scene.shadow.technique.name()),
            figures: Some(figures),
            findings,
        };
        CheckOutcome {
            report,
            student,
            student_white_map: white,
            shadowlab_picture: shadowlab.picture,
            shadowlab_visibility,
            ground_truth,
            positions,
        }
    }
}

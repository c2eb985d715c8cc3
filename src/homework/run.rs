//! A homework check that never waits for the GPU unless told to: each `step` collects what has
//! arrived and submits the next piece, so a page's frames can drive it as the render thread does:
//! the student's passes (over the framework's map, a white one and a lossless one, and where
//! their functions read), then shadowlab's frame and its analysis (where the surfaces are), the
//! light width the student's penumbrae say, shadowlab's frame again at that width where it
//! differs, then the ground truth at it.

use super::findings::{Evidence, Judged, LightInputs, TwinInputs, findings};
use super::images::PackedMap;
use super::light_width::{LightWidthFit, WidthInputs};
use super::session::{CheckOutcome, HomeworkReport};
use super::{
    HomeworkGpuError, HomeworkImages, HomeworkLight, HomeworkRenderer, HomeworkRequest, MapKind,
    RECORDED_FUNCTIONS, ShaderSource, TapImages,
};
use crate::i18n::Lang;
use crate::render::{Analysis, Batches, FrameRequest, GpuWait, GroundTruth, Readback, Renderer};
use crate::scene::{LightSize, Scene, Technique};
use crate::shadow::{DepthImage, ShadowViewGpu};
use glam::Vec3;

/// Run a compiled homework and compare it, a step at a time, waiting for the GPU at each.
/// `renderer` renders shadowlab's side on the same device.
pub fn run_check(
    homework: &HomeworkRenderer,
    renderer: &mut Renderer,
    shader: &ShaderSource,
    scene: &Scene,
    light: &HomeworkLight,
    request: &HomeworkRequest,
    lang: Lang,
) -> Result<CheckOutcome, HomeworkGpuError> {
    let mut run = CheckRun::start(homework, shader, scene, light, request, lang)?;
    loop {
        if let Some(outcome) = run.step(renderer, GpuWait::Block)? {
            return Ok(outcome);
        }
    }
}

/// A check under way.
pub struct CheckRun {
    shader: String,
    /// The student's fragment shader, where findings point at its lines.
    fragment_source: String,
    scene: Scene,
    light: HomeworkLight,
    request: HomeworkRequest,
    lang: Lang,
    stage: Stage,
}

enum Stage {
    /// The student's passes on their way.
    Student(Readback<StudentPasses>),
    /// shadowlab's frame with the compared technique, its analysis and its map, on their way.
    Shadowlab(Box<Compared>, Readback<ShadowlabFrame>),
    /// The ground truth of shadowlab's frame, a batch at a time.
    GroundTruth(Box<Compared>, Box<Shadowlab>, Box<GroundTruth>),
    /// Finished (or failed): nothing more to step.
    Over,
}

/// shadowlab's frame as read back: the picture, the analysis and the light's map.
type ShadowlabFrame = ((image::RgbaImage, Analysis), DepthImage);

/// The student's passes as read back.
type StudentPasses = (((HomeworkImages, HomeworkImages), (HomeworkImages, Option<PackedMap>)), TapImages);

/// The student's side and what it is compared with.
struct Compared {
    student: HomeworkImages,
    white: HomeworkImages,
    lossless: HomeworkImages,
    /// The lossless map as the student's light pass packed it.
    lossless_map: Option<PackedMap>,
    taps: TapImages,
    /// Which of useShadowMap / PCF / PCSS `main` took its visibility from at most pixels (1..=3).
    function: Option<usize>,
    /// The scene with the technique of that function, and (once fitted) the light width the
    /// ground truth takes.
    scene: Scene,
    /// The light width the student's penumbrae say (once shadowlab's frame placed the surfaces).
    width: Option<LightWidthFit>,
}

/// shadowlab's side once read back.
struct Shadowlab {
    picture: image::RgbaImage,
    analysis: Analysis,
    map: DepthImage,
    /// The light's shadow view as the GPU had it (where the twin projects the receivers).
    view: ShadowViewGpu,
}

/// shadowlab's technique for the function `main` used (1 useShadowMap, 2 PCF, 3 PCSS).
fn technique_for(function: usize) -> Technique {
    match function {
        1 => Technique::Hard,
        2 => Technique::Pcf,
        _ => Technique::Pcss,
    }
}

/// World positions and normals under each pixel of an analysis (None: no surface).
fn surfaces(analysis: &Analysis) -> (Vec<Option<Vec3>>, Vec<Option<Vec3>>) {
    let at = |v: &[[f32; 4]], i: usize| analysis.hit(i).then(|| Vec3::from_slice(&v[i][..3]));
    let n = analysis.position.len();
    ((0..n).map(|i| at(&analysis.position, i)).collect(), (0..n).map(|i| at(&analysis.normal, i)).collect())
}

impl CheckRun {
    /// Submit the student's passes, drawn with `light` (their matrices); shadowlab's side renders
    /// `scene` (whose light `request.light` is the same frustum). `shader` names the fragment
    /// shader in the report.
    pub fn start(
        homework: &HomeworkRenderer,
        shader: &ShaderSource,
        scene: &Scene,
        light: &HomeworkLight,
        request: &HomeworkRequest,
        lang: Lang,
    ) -> Result<Self, HomeworkGpuError> {
        let over = |map| HomeworkRequest { map, ..*request };
        let student = homework.submit(scene, light, &over(MapKind::Framework))?;
        let white = homework.submit(scene, light, &over(MapKind::White))?;
        let lossless = homework.submit_with_map(scene, light, &over(MapKind::Lossless))?;
        let taps = homework.submit_taps(scene, light, &over(MapKind::Framework))?;
        Ok(Self {
            shader: shader.name.clone(),
            fragment_source: shader.text.clone(),
            scene: scene.clone(),
            light: light.clone(),
            request: *request,
            lang,
            stage: Stage::Student(student.zip(white).zip(lossless).zip(taps)),
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
                    let (((student, white), (lossless, lossless_map)), taps) = images.finish()?;
                    let mut compared = self.compared(student, white, lossless, taps);
                    compared.lossless_map = lossless_map;
                    let coming = self.submit_shadowlab(renderer, &compared.scene)?;
                    (Stage::Shadowlab(Box::new(compared), coming), None)
                }
            }
            Stage::Shadowlab(mut compared, coming) => {
                if !coming.arrived(renderer.device(), wait)? {
                    (Stage::Shadowlab(compared, coming), None)
                } else {
                    let ((picture, analysis), map) = coming.finish()?;
                    if compared.width.is_none() {
                        // The surfaces are placed: measure the student's light, and render again
                        // where the ground truth's light is not the one just drawn.
                        let drawn = compared.scene.lights[self.request.light].size;
                        self.fit_width(&mut compared, &analysis);
                        if compared.scene.lights[self.request.light].size != drawn {
                            let coming = self.submit_shadowlab(renderer, &compared.scene)?;
                            self.stage = Stage::Shadowlab(compared, coming);
                            return Ok(None);
                        }
                    }
                    let view = renderer
                        .last_frame()
                        .and_then(|f| f.first_view_of(self.request.light).map(|(_, v)| *v))
                        .ok_or_else(|| HomeworkGpuError("shadowlab's frame has no light".into()))?;
                    let truth =
                        renderer.start_ground_truth(&compared.scene, self.request.light, Batches::whole())?;
                    let shadowlab = Shadowlab { picture, analysis, map, view };
                    (Stage::GroundTruth(compared, Box::new(shadowlab), Box::new(truth)), None)
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

    /// The light width the student's penumbrae say, and the light the ground truth takes: for
    /// PCSS that width (a light wider than the map's half is held there), for hard shadows and
    /// PCF a point (their edges are a map's or a filter's, not a light's).
    fn fit_width(&self, compared: &mut Compared, analysis: &Analysis) {
        let (positions, normals) = surfaces(analysis);
        let student = &compared.student;
        let visibility = |i: usize| student.visibility(i);
        let inputs = WidthInputs {
            width: analysis.width,
            visibility: &visibility,
            positions: &positions,
            normals: &normals,
        };
        let light = &mut compared.scene.lights[self.request.light];
        let fit = super::light_width::fit(&self.scene, light, self.request.time_s, &inputs);
        let width_world = match compared.scene.shadow.technique {
            Technique::Pcss => fit
                .implied_light_width_world
                .map(|w| w.clamp(0.0, 0.5 * light.frustum_width_world()))
                .unwrap_or(match light.size {
                    LightSize::Width { width_world } => width_world,
                    LightSize::AngularDiameter { .. } => 0.0,
                }),
            _ => 0.0,
        };
        light.size = LightSize::Width { width_world };
        compared.width = Some(fit);
    }

    /// The function `main` used, by vote over the pixels, and the scene with its technique.
    fn compared(
        &self,
        student: HomeworkImages,
        white: HomeworkImages,
        lossless: HomeworkImages,
        taps: TapImages,
    ) -> Compared {
        let mut votes = [0u64; 4];
        for c in &student.calls {
            votes[(c[1] as usize).min(3)] += u64::from(c[3] != 0 && c[1] != 0);
        }
        let function = (1..=3).max_by_key(|&k| votes[k]).filter(|&k| votes[k] > 0);
        let mut scene = self.scene.clone();
        scene.shadow.technique = technique_for(function.unwrap_or(3));
        Compared { student, white, lossless, lossless_map: None, taps, function, scene, width: None }
    }

    /// shadowlab's frame at the homework's settings, with its analysis; read-backs submitted.
    fn submit_shadowlab(
        &self,
        renderer: &mut Renderer,
        scene: &Scene,
    ) -> Result<Readback<ShadowlabFrame>, HomeworkGpuError> {
        let frame = FrameRequest {
            time_s: self.request.time_s,
            size: self.request.size,
            selected_light: self.request.light,
            final_color: true,
            analysis: true,
            timestamps: false,
            only_pixel: None,
        };
        let rendered = renderer.render(scene, &frame)?;
        let (view, _) = rendered
            .first_view_of(self.request.light)
            .ok_or_else(|| HomeworkGpuError("shadowlab's frame has no light".into()))?;
        Ok(renderer
            .color_readback()?
            .zip(renderer.analysis_readback()?)
            .zip(renderer.shadow_map_readback(view)?))
    }

    /// The figures and findings, from everything rendered.
    fn outcome(&self, compared: Compared, shadowlab: Shadowlab, ground_truth: Vec<f32>) -> CheckOutcome {
        let Compared { student, white, lossless, lossless_map, taps, function, scene, width } = compared;
        let analysis = &shadowlab.analysis;
        let ran = student.ran_anywhere();
        let calls: Vec<&'static str> = RECORDED_FUNCTIONS
            .iter()
            .enumerate()
            .filter(|(k, _)| ran & (1 << k) != 0)
            .map(|(_, n)| *n)
            .collect();
        let shadowlab_visibility: Vec<f32> = analysis.shadow.iter().map(|s| s[0]).collect();
        let (positions, normals) = surfaces(analysis);
        let toward_light = -scene.lights[self.request.light].direction_at(self.request.time_s);
        let facing: Vec<Option<f32>> =
            normals.iter().map(|n| n.map(|n| n.normalize_or_zero().dot(toward_light))).collect();
        let objects: Vec<Option<usize>> = (0..analysis.normal.len())
            .map(|i| analysis.hit(i).then(|| analysis.normal[i][3].round() as usize))
            .collect();
        let world_from_object: Vec<glam::Mat4> =
            self.scene.objects.iter().map(|o| o.world_from_object(self.request.time_s)).collect();
        let object_names: Vec<String> = self.scene.objects.iter().map(|o| o.name.clone()).collect();
        let map_size = scene.lights[self.request.light].shadow_map_size;
        let white_map_change = super::findings::white_map_change(&student, &white);
        let twin = TwinInputs { map: &shadowlab.map, view: &shadowlab.view, normals: &normals };
        let evidence = |student| Evidence {
            student,
            lossless: &lossless,
            lossless_map: lossless_map.as_ref(),
            taps: &taps,
            white_map_change: &white_map_change,
            shadowlab: &shadowlab_visibility,
            ground_truth: &ground_truth,
            facing: &facing,
            visibility_function: function,
            positions: &positions,
            objects: &objects,
            light: LightInputs {
                clip_from_object: &self.light.clip_from_object,
                world_from_object: &world_from_object,
                object_names: &object_names,
                map_size,
                clip_from_world: self.light.clip_from_world,
                look_direction: self.light.look_direction,
                from: self.light.from.label(),
                width: width.as_ref(),
                model_matrix: self.light.model_matrix,
                stale: &self.light.stale,
            },
            twin: Some(&twin),
            fragment_source: &self.fragment_source,
        };
        let (framework, exact) = (evidence(&student), evidence(&lossless));
        let figures = super::figures::figures(&Judged::new(&framework));
        let findings = findings(&framework, &exact, self.lang);
        let report = HomeworkReport {
            submission: None,
            shader: self.shader.clone(),
            compiled: true,
            error: None,
            calls,
            visibility_function: function.map(|k| RECORDED_FUNCTIONS[k - 1]),
            compared_with: Some(scene.shadow.technique.name()),
            figures: Some(figures),
            light_width: width.clone(),
            light: None,
            lights: Vec::new(),
            findings,
        };
        CheckOutcome {
            report,
            student,
            student_white_map: white,
            student_lossless_map: lossless,
            taps,
            light: self.light.clone(),
            shadowlab_picture: shadowlab.picture,
            shadowlab_visibility,
            ground_truth,
            positions,
            map: lossless_map,
        }
    }
}

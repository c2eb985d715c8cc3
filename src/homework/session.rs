//! A whole homework check: the student's passes (over the framework's map and over a white one),
//! shadowlab's own technique at the same settings and the ground truth, compared; and the
//! pictures that show it.

use super::check::{CheckInputs, Figures, Finding, check};
use super::{HomeworkError, HomeworkGpuError, HomeworkImages, HomeworkRenderer, HomeworkRequest};
use super::{RECORDED_FUNCTIONS, ShaderSource};
use crate::i18n::Lang;
use crate::render::{FrameRequest, Renderer};
use crate::scene::{Scene, Technique};
use serde::Serialize;

/// Where a shader that did not compile is wrong.
#[derive(Clone, Debug, Serialize, PartialEq, Eq)]
pub struct ShaderErrorReport {
    pub file: String,
    pub line: Option<usize>,
    pub message: String,
}

impl From<&HomeworkError> for ShaderErrorReport {
    fn from(e: &HomeworkError) -> Self {
        match e {
            HomeworkError::Shader { file, line, message } => {
                Self { file: file.clone(), line: *line, message: message.clone() }
            }
            HomeworkError::Rewrite { line, message } => {
                Self { file: String::new(), line: Some(*line), message: message.clone() }
            }
        }
    }
}

/// What a check found, as `report.json` holds it.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct HomeworkReport {
    /// The student's fragment shader, as named on the command line.
    pub shader: String,
    pub compiled: bool,
    pub error: Option<ShaderErrorReport>,
    /// Which of useShadowMap, PCF, PCSS, findBlocker ran anywhere in the picture.
    pub calls: Vec<&'static str>,
    /// The function whose result `main` used as the visibility at most pixels.
    pub visibility_function: Option<&'static str>,
    /// shadowlab's technique the student's is compared with.
    pub compared_with: Option<&'static str>,
    #[serde(flatten)]
    pub figures: Option<Figures>,
    pub findings: Vec<Finding>,
}

impl HomeworkReport {
    /// The report of a shader that did not compile.
    pub fn not_compiled(shader: &str, error: &HomeworkError) -> Self {
        Self {
            shader: shader.to_string(),
            compiled: false,
            error: Some(error.into()),
            calls: Vec::new(),
            visibility_function: None,
            compared_with: None,
            figures: None,
            findings: Vec::new(),
        }
    }
}

/// Everything a check rendered, for the pictures.
pub struct CheckOutcome {
    pub report: HomeworkReport,
    pub student: HomeworkImages,
    /// The same shader over a map cleared to white (what depends on the framework's 0s).
    pub student_white_map: HomeworkImages,
    /// shadowlab's final picture with the technique compared with.
    pub shadowlab_picture: image::RgbaImage,
    pub shadowlab_visibility: Vec<f32>,
    pub ground_truth: Vec<f32>,
    /// The world position under each pixel (None: no surface).
    pub positions: Vec<Option<glam::Vec3>>,
}

/// shadowlab's technique for the function a student's `main` takes its visibility from.
fn technique_for(function: usize) -> Technique {
    match function {
        1 => Technique::Hard,
        2 => Technique::Pcf,
        _ => Technique::Pcss,
    }
}

/// Run a compiled homework and compare it (see the module documentation). `renderer` renders
/// shadowlab's side on the same device.
pub fn run_check(
    homework: &HomeworkRenderer,
    renderer: &mut Renderer,
    shader: &ShaderSource,
    scene: &Scene,
    request: &HomeworkRequest,
    lang: Lang,
) -> Result<CheckOutcome, HomeworkGpuError> {
    let student = homework.render(scene, request)?;
    let white = homework.render(scene, &HomeworkRequest { clear_map_white: true, ..*request })?;
    let ran = student.ran_anywhere();
    let calls: Vec<&'static str> =
        RECORDED_FUNCTIONS.iter().enumerate().filter(|(k, _)| ran & (1 << k) != 0).map(|(_, n)| *n).collect();
    let mut votes = [0u64; 4];
    for c in &student.calls {
        votes[(c[1] as usize).min(3)] += u64::from(c[3] != 0 && c[1] != 0);
    }
    let function = (1..=3).max_by_key(|&k| votes[k]).filter(|&k| votes[k] > 0);

    let mut compared = scene.clone();
    compared.shadow.technique = technique_for(function.unwrap_or(3));
    let frame = FrameRequest {
        time_s: request.time_s,
        size: request.size,
        selected_light: request.light,
        final_color: true,
        analysis: true,
        timestamps: false,
        only_pixel: None,
    };
    renderer.render(&compared, &frame)?;
    let shadowlab_picture = renderer.read_color()?;
    let analysis = renderer.read_analysis()?;
    let ground_truth = renderer.render_reference(&compared, request.light)?;
    let shadowlab_visibility: Vec<f32> = analysis.shadow.iter().map(|s| s[0]).collect();
    let positions: Vec<Option<glam::Vec3>> = (0..analysis.position.len())
        .map(|i| analysis.hit(i).then(|| glam::Vec3::from_slice(&analysis.position[i][..3])))
        .collect();
    let toward_light = -scene.lights[request.light].direction_at(request.time_s);
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
        lang,
    );
    let report = HomeworkReport {
        shader: shader.name.clone(),
        compiled: true,
        error: None,
        calls,
        visibility_function: function.map(|k| RECORDED_FUNCTIONS[k - 1]),
        compared_with: Some(compared.shadow.technique.name()),
        figures: Some(figures),
        findings,
    };
    Ok(CheckOutcome {
        report,
        student,
        student_white_map: white,
        shadowlab_picture,
        shadowlab_visibility,
        ground_truth,
        positions,
    })
}

/// The student's picture of a homework (`fragment`, with `shadow_fragment` for the light pass or
/// the framework's) as the framework draws it at `size`, on `renderer`'s device: what a lesson
/// step that checks a homework shows in its camera view. A shader that does not compile is an
/// error naming its file and line.
pub fn homework_picture(
    renderer: &Renderer,
    fragment: &std::path::Path,
    shadow_fragment: Option<&std::path::Path>,
    scene: &Scene,
    size: (u32, u32),
    time_s: f32,
) -> Result<image::RgbaImage, String> {
    let files = super::HomeworkFiles::read(fragment, None, shadow_fragment).map_err(|e| e.to_string())?;
    let program = super::HomeworkProgram::translate(files).map_err(|e| e.to_string())?;
    let homework =
        HomeworkRenderer::new(renderer.device(), renderer.queue(), &program).map_err(|e| e.to_string())?;
    let request = HomeworkRequest { time_s, size, light: 0, clear_map_white: false };
    let images = homework.render(scene, &request).map_err(|e| e.to_string())?;
    Ok(student_picture(&images))
}

/// What a student's shader wrote, as a picture (its colours are already gamma-encoded); NaN and
/// infinite pixels in `NAN_COLOR`.
fn student_picture(s: &HomeworkImages) -> image::RgbaImage {
    image::RgbaImage::from_fn(s.width, s.height, |x, y| {
        let c = s.color[(y * s.width + x) as usize];
        if c[..3].iter().any(|v| !v.is_finite()) {
            image::Rgba(NAN_COLOR)
        } else {
            image::Rgba([byte(c[0]), byte(c[1]), byte(c[2]), 255])
        }
    })
}

/// Not-a-number and infinite pixels: their own colour in every picture.
pub const NAN_COLOR: [u8; 4] = [255, 0, 255, 255];

fn byte(v: f32) -> u8 {
    (255.0 * v.clamp(0.0, 1.0)).round() as u8
}

impl CheckOutcome {
    /// The penumbra's width at `pixel`, world units: the student's and the ground truth's
    /// (None where the ground truth has no edge there).
    pub fn penumbra_widths(&self, pixel: (u32, u32)) -> Option<(f32, f32)> {
        super::check::penumbra_widths(&self.student, &self.ground_truth, &self.positions, pixel)
    }

    /// The student's picture as their shader wrote it (its colours are already gamma-encoded).
    pub fn student_picture(&self) -> image::RgbaImage {
        student_picture(&self.student)
    }

    /// The student's picture over a shadow map cleared to white.
    pub fn student_picture_white_map(&self) -> image::RgbaImage {
        student_picture(&self.student_white_map)
    }

    /// The student's visibility in grey beside the ground truth's: where no visibility was
    /// returned, dark blue; NaN in its own colour.
    pub fn visibility_picture(&self, ground_truth: bool) -> image::RgbaImage {
        let s = &self.student;
        image::RgbaImage::from_fn(s.width, s.height, |x, y| {
            let i = (y * s.width + x) as usize;
            let v = if ground_truth { s.covered(i).then_some(self.ground_truth[i]) } else { s.visibility(i) };
            match v {
                None => image::Rgba([20, 24, 48, 255]),
                Some(v) if !v.is_finite() => image::Rgba(NAN_COLOR),
                Some(v) => image::Rgba([byte(v), byte(v), byte(v), 255]),
            }
        })
    }

    /// Student minus ground truth: white where they agree, red where the student's is darker,
    /// blue where it is lighter; NaN in its own colour; no surface dark grey.
    pub fn difference_picture(&self) -> image::RgbaImage {
        let s = &self.student;
        image::RgbaImage::from_fn(s.width, s.height, |x, y| {
            let i = (y * s.width + x) as usize;
            match s.visibility(i) {
                None if !s.covered(i) => image::Rgba([40, 40, 40, 255]),
                None => image::Rgba([20, 24, 48, 255]),
                Some(v) if !v.is_finite() => image::Rgba(NAN_COLOR),
                Some(v) => {
                    let d = (v - self.ground_truth[i]).clamp(-1.0, 1.0);
                    let fade = byte(1.0 - d.abs());
                    if d < 0.0 {
                        image::Rgba([255, fade, fade, 255])
                    } else {
                        image::Rgba([fade, fade, 255, 255])
                    }
                }
            }
        })
    }
}

//! What a whole homework check found (the student's passes over the framework's map and over a
//! white one, shadowlab's own technique at the same settings and the ground truth, compared) and
//! the pictures that show it.

use super::{Figures, Finding};
use super::{
    HomeworkError, HomeworkImages, HomeworkLight, HomeworkRenderer, HomeworkRequest, MapKind, TapImages,
};
use crate::render::Renderer;
use crate::scene::Scene;
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
    /// The submission: its name and the files used (None: a lone shader given as such).
    pub submission: Option<SubmissionReport>,
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
    /// The light width the student's penumbrae say (the slabs' shadows against similar
    /// triangles), and the fit's quality.
    pub light_width: Option<super::LightWidthFit>,
    /// The light the student built (their DirectionalLight.js and engine.js), or the framework's.
    pub light: Option<super::student_light::LightReport>,
    /// Every light the student's page made, the checked one marked (absent where the page did
    /// not run).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub lights: Vec<super::student_light::LightEntry>,
    pub findings: Vec<Finding>,
}

/// What a submission handed over, as the report names it.
#[derive(Clone, Debug, Serialize, PartialEq, Eq)]
pub struct SubmissionReport {
    /// The folder's or zip's name (a class report lists students by it).
    pub name: String,
    /// Each framework file, and where in the submission it was found (`framework` where the
    /// submission has none and the framework's own was used).
    pub files: Vec<(String, String)>,
    /// How the files were found where there was a choice, one line each.
    pub notes: Vec<String>,
}

impl SubmissionReport {
    pub fn of(source: &super::HomeworkSource) -> Self {
        let f = &source.files;
        let name = |s: &super::ShaderSource| s.name.clone();
        let script =
            |s: &Option<super::ShaderSource>| s.as_ref().map_or("framework".to_string(), |s| s.name.clone());
        Self {
            name: source.name.clone(),
            files: vec![
                ("phongFragment.glsl".into(), name(&f.phong_fragment)),
                ("phongVertex.glsl".into(), name(&f.phong_vertex)),
                ("shadowFragment.glsl".into(), name(&f.shadow_fragment)),
                ("shadowVertex.glsl".into(), name(&f.shadow_vertex)),
                ("DirectionalLight.js".into(), script(&source.light_script)),
                ("engine.js".into(), script(&source.engine)),
            ],
            notes: source.notes.iter().cloned().chain(per_light_note(source)).collect(),
        }
    }
}

/// The note on the framework's per-light names a submission declares as arrays by light.
fn per_light_note(source: &super::HomeworkSource) -> Option<String> {
    let f = &source.files;
    let mut names = Vec::new();
    for texts in
        [[&f.phong_vertex.text, &f.phong_fragment.text], [&f.shadow_vertex.text, &f.shadow_fragment.text]]
    {
        let layout = super::Interface::gather(&[texts[0], texts[1]]).ok()?;
        names.extend(layout.per_light.into_iter().map(|n| (n, None)));
        names.extend(layout.per_light_copies.into_iter().map(|(copy, base)| (copy, Some(base))));
    }
    names.sort();
    names.dedup();
    let arrays: Vec<&str> =
        names.iter().filter(|(_, base)| base.is_none()).map(|(n, _)| n.as_str()).collect();
    let copies: Vec<String> =
        names.iter().filter_map(|(n, base)| Some(format!("{n} (of {})", base.as_ref()?))).collect();
    let mut kinds = Vec::new();
    if !arrays.is_empty() {
        kinds.push(format!("{} are arrays by light", arrays.join(", ")));
    }
    if !copies.is_empty() {
        kinds.push(format!("{} are copies for other lights", copies.join(", ")));
    }
    (!kinds.is_empty()).then(|| {
        format!(
            "{}: each light is checked on its own, with every element and copy holding it",
            kinds.join("; ")
        )
    })
}

impl HomeworkReport {
    /// The light the check used, with every light the student's page made.
    pub fn set_light(&mut self, light: Option<super::student_light::LightReport>) {
        self.lights = light.as_ref().map_or_else(Vec::new, |l| l.lights.clone());
        self.light = light;
    }

    /// The report of a shader that did not compile.
    pub fn not_compiled(shader: &str, error: &HomeworkError) -> Self {
        Self {
            submission: None,
            shader: shader.to_string(),
            compiled: false,
            error: Some(error.into()),
            calls: Vec::new(),
            visibility_function: None,
            compared_with: None,
            figures: None,
            light_width: None,
            light: None,
            lights: Vec::new(),
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
    /// The same shader over a map kept without loss (what the 8-bit channels' rounding hides).
    pub student_lossless_map: HomeworkImages,
    /// Where the student's recorded functions read the framework's map.
    pub taps: TapImages,
    /// The light the student's passes were drawn with.
    pub light: HomeworkLight,
    /// shadowlab's final picture with the technique compared with.
    pub shadowlab_picture: image::RgbaImage,
    pub shadowlab_visibility: Vec<f32>,
    pub ground_truth: Vec<f32>,
    /// The world position under each pixel (None: no surface).
    pub positions: Vec<Option<glam::Vec3>>,
    /// The student's light pass as their pack wrote it, kept without loss (None: not read back).
    pub map: Option<super::images::PackedMap>,
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
    let request = HomeworkRequest { time_s, size, light: 0, map: MapKind::Framework };
    let light = HomeworkLight::of_scene(scene, 0, time_s, super::FRAMEWORK_LIGHT_INTENSITY)
        .ok_or_else(|| "the scene has no light".to_string())?;
    let images = homework.render(scene, &light, &request).map_err(|e| e.to_string())?;
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
        super::figures::penumbra_widths(&self.student, &self.ground_truth, &self.positions, pixel)
    }

    /// The student's picture as their shader wrote it (its colours are already gamma-encoded).
    pub fn student_picture(&self) -> image::RgbaImage {
        student_picture(&self.student)
    }

    /// The student's picture over a shadow map cleared to white.
    pub fn student_picture_white_map(&self) -> image::RgbaImage {
        student_picture(&self.student_white_map)
    }

    /// The student's picture over a map kept without loss (what the framework's 8-bit rounding
    /// hides shows here).
    /// The student's shadow map as their light pass wrote it, as the light sees it (rows top
    /// first): their packed depth unpacked (base 256), nearer darker, stretched over the depths
    /// written; a texel never written (all four channels 0) is dark red.
    pub fn map_picture(&self) -> Option<image::RgbaImage> {
        let map = self.map.as_ref()?;
        let depth = |t: &[f32; 4]| t[0] + t[1] / 256.0 + t[2] / 65536.0 + t[3] / 16_777_216.0;
        let written = |t: &[f32; 4]| t.iter().any(|c| *c != 0.0);
        let (lo, hi) = map
            .texels
            .iter()
            .filter(|t| written(t))
            .map(depth)
            .filter(|d| d.is_finite())
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), d| (lo.min(d), hi.max(d)));
        let span = if hi > lo { hi - lo } else { 1.0 };
        Some(image::RgbaImage::from_fn(map.size, map.size, |x, y| {
            // The map's row 0 is the bottom of the light's view (WebGL's layout).
            let t = &map.texels[((map.size - 1 - y) * map.size + x) as usize];
            if !written(t) {
                return image::Rgba([90, 0, 0, 255]);
            }
            let v = (255.0 * ((depth(t) - lo) / span).clamp(0.0, 1.0)).round() as u8;
            image::Rgba([v, v, v, 255])
        }))
    }

    pub fn student_picture_lossless_map(&self) -> image::RgbaImage {
        student_picture(&self.student_lossless_map)
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

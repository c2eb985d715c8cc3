//! A student's GAMES202 homework shader, written for the course's WebGL1 framework (GLSL ES 1.00),
//! brought to wgpu.
//!
//! naga's GLSL front end reads Vulkan-style GLSL 440/450 only: `uniform sampler2D`, `varying`,
//! `attribute`, `gl_FragColor` and loose uniforms all fail there. [`rewrite`] turns the student's
//! shader into GLSL 450 mechanically and line for line: every line of the student's file stays on
//! its own line, and whatever has to be added goes on a prelude of [`Rewritten::prelude_lines`]
//! lines before it. naga ignores `#line`, so an error naga reports at line L of the rewritten text
//! is the student's line L - prelude, and [`translate`] reports it that way
//! (`phongFragment.glsl:57: ...`). [`translate`] then runs naga's GLSL front end, the validator
//! and the WGSL back end.
//!
//! The interface (uniform names, varyings, textures) is the framework's, described in
//! [`interface`]; a student's own uniforms and varyings are gathered from both stages with
//! [`Interface::gather`] so that the two stages agree on locations and layout.

mod figures;
pub mod findings;
mod images;
mod instrument;
mod interface;
mod lex;
mod light;
mod light_source;
mod light_width;
mod missing_return;
mod page;
mod pass;
mod penumbra;
mod pipeline;
mod program;
mod rewrite;
mod run;
mod session;
mod student_block;
pub mod student_light;
pub mod submission;
mod translate;
mod webgl1;

pub use figures::Figures;
pub use findings::{Finding, Severity};
pub use images::{HomeworkImages, TapImages, Taps};
pub use instrument::{CALLS_OUTPUT, RECORDED_FUNCTIONS, RETURNED_OUTPUT, TAPS_OUTPUT};
pub use interface::{
    ATTRIBUTES, Binding, BindingKind, CLIP_Y_SIGN_OFFSET_BYTES, FRAMEWORK_UNIFORMS,
    FRAMEWORK_UNIFORMS_SIZE_BYTES, FRAMEWORK_VARYINGS, Interface, SamplerFilter, UniformField,
};
pub use light::{HomeworkLight, LightFrom, ModelMatrixError, ReadLight, gl_from_wgpu_clip, read_light};
pub use light_width::{LightWidthFit, SlabShadow};
pub use pass::{FRAMEWORK_LIGHT_INTENSITY, HomeworkRenderer, HomeworkRequest, MapKind};
pub use program::{HomeworkFiles, HomeworkProgram, HomeworkSource, ShaderSource, TranslatedProgram, is_zip};
pub use rewrite::{FRAG_COLOR, Rewritten, rewrite};
pub use run::{CheckRun, run_check};
pub use session::{
    CheckOutcome, HomeworkReport, NAN_COLOR, ShaderErrorReport, SubmissionReport, homework_picture,
};
pub use translate::{Translated, translate, translate_rewritten};

/// The picture size every check judges at, pixels: `shadowlab homework`'s default `--size`, the
/// class check's, and the app's (which shows the pictures scaled into its panel, letterboxed to
/// this shape). Some findings count pixels (a penumbra's width in pixels, the share of a strip that
/// is lit), so a homework checked at the panel's size could read differently in the app than in a
/// class report.
pub const CHECK_SIZE: (u32, u32) = (960, 540);
/// `CHECK_SIZE` as the command line writes it.
pub const CHECK_SIZE_ARG: &str = "960x540";

/// The two stages a homework shader can be.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    Vertex,
    Fragment,
}

impl Stage {
    pub fn naga(self) -> naga::ShaderStage {
        match self {
            Stage::Vertex => naga::ShaderStage::Vertex,
            Stage::Fragment => naga::ShaderStage::Fragment,
        }
    }
}

/// What went wrong with a student's shader, on one line.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum HomeworkError {
    /// The rewrite could not read a construct; `line` is the student's own (1-based).
    #[error("line {line}: {message}")]
    Rewrite { line: usize, message: String },
    /// naga refused the shader; `line` is the student's own (1-based), or none when naga gave no
    /// position or the position lies in the prelude the rewrite added.
    #[error("{file}:{}{message}", line.map(|l| format!("{l}: ")).unwrap_or_else(|| " ".into()))]
    Shader { file: String, line: Option<usize>, message: String },
}

impl HomeworkError {
    /// The same error, naming the student's file.
    pub fn in_file(self, file: &str) -> HomeworkError {
        match self {
            HomeworkError::Rewrite { line, message } => {
                HomeworkError::Shader { file: file.to_string(), line: Some(line), message }
            }
            other => other,
        }
    }

    /// The student's line the error is on, if it names one.
    pub fn line(&self) -> Option<usize> {
        match self {
            HomeworkError::Rewrite { line, .. } => Some(*line),
            HomeworkError::Shader { line, .. } => *line,
        }
    }
}

/// A GPU error in a homework's pipeline or draw, on one line.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{0}")]
pub struct HomeworkGpuError(pub String);

impl From<crate::render::RenderError> for HomeworkGpuError {
    fn from(e: crate::render::RenderError) -> Self {
        HomeworkGpuError(e.to_string())
    }
}

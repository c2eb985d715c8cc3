//! A rewritten shader through naga: the GLSL front end, the validator, the WGSL back end. Every
//! error comes back on one line naming the student's file and the student's own line.

use super::rewrite::{Rewritten, rewrite};
use super::{HomeworkError, Interface, Stage};

/// A student's shader as WGSL, with the rewrite it came from.
#[derive(Clone, Debug)]
pub struct Translated {
    pub wgsl: String,
    pub rewritten: Rewritten,
}

/// Rewrite one stage of a student's shader (`file` is its name, for the messages) and translate it
/// to validated WGSL.
pub fn translate(
    file: &str,
    source: &str,
    stage: Stage,
    layout: &Interface,
) -> Result<Translated, HomeworkError> {
    let rewritten = rewrite(source, stage, layout).map_err(|e| e.in_file(file))?;
    translate_rewritten(file, rewritten)
}

/// Translate an already rewritten shader to validated WGSL.
pub fn translate_rewritten(file: &str, rewritten: Rewritten) -> Result<Translated, HomeworkError> {
    let glsl = &rewritten.glsl;
    let error = |location: Option<naga::SourceLocation>, message: String| {
        let rewritten_line = location.map(|l| l.line_number as usize);
        let line = rewritten_line.and_then(|l| rewritten.student_line(l));
        let message = match (rewritten_line, line) {
            (Some(l), None) => format!("{message} (in the lines shadowlab adds before the shader, line {l})"),
            _ => message,
        };
        HomeworkError::Shader { file: file.to_string(), line, message: one_line(&message) }
    };

    let options = naga::front::glsl::Options::from(rewritten.stage.naga());
    let module = naga::front::glsl::Frontend::default().parse(&options, glsl).map_err(|errors| {
        let first = errors.errors.first();
        let more = match errors.errors.len() {
            0 | 1 => String::new(),
            n => format!(" (and {} more)", n - 1),
        };
        let message = first.map_or_else(|| "cannot parse".to_string(), |e| e.kind.to_string());
        error(first.and_then(|e| e.location(glsl)), format!("{message}{more}"))
    })?;

    if !rewritten.has_main {
        let last_line = glsl.lines().count().saturating_sub(rewritten.prelude_lines);
        return Err(HomeworkError::Shader {
            file: file.to_string(),
            line: Some(last_line.max(1)),
            message: "no `main` function (the framework runs `void main()`)".into(),
        });
    }
    let info = naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    )
    .validate(&module)
    .map_err(|e| {
        let mut message = e.as_inner().to_string();
        let mut source = std::error::Error::source(e.as_inner());
        while let Some(cause) = source {
            message += &format!(": {cause}");
            source = cause.source();
        }
        if let Some((_, label)) = e.spans().next().filter(|(_, label)| !label.is_empty()) {
            message += &format!(" ({label})");
        }
        error(e.location(glsl), message)
    })?;

    let wgsl = naga::back::wgsl::write_string(&module, &info, naga::back::wgsl::WriterFlags::empty())
        .map_err(|e| error(None, format!("cannot write WGSL: {e}")))?;
    Ok(Translated { wgsl, rewritten })
}

/// A message on one line, its runs of whitespace made single spaces.
fn one_line(message: &str) -> String {
    message.split_whitespace().collect::<Vec<_>>().join(" ")
}

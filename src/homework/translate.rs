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
    // What the browser refuses is refused first, as the student saw it refused.
    super::webgl1::check_source(file, source, stage)?;
    let rewritten = rewrite(source, stage, layout).map_err(|e| e.in_file(file))?;
    with_deep_stack(file, || translate_rewritten(file, rewritten))
}

/// Stack for naga's work: its parser, validator and writer recurse on nested expressions.
const NAGA_STACK_BYTES: usize = 256 << 20;

/// Run `work` on a thread with a stack of `NAGA_STACK_BYTES` (a shader nested within the
/// rewrite's limits still recurses deep in naga), or here where threads cannot be had.
fn with_deep_stack<T: Send>(
    file: &str,
    work: impl FnOnce() -> Result<T, HomeworkError> + Send,
) -> Result<T, HomeworkError> {
    // A page has no threads: naga runs on the page's own stack (which web/build.sh enlarges).
    if cfg!(target_arch = "wasm32") {
        return work();
    }
    let failed =
        |message: &str| HomeworkError::Shader { file: file.to_string(), line: None, message: message.into() };
    std::thread::scope(|scope| {
        let thread = std::thread::Builder::new().name("naga".into()).stack_size(NAGA_STACK_BYTES);
        match thread.spawn_scoped(scope, work) {
            Ok(handle) => handle.join().unwrap_or_else(|_| Err(failed("naga could not read this shader"))),
            Err(_) => Err(failed("no thread for naga to read the shader on")),
        }
    })
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
        if !rewritten.has_main && message.contains("Missing entry point") {
            return no_main(file, glsl, rewritten.prelude_lines);
        }
        error(first.and_then(|e| e.location(glsl)), format!("{message}{more}"))
    })?;
    // An array that big per pixel would run for minutes on a software rasteriser, if at all.
    if let Some((name, n, span)) = oversized_array(&module) {
        return Err(error(
            span.location(glsl).into(),
            format!(
                "{name}: an array of {n} elements for every pixel; shadowlab runs at most {MAX_ARRAY_ELEMENTS} \
                 (the framework's template uses 20 to 100 samples)"
            ),
        ));
    }

    if !rewritten.has_main {
        return Err(no_main(file, glsl, rewritten.prelude_lines));
    }
    let student_lines =
        glsl.lines().count().saturating_sub(rewritten.prelude_lines + rewritten.epilogue_lines);
    let student_line = |l: usize| rewritten.student_line(l).filter(|s| *s <= student_lines);
    let text = super::webgl1::Text::new(glsl, &student_line);
    super::webgl1::check_conversions(file, &module, &text)?;
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
    super::webgl1::check_builtins(file, &module, &info, &text)?;

    let wgsl = naga::back::wgsl::write_string(&module, &info, naga::back::wgsl::WriterFlags::empty())
        .map_err(|e| error(None, format!("cannot write WGSL: {e}")))?;
    Ok(Translated { wgsl, rewritten })
}

/// Most elements an array of a student's shader may have (a sample array is 20 to 100).
pub const MAX_ARRAY_ELEMENTS: u32 = 4096;

/// The first variable (global, or local to a function) that is an array of more than
/// `MAX_ARRAY_ELEMENTS`: its name, size and where it is declared.
fn oversized_array(module: &naga::Module) -> Option<(String, u32, naga::Span)> {
    let too_big = |ty: naga::Handle<naga::Type>| match module.types[ty].inner {
        naga::TypeInner::Array { size: naga::ArraySize::Constant(n), .. } if n.get() > MAX_ARRAY_ELEMENTS => {
            Some(n.get())
        }
        _ => None,
    };
    let globals = module.global_variables.iter().filter_map(|(h, v)| {
        too_big(v.ty).map(|n| (v.name.clone().unwrap_or_default(), n, module.global_variables.get_span(h)))
    });
    let functions =
        module.functions.iter().map(|(_, f)| f).chain(module.entry_points.iter().map(|e| &e.function));
    let locals = functions.flat_map(|f| {
        f.local_variables.iter().filter_map(move |(h, v)| {
            too_big(v.ty).map(|n| (v.name.clone().unwrap_or_default(), n, f.local_variables.get_span(h)))
        })
    });
    globals.chain(locals).next()
}

/// The error of a shader without `main`, on its last line.
fn no_main(file: &str, glsl: &str, prelude_lines: usize) -> HomeworkError {
    let last_line = glsl.lines().count().saturating_sub(prelude_lines);
    HomeworkError::Shader {
        file: file.to_string(),
        line: Some(last_line.max(1)),
        message: "no `main` function (the framework runs `void main()`)".into(),
    }
}

/// A message on one line, its runs of whitespace made single spaces.
fn one_line(message: &str) -> String {
    message.split_whitespace().collect::<Vec<_>>().join(" ")
}

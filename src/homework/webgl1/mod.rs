//! What the student's browser refuses and GLSL 450 accepts. The framework compiles every shader
//! with WebGL 1: GLSL ES 1.00, within the minimum of its Appendix A that WebGL 1 enforces (ANGLE
//! checks loops and indexing for WebGL 1 shaders). The rewrite to GLSL 450 would accept more
//! (implicit int-to-float conversions, `%`, `texture()`, `while`...), so a shader the student saw
//! fail to compile would be checked as if it ran. These rules refuse what the browser refuses, on
//! the student's line, naming the rule; anything this reading cannot follow (a condition of the
//! preprocessor it cannot evaluate, a name it does not find) is left to the browser, never refused.

mod module_rules;
mod preprocess;
mod scope;
mod source_rules;
#[cfg(test)]
mod tests;

pub use module_rules::Text;

use super::Stage;

/// One rule of GLSL ES 1.00 / WebGL 1 that GLSL 450 does not have.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rule {
    /// §4.1.10, §5.8-5.9: no implicit conversions (an int where a float is wanted).
    ImplicitConversion,
    /// §8: the built-in functions take floats (`max(int, int)` does not exist).
    IntBuiltin,
    /// §8: functions of later versions (`texture`, `round`, `inverse`...).
    MissingBuiltin,
    /// §5.1: `%`, shifts and bitwise operators are reserved.
    ReservedOperator,
    /// §3.7: `switch`, `default`, unsigned and double types.
    ReservedWord,
    /// §4.1.3-4.1.4: no `f` or `u` suffix on numbers.
    NumberSuffix,
    /// §4.1.9: no array constructors, no array initialisers.
    ArrayConstructor,
    /// Appendix A §4: `for` loops only.
    LoopKind,
    /// Appendix A §4: `for (int i = constant; i < constant; i++)`.
    LoopForm,
    /// Appendix A §4: the loop index is not assigned in the body.
    LoopIndexAssigned,
    /// Appendix A §5: indices are constants and loop indices.
    IndexNotConstant,
}

/// A line WebGL refuses, and why (the message names the rule and what to write instead).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Refusal {
    /// The student's line (1-based).
    pub line: usize,
    pub rule: Rule,
    pub message: String,
}

impl Refusal {
    /// As the one-line error of `file`, saying how many more refusals follow.
    pub fn into_error(self, file: &str, more: usize) -> super::HomeworkError {
        let more = match more {
            0 => String::new(),
            n => format!(" (and {n} more line{} WebGL refuses)", if n == 1 { "" } else { "s" }),
        };
        super::HomeworkError::Shader {
            file: file.to_string(),
            line: Some(self.line),
            message: format!("WebGL 1 refuses this: {}{more}", self.message),
        }
    }
}

/// The first of `refusals` by line, as an error of `file`.
fn first(mut refusals: Vec<Refusal>, file: &str) -> Result<(), super::HomeworkError> {
    refusals.sort_by_key(|r| r.line);
    refusals.dedup_by_key(|r| (r.line, r.rule));
    let more = refusals.len().saturating_sub(1);
    match refusals.into_iter().next() {
        Some(r) => Err(r.into_error(file, more)),
        None => Ok(()),
    }
}

/// The rules read from the student's own text, before the rewrite.
pub fn source_refusals(source: &str, stage: Stage) -> Vec<Refusal> {
    // `#version 300 es` is WebGL 2's GLSL ES 3.00: loops, `%`, `texture()` are all its own.
    let version =
        source.lines().map(str::trim).find_map(|l| l.strip_prefix('#')?.trim_start().strip_prefix("version"));
    if version.is_some_and(|v| !v.trim().starts_with("100")) {
        return Vec::new();
    }
    let shader = scope::Shader::read(source);
    let mut refusals = Vec::new();
    source_rules::check(&shader, stage, &mut refusals);
    refusals
}

/// Refuse `source` (of `file`) where its text breaks a rule.
pub fn check_source(file: &str, source: &str, stage: Stage) -> Result<(), super::HomeworkError> {
    first(source_refusals(source, stage), file)
}

/// Refuse where naga's module of the rewritten shader shows an implicit conversion (before
/// validation: naga's validator may refuse the same line less clearly).
pub fn check_conversions(file: &str, module: &naga::Module, text: &Text) -> Result<(), super::HomeworkError> {
    let mut refusals = Vec::new();
    module_rules::conversions(module, text, &mut refusals);
    first(refusals, file)
}

/// Refuse where a built-in is called with ints (needs the validator's types).
pub fn check_builtins(
    file: &str,
    module: &naga::Module,
    info: &naga::valid::ModuleInfo,
    text: &Text,
) -> Result<(), super::HomeworkError> {
    let mut refusals = Vec::new();
    module_rules::int_builtins(module, info, text, &mut refusals);
    first(refusals, file)
}

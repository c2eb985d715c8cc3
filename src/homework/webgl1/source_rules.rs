//! The rules read from the student's tokens: words and operators GLSL ES 1.00 reserves or lacks,
//! and the Appendix A limits WebGL 1 enforces on loops and indexing.

use super::scope::{DeclKind, Resolved, Shader, TYPES};
use super::{Refusal, Rule};
use crate::homework::Stage;
use crate::homework::lex::Kind;

/// Operators GLSL ES 1.00 reserves (§5.1: "reserved"): the integer and bitwise ones.
const RESERVED_OPERATORS: [&str; 13] =
    ["%", "<<", ">>", "&", "|", "^", "~", "%=", "<<=", ">>=", "&=", "|=", "^="];

/// Keywords GLSL ES 1.00 reserves for later versions (§3.7), those a homework could reach for,
/// and the unsigned types it does not have.
const RESERVED_WORDS: [&str; 16] = [
    "switch", "default", "case", "unsigned", "uint", "uvec2", "uvec3", "uvec4", "double", "dvec2", "dvec3",
    "dvec4", "goto", "enum", "union", "static",
];

/// Built-in functions GLSL ES 1.00 does not have (later GLSL, or ES 3.00), with what it has instead.
const MISSING_BUILTINS: [(&str, &str); 27] = [
    ("texture", "texture2D (or textureCube)"),
    ("textureProj", "texture2DProj"),
    ("textureLod", "texture2D; a fragment shader has no explicit level in WebGL 1"),
    ("textureGrad", "texture2D"),
    ("textureOffset", "texture2D at uv + offset / resolution"),
    ("texelFetch", "texture2D at the texel's centre, (xy + 0.5) / resolution"),
    ("textureSize", "the resolution as a constant or a uniform"),
    ("round", "floor(x + 0.5)"),
    ("roundEven", "floor(x + 0.5)"),
    ("trunc", "sign(x) * floor(abs(x))"),
    ("isnan", "x != x"),
    ("isinf", "abs(x) > 1e38"),
    ("sinh", "(exp(x) - exp(-x)) / 2.0"),
    ("cosh", "(exp(x) + exp(-x)) / 2.0"),
    ("tanh", "(exp(2.0 * x) - 1.0) / (exp(2.0 * x) + 1.0)"),
    ("asinh", "log(x + sqrt(x * x + 1.0))"),
    ("acosh", "log(x + sqrt(x * x - 1.0))"),
    ("atanh", "0.5 * log((1.0 + x) / (1.0 - x))"),
    ("inverse", "the inverse computed on the CPU, as a uniform"),
    ("transpose", "the transpose built by hand or on the CPU"),
    ("determinant", "the determinant written out"),
    ("outerProduct", "a matrix built from the products"),
    ("modf", "fract(x) and x - fract(x)"),
    ("fma", "a * b + c"),
    ("floatBitsToInt", "nothing: GLSL ES 1.00 has no bit casts"),
    ("intBitsToFloat", "nothing: GLSL ES 1.00 has no bit casts"),
    ("packHalf2x16", "nothing: GLSL ES 1.00 has no packing built-ins"),
];

/// Lookups with an explicit level: vertex shaders only in GLSL ES 1.00 (§8.7).
const VERTEX_ONLY: [&str; 4] = ["texture2DLod", "texture2DProjLod", "textureCubeLod", "texture2DProjLodEXT"];
/// Derivatives: only with `#extension GL_OES_standard_derivatives : enable`.
const DERIVATIVES: [&str; 3] = ["dFdx", "dFdy", "fwidth"];

/// Every refusal the tokens show.
pub fn check(shader: &Shader, stage: Stage, refusals: &mut Vec<Refusal>) {
    words_and_operators(shader, stage, refusals);
    loops(shader, refusals);
    indexing(shader, stage, refusals);
}

fn words_and_operators(shader: &Shader, stage: Stage, refusals: &mut Vec<Refusal>) {
    let derivatives_enabled = shader.source.contains("GL_OES_standard_derivatives");
    for (i, t) in shader.toks.iter().enumerate() {
        let word = shader.text(i);
        let line = t.line;
        let call = shader.text(i + 1) == "(" && !shader.defines_function(word);
        let mut refuse = |rule: Rule, message: String| refusals.push(Refusal { line, rule, message });
        match t.kind {
            Kind::Punct if RESERVED_OPERATORS.contains(&word) => refuse(
                Rule::ReservedOperator,
                format!(
                    "`{word}`: GLSL ES 1.00 reserves the integer and bitwise operators{}",
                    if word.starts_with('%') { " (use mod(), on floats)" } else { "" }
                ),
            ),
            Kind::Number => {
                let hex = word.starts_with("0x") || word.starts_with("0X");
                let float_suffix = !hex && (word.ends_with('f') || word.ends_with('F'));
                let unsigned = word.ends_with('u') || word.ends_with('U');
                if float_suffix || unsigned {
                    let what = if unsigned { "unsigned integers" } else { "`f` suffix on numbers" };
                    let plain = word.trim_end_matches(['f', 'F', 'u', 'U']);
                    refuse(
                        Rule::NumberSuffix,
                        format!("`{word}`: GLSL ES 1.00 has no {what}; write `{plain}`"),
                    );
                }
            }
            Kind::Ident if RESERVED_WORDS.contains(&word) => refuse(
                Rule::ReservedWord,
                format!(
                    "`{word}` is reserved or unknown in GLSL ES 1.00 (no switch, no unsigned or double types)"
                ),
            ),
            Kind::Ident if word == "while" || word == "do" => refuse(
                Rule::LoopKind,
                format!(
                    "`{word}` loop: WebGL 1 runs `for` loops only (GLSL ES 1.00 Appendix A §4); write \
                     `for (int i = 0; i < N; i++)` with a constant N and `break`"
                ),
            ),
            Kind::Ident if call => {
                if let Some((_, instead)) = MISSING_BUILTINS.iter().find(|(name, _)| *name == word) {
                    refuse(
                        Rule::MissingBuiltin,
                        format!("`{word}()` is not a built-in of GLSL ES 1.00; use {instead}"),
                    );
                } else if stage == Stage::Fragment && VERTEX_ONLY.contains(&word) {
                    refuse(
                        Rule::MissingBuiltin,
                        format!("`{word}()` exists in vertex shaders only in GLSL ES 1.00; use texture2D"),
                    );
                } else if DERIVATIVES.contains(&word) && !derivatives_enabled {
                    refuse(
                        Rule::MissingBuiltin,
                        format!(
                            "`{word}()` needs `#extension GL_OES_standard_derivatives : enable` (and the \
                             extension enabled by the page) in WebGL 1"
                        ),
                    );
                }
            }
            _ => {}
        }
        // `vec2[](...)`, `float[3](...)`: array constructors; `float a[2] = ...`: initialisers.
        if TYPES.contains(&word)
            && shader.text(i + 1) == "["
            && let Some(close) = shader.closing(i + 1)
            && shader.text(close + 1) == "("
        {
            refusals.push(Refusal {
                line,
                rule: Rule::ArrayConstructor,
                message: format!(
                    "`{word}[...](...)`: GLSL ES 1.00 has no array constructors; fill the array element \
                             by element (the framework's poissonDiskSamples does)"
                ),
            });
        }
    }
    for &open in &shader.array_sizes {
        if let Some(close) = shader.closing(open)
            && shader.text(close + 1) == "="
        {
            refusals.push(Refusal {
                line: shader.line(open),
                rule: Rule::ArrayConstructor,
                message: format!(
                    "`{}[...] = ...`: GLSL ES 1.00 cannot initialise an array where it is declared; \
                         assign its elements one by one",
                    shader.text(open - 1)
                ),
            });
        }
    }
}

/// Why the expression of tokens `from..to` is not a constant expression (or, with `loop_indices`,
/// not a constant-index expression): the first name in it that is a variable, with what it is.
fn not_constant(shader: &Shader, from: usize, to: usize, loop_indices: bool) -> Option<(String, String)> {
    for k in from..to {
        if !shader.is_ident(k) || shader.text(k + 1) == "(" {
            // A call: constructors and built-ins of constants are constant; a function of the
            // student's is not, but it is rarely where a bound is.
            if shader.is_ident(k) && shader.text(k + 1) == "(" && shader.defines_function(shader.text(k)) {
                return Some((shader.text(k).to_string(), "a function of the shader's own".into()));
            }
            continue;
        }
        match shader.resolve(k) {
            // A loop index is a constant-index expression (it is visible inside its loop only).
            Resolved::Decl(d) if d.kind == DeclKind::LoopIndex && loop_indices => continue,
            Resolved::Decl(d) if d.kind != DeclKind::Const => {
                return Some((
                    shader.text(k).to_string(),
                    format!("{} (line {})", d.kind.describe(), d.line),
                ));
            }
            Resolved::Macro => {
                if let Some((name, what)) =
                    macro_not_constant(shader, shader.text(k), k, loop_indices, &mut Vec::new())
                {
                    return Some((name, what));
                }
            }
            _ => {}
        }
    }
    None
}

/// A macro whose body names a variable (`#define N uSamples`): that variable, resolved where the
/// macro is used (token `at`).
fn macro_not_constant(
    shader: &Shader,
    name: &str,
    at: usize,
    loop_indices: bool,
    seen: &mut Vec<String>,
) -> Option<(String, String)> {
    // Each macro is read once per question: a macro naming itself, or one named many times over
    // in a chain, stays linear.
    if seen.iter().any(|s| s == name) {
        return None;
    }
    seen.push(name.to_string());
    let defined = shader.pre.macros.get(name)?;
    let body = &defined.body;
    for t in crate::homework::lex::tokens(body) {
        if t.kind != Kind::Ident {
            continue;
        }
        let word = &body[t.start..t.end];
        if shader.pre.macros.contains_key(word) {
            if let Some(found) = macro_not_constant(shader, word, at, loop_indices, seen) {
                return Some(found);
            }
            continue;
        }
        // The name as if written at `at`: the innermost declaration of it visible there.
        if let Some(d) = shader.visible_decl(word, at) {
            let is_index = d.kind == DeclKind::LoopIndex && loop_indices;
            if d.kind != DeclKind::Const && !is_index {
                let what = format!(
                    "{} (line {}), through #define {name} (line {})",
                    d.kind.describe(),
                    d.line,
                    defined.line
                );
                return Some((word.to_string(), what));
            }
        }
    }
    None
}

/// Appendix A §4: `for (int i = constant; i relop constant; i++ | i-- | i += constant | ...)`,
/// and the index is never assigned in the body.
fn loops(shader: &Shader, refusals: &mut Vec<Refusal>) {
    for l in &shader.loops {
        let line = shader.line(l.at);
        let mut refuse = |message: String| refusals.push(Refusal { line, rule: Rule::LoopForm, message });
        let semicolons: Vec<usize> = (l.open + 1..l.close).filter(|&k| shader.text(k) == ";").collect();
        let [first, second] = semicolons[..] else { continue };
        // Init: [precision] int|float NAME = constant
        let mut k = l.open + 1;
        if matches!(shader.text(k), "highp" | "mediump" | "lowp") {
            k += 1;
        }
        let index_type_ok = matches!(shader.text(k), "int" | "float");
        if !index_type_ok || !shader.is_ident(k + 1) || shader.text(k + 2) != "=" {
            refuse(
                "`for` header: WebGL 1 needs the loop to declare its index, `for (int i = ...; ...)` \
                 (GLSL ES 1.00 Appendix A §4)"
                    .into(),
            );
            continue;
        }
        let index = shader.text(k + 1);
        let index_at = k + 1;
        if let Some((name, what)) = not_constant(shader, k + 3, first, false) {
            refuse(format!(
                "`for` loop: the index `{index}` starts at `{name}`, {what}; WebGL 1 needs a constant \
                 expression there (GLSL ES 1.00 Appendix A §4)"
            ));
            continue;
        }
        // Condition: index relop constant.
        let c = first + 1;
        let relop = matches!(shader.text(c + 1), "<" | ">" | "<=" | ">=" | "==" | "!=");
        if shader.text(c) != index || !relop {
            refuse(format!(
                "`for` loop: WebGL 1 needs the condition as `{index} < constant` (the index, a comparison, a \
                 constant expression: GLSL ES 1.00 Appendix A §4)"
            ));
            continue;
        }
        if let Some((name, what)) = not_constant(shader, c + 2, second, false) {
            refuse(format!(
                "`for` loop: `{index}` is compared with `{name}`, {what}; WebGL 1 needs a constant bound \
                 (GLSL ES 1.00 Appendix A §4): loop to a #define or const and `break` at `{name}`"
            ));
            continue;
        }
        // Expression: i++, i--, ++i, --i, i += constant, i -= constant.
        let e: Vec<&str> = (second + 1..l.close).map(|k| shader.text(k)).collect();
        let step_ok = match e[..] {
            [a, "++" | "--"] | ["++" | "--", a] => a == index,
            [a, "+=" | "-=", ..] if a == index => not_constant(shader, second + 3, l.close, false).is_none(),
            _ => false,
        };
        if !step_ok {
            refuse(format!(
                "`for` loop: WebGL 1 steps the index as `{index}++`, `{index}--` or `{index} += constant` \
                 only (GLSL ES 1.00 Appendix A §4)"
            ));
            continue;
        }
        // Body: the index is never assigned.
        let Some(index_decl) = shader.visible_decl(index, index_at) else { continue };
        for k in l.close + 1..=l.body_end {
            let is_index = shader.text(k) == index && shader.resolve(k) == Resolved::Decl(index_decl);
            if !is_index {
                continue;
            }
            let assigned = matches!(shader.text(k + 1), "=" | "+=" | "-=" | "*=" | "/=" | "++" | "--")
                || matches!(shader.text(k.saturating_sub(1)), "++" | "--");
            if assigned {
                refusals.push(Refusal {
                    line: shader.line(k),
                    rule: Rule::LoopIndexAssigned,
                    message: format!(
                        "the loop index `{index}` is changed inside its loop; WebGL 1 forbids that (GLSL ES 1.00 \
                         Appendix A §4): `break` or `continue` instead"
                    ),
                });
            }
        }
    }
}

/// Appendix A §5: arrays, vectors and matrices are indexed by constant-index expressions
/// (constants and loop indices) only, except uniforms in a vertex shader.
fn indexing(shader: &Shader, stage: Stage, refusals: &mut Vec<Refusal>) {
    for open in 0..shader.toks.len() {
        if shader.text(open) != "[" || shader.is_array_size(open) || open == 0 {
            continue;
        }
        let before = shader.text(open - 1);
        if !(shader.is_ident(open - 1) || before == "]" || before == ")") || TYPES.contains(&before) {
            continue;
        }
        let Some(close) = shader.closing(open) else { continue };
        if stage == Stage::Vertex
            && shader.is_ident(open - 1)
            && let Resolved::Decl(d) = shader.resolve(open - 1)
            && d.kind == DeclKind::Uniform
        {
            continue;
        }
        if let Some((name, what)) = not_constant(shader, open + 1, close, true) {
            let indexed = if shader.is_ident(open - 1) { before } else { "an array" };
            refusals.push(Refusal {
                line: shader.line(open),
                rule: Rule::IndexNotConstant,
                message: format!(
                    "`{indexed}[...]` is indexed by `{name}`, {what}; WebGL 1 indexes with constants and loop \
                     indices only (GLSL ES 1.00 Appendix A §5)"
                ),
            });
        }
    }
}

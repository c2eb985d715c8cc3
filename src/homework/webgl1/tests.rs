//! One example per rule: a shader GLSL 450 (naga, after the rewrite) accepts and WebGL 1 refuses,
//! refused on the right line with the rule named; and the same shader written as WebGL 1 wants it,
//! accepted.

use super::*;
use crate::homework::{HomeworkError, Interface, translate};

/// A fragment shader whose line 6 onwards is `body` (a function `float f(float x, int n)` and
/// what it needs), with the framework's precision header and a `main` that calls `f`.
fn fragment(body: &str) -> String {
    format!(
        "#ifdef GL_ES\nprecision mediump float;\n#endif\n#define NUM_SAMPLES 20\nvec2 poissonDisk[NUM_SAMPLES];\n\
         {body}\nvoid main() {{ gl_FragColor = vec4(f(0.5, 2)); }}\n"
    )
}

/// Translate as the check does; the error's line and message.
fn refused(source: &str, stage: Stage) -> Option<(Option<usize>, String)> {
    match translate("example.glsl", source, stage, &Interface::framework()) {
        Ok(_) => None,
        Err(HomeworkError::Shader { line, message, .. }) => Some((line, message)),
        Err(e) => Some((e.line(), e.to_string())),
    }
}

/// The rule's example is refused on `line` saying `says`; the fix is accepted; and naga alone
/// (the rewrite without these rules) accepts the example, so the rule is what refuses it.
fn check(rule: Rule, bad: &str, good: &str, line: usize, says: &str) {
    check_with(rule, bad, good, line, says);
    assert!(
        naga_accepts(&fragment(bad)),
        "{rule:?}: naga alone refuses the example, the rule is not what refuses it"
    );
}

/// As `check`, for an example naga's validator refuses too, less clearly than the rule.
fn check_with(rule: Rule, bad: &str, good: &str, line: usize, says: &str) {
    let (bad, good) = (fragment(bad), fragment(good));
    let found = source_refusals(&bad, Stage::Fragment);
    let (at, message) =
        refused(&bad, Stage::Fragment).unwrap_or_else(|| panic!("{rule:?}: accepted:\n{bad}"));
    assert_eq!(at, Some(line), "{rule:?}: {message}");
    assert!(message.contains("WebGL 1 refuses") && message.contains(says), "{rule:?}: {message}");
    // Which rule refused: a source rule lists it; a type rule is the only one left.
    let named = found.iter().any(|r| r.rule == rule)
        || (found.is_empty() && matches!(rule, Rule::ImplicitConversion | Rule::IntBuiltin));
    assert!(named, "{rule:?}: refused by {found:?}");
    assert_eq!(refused(&good, Stage::Fragment), None, "{rule:?}: the fix is refused:\n{good}");
}

/// Whether the rewrite and naga accept `source` (the rules of this module left out).
fn naga_accepts(source: &str) -> bool {
    let Ok(rewritten) = crate::homework::rewrite(source, Stage::Fragment, &Interface::framework()) else {
        return false;
    };
    let options = naga::front::glsl::Options::from(naga::ShaderStage::Fragment);
    let Ok(module) = naga::front::glsl::Frontend::default().parse(&options, &rewritten.glsl) else {
        return false;
    };
    let flags = naga::valid::ValidationFlags::all();
    naga::valid::Validator::new(flags, naga::valid::Capabilities::default()).validate(&module).is_ok()
}

#[test]
fn an_int_where_a_float_is_needed_is_refused_in_arithmetic_assignments_arguments_and_returns() {
    let rule = Rule::ImplicitConversion;
    // Arithmetic with an int #define: refused where it is used, naming the #define.
    check(
        rule,
        "float f(float x, int n) {\n  return x / NUM_SAMPLES;\n}",
        "float f(float x, int n) {\n  return x / float(NUM_SAMPLES);\n}",
        7,
        "`NUM_SAMPLES` (#define NUM_SAMPLES 20, line 4)",
    );
    // An int variable in arithmetic.
    check(
        rule,
        "float f(float x, int n) {\n  return x * n;\n}",
        "float f(float x, int n) {\n  return x * float(n);\n}",
        7,
        "`n` is an int",
    );
    // Assignment of an int literal.
    check(
        rule,
        "float f(float x, int n) {\n  float s = 0.0;\n  s = 1;\n  return s * x;\n}",
        "float f(float x, int n) {\n  float s = 0.0;\n  s = 1.0;\n  return s * x;\n}",
        8,
        "write 1.0",
    );
    // An int literal as a built-in's argument.
    check(
        rule,
        "float f(float x, int n) {\n  return pow(x, 2);\n}",
        "float f(float x, int n) {\n  return pow(x, 2.0);\n}",
        7,
        "`2` is an int",
    );
    // An int argument to the student's own float parameter.
    check(
        rule,
        "float g(float y) { return y; }\nfloat f(float x, int n) {\n  return g(n) * x;\n}",
        "float g(float y) { return y; }\nfloat f(float x, int n) {\n  return g(float(n)) * x;\n}",
        8,
        "`n` is an int",
    );
    // A comparison with an int literal, and a return of one.
    check(
        rule,
        "float f(float x, int n) {\n  if (x < 0) return 0.0;\n  return x;\n}",
        "float f(float x, int n) {\n  if (x < 0.0) return 0.0;\n  return x;\n}",
        7,
        "`0` is an int",
    );
    // naga's validator refuses this one too, saying only that the function is invalid.
    check_with(
        rule,
        "float f(float x, int n) {\n  if (x < 0.0) return 1;\n  return x;\n}",
        "float f(float x, int n) {\n  if (x < 0.0) return 1.0;\n  return x;\n}",
        7,
        "`return 1;` in a function that returns a float",
    );
    // Constructors convert: these are explicit, never refused.
    let constructors = fragment(
        "float f(float x, int n) {\n  vec2 a = vec2(1, n) + vec2(2);\n  return a.x * float(3) * x;\n}",
    );
    assert_eq!(refused(&constructors, Stage::Fragment), None);
}

#[test]
fn a_built_in_called_with_ints_is_refused() {
    check(
        Rule::IntBuiltin,
        "float f(float x, int n) {\n  int m = max(n, 1);\n  return x * float(m);\n}",
        "float f(float x, int n) {\n  float m = max(float(n), 1.0);\n  return x * m;\n}",
        7,
        "`max` of the int `n`",
    );
}

#[test]
fn built_ins_of_later_versions_are_refused() {
    check(
        Rule::MissingBuiltin,
        "float f(float x, int n) {\n  return round(x);\n}",
        "float f(float x, int n) {\n  return floor(x + 0.5);\n}",
        7,
        "`round()` is not a built-in of GLSL ES 1.00",
    );
    // A function of the student's own with that name is theirs to call.
    let own = fragment(
        "float round(float y) { return floor(y + 0.5); }\nfloat f(float x, int n) {\n  return round(x);\n}",
    );
    assert_eq!(refused(&own, Stage::Fragment), None);
}

#[test]
fn reserved_operators_are_refused() {
    check(
        Rule::ReservedOperator,
        "float f(float x, int n) {\n  int m = n % 4;\n  return x * float(m);\n}",
        "float f(float x, int n) {\n  float m = mod(float(n), 4.0);\n  return x * m;\n}",
        7,
        "`%`",
    );
}

#[test]
fn reserved_words_are_refused() {
    check(
        Rule::ReservedWord,
        "float f(float x, int n) {\n  switch (n) { case 1: return x; }\n  return 0.0;\n}",
        "float f(float x, int n) {\n  if (n == 1) { return x; }\n  return 0.0;\n}",
        7,
        "`switch` is reserved",
    );
}

#[test]
fn number_suffixes_are_refused() {
    check(
        Rule::NumberSuffix,
        "float f(float x, int n) {\n  return x * 0.5f;\n}",
        "float f(float x, int n) {\n  return x * 0.5;\n}",
        7,
        "write `0.5`",
    );
}

#[test]
fn array_constructors_and_initialisers_are_refused() {
    check(
        Rule::ArrayConstructor,
        "float f(float x, int n) {\n  float w[2] = float[2](0.25, 0.75);\n  return x * w[1];\n}",
        "float f(float x, int n) {\n  float w[2];\n  w[0] = 0.25;\n  w[1] = 0.75;\n  return x * w[1];\n}",
        7,
        "no array constructors",
    );
}

#[test]
fn while_loops_are_refused() {
    check(
        Rule::LoopKind,
        "float f(float x, int n) {\n  float s = x;\n  while (s < 1.0) { s *= 2.0; }\n  return s;\n}",
        "float f(float x, int n) {\n  float s = x;\n  for (int i = 0; i < 32; i++) { if (s >= 1.0) break; s *= 2.0; }\n  return s;\n}",
        8,
        "`while` loop",
    );
}

#[test]
fn a_loop_to_a_variable_bound_is_refused_and_one_to_a_constant_with_a_break_is_not() {
    check(
        Rule::LoopForm,
        "float f(float x, int n) {\n  float s = 0.0;\n  for (int i = 0; i < n; i++) { s += x; }\n  return s;\n}",
        "float f(float x, int n) {\n  float s = 0.0;\n  for (int i = 0; i < NUM_SAMPLES; i++) { if (i >= n) break; s += x; }\n  return s;\n}",
        8,
        "`i` is compared with `n`, a function parameter (line 6)",
    );
    // A bound through a #define of a uniform is no constant either.
    let via_define = "#define COUNT uCount\nuniform int uCount;\nfloat f(float x, int n) {\n  float s = 0.0;\n  \
                      for (int i = 0; i < COUNT; i++) { s += x; }\n  return s;\n}";
    let found = source_refusals(&fragment(via_define), Stage::Fragment);
    assert!(
        found.iter().any(|r| r.rule == Rule::LoopForm && r.line == 10 && r.message.contains("#define COUNT")),
        "{found:?}"
    );
    // A step other than ++, --, += and -= is refused.
    check(
        Rule::LoopForm,
        "float f(float x, int n) {\n  float s = 0.0;\n  for (int i = 1; i < 64; i *= 2) { s += x; }\n  return s;\n}",
        "float f(float x, int n) {\n  float s = 0.0;\n  for (int i = 1; i < 64; i += 2) { s += x; }\n  return s;\n}",
        8,
        "steps the index",
    );
}

#[test]
fn assigning_the_loop_index_in_its_body_is_refused() {
    check(
        Rule::LoopIndexAssigned,
        "float f(float x, int n) {\n  float s = 0.0;\n  for (int i = 0; i < 8; i++) {\n    s += x;\n    if (s > 1.0) i = 8;\n  }\n  return s;\n}",
        "float f(float x, int n) {\n  float s = 0.0;\n  for (int i = 0; i < 8; i++) {\n    s += x;\n    if (s > 1.0) break;\n  }\n  return s;\n}",
        10,
        "the loop index `i` is changed",
    );
}

#[test]
fn indexing_by_a_variable_is_refused_and_by_a_loop_index_or_constant_is_not() {
    check(
        Rule::IndexNotConstant,
        "float f(float x, int n) {\n  int k = n + 1;\n  return poissonDisk[k].x * x;\n}",
        "float f(float x, int n) {\n  const int k = 3;\n  float s = poissonDisk[k].x;\n  for (int i = 0; i < NUM_SAMPLES; i++) { s += poissonDisk[i].y; }\n  return s * x;\n}",
        8,
        "indexed by `k`, a variable (line 7)",
    );
    // A vertex shader may index a uniform array by anything.
    let vertex = "attribute vec3 aVertexPosition;\nuniform vec4 uOffsets[4];\nuniform int uWhich;\nvoid main() {\n  \
                  gl_Position = vec4(aVertexPosition, 1.0) + uOffsets[uWhich];\n}\n";
    assert!(source_refusals(vertex, Stage::Vertex).is_empty());
    assert!(source_refusals(vertex, Stage::Fragment).iter().any(|r| r.rule == Rule::IndexNotConstant));
}

#[test]
fn code_the_preprocessor_leaves_out_and_webgl2_shaders_are_not_judged() {
    let disabled =
        fragment("float f(float x, int n) {\n#if 0\n  return x * 0.5f;\n#else\n  return x * 0.5;\n#endif\n}");
    assert_eq!(refused(&disabled, Stage::Fragment), None);
    let not_es = fragment(
        "float f(float x, int n) {\n#ifndef GL_ES\n  while (x < 1.0) { x *= 2.0; }\n#endif\n  return x;\n}",
    );
    assert!(source_refusals(&not_es, Stage::Fragment).is_empty());
    let webgl2 = "#version 300 es\nprecision mediump float;\nout vec4 c;\nvoid main() { int m = 5 % 2; c = vec4(m); }\n";
    assert!(source_refusals(webgl2, Stage::Fragment).is_empty());
}

#[test]
fn the_framework_and_the_projects_examples_are_accepted() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/homework");
    let mut seen = 0;
    for entry in std::fs::read_dir(&dir)
        .into_iter()
        .flatten()
        .chain(std::fs::read_dir(dir.join("framework")).into_iter().flatten())
    {
        let path = entry.expect("a directory entry").path();
        let name = path.file_name().and_then(|n| n.to_str()).unwrap_or_default().to_string();
        if !name.ends_with(".glsl") {
            continue;
        }
        let source = std::fs::read_to_string(&path).expect("readable");
        let stage = if name.contains("Vertex") { Stage::Vertex } else { Stage::Fragment };
        assert_eq!(source_refusals(&source, stage), vec![], "{name}");
        seen += 1;
    }
    assert!(seen >= 20, "{seen} shaders");
}

#[test]
fn macros_that_name_themselves_or_each_other_many_times_are_read_once() {
    // A macro whose body names itself hundreds of times (a fuzzed shader hung on this), used as a
    // loop bound and in an `#if`: read once, nothing refused for it, and the reading ends.
    let body = "N ".repeat(400);
    let source = fragment(&format!(
        "#define N {body}\n#if N > 1\n#endif\nfloat f(float x, int n) {{\n  for (int i = 0; i < N; i++) {{ x += 1.0; }}\n  return x;\n}}"
    ));
    assert!(source_refusals(&source, Stage::Fragment).iter().all(|r| r.rule != Rule::LoopForm));
    // A chain where each macro names the next many times: its expansion is cut, not followed.
    let chain: String =
        (0..12).map(|k| format!("#define M{k} {}\n", format!("M{} ", k + 1).repeat(8))).collect();
    let source = fragment(&format!("{chain}#if M0\n#endif\nfloat f(float x, int n) {{ return x; }}"));
    assert_eq!(source_refusals(&source, Stage::Fragment), vec![]);
}

#[test]
fn names_webgl_allows_and_glsl_450_keeps_are_renamed_not_refused() {
    // WebGL 1 compiles these names; GLSL 450 (and Vulkan's GLSL) keeps them as keywords.
    for name in ["sample", "patch", "buffer", "shared", "smooth", "sampler", "precise"] {
        let source = fragment(&format!(
            "float f(float x, int n) {{ vec2 {name} = poissonDisk[0] * x; return {name}.x + float(n); }}"
        ));
        assert_eq!(refused(&source, Stage::Fragment), None, "`{name}` as a local");
    }
}

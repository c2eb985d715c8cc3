//! Where in the student's fragment shader a finding's quantity is written: the constants a depth
//! test compares with (a literal on the line, or a `#define` the line names), the function each
//! line is in, and the depth their light gives a world unit (what turns a bias in [0, 1] depth
//! into world units).

use super::Judged;
use crate::homework::RECORDED_FUNCTIONS;
use crate::homework::lex::{Kind, matching, tokens};
use glam::Vec3;

/// A number the student wrote where a depth test can read it.
#[derive(Clone, Debug, PartialEq)]
pub struct Constant {
    /// The student's line (1-based): the `#define`'s for a macro.
    pub line: usize,
    /// As written: `0.005`, or the macro's name.
    pub text: String,
    pub value: f64,
    /// The recorded function the test is in (`PCF`, `findBlocker`...), where it is in one.
    pub function: Option<&'static str>,
}

/// The recorded functions' bodies: (name, first line, last line).
fn function_lines(source: &str) -> Vec<(&'static str, usize, usize)> {
    let toks = tokens(source);
    let text = |i: usize| toks.get(i).map_or("", |t| &source[t.start..t.end]);
    let mut out = Vec::new();
    let mut depth = 0i32;
    let mut i = 0;
    while i < toks.len() {
        match text(i) {
            "{" => depth += 1,
            "}" => depth -= 1,
            name if depth == 0 && text(i + 1) == "(" => {
                if let Some(recorded) = RECORDED_FUNCTIONS.iter().find(|f| **f == name) {
                    // Its body: the first `{` after the parameters, to the brace closing it.
                    let open = (i + 1..toks.len()).find(|&k| text(k) == "{" || text(k) == ";");
                    if let Some(open) = open.filter(|&k| text(k) == "{") {
                        let close = matching(source, &toks, open, "{", "}");
                        if close > open && text(close) == "}" {
                            out.push((*recorded, toks[open].line, toks[close].line));
                            i = close;
                        }
                    }
                }
            }
            _ => {}
        }
        i += 1;
    }
    out
}

/// The constants in the depth tests of the recorded functions: float literals on a line that
/// compares (`<`, `>`), and the `#define`s such a line names, with values between 0 and 0.2 (a
/// bias in [0, 1] depth; a sample count or a resolution is not one).
pub fn depth_test_constants(source: &str) -> Vec<Constant> {
    let toks = tokens(source);
    let functions = function_lines(source);
    let in_function =
        |line: usize| functions.iter().find(|&&(_, from, to)| (from..=to).contains(&line)).map(|&(f, ..)| f);
    let word = |i: usize| &source[toks[i].start..toks[i].end];
    // `#define NAME number`: name -> (line, value).
    let mut defines = std::collections::HashMap::new();
    for (i, t) in toks.iter().enumerate() {
        if t.kind == Kind::Directive && word(i).trim_start_matches('#').trim() == "define" {
            let (Some(name), Some(value)) = (toks.get(i + 1), toks.get(i + 2)) else { continue };
            let single = toks.get(i + 3).is_none_or(|n| n.line != t.line || !n.in_directive);
            if value.kind == Kind::Number
                && single
                && value.line == t.line
                && let Ok(v) = source[value.start..value.end].trim_end_matches(['f', 'F']).parse::<f64>()
            {
                defines.insert(&source[name.start..name.end], (t.line, v));
            }
        }
    }
    // `float NAME = number;` (a local or a global): name -> [(line, value)].
    let mut locals: std::collections::HashMap<&str, Vec<(usize, f64)>> = std::collections::HashMap::new();
    for i in 0..toks.len().saturating_sub(4) {
        let declared = word(i) == "float"
            && toks[i + 1].kind == Kind::Ident
            && word(i + 2) == "="
            && toks[i + 3].kind == Kind::Number
            && word(i + 4) == ";";
        if declared && let Ok(v) = word(i + 3).trim_end_matches(['f', 'F']).parse::<f64>() {
            locals.entry(word(i + 1)).or_default().push((toks[i + 1].line, v));
        }
    }
    // The declaration of `name` a use on `line` reads: the latest before it in the same function,
    // else one outside every function.
    let local = |name: &str, line: usize| {
        let body = functions.iter().find(|&&(_, from, to)| (from..=to).contains(&line));
        let declared = locals.get(name)?;
        let inside = |l: usize| body.is_some_and(|&(_, from, _)| (from..=line).contains(&l));
        let outside = |l: usize| !functions.iter().any(|&(_, from, to)| (from..=to).contains(&l));
        declared
            .iter()
            .filter(|&&(l, _)| inside(l))
            .max_by_key(|&&(l, _)| l)
            .or_else(|| declared.iter().find(|&&(l, _)| outside(l)))
            .copied()
    };
    let compares: std::collections::BTreeSet<usize> = toks
        .iter()
        .enumerate()
        .filter(|&(i, t)| !t.in_directive && matches!(word(i), "<" | ">") && in_function(t.line).is_some())
        .map(|(_, t)| t.line)
        .filter(|&line| !toks.iter().enumerate().any(|(i, t)| t.line == line && word(i) == "for"))
        .collect();
    let mut out: Vec<Constant> = Vec::new();
    for (i, t) in toks.iter().enumerate() {
        if t.in_directive || !compares.contains(&t.line) {
            continue;
        }
        let found = match t.kind {
            Kind::Number if word(i).contains(['.', 'e']) => {
                word(i).parse::<f64>().ok().map(|v| (t.line, word(i).to_string(), v))
            }
            Kind::Ident => defines
                .get(word(i))
                .copied()
                .or_else(|| local(word(i), t.line))
                .map(|(line, v)| (line, word(i).to_string(), v)),
            _ => None,
        };
        if let Some((line, text, value)) = found.filter(|f| f.2 > 0.0 && f.2 < 0.2) {
            let constant = Constant { line, text, value, function: in_function(t.line) };
            if !out.iter().any(|c| c.line == constant.line && c.text == constant.text) {
                out.push(constant);
            }
        }
    }
    out
}

/// [0, 1] depth per world unit along the light, at the floor under the view (the depth the
/// student's `uLightMVP` gives: 1 / (far - near) for an orthographic light).
pub fn depth_per_world(j: &Judged<'_>) -> Option<f32> {
    let e = j.e;
    let (i, p) = (0..e.positions.len()).find_map(|i| Some((i, e.positions[i]?)))?;
    let o = e.objects.get(i).copied().flatten()?;
    let clip_from_world = *e.light.clip_from_object.get(o)? * e.light.world_from_object.get(o)?.inverse();
    let depth = |q: Vec3| {
        let clip = clip_from_world * q.extend(1.0);
        0.5 * clip.z / clip.w + 0.5
    };
    let at = depth(p);
    let gradient = Vec3::new(depth(p + Vec3::X) - at, depth(p + Vec3::Y) - at, depth(p + Vec3::Z) - at);
    let per_world = gradient.length();
    (per_world.is_finite() && per_world > 0.0).then_some(per_world)
}

#[cfg(test)]
mod tests {
    use super::*;

    const SHADER: &str = "#define EPS 1e-3\n#define BIAS 0.005\n#define NUM 20\n\
        float findBlocker(vec2 uv, float z) {\n  float d = 0.0;\n  if (z - BIAS > d) d += 1.0;\n  return d;\n}\n\
        float PCF(vec4 c) {\n  float v = 0.0;\n  for (int i = 0; i < NUM; i++) { v += 1.0; }\n  \
        return c.z < v + 0.015 ? 1.0 : 0.0;\n}\nfloat useShadowMap(vec4 c) {\n  float bias = 0.03;\n  \
        return c.z - bias > 0.5 ? 0.0 : 1.0;\n}\nvoid main() { float x = 0.5 < 1.0 ? 0.25 : EPS; }\n";

    #[test]
    fn the_constants_of_the_recorded_functions_depth_tests_are_found_with_their_lines() {
        let found = depth_test_constants(SHADER);
        let said: Vec<(usize, &str, Option<&str>)> =
            found.iter().map(|c| (c.line, c.text.as_str(), c.function)).collect();
        // BIAS is named where it is defined (line 2), in findBlocker's test; PCF's literal on its
        // line; a loop bound, a count, `0.5` and `main`'s comparison are not depth tests.
        // A local set to a number is named where it is set (line 15).
        assert_eq!(
            said,
            [
                (2, "BIAS", Some("findBlocker")),
                (12, "0.015", Some("PCF")),
                (15, "bias", Some("useShadowMap"))
            ]
        );
    }
}

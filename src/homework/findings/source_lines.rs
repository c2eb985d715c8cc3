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
    /// Added to or taken from a depth where the test reads it (`depth + BIAS`): a bias, not a
    /// threshold compared with alone (`depth < EPS`, a texel never written).
    pub added: bool,
}

/// The recorded functions' bodies: (name, first line, last line).
fn function_lines(source: &str) -> Vec<(&'static str, usize, usize)> {
    let toks = tokens(source);
    function_bodies(source, &toks)
        .into_iter()
        .filter_map(|(name, open, close)| {
            let recorded = RECORDED_FUNCTIONS.iter().find(|f| **f == name)?;
            Some((*recorded, toks[open].line, toks[close].line))
        })
        .collect()
}

/// The constants in the depth tests of the recorded functions: float literals on a line that
/// compares (`<`, `>`), and the `#define`s such a line names, with values between 0 and 0.2 (a
/// bias in [0, 1] depth; a sample count or a resolution is not one). Once per function.
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
        // `step(z, depth + BIAS)` compares too (1 where depth + BIAS >= z).
        .filter(|&(i, t)| {
            !t.in_directive && matches!(word(i), "<" | ">" | "step") && in_function(t.line).is_some()
        })
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
            let next_to =
                |k: usize| toks.get(k).is_some_and(|n| n.line == t.line && matches!(word(k), "+" | "-"));
            // Or compared with a difference of depths (`z - depth < 0.01`): the same bias.
            let compared_with_difference = i > 0 && matches!(word(i - 1), "<" | ">" | "=") && {
                let start = (0..i).rev().take_while(|&k| toks[k].line == t.line).last().unwrap_or(i);
                (start..i).any(|k| word(k) == "-")
            };
            let added = next_to(i + 1) || (i > 0 && next_to(i - 1)) || compared_with_difference;
            let constant = Constant { line, text, value, function: in_function(t.line), added };
            let same = |c: &Constant| {
                c.line == constant.line
                    && c.text == constant.text
                    && c.function == constant.function
                    && c.added == constant.added
            };
            if !out.iter().any(same) {
                out.push(constant);
            }
        }
    }
    out
}

/// A bias the student's code computes: a local a recorded function's depth test reads, set by an
/// expression that is not a plain number (`float bias = Bias(0.15);`).
#[derive(Clone, Debug, PartialEq)]
pub struct ComputedBias {
    /// Where it is set (1-based), and the function it is in.
    pub line: usize,
    pub function: &'static str,
    pub name: String,
    /// The expression as written, on one line.
    pub expression: String,
}

/// The computed biases in the recorded functions' depth tests (lines that compare with `<` or
/// `>`), named as biases, first in the file first, each once.
pub fn computed_biases(source: &str) -> Vec<ComputedBias> {
    let toks = tokens(source);
    let word = |i: usize| &source[toks[i].start..toks[i].end];
    let functions = function_lines(source);
    let in_function =
        |line: usize| functions.iter().find(|&&(_, from, to)| (from..=to).contains(&line)).map(|&(f, ..)| f);
    let mut out: Vec<ComputedBias> = Vec::new();
    for i in 1..toks.len().saturating_sub(2) {
        // `float NAME = ...;` inside a recorded function, not a plain number.
        if word(i - 1) != "float" || toks[i].kind != Kind::Ident || word(i + 1) != "=" {
            continue;
        }
        let Some(function) = in_function(toks[i].line) else { continue };
        let Some(end) = (i + 2..toks.len()).find(|&k| word(k) == ";") else { continue };
        if end == i + 3 && toks[i + 2].kind == Kind::Number {
            continue;
        }
        let name = word(i);
        // Read by a later comparison in the same function.
        let body = functions.iter().find(|f| f.0 == function).map_or((0, 0), |f| (f.1, f.2));
        let compared = (end..toks.len()).any(|k| {
            word(k) == name
                && toks[k].line <= body.1
                && (k.saturating_sub(3)..(k + 4).min(toks.len())).any(|m| matches!(word(m), "<" | ">"))
        });
        let expression =
            source[toks[i + 2].start..toks[end - 1].end].split_whitespace().collect::<Vec<_>>().join(" ");
        // Named as a bias (`bias`, `EPS`, `shadowBias`, or set by a `Bias(...)` call): a depth or
        // a coordinate compared on the same line is not one.
        let says_bias = |t: &str| {
            let t = t.to_ascii_lowercase();
            t.contains("bias") || t.contains("eps")
        };
        let named = says_bias(name) || says_bias(&expression);
        if compared && named && !out.iter().any(|c| c.expression == expression && c.name == name) {
            out.push(ComputedBias { line: toks[i].line, function, name: name.to_string(), expression });
        }
    }
    out
}

/// The recorded functions with a depth test of their own: a line that compares two depths (not a
/// loop's bound, not one value against a constant alone, `blockerDepth >= 1e-5`, `d < EPS`).
pub fn functions_with_depth_tests(source: &str) -> Vec<&'static str> {
    let toks = tokens(source);
    let word = |i: usize| toks.get(i).map_or("", |t| &source[t.start..t.end]);
    // A number, or a macro's name (upper case by custom).
    let constant = |k: usize| {
        toks.get(k).is_some_and(|t| {
            t.kind == Kind::Number
                || (t.kind == Kind::Ident
                    && word(k).chars().all(|c| c.is_ascii_uppercase() || c == '_' || c.is_ascii_digit()))
        })
    };
    let functions = function_lines(source);
    let mut out = Vec::new();
    for &(name, from, to) in &functions {
        let compares = (0..toks.len()).any(|i| {
            let line = toks[i].line;
            if !(from..=to).contains(&line) || toks[i].in_directive || !matches!(word(i), "<" | ">") {
                return false;
            }
            let on_line = |k: usize| toks[k].line == line;
            if toks.iter().enumerate().any(|(k, t)| t.line == line && word(k) == "for") {
                return false;
            }
            // `value OP constant` (or the mirror) with no sum or difference on the line.
            let after = if word(i + 1) == "=" { i + 2 } else { i + 1 };
            let sums = (0..toks.len()).filter(|&k| on_line(k)).any(|k| matches!(word(k), "+" | "-"));
            let alone = (constant(after) || (i > 0 && constant(i - 1))) && !sums;
            !alone
        });
        if compares && !out.contains(&name) {
            out.push(name);
        }
    }
    out
}

/// How the student's light maps a world point near the floor under the view: the gradients of
/// its map u and of its [0, 1] depth, per world unit.
fn light_gradients(j: &Judged<'_>) -> Option<(Vec3, Vec3)> {
    let e = j.e;
    let (i, p) = (0..e.positions.len()).find_map(|i| Some((i, e.positions[i]?)))?;
    let o = e.objects.get(i).copied().flatten()?;
    let clip_from_world = *e.light.clip_from_object.get(o)? * e.light.world_from_object.get(o)?.inverse();
    let map = |q: Vec3| {
        let clip = clip_from_world * q.extend(1.0);
        Vec3::new(0.5 * clip.x / clip.w + 0.5, 0.0, 0.5 * clip.z / clip.w + 0.5)
    };
    let at = map(p);
    let d = [Vec3::X, Vec3::Y, Vec3::Z].map(|a| map(p + a) - at);
    Some((Vec3::new(d[0].x, d[1].x, d[2].x), Vec3::new(d[0].z, d[1].z, d[2].z)))
}

/// [0, 1] depth per world unit along the light, at the floor under the view (the depth the
/// student's `uLightMVP` gives: 1 / (far - near) for an orthographic light).
pub fn depth_per_world(j: &Judged<'_>) -> Option<f32> {
    let per_world = light_gradients(j)?.1.length();
    (per_world.is_finite() && per_world > 0.0).then_some(per_world)
}

/// World units across the light per unit of the map's uv, at the floor under the view (the
/// orthographic box's width).
pub fn world_per_uv(j: &Judged<'_>) -> Option<f32> {
    let per_world = light_gradients(j)?.0.length();
    (per_world.is_finite() && per_world > 0.0).then(|| 1.0 / per_world)
}

/// A `#define` of a number (or a number on a line of code) within 10% of one of `values`: the
/// constant a measured quantity comes from. The first such in the file.
pub fn constant_near(source: &str, values: &[f32]) -> Option<Constant> {
    let toks = tokens(source);
    let word = |i: usize| &source[toks[i].start..toks[i].end];
    let close = |v: f64| values.iter().any(|&x| x > 0.0 && (v / f64::from(x) - 1.0).abs() <= 0.1);
    (0..toks.len()).find_map(|i| {
        let t = &toks[i];
        if t.kind != Kind::Number || !word(i).contains('.') {
            return None;
        }
        let value = word(i).trim_end_matches(['f', 'F']).parse::<f64>().ok().filter(|v| close(*v))?;
        // Under a `#define NAME`, name the macro.
        let text = if t.in_directive && i >= 2 && word(i - 2).trim_start_matches('#').trim() == "define" {
            word(i - 1).to_string()
        } else {
            word(i).to_string()
        };
        Some(Constant { line: t.line, text, value, function: None, added: false })
    })
}

/// The student's function that turns a map read into a depth: the first `NAME(texture2D(` (or
/// `texture(`) whose NAME the shader defines. (name, the line of its definition's body.)
pub fn unpack_function(source: &str) -> Option<(String, usize)> {
    let toks = tokens(source);
    let text = |i: usize| toks.get(i).map_or("", |t| &source[t.start..t.end]);
    let bodies = function_bodies(source, &toks);
    (0..toks.len()).find_map(|k| {
        let wraps =
            text(k + 1) == "(" && matches!(text(k + 2), "texture2D" | "texture") && text(k + 3) == "(";
        let &(name, open, _) = bodies.iter().find(|b| wraps && b.0 == text(k))?;
        Some((name.to_string(), toks[open].line))
    })
}

/// Every function defined at the top level: (name, token of its body's `{`, token of its `}`),
/// the student's blocker search under the recorded name `findBlocker` whatever they called it.
fn function_bodies<'s>(
    source: &'s str,
    toks: &[crate::homework::lex::Token],
) -> Vec<(&'s str, usize, usize)> {
    let blocker_search = crate::homework::instrument::recorded_name(source, toks, "findBlocker");
    crate::homework::lex::function_bodies(source, toks)
        .into_iter()
        .map(|b| (if Some(b.name) == blocker_search { "findBlocker" } else { b.name }, b.open, b.close))
        .collect()
}

/// A global sample array `function` reads (`poissonDisk[i]`) that nothing fills before it runs:
/// no function that writes the array is called in `function` before the read, nor in the
/// function that calls `function` before that call, nor in `main` before the call that leads
/// there. (array name, the line of the first read in `function`.)
pub fn sample_array_read_unfilled(source: &str, function: &str) -> Option<(String, usize)> {
    let toks = tokens(source);
    let text = |i: usize| toks.get(i).map_or("", |t| &source[t.start..t.end]);
    // Names as written: the calls up to `main` are found by them.
    let bodies: Vec<(&str, usize, usize)> = crate::homework::lex::function_bodies(source, &toks)
        .iter()
        .map(|b| (b.name, b.open, b.close))
        .collect();
    let function = crate::homework::instrument::recorded_name(source, &toks, function).unwrap_or(function);
    let body = |name: &str| bodies.iter().find(|b| b.0 == name).map(|b| (b.1, b.2));
    // Global arrays: `TYPE NAME [` at the top level, outside every body.
    let inside_any = |k: usize| bodies.iter().any(|&(_, open, close)| (open..=close).contains(&k));
    let arrays: Vec<&str> = (1..toks.len())
        .filter(|&k| {
            !inside_any(k) && !toks[k].in_directive && text(k + 1) == "[" && toks[k].kind == Kind::Ident
        })
        .filter(|&k| toks[k - 1].kind == Kind::Ident)
        .map(&text)
        .collect();
    let (open, close) = body(function)?;
    let read = (open..close).find(|&k| arrays.contains(&text(k)) && text(k + 1) == "[")?;
    let array = text(read);
    // Functions that write `array[...] =`.
    let fillers: Vec<&str> = bodies
        .iter()
        .filter(|&&(_, o, c)| {
            (o..c).any(|k| {
                text(k) == array && text(k + 1) == "[" && {
                    let end = matching(source, &toks, k + 1, "[", "]");
                    text(end + 1) == "="
                }
            })
        })
        .map(|b| b.0)
        .collect();
    let calls_filler =
        |from: usize, to: usize| (from..to).any(|k| fillers.contains(&text(k)) && text(k + 1) == "(");
    if fillers.is_empty() || calls_filler(open, read) {
        return (fillers.is_empty()).then(|| (array.to_string(), toks[read].line));
    }
    // Up the calls: each caller before its call of the function below it.
    let mut callee = function;
    for _ in 0..4 {
        let Some(&(caller, o, c)) = bodies
            .iter()
            .find(|&&(name, o, c)| name != callee && (o..c).any(|k| text(k) == callee && text(k + 1) == "("))
        else {
            break;
        };
        let call = (o..c).find(|&k| text(k) == callee && text(k + 1) == "(")?;
        if calls_filler(o, call) {
            return None;
        }
        if caller == "main" {
            break;
        }
        callee = caller;
    }
    Some((array.to_string(), toks[read].line))
}

/// Where `function` returns the number `value` (`return 0.0;`, `return -1.;`): (the return's
/// line, the line of the `if` it is under where there is one).
pub fn return_of(source: &str, function: &str, value: f32) -> Option<(usize, Option<usize>)> {
    let toks = tokens(source);
    let text = |i: usize| toks.get(i).map_or("", |t| &source[t.start..t.end]);
    let bodies = function_bodies(source, &toks);
    let &(_, open, close) = bodies.iter().find(|b| b.0 == function)?;
    (open..close).find_map(|k| {
        if text(k) != "return" {
            return None;
        }
        let (sign, number) = if text(k + 1) == "-" { (-1.0, k + 2) } else { (1.0, k + 1) };
        let written = text(number).trim_end_matches(['f', 'F']).parse::<f32>().ok()? * sign;
        if toks[number].kind != Kind::Number || text(number + 1) != ";" || (written - value).abs() > 1e-4 {
            return None;
        }
        // The nearest `if` before the return within two lines.
        let condition =
            (open..k).rev().take_while(|&m| toks[m].line + 2 >= toks[k].line).find(|&m| text(m) == "if");
        Some((toks[k].line, condition.map(|m| toks[m].line)))
    })
}

/// Where the shader takes a lookup outside the map as lit: an `if` whose condition compares a
/// coordinate (`c.x`, `coord.y`) below 0.0 and one above 1.0, and whose branch sets or returns
/// 1.0 (`if (c.x < 0.0 || c.x > 1.0 || ...) { visibility = 1.0; }`). The `if`'s line.
pub fn outside_map_lit(source: &str) -> Option<usize> {
    let toks = tokens(source);
    let word = |i: usize| toks.get(i).map_or("", |t| &source[t.start..t.end]);
    let number = |i: usize| word(i).trim_end_matches(['f', 'F']).parse::<f64>().ok();
    let coordinate = |i: usize| i >= 2 && matches!(word(i), "x" | "y" | "s" | "t") && word(i - 1) == ".";
    (0..toks.len()).find_map(|k| {
        if word(k) != "if" || word(k + 1) != "(" {
            return None;
        }
        let close = matching(source, &toks, k + 1, "(", ")");
        let below = (k + 2..close).any(|i| word(i) == "<" && coordinate(i - 1) && number(i + 1) == Some(0.0));
        let above = (k + 2..close).any(|i| word(i) == ">" && coordinate(i - 1) && number(i + 1) == Some(1.0));
        let branch_end =
            if word(close + 1) == "{" { matching(source, &toks, close + 1, "{", "}") } else { close + 6 };
        let lit = (close + 1..branch_end.min(toks.len()))
            .any(|i| matches!(word(i), "=" | "return") && number(i + 1) == Some(1.0) && word(i + 2) == ";");
        (below && above && lit).then(|| toks[k].line)
    })
}

/// Where a recorded function reads a texel never written (depth 0, the framework never clears
/// its map) as lit: a value compared alone with a small constant, then `return 1.0`
/// (`if (closestDepth < EPS) { return 1.0; }`). The comparison's line.
pub fn unwritten_texel_lit(source: &str) -> Option<usize> {
    let toks = tokens(source);
    let word = |i: usize| toks.get(i).map_or("", |t| &source[t.start..t.end]);
    let small = |i: usize| {
        let value = match toks.get(i)?.kind {
            Kind::Number => word(i).trim_end_matches(['f', 'F']).parse::<f64>().ok(),
            Kind::Ident => toks.iter().enumerate().find_map(|(k, t)| {
                let define = t.kind == Kind::Directive && word(k).trim_start_matches('#').trim() == "define";
                (define && word(k + 1) == word(i)).then(|| word(k + 2).parse::<f64>().ok()).flatten()
            }),
            _ => None,
        }?;
        (value > 0.0 && value < 0.2).then_some(())
    };
    function_bodies(source, &toks)
        .into_iter()
        .filter(|(name, ..)| RECORDED_FUNCTIONS.contains(name))
        .find_map(|(_, open, close)| {
            (open..close).find_map(|k| {
                let alone = word(k) == "<" && word(k.wrapping_sub(2)) == "(" && word(k + 2) == ")";
                let after = if word(k + 3) == "{" { k + 4 } else { k + 3 };
                let returns_lit = word(after) == "return"
                    && word(after + 1).trim_end_matches(['f', 'F']).parse::<f64>() == Ok(1.0);
                (alone && returns_lit && small(k + 1).is_some()).then(|| toks[k].line)
            })
        })
}

/// The first line of `function`'s body that reads the map itself (`texture2D`, `texture`, or an
/// `unpack` call), not through another function of the student's that does.
pub fn reads_map_in(source: &str, function: &str) -> Option<usize> {
    let toks = tokens(source);
    let text = |i: usize| toks.get(i).map_or("", |t| &source[t.start..t.end]);
    let bodies = function_bodies(source, &toks);
    let &(_, open, close) = bodies.iter().find(|b| b.0 == function)?;
    (open..close)
        .find(|&k| matches!(text(k), "texture2D" | "texture" | "unpack") && text(k + 1) == "(")
        .map(|k| toks[k].line)
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
        assert!(found.iter().all(|c| c.added), "{found:?}");
        // A comparison written as `step` has its bias too.
        let stepped =
            SHADER.replace("return c.z - bias > 0.5 ? 0.0 : 1.0;", "return step(c.z, 0.5 + 0.004);");
        assert!(
            depth_test_constants(&stepped)
                .iter()
                .any(|c| c.text == "0.004" && c.added && c.function == Some("useShadowMap"))
        );
        // A threshold compared alone (a texel never written) is no bias.
        let guarded = SHADER.replace("return c.z < v + 0.015", "return v < 0.015");
        let threshold = depth_test_constants(&guarded);
        assert!(threshold.iter().any(|c| c.text == "0.015" && !c.added), "{threshold:?}");
    }

    const STEPS: &str = "#define LIGHT 0.025\nvec2 disk[4];\nvoid fill(vec2 s) {\n  for (int i = 0; i < 4; i++) { disk[i] = s; }\n}\n\
        float findBlocker(vec2 uv, float z) {\n  float d = texture2D(m, uv + disk[0]).r;\n  if (d <= 4.0) {\n    return 0.0;\n  }\n  return -1.0;\n}\n\
        float PCSS(vec4 c) {\n  float b = findBlocker(c.xy, c.z);\n  float r = unpack(texture2D(m, c.xy));\n  fill(c.xy);\n  return r - b;\n}\n\
        void main() { PCSS(vec4(0.0)); }\n";

    #[test]
    fn a_guard_that_reads_a_texel_never_written_as_lit_is_found_on_its_line() {
        let guarded = "#define EPS 1e-3\nfloat useShadowMap(vec4 c) {\n  float d = unpack(texture2D(m, c.xy));\n  \
            if (d < EPS) {\n    return 1.0;\n  }\n  return d < c.z - EPS ? 0.0 : 1.0;\n}\n";
        assert_eq!(unwritten_texel_lit(guarded), Some(4));
        // On one line, with a literal.
        assert_eq!(
            unwritten_texel_lit(
                &guarded.replace("(d < EPS) {\n    return 1.0;\n  }", "(d < 0.001) return 1.0;")
            ),
            Some(4)
        );
        // A bias (compared with a difference) or a guard that shadows is not it.
        assert_eq!(unwritten_texel_lit(&guarded.replace("return 1.0;\n  }\n", "return 0.0;\n  }\n")), None);
        assert_eq!(unwritten_texel_lit(&guarded.replace("(d < EPS)", "(c.z - d < EPS)")), None);
        // Outside the recorded functions it is not on the lookup's path.
        assert_eq!(unwritten_texel_lit(&guarded.replace("useShadowMap", "helper")), None);
    }

    #[test]
    fn a_lookup_outside_the_map_taken_as_lit_is_found_on_its_line() {
        let shader = "void main() {\n  vec3 c = v.xyz / v.w * 0.5 + 0.5;\n  float visibility;\n  \
            if (c.x < 0.0 || c.x > 1.0 || c.y < 0.0 || c.y > 1.0) {\n    visibility = 1.0;\n  } else {\n    \
            visibility = PCF(m, c);\n  }\n}\n";
        assert_eq!(outside_map_lit(shader), Some(4));
        // One side only, or a branch that shadows, is not it.
        assert_eq!(outside_map_lit(&shader.replace(" || c.x > 1.0 || c.y < 0.0 || c.y > 1.0", "")), None);
        assert_eq!(outside_map_lit(&shader.replace("visibility = 1.0;", "visibility = 0.0;")), None);
    }

    #[test]
    fn the_lines_of_pcss_steps_are_found() {
        // findBlocker reads `disk` on line 7; only PCSS fills it, after calling findBlocker.
        assert_eq!(sample_array_read_unfilled(STEPS, "findBlocker"), Some(("disk".to_string(), 7)));
        let filled_first = STEPS.replace("float b = findBlocker", "fill(c.xy); float b = findBlocker");
        assert_eq!(sample_array_read_unfilled(&filled_first, "findBlocker"), None);
        // `return 0.0;` on line 9 under the `if` on line 8; `return -1.0;` on line 11.
        assert_eq!(return_of(STEPS, "findBlocker", 0.0), Some((9, Some(8))));
        assert_eq!(return_of(STEPS, "findBlocker", -1.0).map(|r| r.0), Some(11));
        assert_eq!(return_of(STEPS, "findBlocker", 0.5), None);
        // PCSS reads the map itself on line 15 (its findBlocker call on line 14 does not count).
        assert_eq!(reads_map_in(STEPS, "PCSS"), Some(15));
        assert_eq!(reads_map_in(STEPS, "main"), None);
        // The #define whose value is (within 10%) the measured one, by its name.
        let found = constant_near(STEPS, &[0.026]).expect("LIGHT");
        assert_eq!((found.line, found.text.as_str()), (1, "LIGHT"));
        assert!(constant_near(STEPS, &[0.05]).is_none());
    }

    #[test]
    fn a_bias_the_code_computes_is_found_where_it_is_set() {
        let shader = "float Bias(float c) { return c * 0.1; }\n\
            float PCF(vec4 coords) {\n  float bias = Bias(0.15);\n  float d = unpack(coords);\n  \
            return coords.z - bias > d ? 0.0 : 1.0;\n}\n";
        let found = computed_biases(shader);
        assert_eq!(found.len(), 1, "{found:?}");
        assert_eq!((found[0].line, found[0].function, found[0].name.as_str()), (3, "PCF", "bias"));
        assert_eq!(found[0].expression, "Bias(0.15)");
    }

    #[test]
    fn depth_tests_are_told_from_thresholds_and_differences_count_as_biases() {
        let shader = "#define EPS 1e-3\nfloat useShadowMap(vec4 c) {\n  float d = unpack(c);\n  \
            if (c.z - d < 0.01) return 1.0;\n  return 0.0;\n}\n\
            float PCF(vec4 c) {\n  float v = 0.0;\n  for (int i = 0; i < 4; i++) { v += useShadowMap(c); }\n  return v;\n}\n\
            float PCSS(vec4 c) {\n  float b = 0.5;\n  if (b >= 1.0e-5) return PCF(c);\n  if (b < EPS) return 1.0;\n  return 0.0;\n}\n";
        // PCF's only comparison is its loop's, PCSS's compare one value with a constant alone.
        assert_eq!(functions_with_depth_tests(shader), ["useShadowMap"]);
        // `c.z - d < 0.01`: a bias, compared with a difference.
        let found = depth_test_constants(shader);
        assert!(
            found.iter().any(|c| c.text == "0.01" && c.added && c.function == Some("useShadowMap")),
            "{found:?}"
        );
    }
}

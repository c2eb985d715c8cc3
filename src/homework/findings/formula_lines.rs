//! Where in the student's fragment shader PCSS's formulas are written: the line that divides a
//! radius by the receiver's depth, and the light size a `#define` sets in world units.

use crate::homework::instrument::recorded_name;
use crate::homework::lex::{FunctionBody, Kind, Token, function_bodies, tokens};

const PCSS: &str = "PCSS";

/// The body of the function recorded as `role` (`PCSS`, `findBlocker`), under the student's name.
fn recorded_body<'s>(source: &'s str, toks: &[Token], role: &str) -> Option<FunctionBody<'s>> {
    let own = recorded_name(source, toks, role)?;
    function_bodies(source, toks).into_iter().find(|b| b.name == own)
}

/// The first token of the operand after the operator at `k`, past brackets and `float(` casts.
fn operand_start(source: &str, toks: &[Token], k: usize) -> usize {
    let mut at = k + 1;
    while toks.get(at).is_some_and(|t| matches!(&source[t.start..t.end], "(" | "float")) {
        at += 1;
    }
    at
}

/// The first line, in `function` (a recorded function's name: `PCSS`, `findBlocker`) or a
/// function it calls (PCSS: not the blocker search), that divides by the receiver's depth:
/// `/ zReceiver`, `/ float(zReceiver)`, `/ coords.z` with `coords` a shadow coordinate.
/// (line, the line's code.)
pub fn receiver_division(source: &str, function: &str) -> Option<(usize, String)> {
    let toks = tokens(source);
    let text = |i: usize| toks.get(i).map_or("", |t| &source[t.start..t.end]);
    let bodies = function_bodies(source, &toks);
    let blocker_search = recorded_name(source, &toks, "findBlocker");
    let own = recorded_name(source, &toks, function)?;
    let top = bodies.iter().find(|b| b.name == own)?;
    let called: Vec<_> = bodies
        .iter()
        .filter(|b| {
            b.name == own
                || ((b.name != "PCF" || function == PCSS)
                    && (Some(b.name) != blocker_search || function != PCSS)
                    && (top.open..top.close).any(|k| text(k) == b.name && text(k + 1) == "("))
        })
        .collect();
    let receiver = |k: usize| {
        let word = text(k).to_ascii_lowercase();
        toks[k].kind == Kind::Ident
            && (word.contains("receiver")
                || matches!(word.as_str(), "zr" | "dr" | "z_r" | "d_r")
                || (text(k + 1) == "." && text(k + 2) == "z" && word.contains("coord")))
    };
    called.iter().find_map(|b| {
        (b.open..b.close).find_map(|k| {
            if text(k) != "/" {
                return None;
            }
            let at = operand_start(source, &toks, k);
            // `/ (zReceiver - zBlocker)` is a gap, not the receiver's depth.
            let gap = matches!(text(at + 1), "-" | "+")
                || (text(at + 1) == "." && matches!(text(at + 4), "-" | "+"));
            let alone = !gap;
            (receiver(at) && alone).then(|| {
                let line = toks[k].line;
                (line, source.lines().nth(line - 1).unwrap_or("").trim().to_string())
            })
        })
    })
}

/// A `#define` of the light's size in world units, by its name (`LIGHT_WORLD_SIZE 0.5`):
/// (name, line, value).
pub fn world_light_size(source: &str) -> Option<(String, usize, f32)> {
    let toks = tokens(source);
    let text = |i: usize| toks.get(i).map_or("", |t| &source[t.start..t.end]);
    (0..toks.len()).find_map(|k| {
        let define = toks[k].kind == Kind::Directive && text(k).trim_start_matches('#').trim() == "define";
        let name = text(k + 1).to_ascii_uppercase();
        let sized = name.contains("LIGHT")
            && name.contains("WORLD")
            && (name.contains("SIZE") || name.contains("WIDTH"));
        let value = text(k + 2).trim_end_matches(['f', 'F']).parse::<f32>().ok()?;
        (define && sized && value > 0.0 && toks[k + 2].line == toks[k].line)
            .then(|| (text(k + 1).to_string(), toks[k].line, value))
    })
}

/// A constant within 0.02 of `value` that a visibility function (useShadowMap, PCF, PCSS)
/// uses: a `#define` it names, or a number it gives as a result (after `?`, `:`, `=`, `+=` or
/// `return`), looked for in `first` (the function the shader's visibility comes from) first.
/// (as written, line, the function.)
pub fn blocked_value(
    source: &str,
    value: f32,
    first: Option<&'static str>,
) -> Option<(String, usize, &'static str)> {
    let toks = tokens(source);
    let text = |i: usize| toks.get(i).map_or("", |t| &source[t.start..t.end]);
    let number = |i: usize| text(i).trim_end_matches(['f', 'F']).parse::<f32>().ok();
    let near = |v: f32| (v - value).abs() <= 0.02;
    let bodies = function_bodies(source, &toks);
    let defines: Vec<(&str, usize)> = (0..toks.len())
        .filter(|&k| toks[k].kind == Kind::Directive && text(k).trim_start_matches('#').trim() == "define")
        .filter(|&k| {
            toks.get(k + 2).is_some_and(|t| t.line == toks[k].line) && number(k + 2).is_some_and(near)
        })
        .map(|k| (text(k + 1), toks[k].line))
        .collect();
    let functions = ["useShadowMap", "PCF", "PCSS"];
    first.into_iter().chain(functions.into_iter().filter(|f| Some(*f) != first)).find_map(|function| {
        let body = bodies.iter().find(|b| b.name == function)?;
        (body.open..body.close).find_map(|k| {
            if let Some(&(name, line)) = defines.iter().find(|(name, _)| *name == text(k)) {
                return Some((name.to_string(), line, function));
            }
            // A number given as a result (`? 1.0 : 0.6`, `= 0.6`, `return 0.6`), not compared.
            let given = k > 0 && matches!(text(k - 1), "?" | ":" | "=" | "+=" | "return");
            let literal =
                given && toks[k].kind == Kind::Number && text(k).contains('.') && number(k).is_some_and(near);
            literal.then(|| (text(k).to_string(), toks[k].line, function))
        })
    })
}

/// Whether `function` (a recorded function's name) compares anything outside its loops'
/// headers: `<`, `>` or `step(`. A blocker search without one averages every tap it reads.
pub fn compares_in(source: &str, function: &str) -> Option<bool> {
    let toks = tokens(source);
    let text = |i: usize| toks.get(i).map_or("", |t| &source[t.start..t.end]);
    let body = recorded_body(source, &toks, function)?;
    let mut k = body.open;
    while k < body.close {
        if text(k) == "for" && text(k + 1) == "(" {
            k = crate::homework::lex::matching(source, &toks, k + 1, "(", ")");
        } else if matches!(text(k), "<" | ">" | "step") {
            return Some(true);
        }
        k += 1;
    }
    Some(false)
}

/// Whether the bias `bias` (as written) makes `function`'s blocker test stricter where a
/// comparison reads it: added on the smaller side (`depth + BIAS < zR`) or taken from the larger
/// (`zR - BIAS > depth`). False where it loosens the test (`depth - BIAS < zR`); None where no
/// `<` or `>` in the function reads it. (tightens, the test's line.)
pub fn bias_tightens(source: &str, function: &str, bias: &str) -> Option<(bool, usize)> {
    let toks = tokens(source);
    let text = |i: usize| toks.get(i).map_or("", |t| &source[t.start..t.end]);
    let body = recorded_body(source, &toks, function)?;
    let ends = |t: &str| matches!(t, ";" | "{" | "}" | "?" | ":" | "," | "&" | "|");
    (body.open..body.close).filter(|&k| matches!(text(k), "<" | ">") && text(k + 1) != text(k)).find_map(
        |k| {
            // Each operand: out to an unmatched bracket or the statement's end.
            let operand = |step: isize| {
                let (mut at, mut depth, mut out) = (k as isize + step, 0i32, Vec::new());
                let skip_eq = step > 0 && text(k + 1) == "=";
                if skip_eq {
                    at += 1;
                }
                while at > body.open as isize && at < body.close as isize {
                    let t = text(at as usize);
                    let (opens, closes) = if step > 0 { ("(", ")") } else { (")", "(") };
                    if t == opens {
                        depth += 1;
                    } else if t == closes {
                        if depth == 0 {
                            break;
                        }
                        depth -= 1;
                    } else if depth == 0 && (ends(t) || matches!(t, "<" | ">")) {
                        break;
                    }
                    out.push(at as usize);
                    at += step;
                }
                out
            };
            let sign_of =
                |tokens: &[usize]| tokens.iter().find(|&&i| text(i) == bias).map(|&i| text(i - 1) == "-");
            let (left, right) = (operand(-1), operand(1));
            let larger_is_right = text(k) == "<";
            let line = toks[k].line;
            if let Some(minus) = sign_of(&left) {
                return Some((if larger_is_right { !minus } else { minus }, line));
            }
            sign_of(&right).map(|minus| (if larger_is_right { minus } else { !minus }, line))
        },
    )
}

/// `#define NAME value` with a number, or with another such name, resolved: name -> value.
fn numeric_defines(source: &str, toks: &[Token]) -> std::collections::HashMap<String, f64> {
    let text = |i: usize| toks.get(i).map_or("", |t| &source[t.start..t.end]);
    let mut raw: Vec<(String, String)> = Vec::new();
    for k in 0..toks.len() {
        let define = toks[k].kind == Kind::Directive && text(k).trim_start_matches('#').trim() == "define";
        let single = toks.get(k + 3).is_none_or(|n| n.line != toks[k].line);
        if define && single && toks.get(k + 2).is_some_and(|t| t.line == toks[k].line) {
            raw.push((text(k + 1).to_string(), text(k + 2).trim_end_matches(['f', 'F']).to_string()));
        }
    }
    let mut values = std::collections::HashMap::new();
    // A chain resolves in as many rounds as it is long.
    for _ in 0..4 {
        for (name, value) in &raw {
            let v = value.parse::<f64>().ok().or_else(|| values.get(value).copied());
            if let Some(v) = v {
                values.insert(name.clone(), v);
            }
        }
    }
    values
}

/// A loop in `function` (a recorded function's name) that reads the first `n` elements of a
/// sample array declared with more (`for (int i = 0; i < 10; i++) ... poissonDisk[i]` with
/// `vec2 poissonDisk[NUM_SAMPLES]`, 100): (the loop's line, the array's name, n, its size).
pub fn partial_sample_loop(source: &str, function: &str) -> Option<(usize, String, usize, usize)> {
    let toks = tokens(source);
    let text = |i: usize| toks.get(i).map_or("", |t| &source[t.start..t.end]);
    let defines = numeric_defines(source, &toks);
    let value = |i: usize| {
        text(i).trim_end_matches(['f', 'F']).parse::<f64>().ok().or_else(|| defines.get(text(i)).copied())
    };
    let body = recorded_body(source, &toks, function)?;
    // Arrays declared outside every function: `vec2 NAME[SIZE];`.
    let sizes: Vec<(&str, usize)> = (1..toks.len())
        .filter(|&k| matches!(text(k - 1), "vec2" | "vec3") && text(k + 1) == "[" && text(k + 3) == "]")
        .filter_map(|k| Some((text(k), value(k + 2)? as usize)))
        .collect();
    (body.open..body.close).find_map(|k| {
        // `for ( int i = 0 ; i < BOUND ;`
        if !(text(k) == "for" && text(k + 1) == "(" && text(k + 7) == text(k + 3) && text(k + 8) == "<") {
            return None;
        }
        let (index, bound) = (text(k + 3), value(k + 9)? as usize);
        let close = crate::homework::lex::matching(source, &toks, k + 1, "(", ")");
        let end = if text(close + 1) == "{" {
            crate::homework::lex::matching(source, &toks, close + 1, "{", "}")
        } else {
            close + 1
        };
        (close..end).find_map(|e| {
            let &(array, size) = sizes.iter().find(|(name, _)| *name == text(e))?;
            (text(e + 1) == "[" && text(e + 2) == index && text(e + 3) == "]" && bound < size)
                .then(|| (toks[k].line, array.to_string(), bound, size))
        })
    })
}

/// A sample count multiplying a tap's offset in `function` (a recorded function's name):
/// `poissonDisk[i] * float(BLOCKER_SEARCH_NUM_SAMPLES) / ...`, a count used as a radius.
/// (line, the count's name, its value.)
pub fn count_as_radius(source: &str, function: &str) -> Option<(usize, String, f64)> {
    let toks = tokens(source);
    let text = |i: usize| toks.get(i).map_or("", |t| &source[t.start..t.end]);
    let defines = numeric_defines(source, &toks);
    let body = recorded_body(source, &toks, function)?;
    (body.open..body.close).find_map(|k| {
        if text(k) != "*" {
            return None;
        }
        let at = operand_start(source, &toks, k);
        let name = text(at);
        let count = name.to_ascii_uppercase().contains("SAMPLES");
        // On a line that offsets a tap: an array read by index (`poissonDisk[i]`).
        let line = toks[k].line;
        let offsets = (body.open..body.close).any(|e| {
            toks[e].line == line && text(e + 1) == "[" && text(e + 3) == "]" && toks[e].kind == Kind::Ident
        });
        (count && offsets).then(|| Some((line, name.to_string(), *defines.get(name)?))).flatten()
    })
}

/// In PCSS, a local computed from the blocker search's result that nothing reads afterwards
/// (`float penumbra = (zR - zB) * W / zB;` with the filter then sized without it): (line, name).
pub fn unused_from_blocker(source: &str) -> Option<(usize, String)> {
    let toks = tokens(source);
    let text = |i: usize| toks.get(i).map_or("", |t| &source[t.start..t.end]);
    let bodies = function_bodies(source, &toks);
    let search = recorded_name(source, &toks, "findBlocker")?;
    let pcss = recorded_name(source, &toks, PCSS)?;
    let body = bodies.iter().find(|b| b.name == pcss)?;
    // `NAME = ...`, not `==`, `<=`, `!=` or `+=`.
    let assigns = |k: usize| {
        text(k) == "="
            && text(k + 1) != "="
            && !matches!(text(k - 1), "=" | "<" | ">" | "!" | "+" | "-" | "*" | "/")
            && toks[k - 1].kind == Kind::Ident
    };
    let blocker = (body.open..body.close)
        .find(|&k| text(k) == search && text(k + 1) == "(" && assigns(k - 1))
        .map(|k| text(k - 2))?;
    (body.open..body.close).filter(|&k| assigns(k) && text(k - 1) != blocker).find_map(|k| {
        let name = text(k - 1);
        let end = (k..body.close).find(|&e| text(e) == ";")?;
        if !(k + 1..end).any(|e| text(e) == blocker) {
            return None;
        }
        let read = (end..body.close).any(|e| text(e) == name && !assigns(e + 1));
        (!read).then(|| (toks[k].line, name.to_string()))
    })
}

/// The first line in `function` (a recorded function's name) that turns a length into uv by
/// dividing by a uniform, a `#define` or a number of 2 or more (a map size, a frustum's width),
/// not by a sample count: (line, the divisor as written, the line's code).
pub fn uv_divisor(source: &str, function: &str) -> Option<(usize, String, String)> {
    let toks = tokens(source);
    let text = |i: usize| toks.get(i).map_or("", |t| &source[t.start..t.end]);
    let body = recorded_body(source, &toks, function)?;
    // A `#define NAME` or a `uniform [precision] TYPE NAME;`.
    let named = |name: &str| {
        (0..toks.len()).any(|k| {
            let define =
                toks[k].kind == Kind::Directive && text(k).trim_start_matches('#').trim() == "define";
            (define && text(k + 1) == name)
                || (text(k) == "uniform" && (k + 1..toks.len().min(k + 5)).any(|e| text(e) == name))
        })
    };
    (body.open..body.close).find_map(|k| {
        if text(k) != "/" {
            return None;
        }
        let at = operand_start(source, &toks, k);
        let divisor = text(at);
        let lower = divisor.to_ascii_lowercase();
        let counts = ["sample", "num", "count"].iter().any(|c| lower.contains(c));
        let size = match toks.get(at)?.kind {
            Kind::Number => divisor.trim_end_matches(['f', 'F']).parse::<f32>().is_ok_and(|v| v >= 2.0),
            Kind::Ident => named(divisor),
            _ => false,
        };
        (size && !counts && !matches!(text(at + 1), "-" | "+" | "*")).then(|| {
            let line = toks[k].line;
            (line, divisor.to_string(), source.lines().nth(line - 1).unwrap_or("").trim().to_string())
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_line_that_divides_by_the_receiver_is_found_and_a_gap_is_not_one() {
        let source = "float findBlocker(float zReceiver) { return 1.0 / zReceiver; }\n\
                      float radius(float ratio, float zReceiver) {\n  float g = 1.0 / (zReceiver - 0.5);\n  return ratio * 0.01 / zReceiver;\n}\n\
                      float PCSS(vec4 coords) {\n  float zReceiver = coords.z;\n  float b = findBlocker(zReceiver);\n  return radius((zReceiver - b) / b, zReceiver);\n}\n";
        let (line, code) = receiver_division(source, "PCSS").expect("the division");
        assert_eq!((line, code.as_str()), (4, "return ratio * 0.01 / zReceiver;"));
        let sound = source.replace("ratio * 0.01 / zReceiver", "ratio * 0.01");
        assert_eq!(receiver_division(&sound, "PCSS"), None);
        assert_eq!(receiver_division(source, "findBlocker").map(|(l, _)| l), Some(1));
    }

    #[test]
    fn a_light_size_in_world_units_is_read_by_its_name() {
        let source =
            "#define LIGHT_WORLD_SIZE 0.5 // half\n#define LIGHT_SIZE_UV (LIGHT_WORLD_SIZE / 100.0)\n";
        assert_eq!(world_light_size(source), Some(("LIGHT_WORLD_SIZE".to_string(), 1, 0.5)));
        assert_eq!(world_light_size("#define LIGHT_WIDTH 5.0\n"), None);
    }

    #[test]
    fn the_value_a_blocked_tap_counts_is_found_where_a_visibility_function_uses_it() {
        let source = "#define SHADE 0.6\n#define OTHER 0.6\nfloat PCF(float z) {\n  return z > 0.5 ? 1.0 : SHADE;\n}\n";
        assert_eq!(blocked_value(source, 0.61, None), Some(("SHADE".to_string(), 1, "PCF")));
        let literal = "float useShadowMap(float z) {\n  return z > 0.5 ? 1.0 : 0.3;\n}\n";
        assert_eq!(blocked_value(literal, 0.3, Some("PCF")), Some(("0.3".to_string(), 2, "useShadowMap")));
        assert_eq!(blocked_value(literal, 0.5, None), None);
        // A `#define` without a value as the shader's last tokens is no constant (and no panic).
        assert_eq!(blocked_value("#define SHADE", 0.6, None), None);
        assert_eq!(world_light_size("#define LIGHT_WORLD_SIZE"), None);
    }

    #[test]
    fn a_penumbra_nothing_reads_and_the_divisors_that_make_uv_are_found() {
        let source = "#define W 10.0\nuniform float uMapSize;\nuniform float uBox;\n\
                      float findBlocker(vec2 uv, float zR) {\n  float r = W / uBox;\n  return r;\n}\n\
                      float PCF(vec4 c, float f) {\n  float v = f / uMapSize;\n  return v / float(NUM_SAMPLES);\n}\n\
                      float PCSS(vec4 coords) {\n  float zR = coords.z;\n  float zB = findBlocker(coords.xy, zR);\n  \
                      float penumbra = (zR - zB) * W / zB;\n  float size = 0.01;\n  return PCF(coords, size);\n}\n";
        assert_eq!(unused_from_blocker(source), Some((15, "penumbra".to_string())));
        let used = source.replace("PCF(coords, size)", "PCF(coords, penumbra)");
        assert_eq!(unused_from_blocker(&used), None);
        let (line, divisor, _) = uv_divisor(source, "findBlocker").expect("the search's divisor");
        assert_eq!((line, divisor.as_str()), (5, "uBox"));
        let (line, divisor, _) = uv_divisor(source, "PCF").expect("the filter's divisor");
        assert_eq!((line, divisor.as_str()), (9, "uMapSize"));
        // A sample count and a depth are not what turns a length into uv.
        assert_eq!(uv_divisor(source, "PCSS"), None);
        // The loop's own `i < N` is no test of a depth.
        let averages = "float findBlocker(vec2 uv, float zR) {\n  float s = 0.0;\n  for (int i = 0; i < 4; i++) { s += 1.0; }\n  return s / 4.0;\n}\n";
        assert_eq!(compares_in(averages, "findBlocker"), Some(false));
        let tests = averages.replace("s += 1.0;", "if (zR > 0.5) s += 1.0;");
        assert_eq!(compares_in(&tests, "findBlocker"), Some(true));
    }

    #[test]
    fn a_loop_over_the_first_of_the_samples_is_found_with_its_counts() {
        let source = "#define NUM_SAMPLES 100\n#define SEARCH NUM_SAMPLES\nvec2 poissonDisk[NUM_SAMPLES];\n\
                      float findBlocker(vec2 uv) {\n  float s = 0.0;\n  for (int i = 0; i < 10; i++) {\n    s += poissonDisk[i].x;\n  }\n  return s;\n}\n";
        assert_eq!(partial_sample_loop(source, "findBlocker"), Some((6, "poissonDisk".to_string(), 10, 100)));
        let whole = source.replace("i < 10;", "i < SEARCH;");
        assert_eq!(partial_sample_loop(&whole, "findBlocker"), None);
    }

    #[test]
    fn a_sample_count_that_sizes_a_tap_offset_is_found() {
        let source = "#define NUM_SAMPLES 80\n#define SEARCH_SAMPLES NUM_SAMPLES\nvec2 poissonDisk[NUM_SAMPLES];\n\
                      float findBlocker(vec2 uv) {\n  float s = 0.0;\n  for (int i = 0; i < NUM_SAMPLES; i++) {\n    \
                      s += texture2D(m, uv + poissonDisk[i] * float(SEARCH_SAMPLES) / 2048.0).r;\n  }\n  return s / float(NUM_SAMPLES);\n}\n";
        assert_eq!(count_as_radius(source, "findBlocker"), Some((7, "SEARCH_SAMPLES".to_string(), 80.0)));
        assert_eq!(count_as_radius(&source.replace("float(SEARCH_SAMPLES)", "20.0"), "findBlocker"), None);
    }

    #[test]
    fn a_bias_that_tightens_the_blocker_test_is_told_from_one_that_loosens_it() {
        let with = |test: &str| {
            format!("float findBlocker(float d, float zR) {{\n  if ({test}) return 1.0;\n  return 0.0;\n}}\n")
        };
        for (test, tightens) in [
            ("d + BIAS < zR", Some(true)),
            ("d - BIAS < zR", Some(false)),
            ("zR - BIAS >= d", Some(true)),
            ("zR + BIAS > d", Some(false)),
            ("d < zR - BIAS", Some(true)),
            ("d <= (zR + BIAS)", Some(false)),
            ("zR > d + BIAS", Some(true)),
            ("d < zR", None),
        ] {
            assert_eq!(bias_tightens(&with(test), "findBlocker", "BIAS").map(|t| t.0), tightens, "{test}");
        }
    }
}

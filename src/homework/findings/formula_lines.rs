//! Where in the student's fragment shader PCSS's formulas are written: the line that divides a
//! radius by the receiver's depth, and the light size a `#define` sets in world units.

use crate::homework::instrument::recorded_name;
use crate::homework::lex::{Kind, function_bodies, tokens};

const PCSS: &str = "PCSS";

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
            let mut at = k + 1;
            while matches!(text(at), "(" | "float") {
                at += 1;
            }
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
}

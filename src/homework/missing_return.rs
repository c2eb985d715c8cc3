//! A student's function that may run off its end without a `return` (WebGL drivers accept it;
//! naga does not): whether its body ends with one, and the zero the rewrite returns in its place.

use super::lex::Token;

/// Whether a function body's last statement at its own level is a `return`.
pub(super) fn ends_with_return(source: &str, toks: &[Token], open: usize, close: usize) -> bool {
    let mut last_start = None;
    let (mut braces, mut parens) = (0i32, 0i32);
    let mut starts_statement = true;
    for j in open + 1..close {
        let word = &source[toks[j].start..toks[j].end];
        if starts_statement && braces == 0 && parens == 0 && !toks[j].in_directive {
            last_start = Some(word);
            starts_statement = false;
        }
        match word {
            "(" => parens += 1,
            ")" => parens -= 1,
            "{" => braces += 1,
            "}" => {
                braces -= 1;
                starts_statement = braces == 0;
            }
            ";" if braces == 0 && parens == 0 => starts_statement = true,
            _ => {}
        }
    }
    last_start == Some("return")
}

/// A zero of a GLSL type, for the `return` a non-void function lacked (what WebGL drivers
/// commonly give back when such a function runs off its end).
pub(super) fn zero_of(glsl_type: &str) -> Option<String> {
    let size = |prefix: &str| glsl_type.strip_prefix(prefix).filter(|n| matches!(*n, "2" | "3" | "4"));
    Some(match glsl_type {
        "float" => "0.0".into(),
        "int" => "0".into(),
        "uint" => "0u".into(),
        "bool" => "false".into(),
        _ if size("vec").is_some() || size("mat").is_some() => format!("{glsl_type}(0.0)"),
        _ if size("ivec").is_some() => format!("{glsl_type}(0)"),
        _ if size("uvec").is_some() => format!("{glsl_type}(0u)"),
        _ if size("bvec").is_some() => format!("{glsl_type}(false)"),
        _ => return None,
    })
}

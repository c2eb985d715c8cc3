//! Which of the student's lines WebGL compiles, and what their `#define`s say: the rules look only
//! at code the browser sees (a branch under `#if 0` or `#ifndef GL_ES` is never compiled, so
//! nothing in it can be refused).

use crate::homework::lex::{Kind, Token};
use std::collections::HashMap;

/// Whether a line is compiled: `Yes`, `No` (a branch not taken), or `Unknown` (a condition this
/// reading cannot evaluate: its lines are neither judged nor refused).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Active {
    Yes,
    No,
    Unknown,
}

/// The student's `#define`s (name -> body text), and for each line (1-based) whether it is
/// compiled.
pub struct Preprocessed {
    pub macros: HashMap<String, Macro>,
    active: Vec<Active>,
}

#[derive(Clone, Debug)]
pub struct Macro {
    pub body: String,
    pub line: usize,
}

impl Preprocessed {
    /// Whether `line` (1-based) is certainly compiled.
    pub fn compiled(&self, line: usize) -> bool {
        self.active.get(line).copied().unwrap_or(Active::Yes) == Active::Yes
    }
}

/// One open `#if`: whether its taken branch is active, and whether one of its branches was taken
/// already (so `#else` / `#elif` are not).
struct Open {
    outer: Active,
    now: Active,
    taken: Active,
}

/// Read the directives of `source` (lexed as `toks`).
pub fn preprocess(source: &str, toks: &[Token]) -> Preprocessed {
    let lines = source.lines().count() + 2;
    let mut active = vec![Active::Yes; lines];
    let mut macros: HashMap<String, Macro> = HashMap::new();
    let mut stack: Vec<Open> = Vec::new();
    let state = |stack: &[Open]| stack.last().map_or(Active::Yes, |o| o.now);
    let mut i = 0;
    while i < toks.len() {
        let t = toks[i];
        if t.kind != Kind::Directive {
            if let Some(a) = active.get_mut(t.line) {
                *a = state(&stack);
            }
            i += 1;
            continue;
        }
        let name = source[t.start..t.end].trim_start_matches('#').trim().to_string();
        // The directive's own tokens: those after its name on its (continued) line.
        let end = toks[i + 1..].iter().position(|u| !u.in_directive || u.kind == Kind::Directive);
        let args = &toks[i + 1..end.map_or(toks.len(), |n| i + 1 + n)];
        let arg_text = |k: usize| &source[args[k].start..args[k].end];
        let here = state(&stack);
        match name.as_str() {
            "define" if here == Active::Yes && !args.is_empty() => {
                let body = args.get(1).map_or(String::new(), |first| {
                    let body_end = args.last().map_or(first.end, |l| l.end);
                    // A function-like macro's parameters stay in its body text; it is never
                    // read as a constant.
                    source[first.start..body_end].trim().to_string()
                });
                let function_like = args.get(1).is_some_and(|p| p.start == args[0].end && arg_text(1) == "(");
                let body = if function_like { format!("({body}") } else { body };
                macros.insert(arg_text(0).to_string(), Macro { body, line: t.line });
            }
            "undef" if here == Active::Yes && !args.is_empty() => {
                macros.remove(arg_text(0));
            }
            "ifdef" | "ifndef" => {
                let defined = args.first().map(|a| is_defined(&macros, &source[a.start..a.end]));
                let yes = if name == "ifdef" { defined } else { defined.map(|d| !d) };
                let now = and(here, yes.map_or(Active::Unknown, from_bool));
                stack.push(Open { outer: here, now, taken: now });
            }
            "if" => {
                let value = evaluate(source, args, &macros);
                let now = and(here, value.map_or(Active::Unknown, |v| from_bool(v != 0)));
                stack.push(Open { outer: here, now, taken: now });
            }
            "elif" | "else" => {
                if let Some(open) = stack.last_mut() {
                    let condition = if name == "else" {
                        Some(true)
                    } else {
                        evaluate(source, args, &macros).map(|v| v != 0)
                    };
                    let now = match (open.taken, condition) {
                        (Active::Yes, _) => Active::No,
                        (Active::No, Some(c)) => from_bool(c),
                        _ => Active::Unknown,
                    };
                    open.now = and(open.outer, now);
                    open.taken = match (open.taken, now) {
                        (Active::Yes, _) | (_, Active::Yes) => Active::Yes,
                        (Active::No, Active::No) => Active::No,
                        _ => Active::Unknown,
                    };
                }
            }
            "endif" => {
                stack.pop();
            }
            _ => {}
        }
        if let Some(a) = active.get_mut(t.line) {
            *a = here;
        }
        i += 1 + args.len();
    }
    Preprocessed { macros, active }
}

fn from_bool(b: bool) -> Active {
    if b { Active::Yes } else { Active::No }
}

fn and(outer: Active, inner: Active) -> Active {
    match (outer, inner) {
        (Active::No, _) | (_, Active::No) => Active::No,
        (Active::Yes, Active::Yes) => Active::Yes,
        _ => Active::Unknown,
    }
}

/// Macros WebGL defines before the student's first line.
fn predefined(name: &str) -> Option<i64> {
    match name {
        "GL_ES" | "GL_FRAGMENT_PRECISION_HIGH" => Some(1),
        "__VERSION__" => Some(100),
        _ => None,
    }
}

fn is_defined(macros: &HashMap<String, Macro>, name: &str) -> bool {
    macros.contains_key(name) || predefined(name).is_some()
}

/// The value of an `#if` expression: integers, `defined`, macros whose body is such an
/// expression, `! ~ - +`, arithmetic, comparisons, `&& ||` and parentheses. None where it holds
/// anything else.
fn evaluate(source: &str, args: &[Token], macros: &HashMap<String, Macro>) -> Option<i64> {
    let words: Vec<String> = args.iter().map(|t| source[t.start..t.end].to_string()).collect();
    let mut expanded = Vec::new();
    expand(&words, macros, &mut expanded, &mut Vec::new())?;
    let expanded = join_operators(expanded);
    let mut at = 0;
    let value = Expr { words: &expanded, at: &mut at }.or()?;
    (at == expanded.len()).then_some(value)
}

/// Most words an `#if` may expand to: past it, the condition is not evaluated (its lines are
/// neither judged nor refused).
const MAX_EXPANDED_WORDS: usize = 4096;

/// `words` with macros replaced by their bodies (split into words), `defined X` by 0 or 1. As in
/// C, a macro is not expanded again inside its own expansion (`expanding`).
fn expand(
    words: &[String],
    macros: &HashMap<String, Macro>,
    out: &mut Vec<String>,
    expanding: &mut Vec<String>,
) -> Option<()> {
    if out.len() > MAX_EXPANDED_WORDS {
        return None;
    }
    let mut k = 0;
    while k < words.len() {
        let w = &words[k];
        if w == "defined" {
            let (name, skip) = match words.get(k + 1).map(String::as_str) {
                Some("(") => (words.get(k + 2)?, 4),
                Some(_) => (&words[k + 1], 2),
                None => return None,
            };
            out.push(if is_defined(macros, name) { "1" } else { "0" }.into());
            k += skip;
            continue;
        }
        if let Some(v) = predefined(w) {
            out.push(v.to_string());
        } else if let Some(m) = macros.get(w).filter(|_| !expanding.contains(w)) {
            let body: Vec<String> = crate::homework::lex::tokens(&m.body)
                .iter()
                .map(|t| m.body[t.start..t.end].to_string())
                .collect();
            expanding.push(w.clone());
            expand(&body, macros, out, expanding)?;
            expanding.pop();
        } else {
            out.push(w.clone());
        }
        k += 1;
    }
    Some(())
}

/// Punctuation comes a byte a word: `&` `&` is `&&` (and so on for the two-byte operators).
fn join_operators(words: Vec<String>) -> Vec<String> {
    const TWO: [&str; 8] = ["||", "&&", "==", "!=", "<=", ">=", "<<", ">>"];
    let mut out: Vec<String> = Vec::with_capacity(words.len());
    for w in words {
        match out.last_mut() {
            Some(last) if last.len() == 1 && TWO.contains(&format!("{last}{w}").as_str()) => {
                last.push_str(&w)
            }
            _ => out.push(w),
        }
    }
    out
}

/// A recursive-descent reader of an expanded `#if` expression (punctuation comes one byte a word).
struct Expr<'a> {
    words: &'a [String],
    at: &'a mut usize,
}

impl Expr<'_> {
    fn peek(&self, k: usize) -> Option<&str> {
        self.words.get(*self.at + k).map(String::as_str)
    }

    /// Take an operator among `ops`.
    fn take(&mut self, ops: &[&'static str]) -> Option<&'static str> {
        let op = ops.iter().find(|op| self.peek(0) == Some(**op))?;
        *self.at += 1;
        Some(op)
    }

    fn or(&mut self) -> Option<i64> {
        let mut v = self.and()?;
        while self.take(&["||"]).is_some() {
            let r = self.and()?;
            v = i64::from(v != 0 || r != 0);
        }
        Some(v)
    }

    fn and(&mut self) -> Option<i64> {
        let mut v = self.compare()?;
        while self.take(&["&&"]).is_some() {
            let r = self.compare()?;
            v = i64::from(v != 0 && r != 0);
        }
        Some(v)
    }

    fn compare(&mut self) -> Option<i64> {
        let mut v = self.sum()?;
        while let Some(op) = self.take(&["==", "!=", "<=", ">=", "<", ">"]) {
            let r = self.sum()?;
            v = i64::from(match op {
                "==" => v == r,
                "!=" => v != r,
                "<=" => v <= r,
                ">=" => v >= r,
                "<" => v < r,
                _ => v > r,
            });
        }
        Some(v)
    }

    fn sum(&mut self) -> Option<i64> {
        let mut v = self.product()?;
        while let Some(op) = self.take(&["+", "-"]) {
            let r = self.product()?;
            v = if op == "+" { v.checked_add(r)? } else { v.checked_sub(r)? };
        }
        Some(v)
    }

    fn product(&mut self) -> Option<i64> {
        let mut v = self.unary()?;
        while let Some(op) = self.take(&["*", "/", "%"]) {
            let r = self.unary()?;
            v = match op {
                "*" => v.checked_mul(r)?,
                "/" => v.checked_div(r)?,
                _ => v.checked_rem(r)?,
            };
        }
        Some(v)
    }

    fn unary(&mut self) -> Option<i64> {
        if let Some(op) = self.take(&["!", "-", "+", "~"]) {
            let v = self.unary()?;
            return Some(match op {
                "!" => i64::from(v == 0),
                "-" => v.checked_neg()?,
                "~" => !v,
                _ => v,
            });
        }
        if self.peek(0) == Some("(") {
            *self.at += 1;
            let v = self.or()?;
            (self.peek(0) == Some(")")).then_some(())?;
            *self.at += 1;
            return Some(v);
        }
        let word = self.peek(0)?;
        let v = parse_int(word)?;
        *self.at += 1;
        Some(v)
    }
}

/// A GLSL integer literal (decimal, octal or hex).
pub fn parse_int(word: &str) -> Option<i64> {
    if let Some(hex) = word.strip_prefix("0x").or_else(|| word.strip_prefix("0X")) {
        return i64::from_str_radix(hex, 16).ok();
    }
    if word.len() > 1 && word.starts_with('0') {
        return i64::from_str_radix(&word[1..], 8).ok();
    }
    word.parse().ok()
}

//! Just enough of a GLSL lexer for the rewrite: identifiers, numbers, punctuation and preprocessor
//! directives with their byte ranges and lines; whitespace and comments are skipped (the rewrite
//! edits byte ranges of the source, so everything it does not touch stays as it was).

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Ident,
    Number,
    Punct,
    /// `#` and the directive's name (`#define`); the rest of the line is lexed as usual with
    /// `in_directive` set.
    Directive,
}

#[derive(Clone, Copy, Debug)]
pub struct Token {
    pub kind: Kind,
    pub start: usize,
    pub end: usize,
    /// 1-based line of the token's first byte.
    pub line: usize,
    /// Whether the token is on a preprocessor line (a directive's name or its arguments).
    pub in_directive: bool,
}

/// The significant tokens of `source`, in order.
pub fn tokens(source: &str) -> Vec<Token> {
    let bytes = source.as_bytes();
    let mut out = Vec::new();
    let mut at = 0;
    let mut line = 1;
    let mut line_start = true; // only whitespace so far on this line
    let mut in_directive = false;
    while at < bytes.len() {
        let c = bytes[at];
        if c == b'\n' {
            line += 1;
            at += 1;
            line_start = true;
            in_directive = false;
            continue;
        }
        if c == b'\\' && in_directive && bytes.get(at + 1) == Some(&b'\n') {
            // A directive continued on the next line.
            line += 1;
            at += 2;
            continue;
        }
        if c.is_ascii_whitespace() {
            at += 1;
            continue;
        }
        if c == b'/' && bytes.get(at + 1) == Some(&b'/') {
            while at < bytes.len() && bytes[at] != b'\n' {
                at += 1;
            }
            continue;
        }
        if c == b'/' && bytes.get(at + 1) == Some(&b'*') {
            at += 2;
            while at < bytes.len() && !(bytes[at] == b'*' && bytes.get(at + 1) == Some(&b'/')) {
                if bytes[at] == b'\n' {
                    line += 1;
                }
                at += 1;
            }
            at = (at + 2).min(bytes.len());
            continue;
        }
        let start = at;
        let kind = if c == b'#' && line_start {
            at += 1;
            while at < bytes.len() && (bytes[at] == b' ' || bytes[at] == b'\t') {
                at += 1;
            }
            while at < bytes.len() && is_ident_byte(bytes[at]) {
                at += 1;
            }
            in_directive = true;
            Kind::Directive
        } else if c.is_ascii_alphabetic() || c == b'_' {
            while at < bytes.len() && is_ident_byte(bytes[at]) {
                at += 1;
            }
            Kind::Ident
        } else if c.is_ascii_digit() || (c == b'.' && bytes.get(at + 1).is_some_and(u8::is_ascii_digit)) {
            while at < bytes.len() {
                let b = bytes[at];
                let exponent_sign = (b == b'+' || b == b'-')
                    && matches!(bytes[at - 1], b'e' | b'E')
                    && !is_hex(&bytes[start..at]);
                if b.is_ascii_alphanumeric() || b == b'.' || exponent_sign {
                    at += 1;
                } else {
                    break;
                }
            }
            Kind::Number
        } else {
            // One byte, or one whole UTF-8 character outside ASCII (never valid GLSL, but kept whole).
            at += source[at..].chars().next().map_or(1, char::len_utf8);
            Kind::Punct
        };
        line_start = false;
        out.push(Token { kind, start, end: at, line, in_directive });
    }
    out
}

fn is_ident_byte(b: u8) -> bool {
    b.is_ascii_alphanumeric() || b == b'_'
}

fn is_hex(number: &[u8]) -> bool {
    number.len() > 1 && number[0] == b'0' && matches!(number[1], b'x' | b'X')
}

/// The index of the token closing the bracket opened at `open` (the last token if none does).
pub(super) fn matching(source: &str, toks: &[Token], open: usize, opening: &str, closing: &str) -> usize {
    let mut depth = 0;
    for (j, t) in toks.iter().enumerate().skip(open) {
        let word = &source[t.start..t.end];
        if word == opening {
            depth += 1;
        } else if word == closing {
            depth -= 1;
            if depth == 0 {
                return j;
            }
        }
    }
    toks.len() - 1
}

/// The index of the `(` a `)` at `close` closes.
pub(super) fn matching_open(source: &str, toks: &[Token], close: usize) -> usize {
    let mut depth = 0;
    for j in (0..=close).rev() {
        match &source[toks[j].start..toks[j].end] {
            ")" => depth += 1,
            "(" => {
                depth -= 1;
                if depth == 0 {
                    return j;
                }
            }
            _ => {}
        }
    }
    0
}

/// Most bytes a shader may have (a homework shader is 5 to 20 KB).
pub const MAX_SHADER_BYTES: usize = 1 << 20;
/// Most brackets open at once, and most tokens in one statement: a homework shader stays under
/// 20 and 200; naga's parser and validator recurse on both, and a machine-made shader beyond
/// them could overflow a stack.
pub const MAX_NESTING: usize = 128;
pub const MAX_STATEMENT_TOKENS: usize = 4096;

/// A shader too big for the rewrite and naga, refused on the line where it goes too far.
pub(super) fn check_size(source: &str, toks: &[Token]) -> Result<(), super::HomeworkError> {
    if source.len() > MAX_SHADER_BYTES {
        let message = format!("{} bytes: a shader may have {MAX_SHADER_BYTES} at most", source.len());
        return Err(super::HomeworkError::Rewrite { line: 1, message });
    }
    let (mut depth, mut statement) = (0usize, 0usize);
    for t in toks {
        let word = &source[t.start..t.end];
        match word {
            "(" | "[" | "{" => depth += 1,
            ")" | "]" | "}" => depth = depth.saturating_sub(1),
            _ => {}
        }
        statement = if matches!(word, ";" | "{" | "}") { 0 } else { statement + 1 };
        if depth > MAX_NESTING {
            let message = format!("brackets nested more than {MAX_NESTING} deep");
            return Err(super::HomeworkError::Rewrite { line: t.line, message });
        }
        if statement > MAX_STATEMENT_TOKENS {
            let message = format!("a statement of more than {MAX_STATEMENT_TOKENS} tokens");
            return Err(super::HomeworkError::Rewrite { line: t.line, message });
        }
    }
    Ok(())
}

/// How deep in parentheses token `at` is, counted from the `(` at `open`.
pub(super) fn depth_in(source: &str, toks: &[Token], open: usize, at: usize) -> i32 {
    (open..at).fold(0, |depth, k| match &source[toks[k].start..toks[k].end] {
        "(" => depth + 1,
        ")" => depth - 1,
        _ => depth,
    })
}

/// A function defined at the top level: its name, the token of its name and of its body's `{`
/// and `}`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct FunctionBody<'s> {
    pub name: &'s str,
    pub name_at: usize,
    pub open: usize,
    pub close: usize,
}

/// Every function defined at the top level, first in the file first.
pub(crate) fn function_bodies<'s>(source: &'s str, toks: &[Token]) -> Vec<FunctionBody<'s>> {
    let text = |i: usize| toks.get(i).map_or("", |t| &source[t.start..t.end]);
    let mut out = Vec::new();
    let mut depth = 0i32;
    let mut i = 0;
    while i < toks.len() {
        match text(i) {
            "{" => depth += 1,
            "}" => depth -= 1,
            name if depth == 0
                && toks[i].kind == Kind::Ident
                && text(i + 1) == "("
                && !toks[i].in_directive =>
            {
                let open = (i + 1..toks.len()).find(|&k| text(k) == "{" || text(k) == ";");
                if let Some(open) = open.filter(|&k| text(k) == "{") {
                    let close = matching(source, toks, open, "{", "}");
                    if close > open && text(close) == "}" {
                        out.push(FunctionBody { name, name_at: i, open, close });
                        i = close;
                    }
                }
            }
            _ => {}
        }
        i += 1;
    }
    out
}

//! Tokens: identifiers, numbers, strings, templates, punctuators, with line numbers and
//! whether a newline came before each (for automatic semicolon insertion).

use std::sync::Arc;

use super::ScriptError;
use super::ast::Name;

#[derive(Clone, Debug, PartialEq)]
pub(super) enum Tok {
    Ident(Name),
    Num(f64),
    Str(Name),
    Punct(&'static str),
    /// A template literal without `${}` (cooked text).
    Template(Name),
    TemplateHead(Name),
    TemplateMiddle(Name),
    TemplateTail(Name),
    /// A regular expression literal: lexed only so the parser can refuse it by name.
    Regex,
    Eof,
}

#[derive(Clone, Debug)]
pub(super) struct Token {
    pub tok: Tok,
    pub line: usize,
    pub nl_before: bool,
}

/// The tokens lexed (always ending in `Eof`) and the error that stopped lexing, if any:
/// engine.js reading uses the tokens before an error.
pub(super) struct Lexed {
    pub tokens: Vec<Token>,
    pub error: Option<ScriptError>,
}

// Longest first, so the first prefix match is the longest punctuator.
const PUNCTS: [&str; 59] = [
    ">>>=", "...", "===", "!==", "**=", "<<=", ">>=", ">>>", "&&=", "||=", "??=", "=>", "==", "!=", "<=",
    ">=", "&&", "||", "??", "?.", "++", "--", "+=", "-=", "*=", "/=", "%=", "&=", "|=", "^=", "**", "<<",
    ">>", "{", "}", "(", ")", "[", "]", ";", ",", "<", ">", "+", "-", "*", "/", "%", "&", "|", "^", "!", "~",
    "?", ":", "=", ".", "@", "#",
];

/// Keywords after which a `/` starts a regular expression, not a division.
const BEFORE_OPERAND: [&str; 14] = [
    "return",
    "typeof",
    "instanceof",
    "in",
    "of",
    "new",
    "delete",
    "void",
    "throw",
    "case",
    "do",
    "else",
    "yield",
    "await",
];

pub(super) fn is_id_start(c: char) -> bool {
    c.is_alphabetic() || c == '$' || c == '_'
}

fn is_id_part(c: char) -> bool {
    c.is_alphanumeric() || c == '$' || c == '_' || c == '\u{200c}' || c == '\u{200d}'
}

fn is_line_end(c: char) -> bool {
    matches!(c, '\n' | '\r' | '\u{2028}' | '\u{2029}')
}

struct Lexer<'a> {
    chars: Vec<char>,
    pos: usize,
    line: usize,
    file: &'a str,
    tokens: Vec<Token>,
    nl_before: bool,
    /// One entry per open `{`: true when it opened a template's `${`.
    braces: Vec<bool>,
}

pub(super) fn lex(source: &str, file: &str) -> Lexed {
    let mut lx = Lexer {
        chars: source.chars().collect(),
        pos: 0,
        line: 1,
        file,
        tokens: Vec::new(),
        nl_before: true,
        braces: Vec::new(),
    };
    let error = lx.run().err();
    let line = lx.line;
    lx.tokens.push(Token { tok: Tok::Eof, line, nl_before: true });
    Lexed { tokens: lx.tokens, error }
}

impl Lexer<'_> {
    fn peek(&self, ahead: usize) -> Option<char> {
        self.chars.get(self.pos + ahead).copied()
    }

    fn err(&self, message: impl Into<String>) -> ScriptError {
        ScriptError { file: self.file.to_string(), line: self.line, message: message.into() }
    }

    fn push(&mut self, tok: Tok, line: usize) {
        self.tokens.push(Token { tok, line, nl_before: self.nl_before });
        self.nl_before = false;
    }

    /// Consumes one line terminator (CR LF counts once).
    fn newline(&mut self, c: char) {
        self.pos += 1;
        if c == '\r' && self.peek(0) == Some('\n') {
            self.pos += 1;
        }
        self.line += 1;
    }

    fn run(&mut self) -> Result<(), ScriptError> {
        if self.peek(0) == Some('#') && self.peek(1) == Some('!') {
            while self.peek(0).is_some_and(|c| !is_line_end(c)) {
                self.pos += 1;
            }
        }
        loop {
            self.skip_space()?;
            let Some(c) = self.peek(0) else { return Ok(()) };
            let line = self.line;
            if is_id_start(c) {
                let start = self.pos;
                while self.peek(0).is_some_and(is_id_part) {
                    self.pos += 1;
                }
                if self.peek(0) == Some('\\') {
                    return Err(self.err("unsupported: escapes in identifiers"));
                }
                let word: String = self.chars[start..self.pos].iter().collect();
                self.push(Tok::Ident(Arc::from(word)), line);
            } else if c.is_ascii_digit() || (c == '.' && self.peek(1).is_some_and(|d| d.is_ascii_digit())) {
                let n = self.number()?;
                self.push(Tok::Num(n), line);
            } else if c == '"' || c == '\'' {
                self.pos += 1;
                let s = self.string(c)?;
                self.push(Tok::Str(s), line);
            } else if c == '`' {
                self.pos += 1;
                self.template(true, line)?;
            } else if c == '}' && self.braces.last() == Some(&true) {
                self.braces.pop();
                self.pos += 1;
                self.template(false, line)?;
            } else if c == '\\' {
                return Err(self.err("unsupported: escapes in identifiers"));
            } else if c == '/' && self.regex_allowed() {
                self.regex()?;
                self.push(Tok::Regex, line);
            } else {
                self.punct(c, line)?;
            }
        }
    }

    fn skip_space(&mut self) -> Result<(), ScriptError> {
        while let Some(c) = self.peek(0) {
            if is_line_end(c) {
                self.newline(c);
                self.nl_before = true;
            } else if c.is_whitespace() || c == '\u{feff}' {
                self.pos += 1;
            } else if c == '/' && self.peek(1) == Some('/') {
                while self.peek(0).is_some_and(|c| !is_line_end(c)) {
                    self.pos += 1;
                }
            } else if c == '/' && self.peek(1) == Some('*') {
                let start_line = self.line;
                self.pos += 2;
                loop {
                    match self.peek(0) {
                        None => {
                            self.line = start_line;
                            return Err(self.err("syntax error: unterminated /* comment"));
                        }
                        Some('*') if self.peek(1) == Some('/') => {
                            self.pos += 2;
                            break;
                        }
                        Some(c) if is_line_end(c) => {
                            self.newline(c);
                            self.nl_before = true;
                        }
                        Some(_) => self.pos += 1,
                    }
                }
            } else {
                break;
            }
        }
        Ok(())
    }

    fn regex_allowed(&self) -> bool {
        match self.tokens.last().map(|t| &t.tok) {
            None => true,
            Some(Tok::Punct(p)) => !matches!(*p, ")" | "]" | "}"),
            Some(Tok::Ident(w)) => BEFORE_OPERAND.contains(&&**w),
            Some(Tok::TemplateHead(_) | Tok::TemplateMiddle(_)) => true,
            Some(_) => false,
        }
    }

    fn regex(&mut self) -> Result<(), ScriptError> {
        self.pos += 1;
        let mut in_class = false;
        loop {
            match self.peek(0) {
                None => return Err(self.err("syntax error: unterminated regular expression")),
                Some(c) if is_line_end(c) => {
                    return Err(self.err("syntax error: unterminated regular expression"));
                }
                Some('\\') => self.pos += 2,
                Some('[') => {
                    in_class = true;
                    self.pos += 1;
                }
                Some(']') => {
                    in_class = false;
                    self.pos += 1;
                }
                Some('/') if !in_class => {
                    self.pos += 1;
                    break;
                }
                Some(_) => self.pos += 1,
            }
        }
        while self.peek(0).is_some_and(is_id_part) {
            self.pos += 1;
        }
        Ok(())
    }

    fn punct(&mut self, c: char, line: usize) -> Result<(), ScriptError> {
        for p in PUNCTS {
            let n = p.len();
            if p.chars().enumerate().all(|(i, pc)| self.peek(i) == Some(pc)) {
                // `a?.5:b` is a conditional, not optional chaining.
                if p == "?." && self.peek(2).is_some_and(|d| d.is_ascii_digit()) {
                    continue;
                }
                self.pos += n;
                match p {
                    "{" => self.braces.push(false),
                    "}" => {
                        self.braces.pop();
                    }
                    _ => {}
                }
                self.push(Tok::Punct(p), line);
                return Ok(());
            }
        }
        Err(self.err(format!("syntax error: unexpected character `{c}`")))
    }

    fn number(&mut self) -> Result<f64, ScriptError> {
        let radix = match (self.peek(0), self.peek(1)) {
            (Some('0'), Some('x' | 'X')) => 16,
            (Some('0'), Some('o' | 'O')) => 8,
            (Some('0'), Some('b' | 'B')) => 2,
            _ => 10,
        };
        let value = if radix != 10 {
            self.pos += 2;
            let mut v = 0.0f64;
            let mut any = false;
            while let Some(c) = self.peek(0) {
                if c == '_' {
                    self.pos += 1;
                } else if let Some(d) = c.to_digit(radix) {
                    v = v * f64::from(radix) + f64::from(d);
                    any = true;
                    self.pos += 1;
                } else {
                    break;
                }
            }
            if !any {
                return Err(self.err("syntax error: a number prefix without digits"));
            }
            v
        } else {
            let mut text = String::new();
            self.digits(&mut text);
            if self.peek(0) == Some('.') {
                text.push('.');
                self.pos += 1;
                self.digits(&mut text);
            }
            if let Some('e' | 'E') = self.peek(0) {
                let sign = matches!(self.peek(1), Some('+' | '-'));
                let first = self.peek(if sign { 2 } else { 1 });
                if first.is_some_and(|d| d.is_ascii_digit()) {
                    text.push('e');
                    if sign {
                        text.push(self.peek(1).unwrap_or('+'));
                    }
                    self.pos += if sign { 2 } else { 1 };
                    self.digits(&mut text);
                }
            }
            text.parse::<f64>().map_err(|_| self.err(format!("syntax error: bad number `{text}`")))?
        };
        match self.peek(0) {
            Some('n') => Err(self.err("unsupported: BigInt literals")),
            Some(c) if is_id_start(c) || c.is_ascii_digit() => {
                Err(self.err("syntax error: an identifier starts right after a number"))
            }
            _ => Ok(value),
        }
    }

    fn digits(&mut self, text: &mut String) {
        while let Some(c) = self.peek(0) {
            if c.is_ascii_digit() {
                text.push(c);
            } else if c != '_' {
                break;
            }
            self.pos += 1;
        }
    }

    /// Reads one escape after the backslash; None for a line continuation.
    fn escape(&mut self) -> Result<Option<char>, ScriptError> {
        let Some(c) = self.peek(0) else { return Err(self.err("syntax error: unterminated string")) };
        self.pos += 1;
        let simple = match c {
            'n' => '\n',
            't' => '\t',
            'r' => '\r',
            'b' => '\u{8}',
            'f' => '\u{c}',
            'v' => '\u{b}',
            '0' if !self.peek(0).is_some_and(|d| d.is_ascii_digit()) => '\0',
            'x' => return self.hex_escape(2).map(Some),
            'u' if self.peek(0) == Some('{') => {
                self.pos += 1;
                let start = self.pos;
                while self.peek(0).is_some_and(|d| d.is_ascii_hexdigit()) && self.pos - start < 8 {
                    self.pos += 1;
                }
                let hex: String = self.chars[start..self.pos].iter().collect();
                if self.peek(0) != Some('}') {
                    return Err(self.err("syntax error: bad \\u{} escape"));
                }
                self.pos += 1;
                let code =
                    u32::from_str_radix(&hex, 16).map_err(|_| self.err("syntax error: bad \\u{} escape"))?;
                return Ok(Some(char::from_u32(code).unwrap_or('\u{fffd}')));
            }
            'u' => return self.hex_escape(4).map(Some),
            c if is_line_end(c) => {
                self.pos -= 1;
                self.newline(c);
                return Ok(None);
            }
            other => other,
        };
        Ok(Some(simple))
    }

    fn hex_escape(&mut self, n: usize) -> Result<char, ScriptError> {
        let hex: String = (0..n).filter_map(|i| self.peek(i)).collect();
        if hex.len() != n || !hex.chars().all(|d| d.is_ascii_hexdigit()) {
            return Err(self.err("syntax error: bad hexadecimal escape"));
        }
        self.pos += n;
        let code =
            u32::from_str_radix(&hex, 16).map_err(|_| self.err("syntax error: bad hexadecimal escape"))?;
        // A lone surrogate half has no char: keep a replacement character.
        Ok(char::from_u32(code).unwrap_or('\u{fffd}'))
    }

    fn string(&mut self, quote: char) -> Result<Name, ScriptError> {
        let mut out = String::new();
        loop {
            match self.peek(0) {
                None => return Err(self.err("syntax error: unterminated string")),
                Some(c) if is_line_end(c) && c != '\u{2028}' && c != '\u{2029}' => {
                    return Err(self.err("syntax error: unterminated string"));
                }
                Some('\\') => {
                    self.pos += 1;
                    if let Some(c) = self.escape()? {
                        out.push(c);
                    }
                }
                Some(c) => {
                    self.pos += 1;
                    if c == quote {
                        return Ok(Arc::from(out));
                    }
                    out.push(c);
                }
            }
        }
    }

    /// Reads template text up to `${` or the closing backquote.
    fn template(&mut self, opening: bool, line: usize) -> Result<(), ScriptError> {
        let mut out = String::new();
        loop {
            match self.peek(0) {
                None => return Err(self.err("syntax error: unterminated template literal")),
                Some('\\') => {
                    self.pos += 1;
                    if let Some(c) = self.escape()? {
                        out.push(c);
                    }
                }
                Some('`') => {
                    self.pos += 1;
                    let text: Name = Arc::from(out);
                    let tok = if opening { Tok::Template(text) } else { Tok::TemplateTail(text) };
                    self.push(tok, line);
                    return Ok(());
                }
                Some('$') if self.peek(1) == Some('{') => {
                    self.pos += 2;
                    self.braces.push(true);
                    let text: Name = Arc::from(out);
                    let tok = if opening { Tok::TemplateHead(text) } else { Tok::TemplateMiddle(text) };
                    self.push(tok, line);
                    return Ok(());
                }
                Some(c) if is_line_end(c) => {
                    self.newline(c);
                    out.push('\n');
                }
                Some(c) => {
                    self.pos += 1;
                    out.push(c);
                }
            }
        }
    }
}

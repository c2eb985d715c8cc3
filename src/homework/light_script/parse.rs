//! The parser: statements, functions, classes and binding patterns (expressions are in
//! `parse_expr.rs`). Every level of nesting is counted against `Limits::nesting`, so
//! hostile input cannot overflow the stack here or later in the evaluator.

use std::sync::Arc;

use super::ScriptError;
use super::ast::*;
use super::lex::{Tok, Token};

const RESERVED: [&str; 38] = [
    "break",
    "case",
    "catch",
    "class",
    "const",
    "continue",
    "debugger",
    "default",
    "delete",
    "do",
    "else",
    "enum",
    "export",
    "extends",
    "false",
    "finally",
    "for",
    "function",
    "if",
    "import",
    "in",
    "instanceof",
    "new",
    "null",
    "return",
    "super",
    "switch",
    "this",
    "throw",
    "true",
    "try",
    "typeof",
    "var",
    "void",
    "while",
    "with",
    "yield",
    "let",
];

pub(super) struct Parser<'a> {
    pub(super) toks: &'a [Token],
    pub(super) pos: usize,
    pub(super) file: &'a str,
    pub(super) depth: usize,
    pub(super) max_depth: usize,
    pub(super) strict: bool,
    /// `for (x in o)` heads: a bare `in` ends the initialiser instead of being an operator.
    pub(super) no_in: bool,
    pub(super) in_function: bool,
    pub(super) uses_arguments: bool,
    pub(super) var_names: Vec<Name>,
    pub(super) notes: Vec<String>,
    /// Where the stack was when parsing began (see `STACK_BUDGET_BYTES`).
    stack_base: usize,
    /// For each opening bracket, the index of its closing one (made on first use).
    pub(super) closers: Option<Vec<u32>>,
}

/// Parses a whole file.
/// Parse errors are boxed: they travel up every level of the recursive descent.
pub(super) type PErr = Box<ScriptError>;

pub(super) fn parse_program(toks: &[Token], file: &str, max_depth: usize) -> Result<Program, ScriptError> {
    parse_program_boxed(toks, file, max_depth).map_err(|e| *e)
}

fn parse_program_boxed(toks: &[Token], file: &str, max_depth: usize) -> Result<Program, PErr> {
    let mut p = Parser::new(toks, file, max_depth);
    p.strict = p.directive_prologue();
    let mut body = Vec::new();
    while p.peek() != &Tok::Eof {
        body.push(p.statement()?);
    }
    Ok(Program { body, var_names: std::mem::take(&mut p.var_names), notes: p.notes })
}

/// Parses one expression at the start of `toks` (engine.js values); the rest is ignored.
pub(super) fn parse_prefix(toks: &[Token], file: &str, max_depth: usize) -> Result<Expr, ScriptError> {
    Parser::new(toks, file, max_depth).assign_expr().map_err(|e| *e)
}

impl<'a> Parser<'a> {
    fn new(toks: &'a [Token], file: &'a str, max_depth: usize) -> Self {
        Parser {
            toks,
            pos: 0,
            file,
            depth: 0,
            max_depth,
            strict: false,
            no_in: false,
            in_function: false,
            uses_arguments: false,
            var_names: Vec::new(),
            notes: Vec::new(),
            stack_base: super::interp::stack_address(),
            closers: None,
        }
    }

    pub(super) fn token(&self) -> Option<&Token> {
        self.toks.get(self.pos).or(self.toks.last())
    }

    pub(super) fn peek(&self) -> &Tok {
        self.peek_at(0)
    }

    pub(super) fn peek_at(&self, n: usize) -> &Tok {
        self.toks.get(self.pos + n).or(self.toks.last()).map_or(&Tok::Eof, |t| &t.tok)
    }

    pub(super) fn line(&self) -> usize {
        self.token().map_or(0, |t| t.line)
    }

    pub(super) fn nl_before(&self) -> bool {
        self.token().is_none_or(|t| t.nl_before)
    }

    pub(super) fn advance(&mut self) {
        if self.pos < self.toks.len() {
            self.pos += 1;
        }
    }

    pub(super) fn is_punct(&self, p: &str) -> bool {
        matches!(self.peek(), Tok::Punct(q) if *q == p)
    }

    pub(super) fn eat_punct(&mut self, p: &str) -> bool {
        let hit = self.is_punct(p);
        if hit {
            self.advance();
        }
        hit
    }

    pub(super) fn expect_punct(&mut self, p: &str) -> Result<usize, PErr> {
        let line = self.line();
        if self.eat_punct(p) {
            Ok(line)
        } else {
            Err(self.err(format!("syntax error: expected `{p}`, found {}", self.describe())))
        }
    }

    pub(super) fn is_word(&self, w: &str) -> bool {
        matches!(self.peek(), Tok::Ident(x) if &**x == w)
    }

    pub(super) fn eat_word(&mut self, w: &str) -> bool {
        let hit = self.is_word(w);
        if hit {
            self.advance();
        }
        hit
    }

    pub(super) fn err(&self, message: impl Into<String>) -> PErr {
        Box::new(ScriptError { file: self.file.to_string(), line: self.line(), message: message.into() })
    }

    pub(super) fn unsupported(&self, what: &str) -> PErr {
        self.err(format!("unsupported: {what}"))
    }

    pub(super) fn describe(&self) -> String {
        match self.peek() {
            Tok::Ident(w) => format!("`{w}`"),
            Tok::Num(_) => "a number".into(),
            Tok::Str(_) => "a string".into(),
            Tok::Punct(p) => format!("`{p}`"),
            Tok::Template(_) | Tok::TemplateHead(_) => "a template literal".into(),
            Tok::TemplateMiddle(_) | Tok::TemplateTail(_) => "`}`".into(),
            Tok::Regex => "a regular expression".into(),
            Tok::Eof => "the end of the file".into(),
        }
    }

    pub(super) fn unexpected(&self) -> PErr {
        match self.peek() {
            Tok::Regex => self.unsupported("regular expression literals"),
            _ => self.err(format!("syntax error: unexpected {}", self.describe())),
        }
    }

    /// Counts one level of nesting; errors past the limit so recursion stays bounded.
    pub(super) fn enter(&mut self) -> Result<(), PErr> {
        self.depth += 1;
        if self.depth > self.max_depth {
            return Err(self.err(format!("nested deeper than {} levels", self.max_depth)));
        }
        if super::interp::stack_exhausted(self.stack_base) {
            return Err(self.err("nested too deeply to parse"));
        }
        Ok(())
    }

    pub(super) fn leave(&mut self, levels: usize) {
        self.depth = self.depth.saturating_sub(levels);
    }

    /// A name that can be bound: an identifier that is not a reserved word.
    pub(super) fn binding_ident(&mut self) -> Result<Name, PErr> {
        match self.peek() {
            Tok::Ident(w) if !RESERVED.contains(&&**w) => {
                let w = w.clone();
                self.advance();
                Ok(w)
            }
            _ => Err(self.err(format!("syntax error: expected a name, found {}", self.describe()))),
        }
    }

    pub(super) fn is_reserved(w: &str) -> bool {
        RESERVED.contains(&w)
    }

    /// A property name: any identifier, a string or a number.
    pub(super) fn prop_name(&mut self) -> Result<Name, PErr> {
        let name = match self.peek() {
            Tok::Ident(w) | Tok::Str(w) => w.clone(),
            Tok::Num(n) => Arc::from(super::ops::num_to_string(*n)),
            Tok::Punct("#") => return Err(self.unsupported("private `#` members")),
            _ => {
                return Err(
                    self.err(format!("syntax error: expected a property name, found {}", self.describe()))
                );
            }
        };
        self.advance();
        Ok(name)
    }

    /// Ends a statement: `;`, or automatically before `}`, the end, or a newline.
    pub(super) fn semicolon(&mut self) -> Result<(), PErr> {
        if self.eat_punct(";") || self.is_punct("}") || self.peek() == &Tok::Eof || self.nl_before() {
            return Ok(());
        }
        Err(self.err(format!("syntax error: expected `;` or a new line, found {}", self.describe())))
    }

    pub(super) fn at_statement_end(&self) -> bool {
        self.is_punct(";") || self.is_punct("}") || self.peek() == &Tok::Eof || self.nl_before()
    }

    /// True when the body starts with a "use strict" directive.
    pub(super) fn directive_prologue(&self) -> bool {
        let mut i = 0;
        while let Tok::Str(s) = self.peek_at(i) {
            if &**s == "use strict" {
                return true;
            }
            i += 1;
            if matches!(self.peek_at(i), Tok::Punct(";")) {
                i += 1;
            }
        }
        false
    }
}

//! Statements: declarations, control flow, `try`, `switch`, and the module keywords
//! (`export` is skipped, `import` lines are skipped with a note).

use super::ast::*;
use super::lex::Tok;
use super::parse::PErr;
use super::parse::Parser;
use super::parse_fn::collect_names;

impl Parser<'_> {
    pub(super) fn statement(&mut self) -> Result<Stmt, PErr> {
        self.enter()?;
        let line = self.line();
        let kind = self.statement_kind()?;
        self.leave(1);
        Ok(Stmt { kind, line })
    }

    fn statement_kind(&mut self) -> Result<StmtKind, PErr> {
        let word = match self.peek() {
            Tok::Punct("{") => {
                self.advance();
                return Ok(StmtKind::Block(self.block_body()?));
            }
            Tok::Punct(";") => {
                self.advance();
                return Ok(StmtKind::Empty);
            }
            Tok::Ident(w) => w.clone(),
            _ => return self.expression_statement(),
        };
        let next_is_binding = matches!(self.peek_at(1), Tok::Ident(_) | Tok::Punct("[" | "{"));
        match &*word {
            "var" => self.declaration(DeclKind::Var, true),
            "const" => self.declaration(DeclKind::Const, true),
            "let" if next_is_binding => self.declaration(DeclKind::Let, true),
            "function" => {
                let line = self.line();
                self.advance();
                if self.is_punct("*") {
                    return Err(self.unsupported("generator functions"));
                }
                let name = self.binding_ident()?;
                Ok(StmtKind::Function(self.function_rest(Some(name), line)?))
            }
            "async" if matches!(self.peek_at(1), Tok::Ident(w) if &**w == "function") => {
                Err(self.unsupported("async functions"))
            }
            "class" => Ok(StmtKind::Class(self.class_rest(true)?)),
            "if" => {
                self.advance();
                let test = self.paren_expr()?;
                let then = Box::new(self.statement()?);
                let other = if self.eat_word("else") { Some(Box::new(self.statement()?)) } else { None };
                Ok(StmtKind::If(test, then, other))
            }
            "for" => self.for_statement(),
            "while" => {
                self.advance();
                let test = self.paren_expr()?;
                Ok(StmtKind::While(test, Box::new(self.statement()?)))
            }
            "do" => {
                self.advance();
                let body = Box::new(self.statement()?);
                if !self.eat_word("while") {
                    return Err(
                        self.err(format!("syntax error: expected `while`, found {}", self.describe()))
                    );
                }
                let test = self.paren_expr()?;
                self.eat_punct(";");
                Ok(StmtKind::DoWhile(body, test))
            }
            "return" => {
                if !self.in_function {
                    return Err(self.err("syntax error: `return` outside a function"));
                }
                self.advance();
                let value = if self.at_statement_end() { None } else { Some(self.expr()?) };
                self.semicolon()?;
                Ok(StmtKind::Return(value))
            }
            "break" | "continue" => {
                self.advance();
                if matches!(self.peek(), Tok::Ident(_)) && !self.nl_before() {
                    return Err(self.unsupported("labels"));
                }
                self.semicolon()?;
                Ok(if &*word == "break" { StmtKind::Break } else { StmtKind::Continue })
            }
            "throw" => {
                self.advance();
                if self.nl_before() {
                    return Err(self.err("syntax error: a new line right after `throw`"));
                }
                let value = self.expr()?;
                self.semicolon()?;
                Ok(StmtKind::Throw(value))
            }
            "try" => self.try_statement(),
            "switch" => self.switch_statement(),
            "export" => {
                self.advance();
                self.eat_word("default");
                if self.eat_punct("{") {
                    while !self.eat_punct("}") {
                        if self.peek() == &Tok::Eof {
                            return Err(self.unexpected());
                        }
                        self.advance();
                    }
                    self.skip_module_source()?;
                    return Ok(StmtKind::Empty);
                }
                if self.is_word("export") || self.is_word("import") {
                    return Err(self.unexpected());
                }
                self.statement_kind()
            }
            "import" if !matches!(self.peek_at(1), Tok::Punct("(" | ".")) => {
                let line = self.line();
                self.advance();
                while !matches!(self.peek(), Tok::Str(_) | Tok::Eof) {
                    self.advance();
                }
                self.advance();
                self.semicolon()?;
                self.notes.push(format!(
                    "line {line}: `import` skipped (gl-matrix and the framework's classes are globals here)"
                ));
                Ok(StmtKind::Empty)
            }
            "debugger" => {
                self.advance();
                self.semicolon()?;
                Ok(StmtKind::Empty)
            }
            "with" => Err(self.unsupported("`with` statements")),
            _ if matches!(self.peek_at(1), Tok::Punct(":")) && !Self::is_reserved(&word) => {
                Err(self.unsupported("labels"))
            }
            _ => self.expression_statement(),
        }
    }

    /// `export { a } from './x.js'` ends with an optional module name.
    fn skip_module_source(&mut self) -> Result<(), PErr> {
        if self.eat_word("from") {
            self.advance();
        }
        self.semicolon()
    }

    fn expression_statement(&mut self) -> Result<StmtKind, PErr> {
        let e = self.expr()?;
        self.semicolon()?;
        Ok(StmtKind::Expr(e))
    }

    fn paren_expr(&mut self) -> Result<Expr, PErr> {
        self.expect_punct("(")?;
        let e = self.expr()?;
        self.expect_punct(")")?;
        Ok(e)
    }

    /// Statements up to the closing `}` (the `{` is already read).
    pub(super) fn block_body(&mut self) -> Result<Vec<Stmt>, PErr> {
        let open_line = self.toks.get(self.pos.wrapping_sub(1)).map_or(0, |t| t.line);
        let mut body = Vec::new();
        let saved = std::mem::replace(&mut self.no_in, false);
        while !self.eat_punct("}") {
            if self.peek() == &Tok::Eof {
                return Err(self.err(format!("syntax error: missing `}}` for the `{{` on line {open_line}")));
            }
            body.push(self.statement()?);
        }
        self.no_in = saved;
        Ok(body)
    }

    /// `var|let|const` bindings; `end` says whether a `;` must follow (not in a `for` head).
    fn declaration(&mut self, kind: DeclKind, end: bool) -> Result<StmtKind, PErr> {
        self.advance();
        let mut decls = Vec::new();
        loop {
            let target = self.binding_pattern()?;
            if kind == DeclKind::Var {
                collect_names(&target, &mut self.var_names);
            }
            let init = if self.eat_punct("=") { Some(self.assign_expr()?) } else { None };
            decls.push((target, init));
            if !self.eat_punct(",") {
                break;
            }
        }
        if end {
            self.semicolon()?;
        }
        Ok(StmtKind::Decl(kind, decls))
    }

    fn for_statement(&mut self) -> Result<StmtKind, PErr> {
        self.advance();
        if self.is_word("await") {
            return Err(self.unsupported("`for await`"));
        }
        self.expect_punct("(")?;
        let line = self.line();
        let decl = match self.peek() {
            Tok::Ident(w) if &**w == "var" => Some(DeclKind::Var),
            Tok::Ident(w) if &**w == "const" => Some(DeclKind::Const),
            Tok::Ident(w)
                if &**w == "let" && matches!(self.peek_at(1), Tok::Ident(_) | Tok::Punct("[" | "{")) =>
            {
                Some(DeclKind::Let)
            }
            _ => None,
        };
        let mut init = None;
        if let Some(kind) = decl {
            let start = self.pos;
            self.advance();
            let target = self.binding_pattern()?;
            if self.is_word("of") || self.is_word("in") {
                if kind == DeclKind::Var {
                    collect_names(&target, &mut self.var_names);
                }
                return self.for_each_rest(Some(kind), target);
            }
            self.pos = start;
            self.no_in = true;
            let d = self.declaration(kind, false);
            self.no_in = false;
            init = Some(Box::new(Stmt { kind: d?, line }));
        } else if !self.is_punct(";") {
            self.no_in = true;
            let e = self.expr();
            self.no_in = false;
            let e = e?;
            if self.is_word("of") || self.is_word("in") {
                let ExprKind::Ident(name) = e.kind else {
                    return Err(self.unsupported("this kind of `for ... of` target"));
                };
                return self.for_each_rest(None, Pattern::Ident(name));
            }
            init = Some(Box::new(Stmt { kind: StmtKind::Expr(e), line }));
        }
        self.expect_punct(";")?;
        let test = if self.is_punct(";") { None } else { Some(self.expr()?) };
        self.expect_punct(";")?;
        let update = if self.is_punct(")") { None } else { Some(self.expr()?) };
        self.expect_punct(")")?;
        let body = Box::new(self.statement()?);
        Ok(StmtKind::For { init, test, update, body })
    }

    fn for_each_rest(&mut self, decl: Option<DeclKind>, target: Pattern) -> Result<StmtKind, PErr> {
        let is_in = self.is_word("in");
        self.advance();
        let iter = if is_in { self.expr()? } else { self.assign_expr()? };
        self.expect_punct(")")?;
        let body = Box::new(self.statement()?);
        Ok(StmtKind::ForEach { decl, target, iter, body, is_in })
    }

    fn try_statement(&mut self) -> Result<StmtKind, PErr> {
        self.advance();
        self.expect_punct("{")?;
        let body = self.block_body()?;
        let (mut param, mut handler, mut finally) = (None, None, None);
        if self.eat_word("catch") {
            if self.eat_punct("(") {
                param = Some(self.binding_pattern()?);
                self.expect_punct(")")?;
            }
            self.expect_punct("{")?;
            handler = Some(self.block_body()?);
        }
        if self.eat_word("finally") {
            self.expect_punct("{")?;
            finally = Some(self.block_body()?);
        }
        if handler.is_none() && finally.is_none() {
            return Err(self.err("syntax error: `try` without `catch` or `finally`"));
        }
        Ok(StmtKind::Try { body, param, handler, finally })
    }

    fn switch_statement(&mut self) -> Result<StmtKind, PErr> {
        self.advance();
        let subject = self.paren_expr()?;
        self.expect_punct("{")?;
        let mut cases: Vec<Case> = Vec::new();
        while !self.eat_punct("}") {
            let test = if self.eat_word("case") {
                Some(self.expr()?)
            } else if self.eat_word("default") {
                None
            } else {
                return Err(self.unexpected());
            };
            self.expect_punct(":")?;
            let mut body = Vec::new();
            while !(self.is_word("case") || self.is_word("default") || self.is_punct("}")) {
                if self.peek() == &Tok::Eof {
                    return Err(self.unexpected());
                }
                body.push(self.statement()?);
            }
            cases.push(Case { test, body });
        }
        Ok(StmtKind::Switch(subject, cases))
    }
}

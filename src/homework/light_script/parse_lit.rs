//! Literals: templates, arrays and objects (with shorthand, methods and accessors).

use super::ast::*;
use super::lex::Tok;
use super::parse::PErr;
use super::parse::Parser;

impl Parser<'_> {
    pub(super) fn template(&mut self, head: Name, line: usize) -> Result<Expr, PErr> {
        self.advance();
        let mut quasis = vec![head];
        let mut exprs = Vec::new();
        let saved = std::mem::replace(&mut self.no_in, false);
        loop {
            exprs.push(self.expr()?);
            match self.peek().clone() {
                Tok::TemplateMiddle(s) => {
                    self.advance();
                    quasis.push(s);
                }
                Tok::TemplateTail(s) => {
                    self.advance();
                    quasis.push(s);
                    break;
                }
                _ => {
                    return Err(self.err(format!(
                        "syntax error: expected `}}` in a template, found {}",
                        self.describe()
                    )));
                }
            }
        }
        self.no_in = saved;
        Ok(Expr { kind: ExprKind::Template { quasis, exprs }, line })
    }

    pub(super) fn array_literal(&mut self, line: usize) -> Result<Expr, PErr> {
        self.advance();
        let saved = std::mem::replace(&mut self.no_in, false);
        let mut items = Vec::new();
        while !self.eat_punct("]") {
            if self.eat_punct(",") {
                items.push(Item::Hole);
                continue;
            }
            if self.eat_punct("...") {
                items.push(Item::Spread(self.assign_expr()?));
            } else {
                items.push(Item::Plain(self.assign_expr()?));
            }
            if !self.eat_punct(",") {
                self.expect_punct("]")?;
                break;
            }
        }
        self.no_in = saved;
        Ok(Expr { kind: ExprKind::Array(items), line })
    }

    pub(super) fn object_literal(&mut self, line: usize) -> Result<Expr, PErr> {
        self.advance();
        let saved = std::mem::replace(&mut self.no_in, false);
        let mut props = Vec::new();
        while !self.eat_punct("}") {
            if self.eat_punct("...") {
                props.push(ObjProp::Spread(self.assign_expr()?));
            } else {
                props.push(self.object_member()?);
            }
            if !self.eat_punct(",") {
                self.expect_punct("}")?;
                break;
            }
        }
        self.no_in = saved;
        Ok(Expr { kind: ExprKind::Object(props), line })
    }

    fn object_member(&mut self) -> Result<ObjProp, PErr> {
        let line = self.line();
        let ends_key = |t: &Tok| matches!(t, Tok::Punct("," | ":" | "(" | "}" | "="));
        if (self.is_word("async") || self.is_punct("*")) && !ends_key(self.peek_at(1)) {
            return Err(self.unsupported("async and generator methods"));
        }
        if (self.is_word("get") || self.is_word("set")) && !ends_key(self.peek_at(1)) {
            let getter = self.is_word("get");
            self.advance();
            let key = self.member_key()?;
            let def = self.function_rest(None, line)?;
            return Ok(if getter { ObjProp::Getter(key, def) } else { ObjProp::Setter(key, def) });
        }
        let shorthand = match self.peek() {
            Tok::Ident(w) if !Self::is_reserved(w) => Some(w.clone()),
            _ => None,
        };
        let key = self.member_key()?;
        if self.eat_punct(":") {
            return Ok(ObjProp::Value(key, self.assign_expr()?));
        }
        if self.is_punct("(") {
            let name = match &key {
                PropKey::Name(n) => Some(n.clone()),
                PropKey::Computed(_) => None,
            };
            let def = self.function_rest(name, line)?;
            return Ok(ObjProp::Value(key, Expr { kind: ExprKind::Function(def), line }));
        }
        match shorthand {
            Some(name) if !self.is_punct("=") => {
                Ok(ObjProp::Value(key, Expr { kind: ExprKind::Ident(name), line }))
            }
            _ => Err(self.err(format!("syntax error: expected `:`, found {}", self.describe()))),
        }
    }
}

//! Functions, parameters, classes and binding patterns.

use std::sync::Arc;

use super::ast::*;
use super::lex::Tok;
use super::parse::PErr;
use super::parse::Parser;

impl Parser<'_> {
    /// Parameters and body of a function whose name (if any) is already read.
    pub(super) fn function_rest(&mut self, name: Option<Name>, line: usize) -> Result<Arc<FuncDef>, PErr> {
        self.enter()?;
        let outer = self.open_function();
        self.expect_punct("(")?;
        let (params, rest) = self.params()?;
        self.expect_punct("{")?;
        if self.directive_prologue() {
            self.strict = true;
        }
        let body = self.block_body()?;
        let end_line = self.toks.get(self.pos.wrapping_sub(1)).map_or(line, |t| t.line);
        let def =
            self.close_function(outer, name, params, rest, FuncBody::Block(body), false, line, end_line);
        self.leave(1);
        Ok(def)
    }

    /// Starts a function's own `var` and `arguments` bookkeeping; returns the outer one.
    pub(super) fn open_function(&mut self) -> (Vec<Name>, bool, bool, bool, bool) {
        let outer = (
            std::mem::take(&mut self.var_names),
            self.uses_arguments,
            self.in_function,
            self.strict,
            self.no_in,
        );
        self.uses_arguments = false;
        self.in_function = true;
        self.no_in = false;
        outer
    }

    #[allow(clippy::too_many_arguments)]
    pub(super) fn close_function(
        &mut self,
        outer: (Vec<Name>, bool, bool, bool, bool),
        name: Option<Name>,
        params: Vec<PatItem>,
        rest: Option<Pattern>,
        body: FuncBody,
        arrow: bool,
        line: usize,
        end_line: usize,
    ) -> Arc<FuncDef> {
        let var_names = std::mem::replace(&mut self.var_names, outer.0);
        let uses_arguments = self.uses_arguments;
        // An arrow sees its enclosing function's `arguments`.
        self.uses_arguments = outer.1 || (arrow && uses_arguments);
        self.in_function = outer.2;
        self.strict = outer.3;
        self.no_in = outer.4;
        Arc::new(FuncDef { name, params, rest, body, arrow, uses_arguments, var_names, line, end_line })
    }

    /// `a, b = 1, [c], ...rest)`: the `(` is already read; reads the `)`.
    pub(super) fn params(&mut self) -> Result<(Vec<PatItem>, Option<Pattern>), PErr> {
        let mut params = Vec::new();
        let mut rest = None;
        while !self.eat_punct(")") {
            if self.eat_punct("...") {
                rest = Some(self.binding_pattern()?);
                self.expect_punct(")")?;
                break;
            }
            let target = self.binding_pattern()?;
            let default = if self.eat_punct("=") { Some(self.assign_expr()?) } else { None };
            params.push(PatItem { target, default });
            if !self.eat_punct(",") {
                self.expect_punct(")")?;
                break;
            }
        }
        Ok((params, rest))
    }

    pub(super) fn binding_pattern(&mut self) -> Result<Pattern, PErr> {
        self.enter()?;
        let pattern = if self.eat_punct("[") {
            let mut items = Vec::new();
            let mut rest = None;
            while !self.eat_punct("]") {
                if self.eat_punct(",") {
                    items.push(None);
                    continue;
                }
                if self.eat_punct("...") {
                    rest = Some(Box::new(self.binding_pattern()?));
                    self.expect_punct("]")?;
                    break;
                }
                let target = self.binding_pattern()?;
                let default = if self.eat_punct("=") { Some(self.assign_expr()?) } else { None };
                items.push(Some(PatItem { target, default }));
                if !self.eat_punct(",") {
                    self.expect_punct("]")?;
                    break;
                }
            }
            Pattern::Array { items, rest }
        } else if self.eat_punct("{") {
            let mut props = Vec::new();
            let mut rest = None;
            while !self.eat_punct("}") {
                if self.eat_punct("...") {
                    rest = Some(self.binding_ident()?);
                    self.expect_punct("}")?;
                    break;
                }
                let shorthand = matches!(self.peek(), Tok::Ident(_));
                let key = if self.eat_punct("[") {
                    let e = self.assign_expr()?;
                    self.expect_punct("]")?;
                    PropKey::Computed(e)
                } else {
                    PropKey::Name(self.prop_name()?)
                };
                let target = if self.eat_punct(":") {
                    self.binding_pattern()?
                } else {
                    match &key {
                        PropKey::Name(n) if shorthand && !Self::is_reserved(n) => Pattern::Ident(n.clone()),
                        _ => {
                            return Err(
                                self.err(format!("syntax error: expected `:`, found {}", self.describe()))
                            );
                        }
                    }
                };
                let default = if self.eat_punct("=") { Some(self.assign_expr()?) } else { None };
                props.push((key, PatItem { target, default }));
                if !self.eat_punct(",") {
                    self.expect_punct("}")?;
                    break;
                }
            }
            Pattern::Object { props, rest }
        } else {
            Pattern::Ident(self.binding_ident()?)
        };
        self.leave(1);
        Ok(pattern)
    }

    /// A class from its `class` keyword: `class Name extends Parent { members }`.
    pub(super) fn class_rest(&mut self, need_name: bool) -> Result<Arc<ClassDef>, PErr> {
        let line = self.line();
        self.advance();
        let name = if matches!(self.peek(), Tok::Ident(w) if &**w != "extends") {
            Some(self.binding_ident()?)
        } else if need_name {
            return Err(self.err(format!("syntax error: expected a class name, found {}", self.describe())));
        } else {
            None
        };
        let parent = if self.eat_word("extends") { Some(self.lhs_expr()?) } else { None };
        let open_line = self.expect_punct("{")?;
        self.enter()?;
        // Class bodies are strict code.
        let saved_strict = std::mem::replace(&mut self.strict, true);
        let mut ctor = None;
        let mut members = Vec::new();
        while !self.eat_punct("}") {
            if self.eat_punct(";") {
                continue;
            }
            if self.peek() == &Tok::Eof {
                return Err(self.err(format!("syntax error: missing `}}` for the class on line {open_line}")));
            }
            let mline = self.line();
            let modifier_ends = |t: &Tok| matches!(t, Tok::Punct("(" | "=" | ";" | "}"));
            let is_static = self.is_word("static") && !modifier_ends(self.peek_at(1));
            if is_static {
                self.advance();
                if self.is_punct("{") {
                    return Err(self.unsupported("static blocks"));
                }
            }
            if self.is_word("async") && !modifier_ends(self.peek_at(1)) {
                return Err(self.unsupported("async methods"));
            }
            if self.is_punct("*") {
                return Err(self.unsupported("generator methods"));
            }
            let accessor = if (self.is_word("get") || self.is_word("set")) && !modifier_ends(self.peek_at(1))
            {
                let getter = self.is_word("get");
                self.advance();
                Some(getter)
            } else {
                None
            };
            let key = self.member_key()?;
            if self.is_punct("(") {
                let fname = match &key {
                    PropKey::Name(n) => Some(n.clone()),
                    PropKey::Computed(_) => None,
                };
                let def = self.function_rest(fname, mline)?;
                let is_ctor = matches!(&key, PropKey::Name(n) if &**n == "constructor");
                let kind = match accessor {
                    Some(true) => MemberKind::Getter(def),
                    Some(false) => MemberKind::Setter(def),
                    None if is_ctor && !is_static => {
                        ctor = Some(def);
                        continue;
                    }
                    None => MemberKind::Method(def),
                };
                members.push(ClassMember { is_static, key, kind, line: mline });
            } else {
                if accessor.is_some() {
                    return Err(self.err(format!("syntax error: expected `(`, found {}", self.describe())));
                }
                let init = if self.eat_punct("=") { Some(self.assign_expr()?) } else { None };
                self.semicolon()?;
                members.push(ClassMember { is_static, key, kind: MemberKind::Field(init), line: mline });
            }
        }
        self.strict = saved_strict;
        self.leave(1);
        Ok(Arc::new(ClassDef { name, parent, ctor, members, line }))
    }

    /// A member or property key: a name, string, number or `[computed]`.
    pub(super) fn member_key(&mut self) -> Result<PropKey, PErr> {
        if self.eat_punct("[") {
            let saved = std::mem::replace(&mut self.no_in, false);
            let e = self.assign_expr()?;
            self.no_in = saved;
            self.expect_punct("]")?;
            Ok(PropKey::Computed(e))
        } else {
            Ok(PropKey::Name(self.prop_name()?))
        }
    }
}

/// The names a pattern binds (for `var` hoisting). Patterns are nesting-bounded.
pub(super) fn collect_names(p: &Pattern, out: &mut Vec<Name>) {
    match p {
        Pattern::Ident(n) => out.push(n.clone()),
        Pattern::Array { items, rest } => {
            for item in items.iter().flatten() {
                collect_names(&item.target, out);
            }
            if let Some(r) = rest {
                collect_names(r, out);
            }
        }
        Pattern::Object { props, rest } => {
            for (_, item) in props {
                collect_names(&item.target, out);
            }
            if let Some(r) = rest {
                out.push(r.clone());
            }
        }
    }
}

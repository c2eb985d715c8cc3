//! Expressions, by precedence climbing. Each chain link (`a + b`, `.x`, `(..)`) and each
//! prefix operator counts one nesting level, so the tree's depth stays within the limit.

use super::ast::*;
use super::lex::Tok;
use super::parse::PErr;
use super::parse::Parser;

enum Op {
    Bin(BinOp),
    Logic(LogicOp),
}

const POW_PRECEDENCE: u8 = 12;

fn binary_punct(p: &str) -> Option<(Op, u8)> {
    use BinOp::*;
    let (op, prec) = match p {
        "??" => (Op::Logic(LogicOp::Nullish), 1),
        "||" => (Op::Logic(LogicOp::Or), 2),
        "&&" => (Op::Logic(LogicOp::And), 3),
        "|" => (Op::Bin(BitOr), 4),
        "^" => (Op::Bin(BitXor), 5),
        "&" => (Op::Bin(BitAnd), 6),
        "==" => (Op::Bin(Eq), 7),
        "!=" => (Op::Bin(Ne), 7),
        "===" => (Op::Bin(StrictEq), 7),
        "!==" => (Op::Bin(StrictNe), 7),
        "<" => (Op::Bin(Lt), 8),
        ">" => (Op::Bin(Gt), 8),
        "<=" => (Op::Bin(Le), 8),
        ">=" => (Op::Bin(Ge), 8),
        "<<" => (Op::Bin(Shl), 9),
        ">>" => (Op::Bin(Shr), 9),
        ">>>" => (Op::Bin(UShr), 9),
        "+" => (Op::Bin(Add), 10),
        "-" => (Op::Bin(Sub), 10),
        "*" => (Op::Bin(Mul), 11),
        "/" => (Op::Bin(Div), 11),
        "%" => (Op::Bin(Rem), 11),
        "**" => (Op::Bin(Pow), POW_PRECEDENCE),
        _ => return None,
    };
    Some((op, prec))
}

fn assign_punct(p: &str) -> Option<AssignOp> {
    use BinOp::*;
    Some(match p {
        "=" => AssignOp::Assign,
        "+=" => AssignOp::Op(Add),
        "-=" => AssignOp::Op(Sub),
        "*=" => AssignOp::Op(Mul),
        "/=" => AssignOp::Op(Div),
        "%=" => AssignOp::Op(Rem),
        "**=" => AssignOp::Op(Pow),
        "<<=" => AssignOp::Op(Shl),
        ">>=" => AssignOp::Op(Shr),
        ">>>=" => AssignOp::Op(UShr),
        "&=" => AssignOp::Op(BitAnd),
        "|=" => AssignOp::Op(BitOr),
        "^=" => AssignOp::Op(BitXor),
        "&&=" => AssignOp::Logic(LogicOp::And),
        "||=" => AssignOp::Logic(LogicOp::Or),
        "??=" => AssignOp::Logic(LogicOp::Nullish),
        _ => return None,
    })
}

fn is_simple_target(e: &Expr) -> bool {
    matches!(e.kind, ExprKind::Ident(_) | ExprKind::Member { .. } | ExprKind::Index { .. })
}

impl Parser<'_> {
    pub(super) fn expr(&mut self) -> Result<Expr, PErr> {
        let first = self.assign_expr()?;
        if !self.is_punct(",") {
            return Ok(first);
        }
        let line = first.line;
        let mut items = vec![first];
        while self.eat_punct(",") {
            items.push(self.assign_expr()?);
        }
        Ok(Expr { kind: ExprKind::Seq(items), line })
    }

    pub(super) fn assign_expr(&mut self) -> Result<Expr, PErr> {
        self.enter()?;
        let e = self.assign_inner();
        self.leave(1);
        e
    }

    fn assign_inner(&mut self) -> Result<Expr, PErr> {
        let line = self.line();
        if self.is_word("async") && self.async_function_ahead() {
            return Err(self.unsupported("async functions"));
        }
        if let Tok::Ident(w) = self.peek()
            && !Self::is_reserved(w)
            && matches!(self.peek_at(1), Tok::Punct("=>"))
        {
            let name = w.clone();
            self.advance();
            self.advance();
            let params = vec![PatItem { target: Pattern::Ident(name), default: None }];
            return self.arrow_rest(params, None, line);
        }
        if self.is_punct("(") && self.arrow_after_paren(self.pos) {
            self.advance();
            let (params, rest) = self.params()?;
            if self.nl_before() {
                return Err(self.err("syntax error: a new line before `=>`"));
            }
            self.expect_punct("=>")?;
            return self.arrow_rest(params, rest, line);
        }
        let target = self.conditional()?;
        let op = match self.peek() {
            Tok::Punct(p) => assign_punct(p),
            _ => None,
        };
        let Some(op) = op else { return Ok(target) };
        if !is_simple_target(&target) {
            return Err(match target.kind {
                ExprKind::Array(_) | ExprKind::Object(_) => self.unsupported("destructuring assignment"),
                _ => self.err("syntax error: invalid assignment target"),
            });
        }
        self.advance();
        let value = self.assign_expr()?;
        let strict = self.strict;
        Ok(Expr {
            kind: ExprKind::Assign { op, target: Box::new(target), value: Box::new(value), strict },
            line,
        })
    }

    fn async_function_ahead(&mut self) -> bool {
        if self.toks.get(self.pos + 1).is_none_or(|t| t.nl_before) {
            return false;
        }
        match self.peek_at(1) {
            Tok::Ident(w) if &**w == "function" => true,
            Tok::Ident(_) => matches!(self.peek_at(2), Tok::Punct("=>")),
            Tok::Punct("(") => self.arrow_after_paren(self.pos + 1),
            _ => false,
        }
    }

    /// Whether the `(` at `start` closes with `) =>`. Brackets are matched once per parse,
    /// so heavily parenthesised input stays linear.
    fn arrow_after_paren(&mut self, start: usize) -> bool {
        let toks = self.toks;
        let closers = self.closers.get_or_insert_with(|| {
            let mut close = vec![u32::MAX; toks.len()];
            let mut open = Vec::new();
            for (i, t) in toks.iter().enumerate() {
                match t.tok {
                    Tok::Punct("(" | "[" | "{") => open.push(i),
                    Tok::Punct(")" | "]" | "}") => {
                        if let (Some(o), Ok(c)) = (open.pop(), u32::try_from(i)) {
                            close[o] = c;
                        }
                    }
                    _ => {}
                }
            }
            close
        });
        match closers.get(start) {
            Some(&c) if c != u32::MAX => {
                matches!(toks.get(c as usize + 1).map(|t| &t.tok), Some(Tok::Punct("=>")))
            }
            _ => false,
        }
    }

    fn arrow_rest(&mut self, params: Vec<PatItem>, rest: Option<Pattern>, line: usize) -> Result<Expr, PErr> {
        let outer = self.open_function();
        let (body, end_line) = if self.eat_punct("{") {
            let body = self.block_body()?;
            let end = self.toks.get(self.pos.wrapping_sub(1)).map_or(line, |t| t.line);
            (FuncBody::Block(body), end)
        } else {
            let e = self.assign_expr()?;
            let end = e.line;
            (FuncBody::Expr(Box::new(e)), end)
        };
        let def = self.close_function(outer, None, params, rest, body, true, line, end_line);
        Ok(Expr { kind: ExprKind::Function(def), line })
    }

    fn conditional(&mut self) -> Result<Expr, PErr> {
        let test = self.binary(0)?;
        if !self.is_punct("?") {
            return Ok(test);
        }
        let line = self.line();
        self.advance();
        let saved = std::mem::replace(&mut self.no_in, false);
        let yes = self.assign_expr()?;
        self.no_in = saved;
        self.expect_punct(":")?;
        let no = self.assign_expr()?;
        Ok(Expr { kind: ExprKind::Cond(Box::new(test), Box::new(yes), Box::new(no)), line })
    }

    fn binary_op(&self) -> Option<(Op, u8)> {
        match self.peek() {
            Tok::Punct(p) => binary_punct(p),
            Tok::Ident(w) if &**w == "instanceof" => Some((Op::Bin(BinOp::InstanceOf), 8)),
            Tok::Ident(w) if &**w == "in" && !self.no_in => Some((Op::Bin(BinOp::In), 8)),
            _ => None,
        }
    }

    fn binary(&mut self, min_prec: u8) -> Result<Expr, PErr> {
        let mut left = self.unary()?;
        let mut links = 0;
        while let Some((op, prec)) = self.binary_op() {
            if prec < min_prec {
                break;
            }
            let line = self.line();
            self.advance();
            self.enter()?;
            links += 1;
            // `**` is right-associative; the others bind left.
            let right = self.binary(if prec == POW_PRECEDENCE { prec } else { prec + 1 })?;
            let (l, r) = (Box::new(left), Box::new(right));
            let kind = match op {
                Op::Bin(b) => ExprKind::Binary(b, l, r),
                Op::Logic(g) => ExprKind::Logical(g, l, r),
            };
            left = Expr { kind, line };
        }
        self.leave(links);
        Ok(left)
    }

    fn unary(&mut self) -> Result<Expr, PErr> {
        let line = self.line();
        let op = match self.peek() {
            Tok::Punct("!") => Some(UnaryOp::Not),
            Tok::Punct("-") => Some(UnaryOp::Neg),
            Tok::Punct("+") => Some(UnaryOp::Plus),
            Tok::Punct("~") => Some(UnaryOp::BitNot),
            Tok::Ident(w) if &**w == "typeof" => Some(UnaryOp::Typeof),
            Tok::Ident(w) if &**w == "void" => Some(UnaryOp::Void),
            Tok::Ident(w) if &**w == "delete" => return Err(self.unsupported("`delete`")),
            Tok::Ident(w)
                if &**w == "await"
                    && !matches!(self.peek_at(1), Tok::Punct(";" | ")" | "," | "]" | "}" | "=")) =>
            {
                return Err(self.unsupported("`await`"));
            }
            _ => None,
        };
        if let Some(op) = op {
            self.advance();
            self.enter()?;
            let operand = self.unary()?;
            self.leave(1);
            return Ok(Expr { kind: ExprKind::Unary(op, Box::new(operand)), line });
        }
        if self.is_punct("++") || self.is_punct("--") {
            let inc = self.is_punct("++");
            self.advance();
            self.enter()?;
            let target = self.unary()?;
            self.leave(1);
            if !is_simple_target(&target) {
                return Err(self.err("syntax error: invalid `++`/`--` target"));
            }
            return Ok(Expr { kind: ExprKind::Update { inc, prefix: true, target: Box::new(target) }, line });
        }
        let e = self.lhs_expr()?;
        if (self.is_punct("++") || self.is_punct("--")) && !self.nl_before() {
            if !is_simple_target(&e) {
                return Err(self.err("syntax error: invalid `++`/`--` target"));
            }
            let inc = self.is_punct("++");
            self.advance();
            return Ok(Expr { kind: ExprKind::Update { inc, prefix: false, target: Box::new(e) }, line });
        }
        Ok(e)
    }

    /// A call and member chain: `a.b[c](d)?.e`.
    pub(super) fn lhs_expr(&mut self) -> Result<Expr, PErr> {
        let mut e = if self.is_word("new") {
            self.new_expr()?
        } else if self.is_word("super") {
            self.super_expr()?
        } else {
            self.primary()?
        };
        let mut links = 0;
        let mut optional_chain = false;
        loop {
            let line = self.line();
            let obj = Box::new(e);
            let kind = if self.eat_punct(".") {
                ExprKind::Member { obj, prop: self.dot_name()?, optional: false }
            } else if self.eat_punct("?.") {
                optional_chain = true;
                if self.is_punct("(") {
                    ExprKind::Call { callee: obj, args: self.arguments()?, optional: true }
                } else if self.eat_punct("[") {
                    ExprKind::Index { obj, index: Box::new(self.bracket_rest()?), optional: true }
                } else {
                    ExprKind::Member { obj, prop: self.dot_name()?, optional: true }
                }
            } else if self.eat_punct("[") {
                ExprKind::Index { obj, index: Box::new(self.bracket_rest()?), optional: false }
            } else if self.is_punct("(") {
                ExprKind::Call { callee: obj, args: self.arguments()?, optional: false }
            } else if matches!(self.peek(), Tok::Template(_) | Tok::TemplateHead(_)) {
                return Err(self.unsupported("tagged templates"));
            } else {
                e = *obj;
                break;
            };
            e = Expr { kind, line };
            self.enter()?;
            links += 1;
        }
        self.leave(links);
        if optional_chain {
            let line = e.line;
            e = Expr { kind: ExprKind::OptChain(Box::new(e)), line };
        }
        Ok(e)
    }

    fn dot_name(&mut self) -> Result<Name, PErr> {
        match self.peek() {
            Tok::Ident(w) => {
                let w = w.clone();
                self.advance();
                Ok(w)
            }
            Tok::Punct("#") => Err(self.unsupported("private `#` members")),
            _ => Err(self
                .err(format!("syntax error: expected a property name after `.`, found {}", self.describe()))),
        }
    }

    fn bracket_rest(&mut self) -> Result<Expr, PErr> {
        let saved = std::mem::replace(&mut self.no_in, false);
        let e = self.expr()?;
        self.no_in = saved;
        self.expect_punct("]")?;
        Ok(e)
    }

    fn new_expr(&mut self) -> Result<Expr, PErr> {
        let line = self.line();
        self.advance();
        if self.is_punct(".") {
            return Err(self.unsupported("`new.target`"));
        }
        self.enter()?;
        let mut callee = if self.is_word("new") { self.new_expr()? } else { self.primary()? };
        let mut links = 0;
        loop {
            let mline = self.line();
            let obj = Box::new(callee);
            let kind = if self.eat_punct(".") {
                ExprKind::Member { obj, prop: self.dot_name()?, optional: false }
            } else if self.eat_punct("[") {
                ExprKind::Index { obj, index: Box::new(self.bracket_rest()?), optional: false }
            } else if self.is_punct("?.") {
                return Err(self.err("syntax error: optional chaining in a `new` expression"));
            } else {
                callee = *obj;
                break;
            };
            callee = Expr { kind, line: mline };
            self.enter()?;
            links += 1;
        }
        let args = if self.is_punct("(") { self.arguments()? } else { Vec::new() };
        self.leave(links + 1);
        Ok(Expr { kind: ExprKind::New { callee: Box::new(callee), args }, line })
    }

    fn super_expr(&mut self) -> Result<Expr, PErr> {
        let line = self.line();
        self.advance();
        let kind = if self.is_punct("(") {
            ExprKind::SuperCall(self.arguments()?)
        } else if self.eat_punct(".") {
            ExprKind::SuperMember(self.dot_name()?)
        } else {
            return Err(self.unsupported("this use of `super`"));
        };
        Ok(Expr { kind, line })
    }

    /// `(a, ...b)`: the argument list of a call.
    fn arguments(&mut self) -> Result<Vec<Item>, PErr> {
        self.expect_punct("(")?;
        let saved = std::mem::replace(&mut self.no_in, false);
        let mut args = Vec::new();
        while !self.eat_punct(")") {
            if self.eat_punct("...") {
                args.push(Item::Spread(self.assign_expr()?));
            } else {
                args.push(Item::Plain(self.assign_expr()?));
            }
            if !self.eat_punct(",") {
                self.expect_punct(")")?;
                break;
            }
        }
        self.no_in = saved;
        Ok(args)
    }

    fn primary(&mut self) -> Result<Expr, PErr> {
        let line = self.line();
        let kind = match self.peek().clone() {
            Tok::Num(n) => ExprKind::Num(n),
            Tok::Str(s) | Tok::Template(s) => ExprKind::Str(s),
            Tok::TemplateHead(head) => return self.template(head, line),
            Tok::Punct("(") => {
                self.advance();
                let saved = std::mem::replace(&mut self.no_in, false);
                let e = self.expr()?;
                self.no_in = saved;
                self.expect_punct(")")?;
                return Ok(e);
            }
            Tok::Punct("[") => return self.array_literal(line),
            Tok::Punct("{") => return self.object_literal(line),
            Tok::Ident(w) => match &*w {
                "this" => ExprKind::This,
                "null" => ExprKind::Null,
                "true" => ExprKind::Bool(true),
                "false" => ExprKind::Bool(false),
                "function" => {
                    self.advance();
                    if self.is_punct("*") {
                        return Err(self.unsupported("generator functions"));
                    }
                    let name =
                        if matches!(self.peek(), Tok::Ident(_)) { Some(self.binding_ident()?) } else { None };
                    let def = self.function_rest(name, line)?;
                    return Ok(Expr { kind: ExprKind::Function(def), line });
                }
                "class" => {
                    let def = self.class_rest(false)?;
                    return Ok(Expr { kind: ExprKind::Class(def), line });
                }
                "import" => return Err(self.unsupported("dynamic `import`")),
                "arguments" => {
                    self.uses_arguments = true;
                    ExprKind::Ident(w)
                }
                other if Self::is_reserved(other) => return Err(self.unexpected()),
                _ => ExprKind::Ident(w),
            },
            _ => return Err(self.unexpected()),
        };
        self.advance();
        Ok(Expr { kind, line })
    }
}

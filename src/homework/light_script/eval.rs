//! Expressions. Every evaluation costs one step and one level of the evaluator's depth
//! budget, so neither endless loops nor deep trees can run away.

use std::sync::Arc;

use super::ast::{AssignOp, Expr, ExprKind, FuncDef, Item, LogicOp, Name, ObjProp, UnaryOp};
use super::ops::{to_int32, truthy};
use super::value::{Abort, FnCtx, Interp, Key, ObjKind, Prop, ScopeId, Value};

type R<T> = Result<T, Abort>;

/// Where an assignment or `++` writes.
enum Place {
    Var(Name),
    Member(Value, Key),
}

/// A short readable name for an expression in error messages (`this.light.pos`).
pub(super) fn describe(e: &Expr) -> String {
    let mut out = String::new();
    describe_into(e, &mut out, 0);
    if out.chars().count() > 80 {
        out = out.chars().take(77).collect::<String>() + "...";
    }
    out
}

fn describe_into(e: &Expr, out: &mut String, depth: usize) {
    if depth > 8 || out.len() > 80 {
        out.push_str("...");
        return;
    }
    match &e.kind {
        ExprKind::Ident(n) => out.push_str(n),
        ExprKind::This => out.push_str("this"),
        ExprKind::Member { obj, prop, .. } => {
            describe_into(obj, out, depth + 1);
            out.push('.');
            out.push_str(prop);
        }
        ExprKind::Index { obj, .. } => {
            describe_into(obj, out, depth + 1);
            out.push_str("[...]");
        }
        ExprKind::Call { callee, .. } => {
            describe_into(callee, out, depth + 1);
            out.push_str("(...)");
        }
        ExprKind::OptChain(x) => describe_into(x, out, depth + 1),
        ExprKind::SuperMember(n) => {
            out.push_str("super.");
            out.push_str(n);
        }
        _ => out.push_str("expression"),
    }
}

type ExprFn = fn(&mut Interp, &Expr, ScopeId) -> R<Value>;

impl Interp {
    /// Evaluates `e`: one step and one level of the depth budget. The match only picks a
    /// handler, so this frame, which every nesting level repeats, stays small.
    pub(super) fn eval_expr(&mut self, e: &Expr, scope: ScopeId) -> R<Value> {
        self.enter_node(e.line)?;
        let f: ExprFn = match &e.kind {
            ExprKind::Num(_) | ExprKind::Str(_) | ExprKind::Bool(_) | ExprKind::Null | ExprKind::This => {
                Self::x_simple
            }
            ExprKind::Template { .. } => Self::x_template,
            ExprKind::Ident(_) => Self::x_ident,
            ExprKind::Array(_) => Self::x_array,
            ExprKind::Object(_) => Self::x_object,
            ExprKind::Function(_) => Self::x_function,
            ExprKind::Class(_) => Self::x_class,
            ExprKind::Unary(..) => Self::x_unary,
            ExprKind::Update { .. } => Self::x_update,
            ExprKind::Binary(..) => Self::x_binary,
            ExprKind::Logical(..) => Self::x_logical,
            ExprKind::Cond(..) => Self::x_cond,
            ExprKind::Assign { .. } => Self::x_assign,
            ExprKind::Seq(_) => Self::x_seq,
            ExprKind::Member { .. } => Self::x_member,
            ExprKind::Index { .. } => Self::x_index,
            ExprKind::Call { .. } => Self::x_call,
            ExprKind::New { .. } => Self::x_new,
            ExprKind::SuperCall(_) => Self::x_super_call,
            ExprKind::SuperMember(_) => Self::x_super_member,
            ExprKind::OptChain(_) => Self::x_opt_chain,
        };
        let r = f(self, e, scope);
        self.eval_depth -= 1;
        r
    }

    fn x_simple(&mut self, e: &Expr, scope: ScopeId) -> R<Value> {
        Ok(match &e.kind {
            ExprKind::Num(n) => Value::Num(*n),
            ExprKind::Str(s) => Value::Str(s.clone()),
            ExprKind::Bool(b) => Value::Bool(*b),
            ExprKind::This => self.fn_ctx(scope).this,
            _ => Value::Null,
        })
    }

    fn x_ident(&mut self, e: &Expr, scope: ScopeId) -> R<Value> {
        let ExprKind::Ident(name) = &e.kind else { return Ok(Value::Undefined) };
        self.get_var(scope, name, e.line)
    }

    fn x_template(&mut self, e: &Expr, scope: ScopeId) -> R<Value> {
        let ExprKind::Template { quasis, exprs } = &e.kind else { return Ok(Value::Undefined) };
        let mut out = String::new();
        for (i, q) in quasis.iter().enumerate() {
            out.push_str(q);
            if let Some(x) = exprs.get(i) {
                let v = self.eval_expr(x, scope)?;
                let s = self.string_of(&v, e.line)?;
                self.check_string_len(out.len() + s.len(), e.line)?;
                out.push_str(&s);
            }
        }
        self.new_string(out, e.line)
    }

    fn x_array(&mut self, e: &Expr, scope: ScopeId) -> R<Value> {
        let ExprKind::Array(items) = &e.kind else { return Ok(Value::Undefined) };
        let values = self.eval_items(items, scope, e.line)?;
        self.new_array(values, e.line)
    }

    fn x_function(&mut self, e: &Expr, scope: ScopeId) -> R<Value> {
        let ExprKind::Function(def) = &e.kind else { return Ok(Value::Undefined) };
        self.eval_function(def, scope, e.line)
    }

    fn x_class(&mut self, e: &Expr, scope: ScopeId) -> R<Value> {
        let ExprKind::Class(def) = &e.kind else { return Ok(Value::Undefined) };
        self.make_class(def, scope)
    }

    fn x_unary(&mut self, e: &Expr, scope: ScopeId) -> R<Value> {
        let ExprKind::Unary(op, x) = &e.kind else { return Ok(Value::Undefined) };
        self.eval_unary(*op, x, scope, e.line)
    }

    fn x_update(&mut self, e: &Expr, scope: ScopeId) -> R<Value> {
        let ExprKind::Update { inc, prefix, target } = &e.kind else { return Ok(Value::Undefined) };
        let line = e.line;
        let place = self.eval_place(target, scope)?;
        let old = self.read_place(&place, scope, line)?;
        let old = self.number_of(&old, line)?;
        let new = if *inc { old + 1.0 } else { old - 1.0 };
        self.write_place(&place, Value::Num(new), scope, false, line)?;
        Ok(Value::Num(if *prefix { new } else { old }))
    }

    fn x_binary(&mut self, e: &Expr, scope: ScopeId) -> R<Value> {
        let ExprKind::Binary(op, a, b) = &e.kind else { return Ok(Value::Undefined) };
        let a = self.eval_expr(a, scope)?;
        let b = self.eval_expr(b, scope)?;
        self.binary(*op, a, b, e.line)
    }

    fn x_logical(&mut self, e: &Expr, scope: ScopeId) -> R<Value> {
        let ExprKind::Logical(op, a, b) = &e.kind else { return Ok(Value::Undefined) };
        let a = self.eval_expr(a, scope)?;
        if Self::logic_done(*op, &a) { Ok(a) } else { self.eval_expr(b, scope) }
    }

    fn x_cond(&mut self, e: &Expr, scope: ScopeId) -> R<Value> {
        let ExprKind::Cond(t, a, b) = &e.kind else { return Ok(Value::Undefined) };
        let t = self.eval_expr(t, scope)?;
        self.eval_expr(if truthy(&t) { a } else { b }, scope)
    }

    fn x_assign(&mut self, e: &Expr, scope: ScopeId) -> R<Value> {
        let ExprKind::Assign { op, target, value, strict } = &e.kind else { return Ok(Value::Undefined) };
        self.eval_assign(*op, target, value, *strict, scope, e.line)
    }

    fn x_seq(&mut self, e: &Expr, scope: ScopeId) -> R<Value> {
        let ExprKind::Seq(items) = &e.kind else { return Ok(Value::Undefined) };
        let mut last = Value::Undefined;
        for x in items {
            last = self.eval_expr(x, scope)?;
        }
        Ok(last)
    }

    fn x_member(&mut self, e: &Expr, scope: ScopeId) -> R<Value> {
        let ExprKind::Member { obj, prop, optional } = &e.kind else { return Ok(Value::Undefined) };
        let base = self.eval_expr(obj, scope)?;
        if *optional && base.is_nullish() {
            return Err(Abort::Short);
        }
        self.get_member(&base, &Key::Name(prop.clone()), e.line)
    }

    fn x_index(&mut self, e: &Expr, scope: ScopeId) -> R<Value> {
        let ExprKind::Index { obj, index, optional } = &e.kind else { return Ok(Value::Undefined) };
        let base = self.eval_expr(obj, scope)?;
        if *optional && base.is_nullish() {
            return Err(Abort::Short);
        }
        let k = self.eval_expr(index, scope)?;
        let key = self.key_of(&k, e.line)?;
        self.get_member(&base, &key, e.line)
    }

    fn x_call(&mut self, e: &Expr, scope: ScopeId) -> R<Value> {
        let ExprKind::Call { callee, args, optional } = &e.kind else { return Ok(Value::Undefined) };
        let (f, this) = self.eval_callee(callee, *optional, scope)?;
        let args = self.eval_items(args, scope, e.line)?;
        if !self.is_callable(&f) {
            return Err(self.not_a_function(callee, e.line));
        }
        self.call_full(&f, this, args, e.line).map(|(v, _)| v)
    }

    #[cold]
    #[inline(never)]
    fn not_a_function(&mut self, callee: &Expr, line: usize) -> Abort {
        let name = describe(callee);
        self.type_error(line, format!("`{name}` is not a function"))
    }

    fn x_new(&mut self, e: &Expr, scope: ScopeId) -> R<Value> {
        let ExprKind::New { callee, args } = &e.kind else { return Ok(Value::Undefined) };
        let f = self.eval_expr(callee, scope)?;
        let args = self.eval_items(args, scope, e.line)?;
        if !self.is_callable(&f) {
            let name = describe(callee);
            return Err(self.type_error(e.line, format!("`{name}` is not a class")));
        }
        self.construct(&f, args, e.line)
    }

    fn x_super_call(&mut self, e: &Expr, scope: ScopeId) -> R<Value> {
        let ExprKind::SuperCall(args) = &e.kind else { return Ok(Value::Undefined) };
        self.eval_super_call(args, scope, e.line)
    }

    fn x_super_member(&mut self, e: &Expr, scope: ScopeId) -> R<Value> {
        let ExprKind::SuperMember(name) = &e.kind else { return Ok(Value::Undefined) };
        let ctx = self.fn_ctx(scope);
        self.super_member(name, &ctx, e.line)
    }

    fn x_opt_chain(&mut self, e: &Expr, scope: ScopeId) -> R<Value> {
        let ExprKind::OptChain(inner) = &e.kind else { return Ok(Value::Undefined) };
        match self.eval_expr(inner, scope) {
            Err(Abort::Short) => Ok(Value::Undefined),
            r => r,
        }
    }

    fn x_object(&mut self, e: &Expr, scope: ScopeId) -> R<Value> {
        let ExprKind::Object(props) = &e.kind else { return Ok(Value::Undefined) };
        self.eval_object(props, scope, e.line)
    }

    /// Whether `a op b` is decided by `a` alone.
    fn logic_done(op: LogicOp, a: &Value) -> bool {
        match op {
            LogicOp::And => !truthy(a),
            LogicOp::Or => truthy(a),
            LogicOp::Nullish => !a.is_nullish(),
        }
    }

    /// Array literal elements and call arguments, with spread.
    pub(super) fn eval_items(&mut self, items: &[Item], scope: ScopeId, line: usize) -> R<Vec<Value>> {
        let mut out = Vec::with_capacity(items.len());
        for item in items {
            match item {
                Item::Hole => out.push(Value::Undefined),
                Item::Plain(e) => out.push(self.eval_expr(e, scope)?),
                Item::Spread(e) => {
                    let v = self.eval_expr(e, scope)?;
                    let list = self.list_of(&v, e.line)?;
                    self.check_array_len(out.len() + list.len(), line)?;
                    out.extend(list);
                }
            }
        }
        Ok(out)
    }

    #[inline(never)]
    fn eval_object(&mut self, props: &[ObjProp], scope: ScopeId, line: usize) -> R<Value> {
        let id = self.alloc(ObjKind::Plain, None, line)?;
        let obj = Value::Obj(id);
        for p in props {
            match p {
                ObjProp::Value(key, e) => {
                    let k = self.prop_key(key, scope)?;
                    let v = self.eval_expr(e, scope)?;
                    self.set_member(&obj, &k, v, line)?;
                }
                ObjProp::Getter(key, def) | ObjProp::Setter(key, def) => {
                    let k = self.prop_key(key, scope)?.text();
                    let f = self.make_closure(def, scope, None, line)?.obj();
                    let (get, set) = if matches!(p, ObjProp::Getter(..)) { (f, None) } else { (None, f) };
                    self.define_accessor(id, k, get, set);
                }
                ObjProp::Spread(e) => {
                    let v = self.eval_expr(e, scope)?;
                    let Some(src) = v.obj() else { continue };
                    let len = self.array_len(src);
                    let names: Vec<Name> = self.obj(src).props.keys().to_vec();
                    self.charge((len + names.len()) as u64, line)?;
                    for i in 0..len {
                        let x = self.index_value(src, i);
                        self.set_member(&obj, &Key::Index(i), x, line)?;
                    }
                    for n in names {
                        let x = self.get_member(&v, &Key::Name(n.clone()), line)?;
                        self.obj_mut(id).props.insert(n, Prop::Data(x));
                    }
                }
            }
        }
        Ok(obj)
    }

    #[inline(never)]
    fn eval_function(&mut self, def: &Arc<FuncDef>, scope: ScopeId, line: usize) -> R<Value> {
        match &def.name {
            // A named function expression sees its own name.
            Some(name) if !def.arrow => {
                let fs = self.push_scope(scope, None, line)?;
                let f = self.make_closure(def, fs, None, line)?;
                self.declare(fs, name.clone(), f.clone(), false);
                Ok(f)
            }
            _ => self.make_closure(def, scope, None, line),
        }
    }

    #[inline(never)]
    fn eval_unary(&mut self, op: UnaryOp, x: &Expr, scope: ScopeId, line: usize) -> R<Value> {
        if op == UnaryOp::Typeof
            && let ExprKind::Ident(n) = &x.kind
        {
            // `typeof undeclared` is "undefined", not an error.
            let v = self.lookup_var(scope, n).unwrap_or(Value::Undefined);
            return Ok(Value::str(self.typeof_str(&v)));
        }
        let v = self.eval_expr(x, scope)?;
        Ok(match op {
            UnaryOp::Typeof => Value::str(self.typeof_str(&v)),
            UnaryOp::Void => Value::Undefined,
            UnaryOp::Not => Value::Bool(!truthy(&v)),
            UnaryOp::Neg => Value::Num(-self.number_of(&v, line)?),
            UnaryOp::Plus => Value::Num(self.number_of(&v, line)?),
            UnaryOp::BitNot => Value::Num(f64::from(!to_int32(self.number_of(&v, line)?))),
        })
    }

    fn eval_place(&mut self, target: &Expr, scope: ScopeId) -> R<Place> {
        match &target.kind {
            ExprKind::Ident(n) => Ok(Place::Var(n.clone())),
            ExprKind::Member { obj, prop, .. } => {
                let base = self.eval_expr(obj, scope)?;
                Ok(Place::Member(base, Key::Name(prop.clone())))
            }
            ExprKind::Index { obj, index, .. } => {
                let base = self.eval_expr(obj, scope)?;
                let k = self.eval_expr(index, scope)?;
                let key = self.key_of(&k, target.line)?;
                Ok(Place::Member(base, key))
            }
            _ => Err(self.type_error(target.line, "invalid assignment target".into())),
        }
    }

    fn read_place(&mut self, place: &Place, scope: ScopeId, line: usize) -> R<Value> {
        match place {
            Place::Var(n) => self.get_var(scope, n, line),
            Place::Member(base, key) => self.get_member(base, key, line),
        }
    }

    fn write_place(&mut self, place: &Place, v: Value, scope: ScopeId, strict: bool, line: usize) -> R<()> {
        match place {
            Place::Var(n) => self.assign_var(scope, n, v, strict, line),
            Place::Member(base, key) => self.set_member(base, key, v, line),
        }
    }

    #[inline(never)]
    fn eval_assign(
        &mut self,
        op: AssignOp,
        target: &Expr,
        value: &Expr,
        strict: bool,
        scope: ScopeId,
        line: usize,
    ) -> R<Value> {
        let place = self.eval_place(target, scope)?;
        let v = match op {
            AssignOp::Assign => self.eval_expr(value, scope)?,
            AssignOp::Op(b) => {
                let old = self.read_place(&place, scope, line)?;
                let rhs = self.eval_expr(value, scope)?;
                self.binary(b, old, rhs, line)?
            }
            AssignOp::Logic(l) => {
                let old = self.read_place(&place, scope, line)?;
                if Self::logic_done(l, &old) {
                    return Ok(old);
                }
                self.eval_expr(value, scope)?
            }
        };
        self.write_place(&place, v.clone(), scope, strict, line)?;
        Ok(v)
    }

    /// The function a call calls and its `this`.
    fn eval_callee(&mut self, callee: &Expr, optional: bool, scope: ScopeId) -> R<(Value, Value)> {
        let (f, this) = match &callee.kind {
            ExprKind::Member { obj, prop, optional: o } => {
                let base = self.eval_expr(obj, scope)?;
                if *o && base.is_nullish() {
                    return Err(Abort::Short);
                }
                (self.get_member(&base, &Key::Name(prop.clone()), callee.line)?, base)
            }
            ExprKind::Index { obj, index, optional: o } => {
                let base = self.eval_expr(obj, scope)?;
                if *o && base.is_nullish() {
                    return Err(Abort::Short);
                }
                let k = self.eval_expr(index, scope)?;
                let key = self.key_of(&k, callee.line)?;
                (self.get_member(&base, &key, callee.line)?, base)
            }
            ExprKind::SuperMember(name) => {
                let ctx = self.fn_ctx(scope);
                (self.super_member(name, &ctx, callee.line)?, ctx.this)
            }
            _ => (self.eval_expr(callee, scope)?, Value::Undefined),
        };
        if optional && f.is_nullish() {
            return Err(Abort::Short);
        }
        Ok((f, this))
    }

    #[inline(never)]
    fn eval_super_call(&mut self, args: &[Item], scope: ScopeId, line: usize) -> R<Value> {
        let ctx = self.fn_ctx(scope);
        let parent = ctx.home.and_then(|h| self.class_data(h)).and_then(|d| d.parent);
        let (Some(home), Some(parent), Some(obj)) = (ctx.home, parent, ctx.this.obj()) else {
            return Err(self.type_error(
                line,
                "`super(...)` outside the constructor of a class that extends another".into(),
            ));
        };
        let args = self.eval_items(args, scope, line)?;
        self.init_parent(parent, obj, args, line)?;
        self.init_fields(home, obj, line)?;
        Ok(Value::Undefined)
    }

    fn super_member(&mut self, name: &Name, ctx: &FnCtx, line: usize) -> R<Value> {
        let Some(home) = ctx.home else {
            return Err(self.type_error(line, "`super` outside a class method".into()));
        };
        let Some(parent) = self.class_data(home).and_then(|d| d.parent) else { return Ok(Value::Undefined) };
        let key = Key::Name(name.clone());
        if ctx.this == Value::Obj(home) {
            return self.get_member(&Value::Obj(parent), &key, line);
        }
        let proto = self.get_member(&Value::Obj(parent), &Key::name("prototype"), line)?;
        if proto.obj().is_none() {
            return Ok(Value::Undefined);
        }
        self.get_member(&proto, &key, line)
    }
}

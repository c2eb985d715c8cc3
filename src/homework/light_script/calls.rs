//! Calling and constructing: closures, natives, classes (with `extends` and `super`),
//! and making function and class values.

use std::sync::Arc;

use super::ast::{ClassDef, FuncBody, FuncDef, MemberKind, PropKey};
use super::value::{
    Abort, ClassData, Closure, Flow, FnCtx, Interp, Key, NativeCall, ObjId, ObjKind, ScopeId, Value,
};

type R<T> = Result<T, Abort>;

/// How a pattern binds its names.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum BindMode {
    Let,
    Const,
    /// `var` (already hoisted) and plain assignment: update the existing binding.
    Assign {
        strict: bool,
    },
}

impl Interp {
    pub(super) fn call(&mut self, f: &Value, this: Value, args: Vec<Value>, line: usize) -> R<Value> {
        self.call_full(f, this, args, line).map(|(v, _)| v)
    }

    /// Calls `f`; also returns the line of the `return` that produced the value.
    pub(super) fn call_full(
        &mut self,
        f: &Value,
        this: Value,
        args: Vec<Value>,
        line: usize,
    ) -> R<(Value, usize)> {
        let closure = match f.obj().map(|id| &self.obj(id).kind) {
            Some(ObjKind::Closure(c)) => Some(c.clone()),
            _ => None,
        };
        match closure {
            Some(c) => self.call_closure(&c, this, args, line),
            None => self.call_other(f, this, args, line),
        }
    }

    #[inline(never)]
    fn call_other(&mut self, f: &Value, this: Value, args: Vec<Value>, line: usize) -> R<(Value, usize)> {
        let Some(id) = f.obj() else {
            return Err(self.type_error(line, "calling a value that is not a function".into()));
        };
        match &self.obj(id).kind {
            ObjKind::Native { name, f } => {
                let (name, f) = (*name, *f);
                self.enter_call(line)?;
                let r = f(self, &NativeCall { this: &this, args: &args, line, is_new: false, name });
                self.call_depth -= 1;
                r.map(|v| (v, line))
            }
            ObjKind::Inert => Ok((Value::Obj(self.sink), line)),
            ObjKind::Class(c) => {
                let name = c.def.name.clone().unwrap_or_else(|| Arc::from("anonymous"));
                Err(self.type_error(line, format!("class `{name}` cannot be called without `new`")))
            }
            _ => Err(self.type_error(line, "calling a value that is not a function".into())),
        }
    }

    pub(super) fn call_closure(
        &mut self,
        c: &Closure,
        this: Value,
        args: Vec<Value>,
        line: usize,
    ) -> R<(Value, usize)> {
        self.enter_call(line)?;
        let ctx = if c.def.arrow { None } else { Some(FnCtx { this, home: c.home }) };
        let r = match self.push_scope(c.scope, ctx, line) {
            Ok(fs) => {
                let r = self.run_function(&c.def, fs, args);
                self.pop_scope(fs);
                r
            }
            Err(e) => Err(e),
        };
        self.call_depth -= 1;
        r
    }

    fn run_function(&mut self, def: &FuncDef, fs: ScopeId, args: Vec<Value>) -> R<(Value, usize)> {
        self.bind_args(def, fs, args)?;
        match &def.body {
            FuncBody::Expr(e) => Ok((self.eval_expr(e, fs)?, e.line)),
            FuncBody::Block(stmts) => match self.exec_stmts(stmts, fs)? {
                Flow::Return(v, line) => Ok((v, line)),
                _ => Ok((Value::Undefined, def.end_line)),
            },
        }
    }

    /// Parameters (with defaults and rest), `arguments`, and hoisted `var`s.
    #[inline(never)]
    fn bind_args(&mut self, def: &FuncDef, fs: ScopeId, args: Vec<Value>) -> R<()> {
        if def.uses_arguments && !def.arrow {
            let arguments = self.new_array(args.clone(), def.line)?;
            self.declare(fs, Arc::from("arguments"), arguments, true);
        }
        for (i, p) in def.params.iter().enumerate() {
            let mut v = args.get(i).cloned().unwrap_or(Value::Undefined);
            if let (Value::Undefined, Some(d)) = (&v, &p.default) {
                v = self.eval_expr(d, fs)?;
            }
            self.bind_pattern(&p.target, v, fs, BindMode::Let, def.line)?;
        }
        if let Some(rest) = &def.rest {
            let extra = args.get(def.params.len()..).unwrap_or(&[]).to_vec();
            let arr = self.new_array(extra, def.line)?;
            self.bind_pattern(rest, arr, fs, BindMode::Let, def.line)?;
        }
        for name in &def.var_names {
            if !self.has_own_var(fs, name) {
                self.declare(fs, name.clone(), Value::Undefined, true);
            }
        }
        Ok(())
    }

    pub(super) fn construct(&mut self, f: &Value, args: Vec<Value>, line: usize) -> R<Value> {
        let Some(id) = f.obj() else {
            return Err(self.type_error(line, "`new` on a value that is not a class".into()));
        };
        match &self.obj(id).kind {
            ObjKind::Class(_) => {
                let proto = self.get_member(f, &Key::name("prototype"), line)?.obj();
                let obj = self.alloc(ObjKind::Plain, proto, line)?;
                self.enter_call(line)?;
                let r = self.init_instance(id, obj, args, line);
                self.call_depth -= 1;
                r
            }
            ObjKind::Closure(c) if !c.def.arrow => {
                let c = c.clone();
                let proto = self.get_member(f, &Key::name("prototype"), line)?.obj();
                let obj = self.alloc(ObjKind::Plain, proto, line)?;
                let (r, _) = self.call_closure(&c, Value::Obj(obj), args, line)?;
                Ok(if r.obj().is_some() { r } else { Value::Obj(obj) })
            }
            ObjKind::Native { name, f } => {
                let (name, f) = (*name, *f);
                self.enter_call(line)?;
                let r =
                    f(self, &NativeCall { this: &Value::Undefined, args: &args, line, is_new: true, name });
                self.call_depth -= 1;
                r
            }
            ObjKind::Inert => Ok(Value::Obj(self.alloc(ObjKind::Inert, None, line)?)),
            _ => Err(self.type_error(line, "`new` on a value that is not a class".into())),
        }
    }

    pub(super) fn class_data(&self, class: ObjId) -> Option<ClassData> {
        match &self.obj(class).kind {
            ObjKind::Class(d) => Some(d.clone()),
            _ => None,
        }
    }

    /// Runs a class's constructor (or its parent's, when it has none) on `obj`.
    fn init_instance(&mut self, class: ObjId, obj: ObjId, args: Vec<Value>, line: usize) -> R<Value> {
        let Some(data) = self.class_data(class) else { return Ok(Value::Obj(obj)) };
        let ctor = data.ctor.and_then(|c| match &self.obj(c).kind {
            ObjKind::Closure(cl) => Some(cl.clone()),
            _ => None,
        });
        match ctor {
            Some(c) => {
                // A derived class initialises its fields when `super(...)` returns.
                if data.parent.is_none() {
                    self.init_fields(class, obj, line)?;
                }
                let (r, _) = self.call_closure(&c, Value::Obj(obj), args, line)?;
                Ok(if r.obj().is_some() { r } else { Value::Obj(obj) })
            }
            None => {
                if let Some(p) = data.parent {
                    self.init_parent(p, obj, args, line)?;
                }
                self.init_fields(class, obj, line)?;
                Ok(Value::Obj(obj))
            }
        }
    }

    /// `super(...)`: the parent's constructor on the same object.
    pub(super) fn init_parent(&mut self, parent: ObjId, obj: ObjId, args: Vec<Value>, line: usize) -> R<()> {
        match &self.obj(parent).kind {
            ObjKind::Class(_) => {
                self.enter_call(line)?;
                let r = self.init_instance(parent, obj, args, line);
                self.call_depth -= 1;
                r?;
            }
            ObjKind::Closure(c) => {
                let c = c.clone();
                self.call_closure(&c, Value::Obj(obj), args, line)?;
            }
            ObjKind::Native { name, f } => {
                let (name, f) = (*name, *f);
                self.enter_call(line)?;
                let r =
                    f(self, &NativeCall { this: &Value::Obj(obj), args: &args, line, is_new: true, name });
                self.call_depth -= 1;
                r?;
            }
            _ => {}
        }
        Ok(())
    }

    pub(super) fn init_fields(&mut self, class: ObjId, obj: ObjId, line: usize) -> R<()> {
        let Some(data) = self.class_data(class) else { return Ok(()) };
        for m in &data.def.members {
            let (false, MemberKind::Field(init)) = (m.is_static, &m.kind) else { continue };
            let ctx = FnCtx { this: Value::Obj(obj), home: Some(class) };
            let fs = self.push_scope(data.scope, Some(ctx), line)?;
            let r = self.field_value(&m.key, init.as_ref(), fs);
            self.pop_scope(fs);
            let (key, value) = r?;
            self.set_member(&Value::Obj(obj), &key, value, m.line)?;
        }
        Ok(())
    }

    fn field_value(
        &mut self,
        key: &PropKey,
        init: Option<&super::ast::Expr>,
        fs: ScopeId,
    ) -> R<(Key, Value)> {
        let key = self.prop_key(key, fs)?;
        let value = match init {
            Some(e) => self.eval_expr(e, fs)?,
            None => Value::Undefined,
        };
        Ok((key, value))
    }

    pub(super) fn prop_key(&mut self, key: &PropKey, scope: ScopeId) -> R<Key> {
        match key {
            PropKey::Name(n) => Ok(Key::Name(n.clone())),
            PropKey::Computed(e) => {
                let v = self.eval_expr(e, scope)?;
                self.key_of(&v, e.line)
            }
        }
    }

    pub(super) fn make_closure(
        &mut self,
        def: &Arc<FuncDef>,
        scope: ScopeId,
        home: Option<ObjId>,
        line: usize,
    ) -> R<Value> {
        self.mark_captured(scope);
        let c = Closure { def: def.clone(), scope, home };
        Ok(Value::Obj(self.alloc(ObjKind::Closure(c), None, line)?))
    }

    pub(super) fn make_class(&mut self, def: &Arc<ClassDef>, scope: ScopeId) -> R<Value> {
        let line = def.line;
        let parent = match &def.parent {
            None => None,
            Some(e) => {
                let v = self.eval_expr(e, scope)?;
                match v.obj() {
                    Some(id) if self.is_callable(&v) => Some(id),
                    _ => {
                        let name = def.name.as_deref().unwrap_or("anonymous");
                        return Err(self.type_error(
                            line,
                            format!("class `{name}` extends a value that is not a class"),
                        ));
                    }
                }
            }
        };
        let cs = self.push_scope(scope, None, line)?;
        self.mark_captured(cs);
        let parent_proto = match parent {
            Some(p) => self.get_member(&Value::Obj(p), &Key::name("prototype"), line)?.obj(),
            None => None,
        };
        let proto = self.alloc(ObjKind::Plain, parent_proto, line)?;
        let data = ClassData { def: def.clone(), scope: cs, parent, ctor: None };
        let class = self.alloc(ObjKind::Class(data), parent, line)?;
        self.set_own(class, "prototype", Value::Obj(proto));
        self.set_own(proto, "constructor", Value::Obj(class));
        if let Some(c) = &def.ctor {
            let f = self.make_closure(c, cs, Some(class), line)?.obj();
            if let ObjKind::Class(d) = &mut self.obj_mut(class).kind {
                d.ctor = f;
            }
        }
        if let Some(n) = &def.name {
            self.declare(cs, n.clone(), Value::Obj(class), false);
        }
        for m in &def.members {
            let target = if m.is_static { class } else { proto };
            let key = self.prop_key(&m.key, cs)?.text();
            match &m.kind {
                MemberKind::Method(f) => {
                    let v = self.make_closure(f, cs, Some(class), m.line)?;
                    self.set_own(target, &key, v);
                }
                MemberKind::Getter(f) | MemberKind::Setter(f) => {
                    let v = self.make_closure(f, cs, Some(class), m.line)?.obj();
                    let getter = matches!(m.kind, MemberKind::Getter(_));
                    let (get, set) = if getter { (v, None) } else { (None, v) };
                    self.define_accessor(target, key, get, set);
                }
                MemberKind::Field(Some(init)) if m.is_static => {
                    let ctx = FnCtx { this: Value::Obj(class), home: Some(class) };
                    let fs = self.push_scope(cs, Some(ctx), m.line)?;
                    let v = self.eval_expr(init, fs);
                    self.pop_scope(fs);
                    self.set_own(class, &key, v?);
                }
                MemberKind::Field(_) => {}
            }
        }
        Ok(Value::Obj(class))
    }
}

//! Statements: blocks with hoisted function declarations, loops (with a fresh `let`
//! binding per iteration when a closure captured it), `try`, `switch`, and patterns.

use super::ast::{Case, DeclKind, Expr, Pattern, Stmt, StmtKind};
use super::calls::BindMode;
use super::ops::{strict_eq, truthy};
use super::value::{Abort, Flow, Interp, Key, ObjKind, Prop, ScopeId, Value};

type R<T> = Result<T, Abort>;
type StmtFn = fn(&mut Interp, &Stmt, ScopeId) -> R<Flow>;

fn needs_scope(stmts: &[Stmt]) -> bool {
    stmts.iter().any(|s| {
        matches!(
            s.kind,
            StmtKind::Decl(DeclKind::Let | DeclKind::Const, _) | StmtKind::Function(_) | StmtKind::Class(_)
        )
    })
}

fn decl_mode(decl: Option<DeclKind>, strict: bool) -> BindMode {
    match decl {
        Some(DeclKind::Let) => BindMode::Let,
        Some(DeclKind::Const) => BindMode::Const,
        Some(DeclKind::Var) => BindMode::Assign { strict: false },
        None => BindMode::Assign { strict },
    }
}

impl Interp {
    /// Runs statements in `scope`, function declarations first (they are hoisted).
    pub(super) fn exec_stmts(&mut self, stmts: &[Stmt], scope: ScopeId) -> R<Flow> {
        // The hoisting scan is work too: a huge block re-entered in a loop must cost steps.
        self.charge((stmts.len() / 8) as u64, stmts.first().map_or(0, |s| s.line))?;
        for s in stmts {
            if let StmtKind::Function(def) = &s.kind {
                let f = self.make_closure(def, scope, None, s.line)?;
                if let Some(n) = &def.name {
                    self.declare(scope, n.clone(), f, true);
                }
            }
        }
        for s in stmts {
            match self.exec_stmt(s, scope)? {
                Flow::Normal => {}
                other => return Ok(other),
            }
        }
        Ok(Flow::Normal)
    }

    #[inline(never)]
    fn exec_block(&mut self, stmts: &[Stmt], scope: ScopeId, line: usize) -> R<Flow> {
        if !needs_scope(stmts) {
            return self.exec_stmts(stmts, scope);
        }
        let bs = self.push_scope(scope, None, line)?;
        let r = self.exec_stmts(stmts, bs);
        self.pop_scope(bs);
        r
    }

    /// Runs one statement: a step and a level of depth; the match only picks a handler,
    /// keeping the frame every nesting level repeats small.
    pub(super) fn exec_stmt(&mut self, s: &Stmt, scope: ScopeId) -> R<Flow> {
        self.enter_node(s.line)?;
        let f: StmtFn = match &s.kind {
            StmtKind::Expr(_) => Self::s_expr,
            StmtKind::Decl(..) => Self::s_decl,
            StmtKind::Function(_) | StmtKind::Empty => Self::s_empty,
            StmtKind::Class(_) => Self::s_class,
            StmtKind::Return(_) => Self::s_return,
            StmtKind::If(..) => Self::s_if,
            StmtKind::Block(_) => Self::s_block,
            StmtKind::For { .. } => Self::s_for,
            StmtKind::ForEach { .. } => Self::s_for_each,
            StmtKind::While(..) => Self::s_while,
            StmtKind::DoWhile(..) => Self::s_do_while,
            StmtKind::Break => Self::s_break,
            StmtKind::Continue => Self::s_continue,
            StmtKind::Throw(_) => Self::s_throw,
            StmtKind::Try { .. } => Self::s_try,
            StmtKind::Switch(..) => Self::s_switch,
        };
        let r = f(self, s, scope);
        self.eval_depth -= 1;
        r
    }

    fn s_empty(&mut self, _: &Stmt, _: ScopeId) -> R<Flow> {
        Ok(Flow::Normal)
    }

    fn s_break(&mut self, _: &Stmt, _: ScopeId) -> R<Flow> {
        Ok(Flow::Break)
    }

    fn s_continue(&mut self, _: &Stmt, _: ScopeId) -> R<Flow> {
        Ok(Flow::Continue)
    }

    fn s_expr(&mut self, s: &Stmt, scope: ScopeId) -> R<Flow> {
        let StmtKind::Expr(e) = &s.kind else { return Ok(Flow::Normal) };
        self.eval_expr(e, scope)?;
        Ok(Flow::Normal)
    }

    fn s_decl(&mut self, s: &Stmt, scope: ScopeId) -> R<Flow> {
        let StmtKind::Decl(kind, decls) = &s.kind else { return Ok(Flow::Normal) };
        for (pattern, init) in decls {
            let v = match init {
                Some(e) => self.eval_expr(e, scope)?,
                // `var x;` keeps x's value; `let x;` makes it undefined.
                None if *kind == DeclKind::Var => continue,
                None => Value::Undefined,
            };
            self.bind_pattern(pattern, v, scope, decl_mode(Some(*kind), false), s.line)?;
        }
        Ok(Flow::Normal)
    }

    fn s_class(&mut self, s: &Stmt, scope: ScopeId) -> R<Flow> {
        let StmtKind::Class(def) = &s.kind else { return Ok(Flow::Normal) };
        let v = self.make_class(def, scope)?;
        if let Some(n) = &def.name {
            self.declare(scope, n.clone(), v, true);
        }
        Ok(Flow::Normal)
    }

    fn s_return(&mut self, s: &Stmt, scope: ScopeId) -> R<Flow> {
        let v = match &s.kind {
            StmtKind::Return(Some(e)) => self.eval_expr(e, scope)?,
            _ => Value::Undefined,
        };
        Ok(Flow::Return(v, s.line))
    }

    fn s_if(&mut self, s: &Stmt, scope: ScopeId) -> R<Flow> {
        let StmtKind::If(test, then, other) = &s.kind else { return Ok(Flow::Normal) };
        let t = self.eval_expr(test, scope)?;
        match (truthy(&t), other) {
            (true, _) => self.exec_stmt(then, scope),
            (false, Some(o)) => self.exec_stmt(o, scope),
            (false, None) => Ok(Flow::Normal),
        }
    }

    fn s_block(&mut self, s: &Stmt, scope: ScopeId) -> R<Flow> {
        let StmtKind::Block(stmts) = &s.kind else { return Ok(Flow::Normal) };
        self.exec_block(stmts, scope, s.line)
    }

    fn s_for(&mut self, s: &Stmt, scope: ScopeId) -> R<Flow> {
        let StmtKind::For { init, test, update, body } = &s.kind else { return Ok(Flow::Normal) };
        let (init, test, update) = (init.as_deref(), test.as_ref(), update.as_ref());
        let lexical =
            matches!(init.map(|i| &i.kind), Some(StmtKind::Decl(DeclKind::Let | DeclKind::Const, _)));
        if !lexical {
            let mut ls = scope;
            return self.for_loop(init, test, update, body, scope, &mut ls, false);
        }
        let mut ls = self.push_scope(scope, None, s.line)?;
        let r = self.for_loop(init, test, update, body, scope, &mut ls, true);
        self.pop_scope(ls);
        r
    }

    fn s_for_each(&mut self, s: &Stmt, scope: ScopeId) -> R<Flow> {
        let StmtKind::ForEach { decl, target, iter, body, is_in } = &s.kind else { return Ok(Flow::Normal) };
        self.for_each(*decl, target, iter, body, *is_in, scope, s.line)
    }

    fn s_while(&mut self, s: &Stmt, scope: ScopeId) -> R<Flow> {
        let StmtKind::While(test, body) = &s.kind else { return Ok(Flow::Normal) };
        loop {
            let t = self.eval_expr(test, scope)?;
            if !truthy(&t) {
                break;
            }
            match self.exec_stmt(body, scope)? {
                Flow::Break => break,
                Flow::Return(v, l) => return Ok(Flow::Return(v, l)),
                _ => {}
            }
        }
        Ok(Flow::Normal)
    }

    fn s_do_while(&mut self, s: &Stmt, scope: ScopeId) -> R<Flow> {
        let StmtKind::DoWhile(body, test) = &s.kind else { return Ok(Flow::Normal) };
        loop {
            match self.exec_stmt(body, scope)? {
                Flow::Break => break,
                Flow::Return(v, l) => return Ok(Flow::Return(v, l)),
                _ => {}
            }
            let t = self.eval_expr(test, scope)?;
            if !truthy(&t) {
                break;
            }
        }
        Ok(Flow::Normal)
    }

    fn s_throw(&mut self, s: &Stmt, scope: ScopeId) -> R<Flow> {
        let StmtKind::Throw(e) = &s.kind else { return Ok(Flow::Normal) };
        let value = self.eval_expr(e, scope)?;
        Err(Abort::Throw(Box::new((value, s.line))))
    }

    fn s_try(&mut self, s: &Stmt, scope: ScopeId) -> R<Flow> {
        let StmtKind::Try { body, param, handler, finally } = &s.kind else { return Ok(Flow::Normal) };
        self.exec_try(body, param.as_ref(), handler.as_deref(), finally.as_deref(), scope, s.line)
    }

    fn s_switch(&mut self, s: &Stmt, scope: ScopeId) -> R<Flow> {
        let StmtKind::Switch(subject, cases) = &s.kind else { return Ok(Flow::Normal) };
        let v = self.eval_expr(subject, scope)?;
        let ss = self.push_scope(scope, None, s.line)?;
        let r = self.switch_body(&v, cases, ss);
        self.pop_scope(ss);
        r
    }

    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    fn for_loop(
        &mut self,
        init: Option<&Stmt>,
        test: Option<&Expr>,
        update: Option<&Expr>,
        body: &Stmt,
        outer: ScopeId,
        ls: &mut ScopeId,
        lexical: bool,
    ) -> R<Flow> {
        if let Some(i) = init {
            self.exec_stmt(i, *ls)?;
        }
        loop {
            if let Some(t) = test {
                let v = self.eval_expr(t, *ls)?;
                if !truthy(&v) {
                    break;
                }
            }
            match self.exec_stmt(body, *ls)? {
                Flow::Break => break,
                Flow::Return(v, l) => return Ok(Flow::Return(v, l)),
                _ => {}
            }
            if lexical && self.scopes[ls.0].captured {
                // Closures made in this iteration keep its bindings; the next one gets a copy.
                let vars = self.scopes[ls.0].vars.clone();
                self.charge(vars.len() as u64, body.line)?;
                let copy = self.push_scope(outer, None, body.line)?;
                self.scopes[copy.0].vars = vars;
                *ls = copy;
            }
            if let Some(u) = update {
                self.eval_expr(u, *ls)?;
            }
        }
        Ok(Flow::Normal)
    }

    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    fn for_each(
        &mut self,
        decl: Option<DeclKind>,
        target: &Pattern,
        iter: &Expr,
        body: &Stmt,
        is_in: bool,
        scope: ScopeId,
        line: usize,
    ) -> R<Flow> {
        let subject = self.eval_expr(iter, scope)?;
        // `for in` walks a snapshot of the keys; `for of` reads elements live, as JS does.
        let keys: Option<Vec<Value>> = if is_in { Some(self.own_keys(&subject, line)?) } else { None };
        let chars: Option<Vec<Value>> = match (&subject, &keys) {
            (Value::Str(s), None) => {
                self.charge((s.len() / 16) as u64, line)?;
                Some(s.chars().map(|c| Value::str(c.encode_utf8(&mut [0; 4]))).collect())
            }
            _ => None,
        };
        let array =
            subject.obj().filter(|id| matches!(self.obj(*id).kind, ObjKind::Array(_) | ObjKind::F32(_)));
        if keys.is_none() && chars.is_none() && array.is_none() {
            return Err(self.type_error(line, "`for ... of` over a value that is not an array".into()));
        }
        let strict = false;
        let mut i = 0;
        loop {
            let item = match (&keys, &chars, array) {
                (Some(k), _, _) | (None, Some(k), _) => k.get(i).cloned(),
                (None, None, Some(id)) => (i < self.array_len(id)).then(|| self.index_value(id, i)),
                _ => None,
            };
            let Some(item) = item else { break };
            i += 1;
            let lexical = matches!(decl, Some(DeclKind::Let | DeclKind::Const));
            let is = if lexical { self.push_scope(scope, None, line)? } else { scope };
            let r = match self.bind_pattern(target, item, is, decl_mode(decl, strict), line) {
                Ok(()) => self.exec_stmt(body, is),
                Err(e) => Err(e),
            };
            if lexical {
                self.pop_scope(is);
            }
            match r? {
                Flow::Break => break,
                Flow::Return(v, l) => return Ok(Flow::Return(v, l)),
                _ => {}
            }
        }
        Ok(Flow::Normal)
    }

    /// The keys `for (k in v)` visits: indices, then own enumerable property names.
    fn own_keys(&mut self, v: &Value, line: usize) -> R<Vec<Value>> {
        let Some(id) = v.obj() else {
            if let Value::Str(s) = v {
                return Ok((0..s.chars().count()).map(|i| Value::str(&i.to_string())).collect());
            }
            return Ok(Vec::new());
        };
        let len = self.array_len(id);
        self.charge((len + self.obj(id).props.len()) as u64, line)?;
        let mut keys: Vec<Value> = (0..len).map(|i| Value::str(&i.to_string())).collect();
        keys.extend(self.obj(id).props.keys().iter().map(|k| Value::Str(k.clone())));
        Ok(keys)
    }

    #[inline(never)]
    fn exec_try(
        &mut self,
        body: &[Stmt],
        param: Option<&Pattern>,
        handler: Option<&[Stmt]>,
        finally: Option<&[Stmt]>,
        scope: ScopeId,
        line: usize,
    ) -> R<Flow> {
        let mut result = self.exec_block(body, scope, line);
        if let (Err(Abort::Throw(thrown)), Some(h)) = (&result, handler) {
            let value = thrown.0.clone();
            let cs = self.push_scope(scope, None, line)?;
            result = match param {
                Some(p) => self
                    .bind_pattern(p, value, cs, BindMode::Let, line)
                    .and_then(|()| self.exec_block(h, cs, line)),
                None => self.exec_block(h, cs, line),
            };
            self.pop_scope(cs);
        }
        if let Some(f) = finally {
            // Limits are final: no more script code runs after one is hit.
            if matches!(result, Err(Abort::Fatal(_))) {
                return result;
            }
            match self.exec_block(f, scope, line)? {
                Flow::Normal => {}
                other => return Ok(other),
            }
        }
        result
    }

    fn switch_body(&mut self, v: &Value, cases: &[Case], ss: ScopeId) -> R<Flow> {
        let mut start = None;
        for (i, c) in cases.iter().enumerate() {
            if let Some(t) = &c.test {
                let tv = self.eval_expr(t, ss)?;
                if strict_eq(v, &tv) {
                    start = Some(i);
                    break;
                }
            }
        }
        let Some(start) = start.or_else(|| cases.iter().position(|c| c.test.is_none())) else {
            return Ok(Flow::Normal);
        };
        for c in cases.get(start..).unwrap_or(&[]) {
            match self.exec_stmts(&c.body, ss)? {
                Flow::Normal => {}
                Flow::Break => return Ok(Flow::Normal),
                other => return Ok(other),
            }
        }
        Ok(Flow::Normal)
    }

    /// Arrays, Float32Arrays and strings as a list (spread and array patterns).
    pub(super) fn list_of(&mut self, v: &Value, line: usize) -> R<Vec<Value>> {
        match v {
            Value::Str(s) => {
                self.charge((s.len() / 16) as u64, line)?;
                Ok(s.chars().map(|c| Value::str(c.encode_utf8(&mut [0; 4]))).collect())
            }
            Value::Obj(id) if matches!(self.obj(*id).kind, ObjKind::Array(_) | ObjKind::F32(_)) => {
                let len = self.array_len(*id);
                self.charge(len as u64, line)?;
                Ok((0..len).map(|i| self.index_value(*id, i)).collect())
            }
            _ => Err(self.type_error(line, "spreading or destructuring a value that is not an array".into())),
        }
    }

    pub(super) fn bind_pattern(
        &mut self,
        p: &Pattern,
        v: Value,
        scope: ScopeId,
        mode: BindMode,
        line: usize,
    ) -> R<()> {
        match p {
            Pattern::Ident(name) => match mode {
                BindMode::Let | BindMode::Const if !self.has_own_var(scope, name) => {
                    self.charge_memory(name.len() + 64, line)?;
                    self.declare(scope, name.clone(), v, mode == BindMode::Let);
                    Ok(())
                }
                BindMode::Let => {
                    self.declare(scope, name.clone(), v, true);
                    Ok(())
                }
                BindMode::Const => {
                    self.declare(scope, name.clone(), v, false);
                    Ok(())
                }
                BindMode::Assign { strict } => self.assign_var(scope, name, v, strict, line),
            },
            Pattern::Array { items, rest } => {
                let list = self.list_of(&v, line)?;
                for (i, item) in items.iter().enumerate() {
                    let Some(item) = item else { continue };
                    let mut x = list.get(i).cloned().unwrap_or(Value::Undefined);
                    if let (Value::Undefined, Some(d)) = (&x, &item.default) {
                        x = self.eval_expr(d, scope)?;
                    }
                    self.bind_pattern(&item.target, x, scope, mode, line)?;
                }
                if let Some(r) = rest {
                    let tail = list.get(items.len()..).unwrap_or(&[]).to_vec();
                    let arr = self.new_array(tail, line)?;
                    self.bind_pattern(r, arr, scope, mode, line)?;
                }
                Ok(())
            }
            Pattern::Object { props, rest } => {
                if v.is_nullish() {
                    return Err(self.type_error(
                        line,
                        format!("cannot destructure {}", if v == Value::Null { "null" } else { "undefined" }),
                    ));
                }
                let mut used = Vec::new();
                for (key, item) in props {
                    let k = self.prop_key(key, scope)?;
                    used.push(k.text());
                    let mut x = self.get_member(&v, &k, line)?;
                    if let (Value::Undefined, Some(d)) = (&x, &item.default) {
                        x = self.eval_expr(d, scope)?;
                    }
                    self.bind_pattern(&item.target, x, scope, mode, line)?;
                }
                if let Some(r) = rest {
                    let obj = self.alloc(ObjKind::Plain, None, line)?;
                    if let Some(src) = v.obj() {
                        let pairs: Vec<_> = self
                            .obj(src)
                            .props
                            .keys()
                            .iter()
                            .filter(|k| !used.contains(k))
                            .cloned()
                            .collect();
                        self.charge(pairs.len() as u64, line)?;
                        for k in pairs {
                            let x = self.get_member(&v, &Key::Name(k.clone()), line)?;
                            self.obj_mut(obj).props.insert(k, Prop::Data(x));
                        }
                    }
                    self.bind_pattern(&Pattern::Ident(r.clone()), Value::Obj(obj), scope, mode, line)?;
                }
                Ok(())
            }
        }
    }
}

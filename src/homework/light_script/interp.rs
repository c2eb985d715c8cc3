//! What the interpreter does with its state (`Interp`, in `value.rs` beside the objects and
//! scopes it owns): allocation, the step budget, depth counters, and variable lookup. Property
//! access is in `props.rs`, calls in `calls.rs`, statements in `exec.rs`, expressions in
//! `eval.rs`, the globals in `builtins.rs`.

use std::collections::BTreeMap;

use super::ast::Name;
use super::value::{
    Abort, Binding, FnCtx, Interp, ObjId, ObjKind, Object, Prop, PropMap, Scope, ScopeId, Value,
};
use super::{Limits, ScriptError};

type R<T> = Result<T, Abort>;

pub(super) const GLOBAL: ScopeId = ScopeId(0);

/// Objects the sandbox itself needs (builtins) on top of the script's allowance.
const BUILTIN_OBJECTS: usize = 4096;

/// Stack the sandbox lets itself use below its entry point: a backstop behind the counted
/// limits (nesting, call depth), whose cost in bytes differs between builds. Release
/// builds stay well inside wasm32's default 1 MiB stack; debug builds, with frames several
/// times larger, inside a 2 MiB test thread.
pub(super) const STACK_BUDGET_BYTES: usize = if cfg!(debug_assertions) { 1536 << 10 } else { 512 << 10 };

/// The address of a local: how deep the stack is right now (it grows downwards).
pub(super) fn stack_address() -> usize {
    let marker = 0u8;
    std::hint::black_box(&marker) as *const u8 as usize
}

pub(super) fn stack_exhausted(base: usize) -> bool {
    base.saturating_sub(stack_address()) > STACK_BUDGET_BYTES
}

/// Memory a script may allocate over the interpreter's life (objects, elements, strings,
/// scopes; counted as allocated, never refunded). Real light scripts use kilobytes.
pub(super) const MEMORY_BUDGET_BYTES: usize = 64 << 20;

const VALUE_BYTES: usize = std::mem::size_of::<Value>();

/// Most gl-matrix calls a single `light_matrix` run records.
pub(super) const MAX_GL_CALLS: usize = 4096;

impl Interp {
    /// The state alone, without globals: `builtins::interpreter` installs them.
    pub(super) fn new(file: &str, limits: Limits) -> Interp {
        let global = Scope {
            vars: BTreeMap::new(),
            parent: None,
            ctx: Some(FnCtx { this: Value::Undefined, home: None }),
            captured: true,
        };
        let mut it = Interp {
            heap: Vec::new(),
            scopes: vec![global],
            limits,
            steps_left: limits.steps,
            call_depth: 0,
            eval_depth: 0,
            max_eval_depth: limits
                .nesting
                .saturating_mul(2)
                .saturating_add(limits.call_depth.saturating_mul(6)),
            stack_base: stack_address(),
            memory_used: 0,
            file: file.to_string(),
            gl_log: None,
            method_cache: BTreeMap::new(),
            sink: ObjId(0),
        };
        it.sink = it.alloc_raw(ObjKind::Inert, None);
        it
    }

    pub(super) fn reset_budget(&mut self) {
        self.steps_left = self.limits.steps;
        self.call_depth = 0;
        self.eval_depth = 0;
        self.stack_base = stack_address();
    }

    pub(super) fn obj(&self, id: ObjId) -> &Object {
        &self.heap[id.0]
    }

    pub(super) fn obj_mut(&mut self, id: ObjId) -> &mut Object {
        &mut self.heap[id.0]
    }

    pub(super) fn script_error(&self, line: usize, message: String) -> ScriptError {
        ScriptError { file: self.file.clone(), line, message }
    }

    pub(super) fn fatal(&self, line: usize, message: String) -> Abort {
        Abort::Fatal(Box::new(self.script_error(line, message)))
    }

    pub(super) fn step(&mut self, line: usize) -> R<()> {
        self.charge(1, line)
    }

    /// Spends `n` steps of the budget (bulk work in natives costs in proportion).
    pub(super) fn charge(&mut self, n: u64, line: usize) -> R<()> {
        if n > self.steps_left {
            self.steps_left = 0;
            return Err(self.fatal(
                line,
                format!("did not finish within {} steps (an endless loop?)", self.limits.steps),
            ));
        }
        self.steps_left -= n;
        Ok(())
    }

    /// One step and one level of evaluation depth (undone by the caller's `eval_depth -= 1`).
    pub(super) fn enter_node(&mut self, line: usize) -> R<()> {
        if self.steps_left == 0 || self.eval_depth >= self.max_eval_depth || stack_exhausted(self.stack_base)
        {
            return Err(self.node_limit(line));
        }
        self.steps_left -= 1;
        self.eval_depth += 1;
        Ok(())
    }

    #[cold]
    #[inline(never)]
    fn node_limit(&mut self, line: usize) -> Abort {
        if self.steps_left == 0 {
            return self.fatal(
                line,
                format!("did not finish within {} steps (an endless loop?)", self.limits.steps),
            );
        }
        self.fatal(line, "expressions and calls nested too deeply to evaluate".into())
    }

    pub(super) fn enter_call(&mut self, line: usize) -> R<()> {
        if self.call_depth >= self.limits.call_depth {
            return Err(self.fatal(line, format!("calls nested deeper than {}", self.limits.call_depth)));
        }
        if stack_exhausted(self.stack_base) {
            return Err(self.fatal(line, "expressions and calls nested too deeply to evaluate".into()));
        }
        self.call_depth += 1;
        Ok(())
    }

    /// Throws an Error object the sandbox made; `display` is how an uncaught one reads.
    pub(super) fn throw_engine(
        &mut self,
        line: usize,
        name: &str,
        message: String,
        display: String,
    ) -> Abort {
        let id = self.alloc_raw(ObjKind::Error { display: Some(display) }, None);
        self.set_own(id, "name", Value::str(name));
        self.set_own(id, "message", Value::str(&message));
        Abort::Throw(Box::new((Value::Obj(id), line)))
    }

    pub(super) fn type_error(&mut self, line: usize, message: String) -> Abort {
        let display = format!("TypeError: {message}");
        self.throw_engine(line, "TypeError", message, display)
    }

    /// A TypeError whose uncaught text is just `message` (gl-matrix argument checks).
    pub(super) fn arg_error(&mut self, line: usize, message: String) -> Abort {
        self.throw_engine(line, "TypeError", message.clone(), message)
    }

    pub(super) fn not_defined(&mut self, name: &str, line: usize) -> Abort {
        let message = format!("`{name}` is not defined (a light script here has gl-matrix and Math only)");
        self.throw_engine(line, "ReferenceError", message.clone(), message)
    }

    pub(super) fn alloc_raw(&mut self, kind: ObjKind, proto: Option<ObjId>) -> ObjId {
        self.heap.push(Object { kind, props: PropMap::default(), proto });
        ObjId(self.heap.len() - 1)
    }

    /// Counts `bytes` against the memory budget.
    pub(super) fn charge_memory(&mut self, bytes: usize, line: usize) -> R<()> {
        self.memory_used = self.memory_used.saturating_add(bytes);
        if self.memory_used > MEMORY_BUDGET_BYTES {
            return Err(
                self.fatal(line, format!("used more than {} MiB of memory", MEMORY_BUDGET_BYTES >> 20))
            );
        }
        Ok(())
    }

    pub(super) fn charge_values(&mut self, count: usize, line: usize) -> R<()> {
        self.charge_memory(count.saturating_mul(VALUE_BYTES), line)
    }

    pub(super) fn alloc(&mut self, kind: ObjKind, proto: Option<ObjId>, line: usize) -> R<ObjId> {
        self.charge_memory(std::mem::size_of::<Object>(), line)?;
        let cap = self.limits.array_len.saturating_add(BUILTIN_OBJECTS);
        if self.heap.len() >= cap {
            return Err(self.fatal(line, format!("made more than {cap} objects")));
        }
        Ok(self.alloc_raw(kind, proto))
    }

    pub(super) fn check_array_len(&self, len: usize, line: usize) -> R<()> {
        if len > self.limits.array_len {
            return Err(self.fatal(line, format!("an array longer than {} elements", self.limits.array_len)));
        }
        Ok(())
    }

    pub(super) fn check_string_len(&self, len: usize, line: usize) -> R<()> {
        if len > self.limits.string_len {
            return Err(self.fatal(line, format!("a string longer than {} bytes", self.limits.string_len)));
        }
        Ok(())
    }

    pub(super) fn new_array(&mut self, items: Vec<Value>, line: usize) -> R<Value> {
        self.check_array_len(items.len(), line)?;
        self.charge_values(items.len(), line)?;
        Ok(Value::Obj(self.alloc(ObjKind::Array(items), None, line)?))
    }

    pub(super) fn new_f32(&mut self, items: Vec<f32>, line: usize) -> R<Value> {
        self.check_array_len(items.len(), line)?;
        self.charge_memory(items.len().saturating_mul(4), line)?;
        Ok(Value::Obj(self.alloc(ObjKind::F32(items), None, line)?))
    }

    pub(super) fn new_string(&mut self, s: String, line: usize) -> R<Value> {
        self.check_string_len(s.len(), line)?;
        self.charge((s.len() / 16) as u64, line)?;
        self.charge_memory(s.len(), line)?;
        Ok(Value::str(&s))
    }

    /// Sets a data property directly (no setters, no limits): for the sandbox's own objects.
    pub(super) fn set_own(&mut self, id: ObjId, name: &str, value: Value) {
        self.obj_mut(id).props.insert(Name::from(name), Prop::Data(value));
    }

    pub(super) fn push_scope(&mut self, parent: ScopeId, ctx: Option<FnCtx>, line: usize) -> R<ScopeId> {
        self.charge_memory(std::mem::size_of::<Scope>(), line)?;
        let cap = self.limits.array_len.saturating_add(BUILTIN_OBJECTS);
        if self.scopes.len() >= cap {
            return Err(self.fatal(line, format!("made more than {cap} scopes")));
        }
        self.scopes.push(Scope { vars: BTreeMap::new(), parent: Some(parent), ctx, captured: false });
        Ok(ScopeId(self.scopes.len() - 1))
    }

    /// Frees a scope when it is the newest and no closure refers to it.
    pub(super) fn pop_scope(&mut self, s: ScopeId) {
        if s.0 + 1 == self.scopes.len() && s != GLOBAL && !self.scopes[s.0].captured {
            self.scopes.pop();
        }
    }

    pub(super) fn mark_captured(&mut self, s: ScopeId) {
        let mut cur = Some(s);
        while let Some(c) = cur {
            let scope = &mut self.scopes[c.0];
            if scope.captured {
                break;
            }
            scope.captured = true;
            cur = scope.parent;
        }
    }

    pub(super) fn declare(&mut self, scope: ScopeId, name: Name, value: Value, mutable: bool) {
        self.scopes[scope.0].vars.insert(name, Binding { value, mutable });
    }

    pub(super) fn has_own_var(&self, scope: ScopeId, name: &str) -> bool {
        self.scopes[scope.0].vars.contains_key(name)
    }

    fn find_var(&self, scope: ScopeId, name: &str) -> Option<ScopeId> {
        let mut cur = Some(scope);
        while let Some(c) = cur {
            let s = &self.scopes[c.0];
            if s.vars.contains_key(name) {
                return Some(c);
            }
            cur = s.parent;
        }
        None
    }

    pub(super) fn lookup_var(&self, scope: ScopeId, name: &str) -> Option<Value> {
        let s = self.find_var(scope, name)?;
        self.scopes[s.0].vars.get(name).map(|b| b.value.clone())
    }

    pub(super) fn get_var(&mut self, scope: ScopeId, name: &str, line: usize) -> R<Value> {
        match self.lookup_var(scope, name) {
            Some(v) => Ok(v),
            None => Err(self.not_defined(name, line)),
        }
    }

    /// `name = value`: strict code may not create globals by assignment.
    pub(super) fn assign_var(
        &mut self,
        scope: ScopeId,
        name: &Name,
        value: Value,
        strict: bool,
        line: usize,
    ) -> R<()> {
        let Some(s) = self.find_var(scope, name) else {
            if strict {
                return Err(self.not_defined(name, line));
            }
            self.declare(super::interp::GLOBAL, name.clone(), value, true);
            return Ok(());
        };
        match self.scopes[s.0].vars.get_mut(&**name) {
            Some(b) if b.mutable => {
                b.value = value;
                Ok(())
            }
            _ => Err(self.type_error(line, format!("assignment to the constant `{name}`"))),
        }
    }

    pub(super) fn fn_ctx(&self, scope: ScopeId) -> FnCtx {
        let mut cur = Some(scope);
        while let Some(c) = cur {
            let s = &self.scopes[c.0];
            if let Some(ctx) = &s.ctx {
                return ctx.clone();
            }
            cur = s.parent;
        }
        FnCtx { this: Value::Undefined, home: None }
    }

    /// The message an uncaught abort becomes.
    pub(super) fn uncaught(&mut self, abort: Abort) -> ScriptError {
        match abort {
            Abort::Fatal(e) => *e,
            Abort::Short => self.script_error(0, "internal: optional chain escaped".into()),
            Abort::Throw(thrown) => {
                let (value, line) = *thrown;
                if let Some(id) = value.obj()
                    && let ObjKind::Error { display: Some(d) } = &self.obj(id).kind
                {
                    return self.script_error(line, d.clone());
                }
                // Converting may run script code (a toString): give it a small budget.
                self.steps_left = self.steps_left.max(10_000);
                let text = match self.string_of(&value, line) {
                    Ok(s) => s.to_string(),
                    Err(_) => "(a value that cannot be shown)".into(),
                };
                let short: String = text.chars().take(200).collect();
                self.script_error(line, format!("uncaught exception: {short}"))
            }
        }
    }
}

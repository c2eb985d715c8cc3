//! Values, heap objects and scopes, and the interpreter's state that owns them (`Interp`: a
//! native function is called with it, so the two are defined together). Objects and scopes
//! live in its arenas and are named by index: no reference cycles, no `RefCell` borrows to
//! panic on, and dropping the interpreter frees everything at once.

use std::collections::BTreeMap;
use std::sync::Arc;

use super::ast::{ClassDef, FuncDef, Name};
use super::{GlCall, Limits, ScriptError};

#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(super) struct ObjId(pub usize);

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct ScopeId(pub usize);

#[derive(Clone, Debug, PartialEq)]
pub(super) enum Value {
    Undefined,
    Null,
    Bool(bool),
    Num(f64),
    Str(Name),
    Obj(ObjId),
}

impl Value {
    pub(super) fn str(s: &str) -> Value {
        Value::Str(Arc::from(s))
    }

    pub(super) fn is_nullish(&self) -> bool {
        matches!(self, Value::Undefined | Value::Null)
    }

    pub(super) fn obj(&self) -> Option<ObjId> {
        match self {
            Value::Obj(id) => Some(*id),
            _ => None,
        }
    }
}

/// A property key after conversion: array indices are kept numeric.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Key {
    Index(usize),
    Name(Name),
}

impl Key {
    pub(super) fn name(s: &str) -> Key {
        Key::Name(Arc::from(s))
    }

    pub(super) fn text(&self) -> Name {
        match self {
            Key::Index(i) => Arc::from(i.to_string()),
            Key::Name(n) => n.clone(),
        }
    }
}

/// What a native function receives.
pub(super) struct NativeCall<'a> {
    pub this: &'a Value,
    pub args: &'a [Value],
    pub line: usize,
    pub is_new: bool,
    pub name: &'static str,
}

impl NativeCall<'_> {
    pub(super) fn arg(&self, i: usize) -> Value {
        self.args.get(i).cloned().unwrap_or(Value::Undefined)
    }
}

pub(super) type NativeFn = fn(&mut Interp, &NativeCall<'_>) -> Result<Value, Abort>;

#[derive(Clone)]
pub(super) struct Closure {
    pub def: Arc<FuncDef>,
    pub scope: ScopeId,
    /// The class whose method this is (for `super`).
    pub home: Option<ObjId>,
}

#[derive(Clone)]
pub(super) struct ClassData {
    pub def: Arc<ClassDef>,
    pub scope: ScopeId,
    pub parent: Option<ObjId>,
    pub ctor: Option<ObjId>,
}

pub(super) enum ObjKind {
    Plain,
    Array(Vec<Value>),
    /// A Float32Array: stores f32-rounded numbers, fixed length.
    F32(Vec<f32>),
    Closure(Closure),
    Class(ClassData),
    Native {
        name: &'static str,
        f: NativeFn,
    },
    /// A framework stand-in: any missing property reads as the inert sink, calls return it.
    Inert,
    /// An Error object; `display` is set for errors the sandbox itself raises.
    Error {
        display: Option<String>,
    },
}

#[derive(Clone)]
pub(super) enum Prop {
    Data(Value),
    Accessor { get: Option<ObjId>, set: Option<ObjId> },
}

/// Properties in insertion order with logarithmic lookup.
#[derive(Default)]
pub(super) struct PropMap {
    order: Vec<Name>,
    map: BTreeMap<Name, Prop>,
}

impl PropMap {
    pub(super) fn get(&self, key: &str) -> Option<&Prop> {
        self.map.get(key)
    }

    pub(super) fn insert(&mut self, key: Name, prop: Prop) {
        if let Some(slot) = self.map.get_mut(&key) {
            *slot = prop;
        } else {
            self.order.push(key.clone());
            self.map.insert(key, prop);
        }
    }

    pub(super) fn len(&self) -> usize {
        self.order.len()
    }

    pub(super) fn keys(&self) -> &[Name] {
        &self.order
    }
}

pub(super) struct Object {
    pub kind: ObjKind,
    pub props: PropMap,
    pub proto: Option<ObjId>,
}

#[derive(Clone)]
pub(super) struct Binding {
    pub value: Value,
    pub mutable: bool,
}

/// What a non-arrow function call binds: `this`, and the class for `super`.
#[derive(Clone)]
pub(super) struct FnCtx {
    pub this: Value,
    pub home: Option<ObjId>,
}

pub(super) struct Scope {
    pub vars: BTreeMap<Name, Binding>,
    pub parent: Option<ScopeId>,
    pub ctx: Option<FnCtx>,
    /// A closure refers to this scope: it must outlive its block.
    pub captured: bool,
}

/// Why evaluation stopped early. Boxed payloads keep `Result<Value, Abort>` small: it is
/// returned through every level of the tree walker, so its size multiplies stack use.
pub(super) enum Abort {
    /// A JavaScript exception (catchable): the value thrown and the line of the throw.
    Throw(Box<(Value, usize)>),
    /// A limit or an internal refusal: not catchable by the script.
    Fatal(Box<ScriptError>),
    /// A `?.` met null or undefined: the chain's value is undefined.
    Short,
}

/// How a statement finished.
pub(super) enum Flow {
    Normal,
    Return(Value, usize),
    Break,
    Continue,
}

/// Prototype chains are followed this far at most: a script can grow one by one link per
/// step (`F.prototype = new F()` in a loop), and each look-up must stay cheap.
pub(super) const MAX_PROTO_HOPS: usize = 100;

/// The interpreter's state: the arenas every object and scope lives in, its budgets and
/// counters (what it does with them is in `interp.rs` and the files beside it).
pub(super) struct Interp {
    pub heap: Vec<Object>,
    pub scopes: Vec<Scope>,
    pub limits: Limits,
    pub steps_left: u64,
    pub call_depth: usize,
    /// Rust recursion in the tree walker (expressions + statements), capped so any
    /// input the parser accepted still cannot overflow the stack: the cap allows two
    /// levels per parser nesting level and six per call, enough for recursion written
    /// plainly to meet `call_depth` first.
    pub eval_depth: usize,
    pub max_eval_depth: usize,
    /// Where the stack was when the current run began.
    pub stack_base: usize,
    /// Bytes allocated so far (see `interp::MEMORY_BUDGET_BYTES`).
    pub memory_used: usize,
    pub file: String,
    pub gl_log: Option<Vec<GlCall>>,
    pub method_cache: BTreeMap<&'static str, ObjId>,
    /// The one inert value framework stand-ins hand out.
    pub sink: ObjId,
}

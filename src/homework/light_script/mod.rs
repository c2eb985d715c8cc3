//! A small sandboxed JavaScript interpreter for a GAMES202 homework-1 light:
//! `lights/DirectionalLight.js` (its `CalcLightMVP(translate, scale)` built with
//! gl-matrix) and the light `engine.js` constructs.
//!
//! Pure and deterministic: no I/O, clock, randomness or threads, so it runs the same on
//! the desktop and in a browser (wasm32). Every input is bounded: a step budget for time
//! (bulk work in built-ins is charged in proportion), length limits for arrays and
//! strings, a 64 MiB allocation budget, and nesting limits in the parser and the
//! evaluator so the tree walker cannot overflow the stack. Those counted limits decide;
//! a check of the stack actually used (at most 512 KiB below the entry point in release
//! builds, 1.5 MiB in debug builds) only backs them up, and can only fire on input nested
//! far beyond any real light. Failures are one-line `ScriptError`s naming a file and line;
//! nothing panics on any input.
//!
//! The gl-matrix functions follow gl-matrix 3.x [GlMatrix-Mat4] operation for operation, so
//! results are the browser's to the bit (checked against gl-matrix 3.4.4 in V8 while writing
//! this).

mod ast;
mod builtins;
mod builtins_more;
mod calls;
mod engine_js;
mod eval;
mod exec;
mod glbind;
mod glmatrix;
mod interp;
mod lex;
mod methods;
mod natives;
mod ops;
mod parse;
mod parse_expr;
mod parse_fn;
mod parse_lit;
mod parse_stmt;
mod props;
mod string_methods;
mod value;

#[cfg(test)]
mod tests_engine;
#[cfg(test)]
mod tests_errors;
#[cfg(test)]
mod tests_fuzz;
#[cfg(test)]
mod tests_light;

#[cfg_attr(not(target_arch = "wasm32"), allow(unused_imports))]
pub use engine_js::engine_light;

use ast::Pattern;
use interp::GLOBAL;
use value::{Interp, Key, ObjKind, Value};

/// Sources larger than this are refused (bytes).
pub const MAX_SOURCE_BYTES: usize = 1 << 20;

/// A script error on one line: `DirectionalLight.js:37: mat4.ortho needs 7 arguments`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ScriptError {
    pub file: String,
    /// 1-based; 0 when no line applies.
    pub line: usize,
    pub message: String,
}

impl std::fmt::Display for ScriptError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.line == 0 {
            write!(f, "{}: {}", self.file, self.message)
        } else {
            write!(f, "{}:{}: {}", self.file, self.line, self.message)
        }
    }
}

impl std::error::Error for ScriptError {}

/// Bounds on one run of a script.
#[derive(Clone, Copy, Debug)]
pub struct Limits {
    /// Statement and expression evaluations per run (load, construction, each matrix).
    pub steps: u64,
    /// Nested calls (JavaScript functions and natives).
    pub call_depth: usize,
    /// Nesting levels the parser accepts (blocks, parentheses, operator chains).
    pub nesting: usize,
    /// Elements per array; also bounds objects, scopes and properties per object.
    pub array_len: usize,
    /// Bytes per string.
    pub string_len: usize,
}

impl Default for Limits {
    fn default() -> Self {
        Limits { steps: 5_000_000, call_depth: 200, nesting: 200, array_len: 1 << 20, string_len: 1 << 20 }
    }
}

/// Where a value came from in the student's files.
#[derive(Clone, Debug, PartialEq)]
pub struct Sourced<T> {
    pub value: T,
    pub file: String,
    /// 0 (with file "framework") for the framework's defaults.
    pub line: usize,
}

impl<T> Sourced<T> {
    fn framework(value: T) -> Self {
        Sourced { value, file: "framework".into(), line: 0 }
    }
}

/// The light engine.js builds:
/// `new DirectionalLight(intensity, color, lightPos, focalPoint, lightUp, hasShadowMap, gl)`.
#[derive(Clone, Debug, PartialEq)]
pub struct EngineLight {
    pub intensity: Sourced<f64>,
    pub color: Sourced<[f64; 3]>,
    pub position: Sourced<[f64; 3]>,
    pub focal_point: Sourced<[f64; 3]>,
    pub up: Sourced<[f64; 3]>,
    pub notes: Vec<String>,
}

impl EngineLight {
    /// The framework's light: intensity 5000, white, at (0, 80, 80) looking at the origin, y up.
    pub fn framework() -> Self {
        EngineLight {
            intensity: Sourced::framework(5000.0),
            color: Sourced::framework([1.0, 1.0, 1.0]),
            position: Sourced::framework([0.0, 80.0, 80.0]),
            focal_point: Sourced::framework([0.0, 0.0, 0.0]),
            up: Sourced::framework([0.0, 1.0, 0.0]),
            notes: Vec::new(),
        }
    }
}

/// One gl-matrix call made while computing a matrix (what a report can show a TA).
#[derive(Clone, Debug, PartialEq)]
pub struct GlCall {
    /// "mat4.ortho".
    pub name: String,
    /// The numeric arguments only (vectors and matrices flattened), not the `out` array.
    pub args: Vec<f64>,
    pub line: usize,
}

/// A light matrix a student's CalcLightMVP returned.
#[derive(Clone, Debug, PartialEq)]
pub struct LightMatrix {
    /// Column-major, gl-matrix's layout; non-finite entries are kept for the caller to judge.
    pub clip_from_object: [f32; 16],
    /// The gl-matrix calls of this run, in order (at most the first 4096).
    pub calls: Vec<GlCall>,
    /// The line of the `return` that produced the matrix.
    pub return_line: usize,
}

/// DirectionalLight.js loaded: the class evaluated and a light object made as the
/// framework makes it.
pub struct LightScript {
    interp: Interp,
    light: Value,
    notes: Vec<String>,
}

fn line0(file: &str, message: impl Into<String>) -> ScriptError {
    ScriptError { file: file.to_string(), line: 0, message: message.into() }
}

impl LightScript {
    /// Runs the file's top level, then constructs the light with engine.js's values, the
    /// framework's classes stubbed (Mesh, EmissiveMaterial, FBO, setTransform, an inert
    /// `gl`). A constructor that fails is replaced by an object with the template's fields
    /// (noted). Err: the file does not parse, has no `DirectionalLight` with a
    /// `CalcLightMVP` method, or its top level throws or exceeds the limits.
    pub fn load(
        source: &str,
        file: &str,
        engine: &EngineLight,
        limits: Limits,
    ) -> Result<LightScript, ScriptError> {
        if source.len() > MAX_SOURCE_BYTES {
            return Err(line0(file, format!("the file is larger than {MAX_SOURCE_BYTES} bytes")));
        }
        let lexed = lex::lex(source, file);
        if let Some(e) = lexed.error {
            return Err(e);
        }
        let program = parse::parse_program(&lexed.tokens, file, limits.nesting)?;
        let mut it = builtins::interpreter(file, limits);
        for name in &program.var_names {
            if !it.has_own_var(GLOBAL, name) {
                it.declare(GLOBAL, name.clone(), Value::Undefined, true);
            }
        }
        if let Err(e) = it.exec_stmts(&program.body, GLOBAL) {
            return Err(it.uncaught(e));
        }
        let mut notes = program.notes;
        let class = it.lookup_var(GLOBAL, "DirectionalLight").filter(|v| {
            v.obj().is_some_and(|id| matches!(it.obj(id).kind, ObjKind::Class(_) | ObjKind::Closure(_)))
        });
        let Some(class) = class else {
            return Err(line0(file, "no class or function named DirectionalLight"));
        };
        it.reset_budget();
        let method = it.get_member(&class, &Key::name("prototype"), 0).and_then(|p| {
            if p.obj().is_some() {
                it.get_member(&p, &Key::name("CalcLightMVP"), 0)
            } else {
                Ok(Value::Undefined)
            }
        });
        match method {
            Ok(m) if it.is_callable(&m) => {}
            Ok(_) => return Err(line0(file, "DirectionalLight has no CalcLightMVP method")),
            Err(e) => return Err(it.uncaught(e)),
        }
        it.reset_budget();
        let args = match Self::engine_args(&mut it, engine) {
            Ok(a) => a,
            Err(e) => return Err(it.uncaught(e)),
        };
        let light = match it.construct(&class, args, 0) {
            Ok(v) if v.obj().is_some() => v,
            outcome => {
                let why = match outcome {
                    Err(e) => it.uncaught(e).to_string(),
                    Ok(_) => "it returned no object".to_string(),
                };
                notes.push(format!(
                    "the DirectionalLight constructor failed ({why}); used an object with the template's fields instead"
                ));
                it.reset_budget();
                match Self::fallback_light(&mut it, &class, engine) {
                    Ok(v) => v,
                    Err(e) => return Err(it.uncaught(e)),
                }
            }
        };
        Ok(LightScript { interp: it, light, notes })
    }

    /// `(intensity, color, lightPos, focalPoint, lightUp, true, gl)` as engine.js passes them.
    fn engine_args(it: &mut Interp, e: &EngineLight) -> Result<Vec<Value>, value::Abort> {
        let mut args = vec![Value::Num(e.intensity.value)];
        for v in [e.color.value, e.position.value, e.focal_point.value, e.up.value] {
            args.push(it.new_array(v.iter().map(|x| Value::Num(*x)).collect(), 0)?);
        }
        args.push(Value::Bool(true));
        args.push(Value::Obj(it.alloc(ObjKind::Inert, None, 0)?));
        Ok(args)
    }

    fn fallback_light(it: &mut Interp, class: &Value, e: &EngineLight) -> Result<Value, value::Abort> {
        let proto = it.get_member(class, &Key::name("prototype"), 0)?.obj();
        let obj = it.alloc(ObjKind::Plain, proto, 0)?;
        let args = Self::engine_args(it, e)?;
        let names = ["lightIntensity", "lightColor", "lightPos", "focalPoint", "lightUp", "hasShadowMap"];
        for (name, v) in names.iter().zip(args) {
            it.set_own(obj, name, v);
        }
        for name in ["mesh", "mat", "fbo"] {
            let inert = it.alloc(ObjKind::Inert, None, 0)?;
            it.set_own(obj, name, Value::Obj(inert));
        }
        Ok(Value::Obj(obj))
    }

    /// What loading noticed (skipped imports, a constructor that failed).
    pub fn notes(&self) -> &[String] {
        &self.notes
    }

    /// Calls CalcLightMVP for an object placed by `translate` and `scale` (world units).
    /// Parameters go by name: one containing "rot" gets [0, 0, 0] (radians), "trans" the
    /// translation, "scal" the scale; others by position (translate, scale). Each call has
    /// a fresh step budget.
    pub fn light_matrix(&mut self, translate: [f64; 3], scale: [f64; 3]) -> Result<LightMatrix, ScriptError> {
        let it = &mut self.interp;
        it.reset_budget();
        let file = it.file.clone();
        let method = match it.get_member(&self.light, &Key::name("CalcLightMVP"), 0) {
            Ok(m) if it.is_callable(&m) => m,
            Ok(_) => return Err(line0(&file, "the light object has no CalcLightMVP method")),
            Err(e) => return Err(it.uncaught(e)),
        };
        let (mut params, line) = match method.obj().map(|id| &it.obj(id).kind) {
            Some(ObjKind::Closure(c)) => (
                c.def
                    .params
                    .iter()
                    .map(|p| match &p.target {
                        Pattern::Ident(n) => n.to_lowercase(),
                        _ => String::new(),
                    })
                    .collect::<Vec<_>>(),
                c.def.line,
            ),
            _ => (Vec::new(), 0),
        };
        // A rest parameter (or a native) takes whatever positions are left.
        let open_ended = match method.obj().map(|id| &it.obj(id).kind) {
            Some(ObjKind::Closure(c)) => c.def.rest.is_some(),
            _ => true,
        };
        if open_ended {
            params.resize(params.len().max(2), String::new());
        }
        let mut args = Vec::new();
        for (i, name) in params.iter().enumerate() {
            let v = if name.contains("rot") {
                Some([0.0; 3])
            } else if name.contains("trans") {
                Some(translate)
            } else if name.contains("scal") {
                Some(scale)
            } else {
                [translate, scale].get(i).copied()
            };
            args.push(match v {
                Some(v) => it
                    .new_array(v.iter().map(|x| Value::Num(*x)).collect(), line)
                    .map_err(|e| it.uncaught(e))?,
                None => Value::Undefined,
            });
        }
        it.gl_log = Some(Vec::new());
        let r = it.call_full(&method, self.light.clone(), args, line);
        let calls = it.gl_log.take().unwrap_or_default();
        let (value, return_line) = r.map_err(|e| it.uncaught(e))?;
        let matrix = Self::matrix_of(it, &value).map_err(|what| ScriptError {
            file,
            line: return_line,
            message: format!("CalcLightMVP returned {what}, not a 4x4 matrix"),
        })?;
        Ok(LightMatrix { clip_from_object: matrix, calls, return_line })
    }

    fn matrix_of(it: &Interp, v: &Value) -> Result<[f32; 16], String> {
        let id = match v {
            Value::Undefined => return Err("undefined".into()),
            Value::Null => return Err("null".into()),
            Value::Obj(id) if matches!(it.obj(*id).kind, ObjKind::Array(_) | ObjKind::F32(_)) => *id,
            Value::Obj(_) => return Err("an object".into()),
            Value::Num(_) => return Err("a number".into()),
            Value::Str(_) => return Err("a string".into()),
            Value::Bool(_) => return Err("a boolean".into()),
        };
        let len = it.array_len(id);
        if len != 16 {
            return Err(format!("an array of {len} elements"));
        }
        let mut out = [0.0f32; 16];
        for (i, slot) in out.iter_mut().enumerate() {
            match it.index_value(id, i) {
                Value::Num(x) => *slot = x as f32,
                other => return Err(format!("an array whose element {i} is {}", it.typeof_str(&other))),
            }
        }
        Ok(out)
    }
}

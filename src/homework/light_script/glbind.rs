//! The gl-matrix API as sandbox natives: argument checks that name the function and
//! parameter, `out` written in place (a Float32Array rounds to f32 on store, as in the
//! browser), and a record of every call while a light matrix is computed.

use super::GlCall;
use super::glmatrix::{self as gm, M4, V3};
use super::interp::{GLOBAL, MAX_GL_CALLS};
use super::natives::namespace;
use super::value::{Abort, Interp, Key, NativeCall, NativeFn, ObjKind, Value};

type R<T> = Result<T, Abort>;

const M16: [&str; 17] = [
    "out", "m00", "m01", "m02", "m03", "m10", "m11", "m12", "m13", "m20", "m21", "m22", "m23", "m30", "m31",
    "m32", "m33",
];

/// Each function's parameter names; a leading "out" is the array written to.
const SIGS: [(&str, &[&str]); 52] = [
    ("mat4.create", &[]),
    ("mat4.clone", &["a"]),
    ("mat4.copy", &["out", "a"]),
    ("mat4.identity", &["out"]),
    ("mat4.fromValues", &M16_VALUES),
    ("mat4.set", &M16),
    ("mat4.translate", &["out", "a", "v"]),
    ("mat4.scale", &["out", "a", "v"]),
    ("mat4.rotate", &["out", "a", "rad", "axis"]),
    ("mat4.rotateX", &["out", "a", "rad"]),
    ("mat4.rotateY", &["out", "a", "rad"]),
    ("mat4.rotateZ", &["out", "a", "rad"]),
    ("mat4.fromTranslation", &["out", "v"]),
    ("mat4.fromScaling", &["out", "v"]),
    ("mat4.fromRotation", &["out", "rad", "axis"]),
    ("mat4.fromXRotation", &["out", "rad"]),
    ("mat4.fromYRotation", &["out", "rad"]),
    ("mat4.fromZRotation", &["out", "rad"]),
    ("mat4.lookAt", &["out", "eye", "center", "up"]),
    ("mat4.targetTo", &["out", "eye", "target", "up"]),
    ("mat4.ortho", &["out", "left", "right", "bottom", "top", "near", "far"]),
    ("mat4.perspective", &["out", "fovy", "aspect", "near", "far"]),
    ("mat4.frustum", &["out", "left", "right", "bottom", "top", "near", "far"]),
    ("mat4.multiply", &["out", "a", "b"]),
    ("mat4.mul", &["out", "a", "b"]),
    ("mat4.invert", &["out", "a"]),
    ("mat4.transpose", &["out", "a"]),
    ("mat4.determinant", &["a"]),
    ("mat4.getTranslation", &["out", "mat"]),
    ("vec3.create", &[]),
    ("vec3.clone", &["a"]),
    ("vec3.fromValues", &["x", "y", "z"]),
    ("vec3.copy", &["out", "a"]),
    ("vec3.set", &["out", "x", "y", "z"]),
    ("vec3.add", &["out", "a", "b"]),
    ("vec3.subtract", &["out", "a", "b"]),
    ("vec3.sub", &["out", "a", "b"]),
    ("vec3.multiply", &["out", "a", "b"]),
    ("vec3.mul", &["out", "a", "b"]),
    ("vec3.scale", &["out", "a", "b"]),
    ("vec3.normalize", &["out", "a"]),
    ("vec3.cross", &["out", "a", "b"]),
    ("vec3.dot", &["a", "b"]),
    ("vec3.length", &["a"]),
    ("vec3.len", &["a"]),
    ("vec3.negate", &["out", "a"]),
    ("vec3.distance", &["a", "b"]),
    ("vec3.transformMat4", &["out", "a", "m"]),
    ("vec4.create", &[]),
    ("vec4.fromValues", &["x", "y", "z", "w"]),
    ("vec4.set", &["out", "x", "y", "z", "w"]),
    ("vec4.transformMat4", &["out", "a", "m"]),
];

const M16_VALUES: [&str; 16] = [
    "m00", "m01", "m02", "m03", "m10", "m11", "m12", "m13", "m20", "m21", "m22", "m23", "m30", "m31", "m32",
    "m33",
];

pub(super) fn install(it: &mut Interp) {
    for prefix in ["mat4", "vec3", "vec4"] {
        let fns: Vec<(&'static str, NativeFn)> =
            SIGS.iter().filter(|(n, _)| n.starts_with(prefix)).map(|(n, _)| (*n, gl as NativeFn)).collect();
        let ns = namespace(it, &fns, &[]);
        it.declare(GLOBAL, prefix.into(), Value::Obj(ns), false);
    }
    let gm_fns: [(&'static str, NativeFn); 2] =
        [("glMatrix.toRadian", gl_util), ("glMatrix.setMatrixArrayType", gl_util)];
    let ns = namespace(it, &gm_fns, &[("EPSILON", gm::EPSILON)]);
    if let Some(f32) = it.lookup_var(GLOBAL, "Float32Array") {
        it.set_own(ns, "ARRAY_TYPE", f32);
    }
    it.declare(GLOBAL, "glMatrix".into(), Value::Obj(ns), false);
}

fn gl_util(it: &mut Interp, c: &NativeCall<'_>) -> R<Value> {
    if c.name == "glMatrix.toRadian" {
        let a = GlArgs { c, params: &["a"] }.num(it, 0)?;
        return Ok(Value::Num(a * (std::f64::consts::PI / 180.0)));
    }
    Ok(Value::Undefined)
}

struct GlArgs<'a, 'b> {
    c: &'a NativeCall<'b>,
    params: &'static [&'static str],
}

fn describe(it: &Interp, v: &Value) -> &'static str {
    match v {
        Value::Undefined => "undefined",
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Num(_) => "a number",
        Value::Str(_) => "a string",
        Value::Obj(id) => match it.obj(*id).kind {
            ObjKind::Array(_) | ObjKind::F32(_) => "an array",
            ObjKind::Closure(_) | ObjKind::Class(_) | ObjKind::Native { .. } => "a function",
            _ => "an object",
        },
    }
}

impl GlArgs<'_, '_> {
    fn fail(&self, it: &mut Interp, i: usize, what: String) -> Abort {
        let param = self.params.get(i).copied().unwrap_or("?");
        it.arg_error(self.c.line, format!("{}: argument {} ({param}) {what}", self.c.name, i + 1))
    }

    fn num(&self, it: &mut Interp, i: usize) -> R<f64> {
        match self.c.arg(i) {
            Value::Num(x) => Ok(x),
            v => {
                let d = describe(it, &v);
                Err(self.fail(it, i, format!("is {d}, not a number")))
            }
        }
    }

    fn array(&self, it: &mut Interp, i: usize, n: usize) -> R<Vec<f64>> {
        let v = self.c.arg(i);
        let Some(id) = v.obj().filter(|id| matches!(it.obj(*id).kind, ObjKind::Array(_) | ObjKind::F32(_)))
        else {
            let d = describe(it, &v);
            return Err(self.fail(it, i, format!("is {d}, not an array of {n} numbers")));
        };
        let len = it.array_len(id);
        if len < n {
            return Err(self.fail(it, i, format!("has {len} elements, needs {n}")));
        }
        (0..n)
            .map(|k| match it.index_value(id, k) {
                Value::Num(x) => Ok(x),
                e => {
                    let d = describe(it, &e);
                    Err(self.fail(it, i, format!("element {k} is {d}, not a number")))
                }
            })
            .collect()
    }

    fn v3(&self, it: &mut Interp, i: usize) -> R<V3> {
        let a = self.array(it, i, 3)?;
        Ok([a[0], a[1], a[2]])
    }

    fn m4(&self, it: &mut Interp, i: usize) -> R<M4> {
        let a = self.array(it, i, 16)?;
        let mut m = [0.0; 16];
        m.copy_from_slice(&a);
        Ok(m)
    }

    /// Writes `values` into the out argument and returns it.
    fn write(&self, it: &mut Interp, values: &[f64]) -> R<Value> {
        let out = self.c.arg(0);
        if !out.obj().is_some_and(|id| matches!(it.obj(id).kind, ObjKind::Array(_) | ObjKind::F32(_))) {
            let d = describe(it, &out);
            return Err(self.fail(it, 0, format!("is {d}, not an array to write the result into")));
        }
        for (k, x) in values.iter().enumerate() {
            it.set_member(&out, &Key::Index(k), Value::Num(*x), self.c.line)?;
        }
        Ok(out)
    }
}

fn record(it: &mut Interp, c: &NativeCall<'_>, has_out: bool) {
    let Some(log) = &it.gl_log else { return };
    if log.len() >= MAX_GL_CALLS {
        return;
    }
    let mut args = Vec::new();
    for v in c.args.iter().skip(usize::from(has_out)) {
        match v {
            Value::Num(x) => args.push(*x),
            Value::Obj(id) if matches!(it.obj(*id).kind, ObjKind::Array(_) | ObjKind::F32(_)) => {
                for k in 0..it.array_len(*id).min(16) {
                    if let Value::Num(x) = it.index_value(*id, k) {
                        args.push(x);
                    }
                }
            }
            _ => {}
        }
    }
    if let Some(log) = &mut it.gl_log {
        log.push(GlCall { name: c.name.to_string(), args, line: c.line });
    }
}

/// All mat4/vec3/vec4 functions, dispatched by name.
fn gl(it: &mut Interp, c: &NativeCall<'_>) -> R<Value> {
    let params = SIGS.iter().find(|(n, _)| *n == c.name).map_or(&[][..], |(_, p)| *p);
    // perspective's far may be left out (an infinite far plane).
    let required = if c.name == "mat4.perspective" { 4 } else { params.len() };
    if c.args.len() < required {
        return Err(it.arg_error(
            c.line,
            format!("{} needs {required} arguments ({}), got {}", c.name, params.join(", "), c.args.len()),
        ));
    }
    let has_out = params.first() == Some(&"out");
    record(it, c, has_out);
    let a = GlArgs { c, params };
    let m = match c.name {
        "mat4.create" => return it.new_f32(gm::identity().map(|x| x as f32).to_vec(), c.line),
        "mat4.clone" => {
            let m = a.m4(it, 0)?;
            return it.new_f32(m.map(|x| x as f32).to_vec(), c.line);
        }
        "mat4.fromValues" => {
            let xs = (0..16).map(|i| a.num(it, i)).collect::<R<Vec<f64>>>()?;
            return it.new_f32(xs.iter().map(|x| *x as f32).collect(), c.line);
        }
        "mat4.determinant" => return Ok(Value::Num(gm::determinant(&a.m4(it, 0)?))),
        "mat4.copy" => a.m4(it, 1)?,
        "mat4.identity" => gm::identity(),
        "mat4.set" => {
            let xs = (1..17).map(|i| a.num(it, i)).collect::<R<Vec<f64>>>()?;
            let mut m = [0.0; 16];
            m.copy_from_slice(&xs);
            m
        }
        "mat4.translate" => gm::translate(&a.m4(it, 1)?, a.v3(it, 2)?),
        "mat4.scale" => gm::scale(&a.m4(it, 1)?, a.v3(it, 2)?),
        "mat4.rotate" | "mat4.fromRotation" => {
            let r = if c.name == "mat4.rotate" {
                let (m, rad, axis) = (a.m4(it, 1)?, a.num(it, 2)?, a.v3(it, 3)?);
                gm::rotate(&m, rad, axis)
            } else {
                let (rad, axis) = (a.num(it, 1)?, a.v3(it, 2)?);
                gm::from_rotation(rad, axis)
            };
            match r {
                Some(m) => m,
                None => return Ok(Value::Null),
            }
        }
        "mat4.rotateX" => gm::rotate_x(&a.m4(it, 1)?, a.num(it, 2)?),
        "mat4.rotateY" => gm::rotate_y(&a.m4(it, 1)?, a.num(it, 2)?),
        "mat4.rotateZ" => gm::rotate_z(&a.m4(it, 1)?, a.num(it, 2)?),
        "mat4.fromTranslation" => gm::from_translation(a.v3(it, 1)?),
        "mat4.fromScaling" => gm::from_scaling(a.v3(it, 1)?),
        "mat4.fromXRotation" => gm::from_axis_rotation(0, a.num(it, 1)?),
        "mat4.fromYRotation" => gm::from_axis_rotation(1, a.num(it, 1)?),
        "mat4.fromZRotation" => gm::from_axis_rotation(2, a.num(it, 1)?),
        "mat4.lookAt" => gm::look_at(a.v3(it, 1)?, a.v3(it, 2)?, a.v3(it, 3)?),
        "mat4.targetTo" => gm::target_to(a.v3(it, 1)?, a.v3(it, 2)?, a.v3(it, 3)?),
        "mat4.ortho" | "mat4.frustum" => {
            let xs = (1..7).map(|i| a.num(it, i)).collect::<R<Vec<f64>>>()?;
            let f = if c.name == "mat4.ortho" { gm::ortho } else { gm::frustum };
            f(xs[0], xs[1], xs[2], xs[3], xs[4], xs[5])
        }
        "mat4.perspective" => {
            let (fovy, aspect, near) = (a.num(it, 1)?, a.num(it, 2)?, a.num(it, 3)?);
            let far = if c.arg(4).is_nullish() { None } else { Some(a.num(it, 4)?) };
            gm::perspective(fovy, aspect, near, far)
        }
        "mat4.multiply" | "mat4.mul" => gm::multiply(&a.m4(it, 1)?, &a.m4(it, 2)?),
        "mat4.invert" => match gm::invert(&a.m4(it, 1)?) {
            Some(m) => m,
            None => return Ok(Value::Null),
        },
        "mat4.transpose" => gm::transpose(&a.m4(it, 1)?),
        "mat4.getTranslation" => {
            let m = a.m4(it, 1)?;
            return a.write(it, &m[12..15]);
        }
        _ => return vec_fn(it, &a),
    };
    a.write(it, &m)
}

fn vec_fn(it: &mut Interp, a: &GlArgs<'_, '_>) -> R<Value> {
    let c = a.c;
    let v: Vec<f64> = match c.name {
        "vec3.create" => return it.new_f32(vec![0.0; 3], c.line),
        "vec4.create" => return it.new_f32(vec![0.0; 4], c.line),
        "vec3.clone" => {
            let v = a.v3(it, 0)?;
            return it.new_f32(v.map(|x| x as f32).to_vec(), c.line);
        }
        "vec3.fromValues" | "vec4.fromValues" => {
            let xs = (0..a.params.len()).map(|i| a.num(it, i)).collect::<R<Vec<f64>>>()?;
            return it.new_f32(xs.iter().map(|x| *x as f32).collect(), c.line);
        }
        "vec3.dot" => {
            let (x, y) = (a.v3(it, 0)?, a.v3(it, 1)?);
            return Ok(Value::Num(x[0] * y[0] + x[1] * y[1] + x[2] * y[2]));
        }
        "vec3.length" | "vec3.len" => return Ok(Value::Num(gm::js_hypot(&a.v3(it, 0)?))),
        "vec3.distance" => {
            let (x, y) = (a.v3(it, 0)?, a.v3(it, 1)?);
            return Ok(Value::Num(gm::js_hypot(&[y[0] - x[0], y[1] - x[1], y[2] - x[2]])));
        }
        "vec3.copy" => a.v3(it, 1)?.to_vec(),
        "vec3.set" | "vec4.set" => (1..a.params.len()).map(|i| a.num(it, i)).collect::<R<Vec<f64>>>()?,
        "vec3.add" | "vec3.subtract" | "vec3.sub" | "vec3.multiply" | "vec3.mul" | "vec3.cross" => {
            let (x, y) = (a.v3(it, 1)?, a.v3(it, 2)?);
            match c.name {
                "vec3.add" => (0..3).map(|i| x[i] + y[i]).collect(),
                "vec3.subtract" | "vec3.sub" => (0..3).map(|i| x[i] - y[i]).collect(),
                "vec3.cross" => gm::cross(x, y).to_vec(),
                _ => (0..3).map(|i| x[i] * y[i]).collect(),
            }
        }
        "vec3.scale" => {
            let (x, s) = (a.v3(it, 1)?, a.num(it, 2)?);
            x.iter().map(|e| e * s).collect()
        }
        "vec3.normalize" => gm::normalize(a.v3(it, 1)?).to_vec(),
        "vec3.negate" => a.v3(it, 1)?.iter().map(|e| -e).collect(),
        "vec3.transformMat4" => gm::transform_point(&a.m4(it, 2)?, a.v3(it, 1)?).to_vec(),
        "vec4.transformMat4" => {
            let x = a.array(it, 1, 4)?;
            gm::transform_vec4(&a.m4(it, 2)?, [x[0], x[1], x[2], x[3]]).to_vec()
        }
        _ => return Err(it.arg_error(c.line, format!("{} is not available here", c.name))),
    };
    a.write(it, &v)
}

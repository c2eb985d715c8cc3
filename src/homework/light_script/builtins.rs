//! The globals a light script can use: Math, Number, Array, Float32Array, Object, JSON,
//! Error, console (silent), glMatrix/mat4/vec3/vec4, and stand-ins for the framework's
//! classes. Nothing else exists: no Date, eval, timers, network or DOM.

use std::f64::consts;
use std::sync::Arc;

use super::Limits;
use super::interp::GLOBAL;
use super::natives::{int_arg, namespace, native_value, num_arg};
use super::ops::{js_pow, parse_float, to_int32, to_uint32, truthy};
use super::value::{Abort, Interp, Key, NativeCall, NativeFn, ObjKind, Value};

type R<T> = Result<T, Abort>;

fn global(it: &mut Interp, name: &str, v: Value) {
    it.declare(GLOBAL, Arc::from(name), v, false);
}

/// A fresh interpreter for `file`, with every global a light script can use.
pub(super) fn interpreter(file: &str, limits: Limits) -> Interp {
    let mut it = Interp::new(file, limits);
    install(&mut it);
    it
}

fn install(it: &mut Interp) {
    global(it, "undefined", Value::Undefined);
    global(it, "NaN", Value::Num(f64::NAN));
    global(it, "Infinity", Value::Num(f64::INFINITY));
    let math_fns: [(&'static str, NativeFn); 31] = [
        ("Math.sqrt", math),
        ("Math.cbrt", math),
        ("Math.sin", math),
        ("Math.cos", math),
        ("Math.tan", math),
        ("Math.asin", math),
        ("Math.acos", math),
        ("Math.atan", math),
        ("Math.sinh", math),
        ("Math.cosh", math),
        ("Math.tanh", math),
        ("Math.abs", math),
        ("Math.floor", math),
        ("Math.ceil", math),
        ("Math.round", math),
        ("Math.exp", math),
        ("Math.log", math),
        ("Math.log2", math),
        ("Math.log10", math),
        ("Math.sign", math),
        ("Math.trunc", math),
        ("Math.fround", math),
        ("Math.atan2", math),
        ("Math.pow", math),
        ("Math.min", math),
        ("Math.max", math),
        ("Math.hypot", math),
        ("Math.random", math),
        ("Math.expm1", math),
        ("Math.log1p", math),
        ("Math.clz32", math),
    ];
    let math_consts = [
        ("PI", consts::PI),
        ("E", consts::E),
        ("LN2", consts::LN_2),
        ("LN10", consts::LN_10),
        ("LOG2E", consts::LOG2_E),
        ("LOG10E", consts::LOG10_E),
        ("SQRT2", consts::SQRT_2),
        ("SQRT1_2", consts::FRAC_1_SQRT_2),
    ];
    let m = namespace(it, &math_fns, &math_consts);
    global(it, "Math", Value::Obj(m));

    let number = native_value(it, "Number", convert);
    if let Some(id) = number.obj() {
        for (name, f) in [
            ("Number.isFinite", convert as NativeFn),
            ("Number.isNaN", convert),
            ("Number.isInteger", convert),
            ("Number.parseFloat", convert),
            ("Number.parseInt", convert),
        ] {
            let v = native_value(it, name, f);
            it.set_own(id, name.rsplit('.').next().unwrap_or(name), v);
        }
        for (name, x) in [
            ("EPSILON", f64::EPSILON),
            ("MAX_VALUE", f64::MAX),
            ("MIN_VALUE", 5e-324),
            ("MAX_SAFE_INTEGER", 9_007_199_254_740_991.0),
            ("MIN_SAFE_INTEGER", -9_007_199_254_740_991.0),
            ("POSITIVE_INFINITY", f64::INFINITY),
            ("NEGATIVE_INFINITY", f64::NEG_INFINITY),
            ("NaN", f64::NAN),
        ] {
            it.set_own(id, name, Value::Num(x));
        }
    }
    global(it, "Number", number);
    for name in ["parseFloat", "parseInt", "isNaN", "isFinite", "String", "Boolean"] {
        let v = native_value(it, name, convert);
        global(it, name, v);
    }
    let console_fns: Vec<(&'static str, NativeFn)> = [
        "console.log",
        "console.warn",
        "console.error",
        "console.info",
        "console.debug",
        "console.table",
        "console.assert",
        "console.group",
        "console.groupEnd",
        "console.time",
        "console.timeEnd",
        "console.trace",
        "console.dir",
    ]
    .into_iter()
    .map(|n| (n, nothing as NativeFn))
    .collect();
    let console = namespace(it, &console_fns, &[]);
    global(it, "console", Value::Obj(console));
    for name in ["Error", "TypeError", "RangeError"] {
        let v = native_value(it, name, error_ctor);
        global(it, name, v);
    }
    super::builtins_more::install(it);
    super::glbind::install(it);
    install_framework(it);
}

fn nothing(_: &mut Interp, _: &NativeCall<'_>) -> R<Value> {
    Ok(Value::Undefined)
}

fn math(it: &mut Interp, c: &NativeCall<'_>) -> R<Value> {
    let name = c.name.trim_start_matches("Math.");
    let many = |it: &mut Interp| -> R<Vec<f64>> { (0..c.args.len()).map(|i| num_arg(it, c, i)).collect() };
    let x = match name {
        "min" | "max" | "hypot" | "atan2" | "pow" | "random" => 0.0,
        _ => num_arg(it, c, 0)?,
    };
    let r = match name {
        "sqrt" => x.sqrt(),
        "cbrt" => x.cbrt(),
        "sin" => x.sin(),
        "cos" => x.cos(),
        "tan" => x.tan(),
        "asin" => x.asin(),
        "acos" => x.acos(),
        "atan" => x.atan(),
        "sinh" => x.sinh(),
        "cosh" => x.cosh(),
        "tanh" => x.tanh(),
        "abs" => x.abs(),
        "floor" => x.floor(),
        "ceil" => x.ceil(),
        "round" => {
            // Halves round up (towards +Infinity), unlike Rust's `round`.
            let f = x.floor();
            if !x.is_finite() || x == f {
                x
            } else if x - f >= 0.5 {
                if f == -1.0 { -0.0 } else { f + 1.0 }
            } else {
                f
            }
        }
        "exp" => x.exp(),
        "expm1" => x.exp_m1(),
        "log" => x.ln(),
        "log1p" => x.ln_1p(),
        "log2" => x.log2(),
        "log10" => x.log10(),
        "sign" => {
            if x.is_nan() || x == 0.0 {
                x
            } else {
                x.signum()
            }
        }
        "trunc" => x.trunc(),
        "fround" => f64::from(x as f32),
        "clz32" => f64::from(to_uint32(x).leading_zeros()),
        "atan2" => num_arg(it, c, 0)?.atan2(num_arg(it, c, 1)?),
        "pow" => js_pow(num_arg(it, c, 0)?, num_arg(it, c, 1)?),
        "min" => many(it)?.into_iter().fold(f64::INFINITY, |a, b| {
            if a.is_nan() || b.is_nan() {
                f64::NAN
            } else if b < a || (b == 0.0 && a == 0.0 && b.is_sign_negative()) {
                b
            } else {
                a
            }
        }),
        "max" => many(it)?.into_iter().fold(f64::NEG_INFINITY, |a, b| {
            if a.is_nan() || b.is_nan() {
                f64::NAN
            } else if b > a || (b == 0.0 && a == 0.0 && a.is_sign_negative()) {
                b
            } else {
                a
            }
        }),
        "hypot" => super::glmatrix::js_hypot(&many(it)?),
        _ => {
            return Err(it.arg_error(
                c.line,
                "Math.random is not available (a light script here must be deterministic)".into(),
            ));
        }
    };
    Ok(Value::Num(r))
}

/// Number, String, Boolean, parseFloat, parseInt, isNaN, isFinite and Number.*.
fn convert(it: &mut Interp, c: &NativeCall<'_>) -> R<Value> {
    let v = c.arg(0);
    Ok(match c.name {
        "Number" => Value::Num(if c.args.is_empty() { 0.0 } else { it.number_of(&v, c.line)? }),
        "String" => {
            if c.args.is_empty() {
                Value::str("")
            } else {
                Value::Str(it.string_of(&v, c.line)?)
            }
        }
        "Boolean" => Value::Bool(truthy(&v)),
        "parseFloat" | "Number.parseFloat" => Value::Num(parse_float(&it.string_of(&v, c.line)?)),
        "parseInt" | "Number.parseInt" => {
            let s = it.string_of(&v, c.line)?;
            let radix = to_int32(int_arg(it, c, 1, 0.0)?);
            Value::Num(parse_int(&s, radix))
        }
        "isNaN" => Value::Bool(it.number_of(&v, c.line)?.is_nan()),
        "isFinite" => Value::Bool(it.number_of(&v, c.line)?.is_finite()),
        "Number.isNaN" => Value::Bool(matches!(v, Value::Num(n) if n.is_nan())),
        "Number.isFinite" => Value::Bool(matches!(v, Value::Num(n) if n.is_finite())),
        _ => Value::Bool(matches!(v, Value::Num(n) if n.is_finite() && n.fract() == 0.0)),
    })
}

fn parse_int(s: &str, radix: i32) -> f64 {
    let t = s.trim_start_matches(super::ops::is_js_space);
    let (neg, t) = match t.strip_prefix('-') {
        Some(rest) => (true, rest),
        None => (false, t.strip_prefix('+').unwrap_or(t)),
    };
    let (radix, t) = match (radix, t.get(..2)) {
        (0 | 16, Some("0x" | "0X")) => (16, &t[2..]),
        (0, _) => (10, t),
        (r, _) => (r, t),
    };
    if !(2..=36).contains(&radix) {
        return f64::NAN;
    }
    let mut v = 0.0f64;
    let mut any = false;
    for ch in t.chars() {
        let Some(d) = ch.to_digit(radix as u32) else { break };
        v = v * f64::from(radix) + f64::from(d);
        any = true;
    }
    match (any, neg) {
        (false, _) => f64::NAN,
        (true, true) => -v,
        (true, false) => v,
    }
}

fn error_ctor(it: &mut Interp, c: &NativeCall<'_>) -> R<Value> {
    let id = it.alloc(ObjKind::Error { display: None }, None, c.line)?;
    it.set_own(id, "name", Value::str(c.name));
    let msg = match c.arg(0) {
        Value::Undefined => Value::str(""),
        v => Value::Str(it.string_of(&v, c.line)?),
    };
    it.set_own(id, "message", msg);
    Ok(Value::Obj(id))
}

/// The framework's classes as inert stand-ins, and `setTransform` as engine.js has it.
fn install_framework(it: &mut Interp) {
    for name in [
        "Mesh",
        "EmissiveMaterial",
        "FBO",
        "Material",
        "PhongMaterial",
        "ShadowMaterial",
        "Texture",
        "MeshRender",
    ] {
        let v = native_value(it, name, stand_in);
        if name == "Mesh"
            && let Some(id) = v.obj()
        {
            let cube = native_value(it, "Mesh.cube", stand_in);
            it.set_own(id, "cube", cube);
        }
        global(it, name, v);
    }
    let st = native_value(it, "setTransform", set_transform);
    global(it, "setTransform", st);
}

fn stand_in(it: &mut Interp, c: &NativeCall<'_>) -> R<Value> {
    Ok(Value::Obj(it.alloc(ObjKind::Inert, None, c.line)?))
}

fn set_transform(it: &mut Interp, c: &NativeCall<'_>) -> R<Value> {
    let id = it.alloc(ObjKind::Plain, None, c.line)?;
    let names = ["modelTransX", "modelTransY", "modelTransZ", "modelScaleX", "modelScaleY", "modelScaleZ"];
    for (i, n) in names.iter().enumerate() {
        it.set_member(&Value::Obj(id), &Key::name(n), c.arg(i), c.line)?;
    }
    Ok(Value::Obj(id))
}

//! Array, Float32Array, Object and JSON globals.

use std::sync::Arc;

use super::interp::GLOBAL;
use super::natives::{length_arg, namespace, native_value};
use super::ops::num_to_string;
use super::value::{Abort, Interp, Key, NativeCall, NativeFn, ObjKind, Value};

type R<T> = Result<T, Abort>;

/// JSON.stringify nests at most this deep (deeper values, and cycles, are an error).
const MAX_JSON_DEPTH: usize = 64;

pub(super) fn install(it: &mut Interp) {
    let array = native_value(it, "Array", array_ctor);
    if let Some(id) = array.obj() {
        for (name, f) in [
            ("Array.isArray", array_static as NativeFn),
            ("Array.from", array_static),
            ("Array.of", array_static),
        ] {
            let v = native_value(it, name, f);
            it.set_own(id, name.rsplit('.').next().unwrap_or(name), v);
        }
    }
    it.declare(GLOBAL, Arc::from("Array"), array, false);
    let f32 = native_value(it, "Float32Array", f32_ctor);
    if let Some(id) = f32.obj() {
        for (name, f) in [("Float32Array.from", f32_static as NativeFn), ("Float32Array.of", f32_static)] {
            let v = native_value(it, name, f);
            it.set_own(id, name.rsplit('.').next().unwrap_or(name), v);
        }
        it.set_own(id, "BYTES_PER_ELEMENT", Value::Num(4.0));
    }
    it.declare(GLOBAL, Arc::from("Float32Array"), f32, false);
    let object_fns: [(&'static str, NativeFn); 5] = [
        ("Object.keys", object_static),
        ("Object.values", object_static),
        ("Object.entries", object_static),
        ("Object.assign", object_static),
        ("Object.freeze", object_static),
    ];
    let object = namespace(it, &object_fns, &[]);
    it.declare(GLOBAL, Arc::from("Object"), Value::Obj(object), false);
    let json = namespace(it, &[("JSON.stringify", json_stringify as NativeFn)], &[]);
    it.declare(GLOBAL, Arc::from("JSON"), Value::Obj(json), false);
}

/// The elements of an array, Float32Array, string, or `{ length: n }` object.
fn array_like(it: &mut Interp, v: &Value, line: usize) -> R<Vec<Value>> {
    if let Some(id) = v.obj()
        && matches!(it.obj(id).kind, ObjKind::Plain)
    {
        let len = it.get_member(v, &Key::name("length"), line)?;
        let n = it.number_of(&len, line)?;
        let n = length_arg(it, if n.is_nan() { 0.0 } else { n.trunc().max(0.0) }, line)?;
        return (0..n).map(|i| it.get_member(v, &Key::Index(i), line)).collect();
    }
    if v.is_nullish() {
        return Err(it.type_error(line, "Array.from needs an array-like value".into()));
    }
    it.list_of(v, line)
}

fn array_ctor(it: &mut Interp, c: &NativeCall<'_>) -> R<Value> {
    if let [Value::Num(n)] = c.args {
        let n = length_arg(it, *n, c.line)?;
        return it.new_array(vec![Value::Undefined; n], c.line);
    }
    it.new_array(c.args.to_vec(), c.line)
}

fn array_static(it: &mut Interp, c: &NativeCall<'_>) -> R<Value> {
    match c.name {
        "Array.isArray" => {
            Ok(Value::Bool(c.arg(0).obj().is_some_and(|id| matches!(it.obj(id).kind, ObjKind::Array(_)))))
        }
        "Array.of" => it.new_array(c.args.to_vec(), c.line),
        _ => {
            let mut items = array_like(it, &c.arg(0), c.line)?;
            let map = c.arg(1);
            if !map.is_nullish() {
                for (i, item) in items.iter_mut().enumerate() {
                    let x = std::mem::replace(item, Value::Undefined);
                    *item = it.call(&map, Value::Undefined, vec![x, Value::Num(i as f64)], c.line)?;
                }
            }
            it.new_array(items, c.line)
        }
    }
}

fn to_f32s(it: &mut Interp, items: &[Value], line: usize) -> R<Vec<f32>> {
    items.iter().map(|v| it.number_of(v, line).map(|x| x as f32)).collect()
}

fn f32_ctor(it: &mut Interp, c: &NativeCall<'_>) -> R<Value> {
    if !c.is_new {
        return Err(it.type_error(c.line, "Float32Array must be called with `new`".into()));
    }
    let items = match c.arg(0) {
        Value::Undefined => Vec::new(),
        Value::Num(n) => {
            let n = length_arg(it, n, c.line)?;
            vec![0.0; n]
        }
        v => {
            let list = array_like(it, &v, c.line)?;
            to_f32s(it, &list, c.line)?
        }
    };
    it.new_f32(items, c.line)
}

fn f32_static(it: &mut Interp, c: &NativeCall<'_>) -> R<Value> {
    let list = if c.name == "Float32Array.of" { c.args.to_vec() } else { array_like(it, &c.arg(0), c.line)? };
    let items = to_f32s(it, &list, c.line)?;
    it.new_f32(items, c.line)
}

fn object_static(it: &mut Interp, c: &NativeCall<'_>) -> R<Value> {
    let target = c.arg(0);
    let Some(id) = target.obj() else {
        if c.name == "Object.freeze" {
            return Ok(target);
        }
        return Err(it.type_error(c.line, format!("{} needs an object", c.name)));
    };
    match c.name {
        "Object.freeze" => Ok(target),
        "Object.assign" => {
            for src in c.args.iter().skip(1) {
                let Some(sid) = src.obj() else { continue };
                let len = it.array_len(sid);
                let names = it.obj(sid).props.keys().to_vec();
                it.charge((len + names.len()) as u64, c.line)?;
                let keys =
                    (0..len).map(Key::Index).chain(names.into_iter().map(Key::Name)).collect::<Vec<_>>();
                for k in keys {
                    let v = it.get_member(src, &k, c.line)?;
                    it.set_member(&target, &k, v, c.line)?;
                }
            }
            Ok(target)
        }
        _ => {
            let len = it.array_len(id);
            let names = it.obj(id).props.keys().to_vec();
            it.charge((len + names.len()) as u64, c.line)?;
            let keys = (0..len).map(Key::Index).chain(names.into_iter().map(Key::Name)).collect::<Vec<_>>();
            let mut out = Vec::with_capacity(keys.len());
            for k in keys {
                let name = Value::Str(k.text());
                out.push(match c.name {
                    "Object.keys" => name,
                    "Object.values" => it.get_member(&target, &k, c.line)?,
                    _ => {
                        let v = it.get_member(&target, &k, c.line)?;
                        it.new_array(vec![name, v], c.line)?
                    }
                });
            }
            it.new_array(out, c.line)
        }
    }
}

fn json_stringify(it: &mut Interp, c: &NativeCall<'_>) -> R<Value> {
    let mut out = String::new();
    if !json_value(it, &c.arg(0), &mut out, 0, c.line)? {
        return Ok(Value::Undefined);
    }
    it.new_string(out, c.line)
}

fn json_quote(s: &str, out: &mut String) {
    out.push('"');
    for ch in s.chars() {
        match ch {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            c if (c as u32) < 0x20 => out.push_str(&format!("\\u{:04x}", c as u32)),
            c => out.push(c),
        }
    }
    out.push('"');
}

/// Appends `v` as JSON; false when `v` has no JSON form (undefined, functions).
fn json_value(it: &mut Interp, v: &Value, out: &mut String, depth: usize, line: usize) -> R<bool> {
    it.step(line)?;
    it.check_string_len(out.len(), line)?;
    if depth > MAX_JSON_DEPTH {
        return Err(it.type_error(line, "JSON.stringify: a cyclic or too deeply nested value".into()));
    }
    match v {
        Value::Undefined => return Ok(false),
        Value::Null => out.push_str("null"),
        Value::Bool(b) => out.push_str(if *b { "true" } else { "false" }),
        Value::Num(n) => out.push_str(&if n.is_finite() { num_to_string(*n) } else { "null".into() }),
        Value::Str(s) => json_quote(s, out),
        Value::Obj(id) => {
            if it.is_callable(v) {
                return Ok(false);
            }
            if matches!(it.obj(*id).kind, ObjKind::Array(_)) {
                out.push('[');
                for i in 0..it.array_len(*id) {
                    if i > 0 {
                        out.push(',');
                    }
                    let x = it.index_value(*id, i);
                    if !json_value(it, &x, out, depth + 1, line)? {
                        out.push_str("null");
                    }
                }
                out.push(']');
            } else {
                // A Float32Array stringifies as an object keyed by index, as in browsers.
                out.push('{');
                let len = it.array_len(*id);
                let names = it.obj(*id).props.keys().to_vec();
                let keys =
                    (0..len).map(Key::Index).chain(names.into_iter().map(Key::Name)).collect::<Vec<_>>();
                let mut first = true;
                for k in keys {
                    let x = it.get_member(v, &k, line)?;
                    let mark = out.len();
                    if !first {
                        out.push(',');
                    }
                    json_quote(&k.text(), out);
                    out.push(':');
                    if json_value(it, &x, out, depth + 1, line)? {
                        first = false;
                    } else {
                        out.truncate(mark);
                    }
                }
                out.push('}');
            }
        }
    }
    Ok(true)
}

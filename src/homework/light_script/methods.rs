//! Built-in methods of arrays, Float32Arrays, numbers and functions (strings' are in
//! `string_methods`). Work that
//! walks elements or characters is charged to the step budget in proportion.

use super::natives::{int_arg, rel_index, short};
use super::ops::{num_to_string, strict_eq};
use super::value::{Abort, Interp, NativeCall, NativeFn, ObjId, ObjKind, Value};

type R<T> = Result<T, Abort>;

const ARRAY: [(&str, NativeFn); 22] = [
    ("Array.prototype.push", push),
    ("Array.prototype.pop", pop),
    ("Array.prototype.shift", shift),
    ("Array.prototype.unshift", unshift),
    ("Array.prototype.slice", slice),
    ("Array.prototype.map", each),
    ("Array.prototype.forEach", each),
    ("Array.prototype.filter", each),
    ("Array.prototype.find", each),
    ("Array.prototype.findIndex", each),
    ("Array.prototype.some", each),
    ("Array.prototype.every", each),
    ("Array.prototype.reduce", reduce),
    ("Array.prototype.concat", concat),
    ("Array.prototype.join", join),
    ("Array.prototype.fill", fill),
    ("Array.prototype.indexOf", index_of),
    ("Array.prototype.includes", index_of),
    ("Array.prototype.reverse", reverse),
    ("Array.prototype.sort", sort),
    ("Array.prototype.at", at),
    ("Array.prototype.toString", join),
];

const F32: [(&str, NativeFn); 18] = [
    ("Float32Array.prototype.slice", slice),
    ("Float32Array.prototype.map", each),
    ("Float32Array.prototype.forEach", each),
    ("Float32Array.prototype.filter", each),
    ("Float32Array.prototype.find", each),
    ("Float32Array.prototype.findIndex", each),
    ("Float32Array.prototype.some", each),
    ("Float32Array.prototype.every", each),
    ("Float32Array.prototype.reduce", reduce),
    ("Float32Array.prototype.join", join),
    ("Float32Array.prototype.fill", fill),
    ("Float32Array.prototype.indexOf", index_of),
    ("Float32Array.prototype.includes", index_of),
    ("Float32Array.prototype.reverse", reverse),
    ("Float32Array.prototype.sort", sort),
    ("Float32Array.prototype.at", at),
    ("Float32Array.prototype.set", f32_set),
    ("Float32Array.prototype.toString", join),
];

const NUMBER: [(&str, NativeFn); 2] =
    [("Number.prototype.toFixed", number), ("Number.prototype.toString", number)];

const FUNCTION: [(&str, NativeFn); 2] =
    [("Function.prototype.call", function), ("Function.prototype.apply", function)];

pub(super) fn lookup(table: &str, name: &str) -> Option<(&'static str, NativeFn)> {
    let list: &[(&'static str, NativeFn)] = match table {
        "array" => &ARRAY,
        "f32" => &F32,
        "string" => &super::string_methods::STRING,
        "number" => &NUMBER,
        "function" => &FUNCTION,
        _ => return None,
    };
    list.iter().find(|(full, _)| full.rsplit('.').next() == Some(name)).copied()
}

fn this_list(it: &mut Interp, c: &NativeCall<'_>) -> R<ObjId> {
    match c.this.obj() {
        Some(id) if matches!(it.obj(id).kind, ObjKind::Array(_) | ObjKind::F32(_)) => Ok(id),
        _ => Err(it.type_error(c.line, format!("{} called on a value that is not an array", c.name))),
    }
}

fn is_f32(it: &Interp, id: ObjId) -> bool {
    matches!(it.obj(id).kind, ObjKind::F32(_))
}

/// A new array of the same kind as `like` (Float32Array rounds its elements).
fn same_kind(it: &mut Interp, like: ObjId, items: Vec<Value>, line: usize) -> R<Value> {
    if is_f32(it, like) {
        let xs = items.iter().map(|v| it.number_of(v, line).map(|x| x as f32)).collect::<R<Vec<f32>>>()?;
        return it.new_f32(xs, line);
    }
    it.new_array(items, line)
}

fn with_vec<T>(it: &mut Interp, id: ObjId, f: impl FnOnce(&mut Vec<Value>) -> T) -> Option<T> {
    match &mut it.obj_mut(id).kind {
        ObjKind::Array(v) => Some(f(v)),
        _ => None,
    }
}

fn push(it: &mut Interp, c: &NativeCall<'_>) -> R<Value> {
    let id = this_list(it, c)?;
    let len = it.array_len(id) + c.args.len();
    it.check_array_len(len, c.line)?;
    it.charge(c.args.len() as u64, c.line)?;
    it.charge_values(c.args.len(), c.line)?;
    with_vec(it, id, |v| v.extend(c.args.iter().cloned()));
    Ok(Value::Num(len as f64))
}

fn pop(it: &mut Interp, c: &NativeCall<'_>) -> R<Value> {
    let id = this_list(it, c)?;
    Ok(with_vec(it, id, |v| v.pop()).flatten().unwrap_or(Value::Undefined))
}

fn shift(it: &mut Interp, c: &NativeCall<'_>) -> R<Value> {
    let id = this_list(it, c)?;
    it.charge(it.array_len(id) as u64, c.line)?;
    Ok(with_vec(it, id, |v| if v.is_empty() { None } else { Some(v.remove(0)) })
        .flatten()
        .unwrap_or(Value::Undefined))
}

fn unshift(it: &mut Interp, c: &NativeCall<'_>) -> R<Value> {
    let id = this_list(it, c)?;
    let len = it.array_len(id) + c.args.len();
    it.check_array_len(len, c.line)?;
    it.charge(len as u64, c.line)?;
    it.charge_values(c.args.len(), c.line)?;
    with_vec(it, id, |v| {
        v.splice(0..0, c.args.iter().cloned());
    });
    Ok(Value::Num(len as f64))
}

fn slice(it: &mut Interp, c: &NativeCall<'_>) -> R<Value> {
    let id = this_list(it, c)?;
    let len = it.array_len(id);
    let start = rel_index(int_arg(it, c, 0, 0.0)?, len);
    let end = rel_index(int_arg(it, c, 1, len as f64)?, len);
    it.charge(end.saturating_sub(start) as u64, c.line)?;
    let items = (start..end.max(start)).map(|i| it.index_value(id, i)).collect();
    same_kind(it, id, items, c.line)
}

fn callback(it: &mut Interp, c: &NativeCall<'_>) -> R<Value> {
    let f = c.arg(0);
    if !it.is_callable(&f) {
        return Err(it.type_error(c.line, format!("{} needs a function", c.name)));
    }
    Ok(f)
}

/// map, forEach, filter, find, findIndex, some, every.
fn each(it: &mut Interp, c: &NativeCall<'_>) -> R<Value> {
    let id = this_list(it, c)?;
    let f = callback(it, c)?;
    let len = it.array_len(id);
    let mut out = Vec::new();
    for i in 0..len {
        it.step(c.line)?;
        let x = it.index_value(id, i);
        let r = it.call(&f, c.arg(1), vec![x.clone(), Value::Num(i as f64), c.this.clone()], c.line)?;
        let hit = super::ops::truthy(&r);
        match short(c) {
            "map" => out.push(r),
            "filter" if hit => out.push(x),
            "find" if hit => return Ok(x),
            "findIndex" if hit => return Ok(Value::Num(i as f64)),
            "some" if hit => return Ok(Value::Bool(true)),
            "every" if !hit => return Ok(Value::Bool(false)),
            _ => {}
        }
    }
    match short(c) {
        "map" | "filter" => same_kind(it, id, out, c.line),
        "findIndex" => Ok(Value::Num(-1.0)),
        "some" => Ok(Value::Bool(false)),
        "every" => Ok(Value::Bool(true)),
        _ => Ok(Value::Undefined),
    }
}

fn reduce(it: &mut Interp, c: &NativeCall<'_>) -> R<Value> {
    let id = this_list(it, c)?;
    let f = callback(it, c)?;
    let len = it.array_len(id);
    let (mut acc, start) = match c.args.get(1) {
        Some(init) => (init.clone(), 0),
        None if len > 0 => (it.index_value(id, 0), 1),
        None => return Err(it.type_error(c.line, "reduce of an empty array with no initial value".into())),
    };
    for i in start..len {
        it.step(c.line)?;
        let x = it.index_value(id, i);
        acc = it.call(&f, Value::Undefined, vec![acc, x, Value::Num(i as f64), c.this.clone()], c.line)?;
    }
    Ok(acc)
}

fn concat(it: &mut Interp, c: &NativeCall<'_>) -> R<Value> {
    let id = this_list(it, c)?;
    let mut items: Vec<Value> = (0..it.array_len(id)).map(|i| it.index_value(id, i)).collect();
    for a in c.args {
        match a.obj() {
            Some(aid) if matches!(it.obj(aid).kind, ObjKind::Array(_)) => {
                items.extend((0..it.array_len(aid)).map(|i| it.index_value(aid, i)));
            }
            _ => items.push(a.clone()),
        }
        it.check_array_len(items.len(), c.line)?;
    }
    it.charge(items.len() as u64, c.line)?;
    it.new_array(items, c.line)
}

fn join(it: &mut Interp, c: &NativeCall<'_>) -> R<Value> {
    let id = this_list(it, c)?;
    let sep = match c.arg(0) {
        Value::Undefined => ",".into(),
        v if short(c) == "join" => it.string_of(&v, c.line)?,
        _ => ",".into(),
    };
    let s = it.join(id, &sep, c.line, 0)?;
    it.new_string(s, c.line)
}

fn fill(it: &mut Interp, c: &NativeCall<'_>) -> R<Value> {
    let id = this_list(it, c)?;
    let len = it.array_len(id);
    let start = rel_index(int_arg(it, c, 1, 0.0)?, len);
    let end = rel_index(int_arg(it, c, 2, len as f64)?, len);
    it.charge(end.saturating_sub(start) as u64, c.line)?;
    let v = c.arg(0);
    let x = if is_f32(it, id) { it.number_of(&v, c.line)? as f32 } else { 0.0 };
    match &mut it.obj_mut(id).kind {
        ObjKind::Array(items) => items.iter_mut().take(end).skip(start).for_each(|e| *e = v.clone()),
        ObjKind::F32(items) => items.iter_mut().take(end).skip(start).for_each(|e| *e = x),
        _ => {}
    }
    Ok(c.this.clone())
}

fn index_of(it: &mut Interp, c: &NativeCall<'_>) -> R<Value> {
    let id = this_list(it, c)?;
    let len = it.array_len(id);
    let from = rel_index(int_arg(it, c, 1, 0.0)?, len);
    it.charge(len.saturating_sub(from) as u64, c.line)?;
    let target = c.arg(0);
    let includes = short(c) == "includes";
    let nan = matches!(target, Value::Num(n) if n.is_nan());
    let found = (from..len).find(|i| {
        let x = it.index_value(id, *i);
        strict_eq(&x, &target) || (includes && nan && matches!(x, Value::Num(n) if n.is_nan()))
    });
    Ok(match (includes, found) {
        (true, f) => Value::Bool(f.is_some()),
        (false, Some(i)) => Value::Num(i as f64),
        (false, None) => Value::Num(-1.0),
    })
}

fn reverse(it: &mut Interp, c: &NativeCall<'_>) -> R<Value> {
    let id = this_list(it, c)?;
    it.charge(it.array_len(id) as u64, c.line)?;
    match &mut it.obj_mut(id).kind {
        ObjKind::Array(v) => v.reverse(),
        ObjKind::F32(v) => v.reverse(),
        _ => {}
    }
    Ok(c.this.clone())
}

fn at(it: &mut Interp, c: &NativeCall<'_>) -> R<Value> {
    let id = this_list(it, c)?;
    let len = it.array_len(id) as f64;
    let i = int_arg(it, c, 0, 0.0)?;
    let i = if i < 0.0 { len + i } else { i };
    Ok(if i >= 0.0 && i < len { it.index_value(id, i as usize) } else { Value::Undefined })
}

fn f32_set(it: &mut Interp, c: &NativeCall<'_>) -> R<Value> {
    let id = this_list(it, c)?;
    let src = it.list_of(&c.arg(0), c.line)?;
    let offset = int_arg(it, c, 1, 0.0)?;
    if offset < 0.0 || offset + src.len() as f64 > it.array_len(id) as f64 {
        return Err(it.type_error(c.line, "Float32Array.set: the source does not fit".into()));
    }
    let xs = src.iter().map(|v| it.number_of(v, c.line).map(|x| x as f32)).collect::<R<Vec<f32>>>()?;
    if let ObjKind::F32(v) = &mut it.obj_mut(id).kind {
        for (slot, x) in v.iter_mut().skip(offset as usize).zip(xs) {
            *slot = x;
        }
    }
    Ok(Value::Undefined)
}

/// A stable merge sort that tolerates inconsistent comparators (Rust's sort may panic).
fn sort(it: &mut Interp, c: &NativeCall<'_>) -> R<Value> {
    let id = this_list(it, c)?;
    let cmp = c.arg(0);
    let numeric = is_f32(it, id);
    let mut a: Vec<Value> = (0..it.array_len(id)).map(|i| it.index_value(id, i)).collect();
    let n = a.len();
    let mut width = 1;
    while width < n {
        let mut merged = Vec::with_capacity(n);
        let mut lo = 0;
        while lo < n {
            let (mid, hi) = ((lo + width).min(n), (lo + 2 * width).min(n));
            let (mut i, mut j) = (lo, mid);
            while i < mid || j < hi {
                it.step(c.line)?;
                let take_left = j >= hi || (i < mid && !before(it, &a[j], &a[i], &cmp, numeric, c.line)?);
                if take_left {
                    merged.push(a[i].clone());
                    i += 1;
                } else {
                    merged.push(a[j].clone());
                    j += 1;
                }
            }
            lo = hi;
        }
        a = merged;
        width *= 2;
    }
    match &mut it.obj_mut(id).kind {
        ObjKind::Array(v) => *v = a,
        ObjKind::F32(v) => {
            *v = a.iter().map(|x| if let Value::Num(n) = x { *n as f32 } else { f32::NAN }).collect()
        }
        _ => {}
    }
    Ok(c.this.clone())
}

/// Whether `x` sorts strictly before `y`.
fn before(it: &mut Interp, x: &Value, y: &Value, cmp: &Value, numeric: bool, line: usize) -> R<bool> {
    if !cmp.is_nullish() {
        let r = it.call(cmp, Value::Undefined, vec![x.clone(), y.clone()], line)?;
        return Ok(it.number_of(&r, line)? < 0.0);
    }
    match (x, y) {
        (Value::Undefined, _) => Ok(false),
        (_, Value::Undefined) => Ok(true),
        (Value::Num(a), Value::Num(b)) if numeric => Ok(a < b),
        _ => Ok(it.string_of(x, line)? < it.string_of(y, line)?),
    }
}

fn number(it: &mut Interp, c: &NativeCall<'_>) -> R<Value> {
    let x = it.number_of(c.this, c.line)?;
    let text = if short(c) == "toFixed" {
        let digits = int_arg(it, c, 0, 0.0)?;
        if !(0.0..=100.0).contains(&digits) {
            return Err(it.type_error(c.line, "toFixed() digits must be between 0 and 100".into()));
        }
        if x.abs() >= 1e21 || !x.is_finite() { num_to_string(x) } else { format!("{x:.*}", digits as usize) }
    } else {
        let radix = int_arg(it, c, 0, 10.0)?;
        if radix == 10.0
            || !x.is_finite()
            || x.fract() != 0.0
            || !(2.0..=36.0).contains(&radix)
            || x.abs() > 9.0e15
        {
            num_to_string(x)
        } else {
            let (mut n, mut digits) = (x.abs() as u64, Vec::new());
            loop {
                digits.push(std::char::from_digit((n % radix as u64) as u32, radix as u32).unwrap_or('?'));
                n /= radix as u64;
                if n == 0 {
                    break;
                }
            }
            let sign = if x < 0.0 { "-" } else { "" };
            format!("{sign}{}", digits.iter().rev().collect::<String>())
        }
    };
    Ok(Value::str(&text))
}

fn function(it: &mut Interp, c: &NativeCall<'_>) -> R<Value> {
    let args = if short(c) == "call" {
        c.args.get(1..).unwrap_or(&[]).to_vec()
    } else {
        match c.arg(1) {
            Value::Undefined | Value::Null => Vec::new(),
            v => it.list_of(&v, c.line)?,
        }
    };
    it.call(c.this, c.arg(0), args, c.line)
}

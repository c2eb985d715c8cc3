//! Native functions made, and their arguments read: what every table of built-ins shares.

use super::ops::num_to_string;
use super::value::{Abort, Interp, NativeCall, NativeFn, ObjId, ObjKind, Value};

type R<T> = Result<T, Abort>;

pub(super) fn native_value(it: &mut Interp, name: &'static str, f: NativeFn) -> Value {
    Value::Obj(it.alloc_raw(ObjKind::Native { name, f }, None))
}

/// An object whose methods are natives named `prefix.method`.
pub(super) fn namespace(it: &mut Interp, fns: &[(&'static str, NativeFn)], consts: &[(&str, f64)]) -> ObjId {
    let id = it.alloc_raw(ObjKind::Plain, None);
    for (name, f) in fns {
        let short = name.rsplit('.').next().unwrap_or(name);
        let v = native_value(it, name, *f);
        it.set_own(id, short, v);
    }
    for (name, x) in consts {
        it.set_own(id, name, Value::Num(*x));
    }
    id
}

pub(super) fn num_arg(it: &mut Interp, c: &NativeCall<'_>, i: usize) -> R<f64> {
    let v = c.arg(i);
    it.number_of(&v, c.line)
}

/// ToIntegerOrInfinity, with `default` for a missing argument.
pub(super) fn int_arg(it: &mut Interp, c: &NativeCall<'_>, i: usize, default: f64) -> R<f64> {
    if matches!(c.arg(i), Value::Undefined) {
        return Ok(default);
    }
    let x = num_arg(it, c, i)?;
    Ok(if x.is_nan() { 0.0 } else { x.trunc() })
}

/// A relative index (negative counts from the end), clamped to 0..=len.
pub(super) fn rel_index(x: f64, len: usize) -> usize {
    if x < 0.0 { (len as f64 + x).max(0.0) as usize } else { x.min(len as f64) as usize }
}

/// A length argument: a whole number within the array limit.
pub(super) fn length_arg(it: &mut Interp, x: f64, line: usize) -> R<usize> {
    if !(x >= 0.0 && x.fract() == 0.0) {
        return Err(it.throw_engine(
            line,
            "RangeError",
            format!("invalid array length {}", num_to_string(x)),
            format!("RangeError: invalid array length {}", num_to_string(x)),
        ));
    }
    if x > it.limits.array_len as f64 {
        return Err(it.fatal(line, format!("an array longer than {} elements", it.limits.array_len)));
    }
    it.charge(x as u64, line)?;
    Ok(x as usize)
}

/// A native's own name: `push` of `Array.prototype.push`.
pub(super) fn short(c: &NativeCall<'_>) -> &'static str {
    c.name.rsplit('.').next().unwrap_or(c.name)
}

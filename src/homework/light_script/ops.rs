//! Conversions and operators with JavaScript's meaning: `+` on strings, loose and
//! strict equality, number formatting, `instanceof` and `in`.

use std::sync::Arc;

use super::ast::{BinOp, Name};
use super::value::{Abort, Interp, Key, MAX_PROTO_HOPS, ObjKind, Value};

type R<T> = Result<T, Abort>;

/// Nested arrays deeper than this join as "" (JavaScript joins cycles as "").
const MAX_JOIN_DEPTH: usize = 32;

/// `Number.prototype.toString()` for radix 10: shortest round-trip digits.
pub(super) fn num_to_string(x: f64) -> String {
    if x.is_nan() {
        return "NaN".into();
    }
    if x == 0.0 {
        return "0".into();
    }
    if x.is_infinite() {
        return if x > 0.0 { "Infinity".into() } else { "-Infinity".into() };
    }
    if x < 0.0 {
        return format!("-{}", num_to_string(-x));
    }
    let sci = format!("{x:e}");
    let (mantissa, exp) = sci.split_once('e').unwrap_or((&sci, "0"));
    let digits: String = mantissa.chars().filter(|c| c.is_ascii_digit()).collect();
    let k = digits.len() as i64;
    let n = exp.parse::<i64>().unwrap_or(0) + 1;
    if k <= n && n <= 21 {
        format!("{digits}{}", "0".repeat((n - k) as usize))
    } else if 0 < n && n <= 21 {
        format!("{}.{}", &digits[..n as usize], &digits[n as usize..])
    } else if -6 < n && n <= 0 {
        format!("0.{}{digits}", "0".repeat((-n) as usize))
    } else {
        let e = n - 1;
        let sign = if e >= 0 { "+" } else { "-" };
        let head = if k == 1 { digits.clone() } else { format!("{}.{}", &digits[..1], &digits[1..]) };
        format!("{head}e{sign}{}", e.abs())
    }
}

pub(super) fn is_js_space(c: char) -> bool {
    c.is_whitespace() || c == '\u{feff}'
}

/// `Number(string)`.
pub(super) fn str_to_num(s: &str) -> f64 {
    let t = s.trim_matches(is_js_space);
    if t.is_empty() {
        return 0.0;
    }
    match t {
        "Infinity" | "+Infinity" => return f64::INFINITY,
        "-Infinity" => return f64::NEG_INFINITY,
        _ => {}
    }
    let radix = match t.get(..2) {
        Some("0x" | "0X") => 16,
        Some("0o" | "0O") => 8,
        Some("0b" | "0B") => 2,
        _ => 10,
    };
    if radix != 10 {
        let mut v = 0.0f64;
        for c in t[2..].chars() {
            match c.to_digit(radix) {
                Some(d) => v = v * f64::from(radix) + f64::from(d),
                None => return f64::NAN,
            }
        }
        return if t.len() > 2 { v } else { f64::NAN };
    }
    if !t.chars().all(|c| c.is_ascii_digit() || matches!(c, '.' | 'e' | 'E' | '+' | '-')) {
        return f64::NAN;
    }
    t.parse::<f64>().unwrap_or(f64::NAN)
}

/// `parseFloat`: the longest numeric prefix.
pub(super) fn parse_float(s: &str) -> f64 {
    let t = s.trim_start_matches(is_js_space);
    let b = t.as_bytes();
    let mut i = 0;
    if i < b.len() && (b[i] == b'+' || b[i] == b'-') {
        i += 1;
    }
    if t[i..].starts_with("Infinity") {
        return if b.first() == Some(&b'-') { f64::NEG_INFINITY } else { f64::INFINITY };
    }
    let digits_from = |mut j: usize| {
        while j < b.len() && b[j].is_ascii_digit() {
            j += 1;
        }
        j
    };
    let int_end = digits_from(i);
    let mut end = int_end;
    if end < b.len() && b[end] == b'.' {
        let frac_end = digits_from(end + 1);
        if frac_end > end + 1 || int_end > i {
            end = frac_end;
        }
    }
    if end == i || (end == i + 1 && b.get(i) == Some(&b'.')) {
        return f64::NAN;
    }
    if end < b.len() && (b[end] == b'e' || b[end] == b'E') {
        let mut j = end + 1;
        if j < b.len() && (b[j] == b'+' || b[j] == b'-') {
            j += 1;
        }
        let exp_end = digits_from(j);
        if exp_end > j {
            end = exp_end;
        }
    }
    t[..end].parse::<f64>().unwrap_or(f64::NAN)
}

pub(super) fn to_int32(x: f64) -> i32 {
    to_uint32(x) as i32
}

pub(super) fn to_uint32(x: f64) -> u32 {
    if !x.is_finite() {
        return 0;
    }
    x.trunc().rem_euclid(4_294_967_296.0) as u32
}

/// `**` and `Math.pow` (JavaScript differs from `powf` at ±1 ** ±Infinity and NaN).
pub(super) fn js_pow(a: f64, b: f64) -> f64 {
    if b.is_nan() || ((a == 1.0 || a == -1.0) && b.is_infinite()) {
        return f64::NAN;
    }
    a.powf(b)
}

pub(super) fn truthy(v: &Value) -> bool {
    match v {
        Value::Undefined | Value::Null => false,
        Value::Bool(b) => *b,
        Value::Num(n) => *n != 0.0 && !n.is_nan(),
        Value::Str(s) => !s.is_empty(),
        Value::Obj(_) => true,
    }
}

pub(super) fn strict_eq(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::Num(x), Value::Num(y)) => x == y,
        _ => a == b,
    }
}

/// A canonical array index ("3", not "03" or "3.0") becomes a numeric key.
pub(super) fn key_from_str(s: &str) -> Key {
    if !s.is_empty()
        && s.len() <= 15
        && s.bytes().all(|c| c.is_ascii_digit())
        && (s == "0" || !s.starts_with('0'))
        && let Ok(i) = s.parse::<usize>()
    {
        return Key::Index(i);
    }
    Key::Name(Arc::from(s))
}

impl Interp {
    pub(super) fn typeof_str(&self, v: &Value) -> &'static str {
        match v {
            Value::Undefined => "undefined",
            Value::Null => "object",
            Value::Bool(_) => "boolean",
            Value::Num(_) => "number",
            Value::Str(_) => "string",
            Value::Obj(id) => match self.obj(*id).kind {
                ObjKind::Closure(_) | ObjKind::Class(_) | ObjKind::Native { .. } => "function",
                _ => "object",
            },
        }
    }

    pub(super) fn key_of(&mut self, v: &Value, line: usize) -> R<Key> {
        match v {
            Value::Num(n) if *n >= 0.0 && n.fract() == 0.0 && *n < 9.0e15 => Ok(Key::Index(*n as usize)),
            Value::Str(s) => Ok(key_from_str(s)),
            other => Ok(Key::Name(self.string_of(other, line)?)),
        }
    }

    pub(super) fn number_of(&mut self, v: &Value, line: usize) -> R<f64> {
        Ok(match v {
            Value::Undefined => f64::NAN,
            Value::Null => 0.0,
            Value::Bool(b) => f64::from(u8::from(*b)),
            Value::Num(n) => *n,
            Value::Str(s) => str_to_num(s),
            Value::Obj(_) => {
                let s = self.string_of(v, line)?;
                str_to_num(&s)
            }
        })
    }

    /// Objects become strings (arrays join), as JavaScript's default conversion does.
    pub(super) fn primitive_of(&mut self, v: Value, line: usize) -> R<Value> {
        match v {
            Value::Obj(_) => Ok(Value::Str(self.string_of(&v, line)?)),
            other => Ok(other),
        }
    }

    pub(super) fn string_of(&mut self, v: &Value, line: usize) -> R<Name> {
        self.string_of_depth(v, line, 0)
    }

    fn string_of_depth(&mut self, v: &Value, line: usize, depth: usize) -> R<Name> {
        let id = match v {
            Value::Undefined => return Ok(Arc::from("undefined")),
            Value::Null => return Ok(Arc::from("null")),
            Value::Bool(b) => return Ok(Arc::from(if *b { "true" } else { "false" })),
            Value::Num(n) => return Ok(Arc::from(num_to_string(*n))),
            Value::Str(s) => return Ok(s.clone()),
            Value::Obj(id) => *id,
        };
        let text = match &self.obj(id).kind {
            ObjKind::Array(_) | ObjKind::F32(_) => return self.join(id, ",", line, depth).map(Arc::from),
            ObjKind::Closure(c) => format!("function {}() {{ ... }}", c.def.name.as_deref().unwrap_or("")),
            ObjKind::Class(c) => format!("class {}", c.def.name.as_deref().unwrap_or("")),
            ObjKind::Native { name, .. } => format!("function {name}() {{ [native code] }}"),
            ObjKind::Error { .. } => {
                let name = self.get_member(v, &Key::name("name"), line)?;
                let msg = self.get_member(v, &Key::name("message"), line)?;
                let name = if name.is_nullish() {
                    Arc::from("Error")
                } else {
                    self.string_of_depth(&name, line, depth + 1)?
                };
                let msg = if msg.is_nullish() {
                    Arc::from("")
                } else {
                    self.string_of_depth(&msg, line, depth + 1)?
                };
                if msg.is_empty() { name.to_string() } else { format!("{name}: {msg}") }
            }
            ObjKind::Plain | ObjKind::Inert => {
                let f = self.get_member(v, &Key::name("toString"), line)?;
                if depth < MAX_JOIN_DEPTH
                    && matches!(f.obj().map(|f| &self.obj(f).kind), Some(ObjKind::Closure(_)))
                {
                    let r = self.call(&f, v.clone(), Vec::new(), line)?;
                    if r.obj().is_none() {
                        return self.string_of_depth(&r, line, depth + 1);
                    }
                }
                "[object Object]".to_string()
            }
        };
        Ok(Arc::from(text))
    }

    /// `Array.prototype.join`, charged one step per element and bounded in length.
    pub(super) fn join(
        &mut self,
        id: super::value::ObjId,
        sep: &str,
        line: usize,
        depth: usize,
    ) -> R<String> {
        if depth > MAX_JOIN_DEPTH {
            return Ok(String::new());
        }
        let len = self.array_len(id);
        self.charge(len as u64, line)?;
        let mut out = String::new();
        for i in 0..len {
            if i > 0 {
                out.push_str(sep);
            }
            let item = self.index_value(id, i);
            if !item.is_nullish() {
                let s = self.string_of_depth(&item, line, depth + 1)?;
                out.push_str(&s);
            }
            self.check_string_len(out.len(), line)?;
        }
        self.charge_memory(out.len(), line)?;
        Ok(out)
    }

    pub(super) fn loose_eq(&mut self, a: &Value, b: &Value, line: usize) -> R<bool> {
        use Value::*;
        Ok(match (a, b) {
            (Undefined | Null, Undefined | Null) => true,
            (Undefined | Null, _) | (_, Undefined | Null) => false,
            (Num(x), Str(s)) | (Str(s), Num(x)) => *x == str_to_num(s),
            (Bool(x), other) | (other, Bool(x)) => {
                let n = Num(f64::from(u8::from(*x)));
                if let Bool(_) = other { strict_eq(a, b) } else { self.loose_eq(&n, other, line)? }
            }
            (Obj(_), Num(_) | Str(_)) => {
                let p = self.primitive_of(a.clone(), line)?;
                self.loose_eq(&p, b, line)?
            }
            (Num(_) | Str(_), Obj(_)) => {
                let p = self.primitive_of(b.clone(), line)?;
                self.loose_eq(a, &p, line)?
            }
            _ => strict_eq(a, b),
        })
    }

    pub(super) fn binary(&mut self, op: BinOp, a: Value, b: Value, line: usize) -> R<Value> {
        use BinOp::*;
        let num = |x: f64| Ok(Value::Num(x));
        match op {
            Add => {
                let (pa, pb) = (self.primitive_of(a, line)?, self.primitive_of(b, line)?);
                if matches!(pa, Value::Str(_)) || matches!(pb, Value::Str(_)) {
                    let (sa, sb) = (self.string_of(&pa, line)?, self.string_of(&pb, line)?);
                    let len = sa.len() + sb.len();
                    self.check_string_len(len, line)?;
                    self.charge((len / 16) as u64, line)?;
                    self.charge_memory(len, line)?;
                    return Ok(Value::Str(Arc::from(format!("{sa}{sb}"))));
                }
                num(self.number_of(&pa, line)? + self.number_of(&pb, line)?)
            }
            Eq => Ok(Value::Bool(self.loose_eq(&a, &b, line)?)),
            Ne => Ok(Value::Bool(!self.loose_eq(&a, &b, line)?)),
            StrictEq => Ok(Value::Bool(strict_eq(&a, &b))),
            StrictNe => Ok(Value::Bool(!strict_eq(&a, &b))),
            Lt | Gt | Le | Ge => {
                let (pa, pb) = (self.primitive_of(a, line)?, self.primitive_of(b, line)?);
                let ord = if let (Value::Str(x), Value::Str(y)) = (&pa, &pb) {
                    Some(x.cmp(y))
                } else {
                    self.number_of(&pa, line)?.partial_cmp(&self.number_of(&pb, line)?)
                };
                let Some(ord) = ord else { return Ok(Value::Bool(false)) };
                Ok(Value::Bool(match op {
                    Lt => ord.is_lt(),
                    Gt => ord.is_gt(),
                    Le => ord.is_le(),
                    _ => ord.is_ge(),
                }))
            }
            InstanceOf => Ok(Value::Bool(self.instance_of(&a, &b, line)?)),
            In => {
                if b.obj().is_none() {
                    return Err(
                        self.type_error(line, "cannot use `in` on a value that is not an object".into())
                    );
                }
                let key = self.key_of(&a, line)?;
                Ok(Value::Bool(self.has_member(&b, &key)))
            }
            _ => {
                let (x, y) = (self.number_of(&a, line)?, self.number_of(&b, line)?);
                match op {
                    Sub => num(x - y),
                    Mul => num(x * y),
                    Div => num(x / y),
                    Rem => num(x % y),
                    Pow => num(js_pow(x, y)),
                    BitAnd => num(f64::from(to_int32(x) & to_int32(y))),
                    BitOr => num(f64::from(to_int32(x) | to_int32(y))),
                    BitXor => num(f64::from(to_int32(x) ^ to_int32(y))),
                    Shl => num(f64::from(to_int32(x).wrapping_shl(to_uint32(y) & 31))),
                    Shr => num(f64::from(to_int32(x) >> (to_uint32(y) & 31))),
                    _ => num(f64::from(to_uint32(x) >> (to_uint32(y) & 31))),
                }
            }
        }
    }

    fn instance_of(&mut self, a: &Value, b: &Value, line: usize) -> R<bool> {
        let Some(ctor) = b.obj().filter(|_| self.is_callable(b)) else {
            return Err(
                self.type_error(line, "the right side of `instanceof` is not a class or function".into())
            );
        };
        let Some(obj) = a.obj() else { return Ok(false) };
        if let ObjKind::Native { name, .. } = self.obj(ctor).kind {
            let kind = &self.obj(obj).kind;
            return Ok(match name {
                "Array" => matches!(kind, ObjKind::Array(_)),
                "Float32Array" => matches!(kind, ObjKind::F32(_)),
                "Error" | "TypeError" | "RangeError" => matches!(kind, ObjKind::Error { .. }),
                "Object" => true,
                _ => false,
            });
        }
        let proto = self.get_member(b, &Key::name("prototype"), line)?;
        let Some(proto) = proto.obj() else { return Ok(false) };
        let mut cur = self.obj(obj).proto;
        let mut hops = 0;
        while let Some(p) = cur {
            if p == proto {
                return Ok(true);
            }
            hops += 1;
            if hops > MAX_PROTO_HOPS {
                break;
            }
            cur = self.obj(p).proto;
        }
        Ok(false)
    }
}

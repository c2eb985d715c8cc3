//! Built-in methods of strings. Work that walks characters is charged to the step budget in
//! proportion.

use super::natives::{int_arg, num_arg, rel_index, short};
use super::value::{Abort, Interp, NativeCall, NativeFn, Value};

type R<T> = Result<T, Abort>;

pub(super) const STRING: [(&str, NativeFn); 20] = [
    ("String.prototype.charAt", string),
    ("String.prototype.at", string),
    ("String.prototype.indexOf", string),
    ("String.prototype.includes", string),
    ("String.prototype.slice", string),
    ("String.prototype.substring", string),
    ("String.prototype.toUpperCase", string),
    ("String.prototype.toLowerCase", string),
    ("String.prototype.trim", string),
    ("String.prototype.trimStart", string),
    ("String.prototype.trimEnd", string),
    ("String.prototype.split", string),
    ("String.prototype.startsWith", string),
    ("String.prototype.endsWith", string),
    ("String.prototype.repeat", string),
    ("String.prototype.padStart", string),
    ("String.prototype.padEnd", string),
    ("String.prototype.concat", string),
    ("String.prototype.toString", string),
    ("String.prototype.replace", string),
];

fn string(it: &mut Interp, c: &NativeCall<'_>) -> R<Value> {
    let s = it.string_of(c.this, c.line)?;
    it.charge((s.len() / 16) as u64, c.line)?;
    let chars: Vec<char> = s.chars().collect();
    let len = chars.len();
    let sub = |a: usize, b: usize| -> String { chars.get(a..b.max(a)).unwrap_or(&[]).iter().collect() };
    let arg_str = |it: &mut Interp, i: usize| -> R<String> {
        match c.arg(i) {
            Value::Undefined => Ok(String::new()),
            v => Ok(it.string_of(&v, c.line)?.to_string()),
        }
    };
    let out = match short(c) {
        "charAt" | "at" => {
            let i = int_arg(it, c, 0, 0.0)?;
            let i = if i < 0.0 && short(c) == "at" { len as f64 + i } else { i };
            if i >= 0.0 && i < len as f64 {
                sub(i as usize, i as usize + 1)
            } else if short(c) == "at" {
                return Ok(Value::Undefined);
            } else {
                String::new()
            }
        }
        "indexOf" | "includes" | "startsWith" | "endsWith" => {
            let needle: Vec<char> = arg_str(it, 0)?.chars().collect();
            let hit = (0..=len.saturating_sub(needle.len()))
                .find(|i| chars.get(*i..*i + needle.len()) == Some(&needle[..]));
            return Ok(match short(c) {
                "indexOf" => Value::Num(hit.map_or(-1.0, |i| i as f64)),
                "includes" => Value::Bool(hit.is_some()),
                "startsWith" => Value::Bool(chars.starts_with(&needle)),
                _ => Value::Bool(chars.ends_with(&needle)),
            });
        }
        "slice" => {
            let a = rel_index(int_arg(it, c, 0, 0.0)?, len);
            sub(a, rel_index(int_arg(it, c, 1, len as f64)?, len))
        }
        "substring" => {
            let a = int_arg(it, c, 0, 0.0)?.clamp(0.0, len as f64) as usize;
            let b = int_arg(it, c, 1, len as f64)?.clamp(0.0, len as f64) as usize;
            sub(a.min(b), a.max(b))
        }
        "toUpperCase" => s.to_uppercase(),
        "toLowerCase" => s.to_lowercase(),
        "trim" => s.trim_matches(super::ops::is_js_space).to_string(),
        "trimStart" => s.trim_start_matches(super::ops::is_js_space).to_string(),
        "trimEnd" => s.trim_end_matches(super::ops::is_js_space).to_string(),
        "split" => {
            let parts: Vec<Value> = match c.arg(0) {
                Value::Undefined => vec![Value::Str(s.clone())],
                _ => {
                    let sep = arg_str(it, 0)?;
                    if sep.is_empty() {
                        chars.iter().map(|ch| Value::str(&ch.to_string())).collect()
                    } else {
                        s.split(sep.as_str()).map(Value::str).collect()
                    }
                }
            };
            return it.new_array(parts, c.line);
        }
        "repeat" => {
            let n = num_arg(it, c, 0)?;
            if !(n >= 0.0 && n.is_finite()) || (s.len() as f64) * n > it.limits.string_len as f64 {
                return Err(it.fatal(
                    c.line,
                    format!("String.repeat would pass {} bytes or has a bad count", it.limits.string_len),
                ));
            }
            s.repeat(n as usize)
        }
        "padStart" | "padEnd" => {
            let target = int_arg(it, c, 0, 0.0)?;
            if target > it.limits.string_len as f64 {
                return Err(it.fatal(c.line, format!("a string longer than {} bytes", it.limits.string_len)));
            }
            let fill = if matches!(c.arg(1), Value::Undefined) { " ".to_string() } else { arg_str(it, 1)? };
            let need = (target.max(0.0) as usize).saturating_sub(len);
            let pad: String = fill.chars().cycle().take(if fill.is_empty() { 0 } else { need }).collect();
            if short(c) == "padStart" { pad + &s } else { s.to_string() + &pad }
        }
        "concat" => {
            let mut out = s.to_string();
            for i in 0..c.args.len() {
                out.push_str(&arg_str(it, i)?);
                it.check_string_len(out.len(), c.line)?;
            }
            out
        }
        "replace" => {
            let (from, to) = (arg_str(it, 0)?, arg_str(it, 1)?);
            s.replacen(from.as_str(), &to, 1)
        }
        _ => s.to_string(),
    };
    it.new_string(out, c.line)
}

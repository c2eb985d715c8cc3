//! Reading the light engine.js builds, without running engine.js (it needs a browser):
//! find the first `new DirectionalLight(...)`, and evaluate its first five arguments in
//! the sandbox, resolving a name to its nearest preceding `NAME = EXPR` in the file.

use super::ast::{Expr, ExprKind, Item, Name, ObjProp};
use super::builtins;
use super::interp::GLOBAL;
use super::lex::{self, Tok, Token};
use super::ops::num_to_string;
use super::parse;
use super::value::{Interp, ObjKind, Value};
use super::{EngineLight, Limits, MAX_SOURCE_BYTES, Sourced};

/// How many definitions deep a value may refer to others (`a = b * 2; b = c; ...`).
const MAX_RESOLVE_DEPTH: usize = 8;

/// How many names reading the light may look up in all (each look-up scans the file).
const MAX_RESOLVES: usize = 64;

const WHAT: [&str; 5] = ["intensity", "color", "position", "focal point", "up vector"];

/// Reads engine.js's light. Never fails: anything unreadable keeps the framework's value,
/// with a note saying which argument and why.
pub fn engine_light(source: &str, file: &str, limits: Limits) -> EngineLight {
    let mut light = EngineLight::framework();
    if source.len() > MAX_SOURCE_BYTES {
        light
            .notes
            .push(format!("{file} is larger than {MAX_SOURCE_BYTES} bytes: used the framework's light"));
        return light;
    }
    let lexed = lex::lex(source, file);
    let toks = &lexed.tokens;
    let calls: Vec<usize> = (0..toks.len())
        .filter(|&i| {
            matches!(&toks[i].tok, Tok::Ident(w) if &**w == "new")
                && matches!(toks.get(i + 1).map(|t| &t.tok), Some(Tok::Ident(w)) if &**w == "DirectionalLight")
                && matches!(toks.get(i + 2).map(|t| &t.tok), Some(Tok::Punct("(")))
        })
        .collect();
    let Some(&at) = calls.first() else {
        let why = match &lexed.error {
            Some(e) => format!("{file} could not be read past line {} ({})", e.line, e.message),
            None => format!("{file} has no `new DirectionalLight(...)`"),
        };
        light.notes.push(format!("{why}: used the framework's light"));
        return light;
    };
    if calls.len() > 1 {
        light.notes.push(format!(
            "{file} makes {} DirectionalLights; the first (line {}) is used",
            calls.len(),
            toks[at].line
        ));
    }
    let call = match parse::parse_prefix(&toks[at..], file, limits.nesting) {
        Ok(Expr { kind: ExprKind::New { args, .. }, .. }) => args,
        Ok(_) => Vec::new(),
        Err(e) => {
            light.notes.push(format!("{file}:{}: the `new DirectionalLight(...)` call could not be read ({}): used the framework's light", e.line, e.message));
            return light;
        }
    };
    let mut reader =
        Reader { it: builtins::interpreter(file, limits), toks, file, nesting: limits.nesting, resolves: 0 };
    for (i, what) in WHAT.iter().enumerate() {
        let read = match call.get(i) {
            Some(Item::Plain(e)) => {
                reader.argument(e, at).and_then(|(v, line)| reader.convert(i, &v).map(|x| (x, line)))
            }
            Some(_) => Err("it is spread or empty".into()),
            None => Err("it is missing".into()),
        };
        match read {
            Ok((Converted::Num(x), line)) => light.intensity = reader.sourced(x, line),
            Ok((Converted::Vec3(v), line)) => {
                let s = reader.sourced(v, line);
                match i {
                    1 => light.color = s,
                    2 => light.position = s,
                    3 => light.focal_point = s,
                    _ => light.up = s,
                }
            }
            Err(why) => {
                let fallback = match i {
                    0 => num_to_string(light.intensity.value),
                    1 => show(light.color.value),
                    2 => show(light.position.value),
                    3 => show(light.focal_point.value),
                    _ => show(light.up.value),
                };
                let line = toks[at].line;
                light.notes.push(format!("{file}:{line}: the light's {what} (argument {}) could not be read: {why}; used the framework's {fallback}", i + 1));
            }
        }
    }
    light
}

fn show(v: [f64; 3]) -> String {
    format!("[{}, {}, {}]", num_to_string(v[0]), num_to_string(v[1]), num_to_string(v[2]))
}

enum Converted {
    Num(f64),
    Vec3([f64; 3]),
}

struct Reader<'a> {
    it: Interp,
    toks: &'a [Token],
    file: &'a str,
    nesting: usize,
    resolves: usize,
}

impl Reader<'_> {
    fn sourced<T>(&self, value: T, line: usize) -> Sourced<T> {
        Sourced { value, file: self.file.to_string(), line }
    }

    /// An argument's value and the line it was written on (a name: its definition's line).
    fn argument(&mut self, e: &Expr, before: usize) -> Result<(Value, usize), String> {
        if let ExprKind::Ident(name) = &e.kind
            && self.it.lookup_var(GLOBAL, name).is_none()
        {
            let (expr, line) = self.resolve(name, before, 0)?;
            let v = self.eval(&expr)?;
            return Ok((v, line));
        }
        self.define_free_names(e, before, 0)?;
        Ok((self.eval(e)?, e.line))
    }

    fn eval(&mut self, e: &Expr) -> Result<Value, String> {
        self.it.reset_budget();
        self.it.eval_expr(e, GLOBAL).map_err(|a| self.it.uncaught(a).message)
    }

    /// The nearest `NAME = EXPR` before token `before` (not `obj.NAME = ...`).
    fn resolve(&mut self, name: &Name, before: usize, depth: usize) -> Result<(Expr, usize), String> {
        if depth > MAX_RESOLVE_DEPTH {
            return Err(format!("`{name}` is defined through more than {MAX_RESOLVE_DEPTH} other names"));
        }
        self.resolves += 1;
        if self.resolves > MAX_RESOLVES {
            return Err(format!("the light's values use more than {MAX_RESOLVES} names"));
        }
        let def = (1..before.min(self.toks.len())).rev().find(|&i| {
            matches!(&self.toks[i - 1].tok, Tok::Ident(w) if w == name)
                && matches!(self.toks[i].tok, Tok::Punct("="))
                && !(i >= 2 && matches!(self.toks[i - 2].tok, Tok::Punct(".")))
        });
        let Some(eq) = def else { return Err(format!("`{name}` is not defined before the call")) };
        let line = self.toks[eq - 1].line;
        let expr = parse::parse_prefix(&self.toks[eq + 1..], self.file, self.nesting)
            .map_err(|e| format!("the definition of `{name}` on line {line}: {}", e.message))?;
        self.define_free_names(&expr, eq - 1, depth + 1)?;
        Ok((expr, line))
    }

    /// Evaluates and defines the names `e` uses that the sandbox does not know yet.
    fn define_free_names(&mut self, e: &Expr, before: usize, depth: usize) -> Result<(), String> {
        let mut names = Vec::new();
        free_names(e, &mut names, 0);
        for n in names {
            if self.it.lookup_var(GLOBAL, &n).is_some() {
                continue;
            }
            let (expr, _) = self.resolve(&n, before, depth)?;
            let v = self.eval(&expr)?;
            self.it.declare(GLOBAL, n, v, true);
        }
        Ok(())
    }

    fn convert(&self, i: usize, v: &Value) -> Result<Converted, String> {
        if i == 0 {
            return match v {
                Value::Num(x) if x.is_finite() => Ok(Converted::Num(*x)),
                other => Err(format!("it is {}, not a finite number", self.describe(other))),
            };
        }
        let id = v.obj().filter(|id| matches!(self.it.obj(*id).kind, ObjKind::Array(_) | ObjKind::F32(_)));
        let Some(id) = id else {
            return Err(format!("it is {}, not an array of 3 numbers", self.describe(v)));
        };
        let len = self.it.array_len(id);
        if len != 3 {
            return Err(format!("it has {len} elements, not 3"));
        }
        let mut out = [0.0; 3];
        for (k, slot) in out.iter_mut().enumerate() {
            match self.it.index_value(id, k) {
                Value::Num(x) if x.is_finite() => *slot = x,
                other => {
                    return Err(format!("its element {k} is {}, not a finite number", self.describe(&other)));
                }
            }
        }
        Ok(Converted::Vec3(out))
    }

    fn describe(&self, v: &Value) -> String {
        match v {
            Value::Num(x) => num_to_string(*x),
            other => self.it.typeof_str(other).to_string(),
        }
    }
}

/// Identifiers an expression reads (not property names, not inside functions); stops a
/// little past the look-up limit.
fn item_exprs(items: &[Item]) -> impl Iterator<Item = &Expr> {
    items.iter().filter_map(|i| if let Item::Plain(x) | Item::Spread(x) = i { Some(x) } else { None })
}

fn free_names(e: &Expr, out: &mut Vec<Name>, depth: usize) {
    if depth > 64 || out.len() > MAX_RESOLVES {
        return;
    }
    let mut kids: Vec<&Expr> = Vec::new();
    match &e.kind {
        ExprKind::Ident(n) if !out.contains(n) => out.push(n.clone()),
        ExprKind::Array(list) => kids.extend(item_exprs(list)),
        ExprKind::Call { callee, args, .. } | ExprKind::New { callee, args } => {
            kids.push(callee);
            kids.extend(item_exprs(args));
        }
        ExprKind::Template { exprs, .. } | ExprKind::Seq(exprs) => kids.extend(exprs.iter()),
        ExprKind::Object(props) => {
            kids.extend(props.iter().filter_map(|p| {
                if let ObjProp::Value(_, x) | ObjProp::Spread(x) = p { Some(x) } else { None }
            }));
        }
        ExprKind::Unary(_, x) | ExprKind::OptChain(x) | ExprKind::Member { obj: x, .. } => kids.push(x),
        ExprKind::Binary(_, a, b) | ExprKind::Logical(_, a, b) | ExprKind::Index { obj: a, index: b, .. } => {
            kids.push(a);
            kids.push(b);
        }
        ExprKind::Cond(a, b, c) => kids.extend([&**a, &**b, &**c]),
        _ => {}
    }
    for k in kids {
        free_names(k, out, depth + 1);
    }
}

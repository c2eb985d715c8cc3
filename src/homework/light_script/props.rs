//! Reading and writing properties: array and Float32Array elements, `length`, own and
//! inherited properties, accessors, and the built-in methods of arrays, strings,
//! numbers and functions.

use super::ast::Name;
use super::value::{Abort, Interp, Key, MAX_PROTO_HOPS, ObjId, ObjKind, Prop, Value};

type R<T> = Result<T, Abort>;

impl Interp {
    pub(super) fn is_callable(&self, v: &Value) -> bool {
        v.obj().is_some_and(|id| {
            matches!(
                self.obj(id).kind,
                ObjKind::Closure(_) | ObjKind::Class(_) | ObjKind::Native { .. } | ObjKind::Inert
            )
        })
    }

    pub(super) fn array_len(&self, id: ObjId) -> usize {
        match &self.obj(id).kind {
            ObjKind::Array(v) => v.len(),
            ObjKind::F32(v) => v.len(),
            _ => 0,
        }
    }

    pub(super) fn index_value(&self, id: ObjId, i: usize) -> Value {
        match &self.obj(id).kind {
            ObjKind::Array(v) => v.get(i).cloned().unwrap_or(Value::Undefined),
            ObjKind::F32(v) => v.get(i).map_or(Value::Undefined, |x| Value::Num(f64::from(*x))),
            _ => Value::Undefined,
        }
    }

    /// An own or inherited property.
    pub(super) fn find_prop(&self, id: ObjId, name: &str) -> Option<Prop> {
        let mut cur = Some(id);
        let mut hops = 0;
        while let Some(c) = cur {
            let o = self.obj(c);
            if let Some(p) = o.props.get(name) {
                return Some(p.clone());
            }
            hops += 1;
            if hops > MAX_PROTO_HOPS {
                return None;
            }
            cur = o.proto;
        }
        None
    }

    /// The shared native object for a built-in method (`array.push`), made on first use.
    fn builtin_method(&mut self, table: &str, name: &str) -> Option<Value> {
        let (full, f) = super::methods::lookup(table, name)?;
        if let Some(id) = self.method_cache.get(full) {
            return Some(Value::Obj(*id));
        }
        let id = self.alloc_raw(ObjKind::Native { name: full, f }, None);
        self.method_cache.insert(full, id);
        Some(Value::Obj(id))
    }

    pub(super) fn get_member(&mut self, base: &Value, key: &Key, line: usize) -> R<Value> {
        match base {
            Value::Undefined | Value::Null => {
                let what = if *base == Value::Null { "null" } else { "undefined" };
                Err(self.type_error(line, format!("cannot read `{}` of {what}", key.text())))
            }
            Value::Bool(_) => Ok(Value::Undefined),
            Value::Num(_) => Ok(self.builtin_method("number", &key.text()).unwrap_or(Value::Undefined)),
            Value::Str(s) => {
                let s = s.clone();
                match key {
                    Key::Index(i) => {
                        self.charge((*i / 16) as u64, line)?;
                        Ok(s.chars()
                            .nth(*i)
                            .map_or(Value::Undefined, |c| Value::str(c.encode_utf8(&mut [0; 4]))))
                    }
                    Key::Name(n) if &**n == "length" => {
                        self.charge((s.len() / 16) as u64, line)?;
                        Ok(Value::Num(s.chars().count() as f64))
                    }
                    Key::Name(n) => Ok(self.builtin_method("string", n).unwrap_or(Value::Undefined)),
                }
            }
            Value::Obj(id) => self.get_obj_member(*id, key, base, line),
        }
    }

    fn get_obj_member(&mut self, id: ObjId, key: &Key, receiver: &Value, line: usize) -> R<Value> {
        let name: Name = match (&self.obj(id).kind, key) {
            (ObjKind::Array(_) | ObjKind::F32(_), Key::Index(i)) => return Ok(self.index_value(id, *i)),
            (ObjKind::Array(_) | ObjKind::F32(_), Key::Name(n)) if &**n == "length" => {
                return Ok(Value::Num(self.array_len(id) as f64));
            }
            (ObjKind::F32(_), Key::Name(n)) if &**n == "BYTES_PER_ELEMENT" => return Ok(Value::Num(4.0)),
            _ => key.text(),
        };
        match self.find_prop(id, &name) {
            Some(Prop::Data(v)) => return Ok(v),
            Some(Prop::Accessor { get: Some(g), .. }) => {
                return self.call(&Value::Obj(g), receiver.clone(), Vec::new(), line);
            }
            Some(Prop::Accessor { get: None, .. }) => return Ok(Value::Undefined),
            None => {}
        }
        let table = match &self.obj(id).kind {
            ObjKind::Array(_) => "array",
            ObjKind::F32(_) => "f32",
            ObjKind::Closure(_) | ObjKind::Class(_) | ObjKind::Native { .. } => "function",
            ObjKind::Inert => return Ok(Value::Obj(self.sink)),
            _ => "",
        };
        if let Some(m) = self.builtin_method(table, &name) {
            return Ok(m);
        }
        let fn_name = match &self.obj(id).kind {
            ObjKind::Closure(c) if &*name == "prototype" && !c.def.arrow => {
                // A plain function's prototype object is made when first asked for.
                let proto = self.alloc(ObjKind::Plain, None, line)?;
                self.set_own(proto, "constructor", Value::Obj(id));
                self.set_own(id, "prototype", Value::Obj(proto));
                return Ok(Value::Obj(proto));
            }
            ObjKind::Closure(c) => c.def.name.clone(),
            ObjKind::Class(c) => c.def.name.clone(),
            ObjKind::Native { name, .. } => Some(Name::from(name.rsplit('.').next().unwrap_or(name))),
            _ => None,
        };
        match fn_name {
            Some(n) if &*name == "name" => Ok(Value::Str(n)),
            _ => Ok(Value::Undefined),
        }
    }

    pub(super) fn has_member(&self, base: &Value, key: &Key) -> bool {
        let Some(id) = base.obj() else { return false };
        match (&self.obj(id).kind, key) {
            (ObjKind::Array(_) | ObjKind::F32(_), Key::Index(i)) => *i < self.array_len(id),
            (ObjKind::Array(_) | ObjKind::F32(_), Key::Name(n)) if &**n == "length" => true,
            _ => self.find_prop(id, &key.text()).is_some(),
        }
    }

    pub(super) fn set_member(&mut self, base: &Value, key: &Key, value: Value, line: usize) -> R<()> {
        let id = match base {
            Value::Undefined | Value::Null => {
                let what = if *base == Value::Null { "null" } else { "undefined" };
                return Err(self.type_error(line, format!("cannot set `{}` of {what}", key.text())));
            }
            Value::Obj(id) => *id,
            _ => return Ok(()),
        };
        if id == self.sink {
            return Ok(());
        }
        let is_length = matches!(key, Key::Name(n) if &**n == "length");
        match (&self.obj(id).kind, key) {
            (ObjKind::Array(_), Key::Index(i)) => return self.set_array_index(id, *i, value, line),
            (ObjKind::Array(_), _) if is_length => {
                let n = self.number_of(&value, line)?;
                if !(n >= 0.0 && n.fract() == 0.0 && n <= self.limits.array_len as f64) {
                    return Err(self.fatal(
                        line,
                        format!("array length {n} is invalid here (at most {})", self.limits.array_len),
                    ));
                }
                let (n, len) = (n as usize, self.array_len(id));
                self.charge(n.saturating_sub(len) as u64, line)?;
                self.charge_values(n.saturating_sub(len), line)?;
                if let ObjKind::Array(v) = &mut self.obj_mut(id).kind {
                    v.resize(n, Value::Undefined);
                }
                return Ok(());
            }
            (ObjKind::F32(_), Key::Index(i)) => {
                let x = self.number_of(&value, line)?;
                if let ObjKind::F32(v) = &mut self.obj_mut(id).kind
                    && let Some(slot) = v.get_mut(*i)
                {
                    *slot = x as f32;
                }
                return Ok(());
            }
            (ObjKind::F32(_), _) if is_length => return Ok(()),
            _ => {}
        }
        let name = key.text();
        match self.find_prop(id, &name) {
            Some(Prop::Accessor { set: Some(s), .. }) => {
                self.call(&Value::Obj(s), base.clone(), vec![value], line)?;
                return Ok(());
            }
            Some(Prop::Accessor { set: None, .. }) => return Ok(()),
            _ => {}
        }
        let props = &self.obj(id).props;
        if props.get(&name).is_none() {
            if props.len() >= self.limits.array_len {
                return Err(self
                    .fatal(line, format!("an object with more than {} properties", self.limits.array_len)));
            }
            self.charge_memory(name.len() + 2 * std::mem::size_of::<Value>() + 32, line)?;
        }
        self.obj_mut(id).props.insert(name, Prop::Data(value));
        Ok(())
    }

    fn set_array_index(&mut self, id: ObjId, i: usize, value: Value, line: usize) -> R<()> {
        let len = self.array_len(id);
        if i >= len {
            self.check_array_len(i.saturating_add(1), line)?;
            self.charge((i + 1 - len) as u64, line)?;
            self.charge_values(i + 1 - len, line)?;
        }
        if let ObjKind::Array(v) = &mut self.obj_mut(id).kind {
            if i >= v.len() {
                v.resize(i + 1, Value::Undefined);
            }
            v[i] = value;
        }
        Ok(())
    }

    /// Adds a getter or setter, keeping the other half if one exists.
    pub(super) fn define_accessor(
        &mut self,
        target: ObjId,
        name: Name,
        get: Option<ObjId>,
        set: Option<ObjId>,
    ) {
        let (old_get, old_set) = match self.obj(target).props.get(&name) {
            Some(Prop::Accessor { get, set }) => (*get, *set),
            _ => (None, None),
        };
        let prop = Prop::Accessor { get: get.or(old_get), set: set.or(old_set) };
        self.obj_mut(target).props.insert(name, prop);
    }
}

//! The rules that need types, read from naga's module of the rewritten shader: GLSL 450 converts an
//! int to a float wherever one is wanted (and naga's front end does the same), GLSL ES 1.00 never
//! does (§4.1.10: "there are no implicit conversions"). naga marks each conversion it adds with the
//! span of the operand, an explicit one (`float(i)`, `vec2(1, i)`) with the constructor's: so a
//! conversion whose text is not a constructor's is one the browser refuses.

use super::{Refusal, Rule};
use naga::{Arena, Expression, Handle, Literal, ScalarKind, Span, Statement, TypeInner};

/// The rewritten text and how its lines map to the student's.
pub struct Text<'a> {
    glsl: &'a str,
    /// The student's line for a rewritten line; none for what the rewrite added around them.
    student_line: &'a dyn Fn(usize) -> Option<usize>,
    /// Where each line of `glsl` starts, bytes.
    line_starts: Vec<usize>,
}

impl<'a> Text<'a> {
    pub fn new(glsl: &'a str, student_line: &'a dyn Fn(usize) -> Option<usize>) -> Self {
        let line_starts = std::iter::once(0).chain(glsl.match_indices('\n').map(|(i, _)| i + 1)).collect();
        Text { glsl, student_line, line_starts }
    }

    /// The 1-based line of byte `at`.
    fn line_of(&self, at: usize) -> usize {
        self.line_starts.partition_point(|&start| start <= at)
    }

    fn of(&self, span: Span) -> &str {
        span.to_range().and_then(|r| self.glsl.get(r)).unwrap_or("").trim()
    }

    /// The student's line where `span` starts (or ends, with `end`).
    fn line(&self, span: Span, end: bool) -> Option<usize> {
        let range = span.to_range()?;
        let at = if end { range.end.saturating_sub(1) } else { range.start };
        (self.student_line)(self.line_of(at))
    }

    /// The `#define` on the student's line `line`, if that line is one: (name, body).
    fn define_on(&self, span: Span) -> Option<(String, String)> {
        let start = span.to_range()?.start;
        let line_start = *self.line_starts.get(self.line_of(start).checked_sub(1)?)?;
        let line_text = self.glsl.get(line_start..)?.lines().next()?.trim();
        let rest = line_text.strip_prefix('#')?.trim_start().strip_prefix("define")?;
        let mut words = rest.split_whitespace();
        let name = words.next()?.to_string();
        Some((name, words.collect::<Vec<_>>().join(" ")))
    }
}

/// The types a constructor can name: an int inside one of these is converted explicitly.
const CONSTRUCTORS: [&str; 16] = [
    "float", "int", "bool", "vec2", "vec3", "vec4", "ivec2", "ivec3", "ivec4", "bvec2", "bvec3", "bvec4",
    "mat2", "mat3", "mat4", "mat",
];

fn is_constructor(text: &str) -> bool {
    let name: String = text.chars().take_while(|c| c.is_ascii_alphanumeric() || *c == '_').collect();
    CONSTRUCTORS.contains(&name.as_str()) && text[name.len()..].trim_start().starts_with('(')
}

fn is_int_literal(text: &str) -> bool {
    let digits = text.strip_prefix("0x").or_else(|| text.strip_prefix("0X"));
    match digits {
        Some(hex) => !hex.is_empty() && hex.chars().all(|c| c.is_ascii_hexdigit()),
        None => !text.is_empty() && text.chars().all(|c| c.is_ascii_digit()),
    }
}

/// The expressions `e` reads.
fn operands(e: &Expression) -> Vec<Handle<Expression>> {
    match *e {
        Expression::Binary { left, right, .. } => vec![left, right],
        Expression::Unary { expr, .. }
        | Expression::As { expr, .. }
        | Expression::Splat { value: expr, .. } => {
            vec![expr]
        }
        Expression::Select { condition, accept, reject } => vec![condition, accept, reject],
        Expression::Compose { ref components, .. } => components.clone(),
        Expression::Access { base, index } => vec![base, index],
        Expression::Math { arg, arg1, arg2, arg3, .. } => {
            [Some(arg), arg1, arg2, arg3].into_iter().flatten().collect()
        }
        Expression::Relational { argument, .. } => vec![argument],
        _ => Vec::new(),
    }
}

/// Every implicit int-to-float conversion in the module, and every `return` of an int literal
/// from a float function.
pub fn conversions(module: &naga::Module, text: &Text, refusals: &mut Vec<Refusal>) {
    arena(&module.global_expressions, None, text, refusals);
    let functions =
        module.functions.iter().map(|(_, f)| f).chain(module.entry_points.iter().map(|e| &e.function));
    for f in functions {
        arena(&f.expressions, Some(&f.body), text, refusals);
        let returns_float = f
            .result
            .as_ref()
            .is_some_and(|r| module.types[r.ty].inner.scalar_kind() == Some(ScalarKind::Float));
        if returns_float {
            int_returns(&f.body, &f.expressions, text, refusals);
        }
    }
}

fn arena(
    expressions: &Arena<Expression>,
    body: Option<&naga::Block>,
    text: &Text,
    refusals: &mut Vec<Refusal>,
) {
    let mut parent: Vec<Option<Handle<Expression>>> = vec![None; expressions.len()];
    for (h, e) in expressions.iter() {
        for o in operands(e) {
            if let Some(p) = parent.get_mut(o.index()) {
                p.get_or_insert(h);
            }
        }
    }
    for (h, e) in expressions.iter() {
        let span = expressions.get_span(h);
        let written = text.of(span);
        let implicit = match *e {
            Expression::Literal(Literal::F32(_) | Literal::F64(_)) => is_int_literal(written),
            Expression::As { kind: ScalarKind::Float, convert: Some(_), .. } => !is_constructor(written),
            _ => false,
        };
        if !implicit || written.is_empty() {
            continue;
        }
        let in_constructor = parent[h.index()].is_some_and(|p| {
            matches!(expressions[p], Expression::Compose { .. } | Expression::Splat { .. })
                && is_constructor(text.of(expressions.get_span(p)))
        });
        if in_constructor {
            continue;
        }
        let Some(mut line) = text.line(span, false) else { continue };
        let mut what = format!("`{written}`");
        let mut instead =
            if is_int_literal(written) { format!("{written}.0") } else { format!("float({written})") };
        if let Some((name, value)) = text.define_on(span) {
            // The int came from a macro: say which, and where it is used.
            what = format!("`{name}` (#define {name} {value}, line {line})");
            instead = format!("{value}.0 in the #define, or float({name})");
            let used =
                parent[h.index()].map(|p| expressions.get_span(p)).or_else(|| body_span_using(body, h));
            if let Some(l) = used.and_then(|s| text.line(s, true)) {
                line = l;
            }
        }
        refusals.push(Refusal {
            line,
            rule: Rule::ImplicitConversion,
            message: format!(
                "{what} is an int where a float is needed; GLSL ES 1.00 converts no int to a float implicitly \
                 (§4.1.10); write {instead}"
            ),
        });
    }
}

/// The span of the statement in `block` (or a block within it) that reads `h`.
fn body_span_using(block: Option<&naga::Block>, h: Handle<Expression>) -> Option<Span> {
    let block = block?;
    for (s, span) in block.span_iter() {
        let reads = match *s {
            Statement::Store { value, .. } => value == h,
            Statement::Return { value } => value == Some(h),
            Statement::Call { ref arguments, .. } => arguments.contains(&h),
            Statement::If { condition, .. } => condition == h,
            _ => false,
        };
        if reads {
            return Some(*span);
        }
        let inner = match *s {
            Statement::Block(ref b) => body_span_using(Some(b), h),
            Statement::If { ref accept, ref reject, .. } => {
                body_span_using(Some(accept), h).or_else(|| body_span_using(Some(reject), h))
            }
            Statement::Loop { ref body, ref continuing, .. } => {
                body_span_using(Some(body), h).or_else(|| body_span_using(Some(continuing), h))
            }
            _ => None,
        };
        if inner.is_some() {
            return inner;
        }
    }
    None
}

/// `return 1;` in a function that returns a float.
fn int_returns(
    block: &naga::Block,
    expressions: &Arena<Expression>,
    text: &Text,
    refusals: &mut Vec<Refusal>,
) {
    for s in block.iter() {
        match *s {
            Statement::Return { value: Some(v) } => {
                if let Expression::Literal(Literal::I32(_) | Literal::U32(_)) = expressions[v] {
                    let span = expressions.get_span(v);
                    let written = text.of(span);
                    if let Some(line) = text.line(span, false) {
                        refusals.push(Refusal {
                            line,
                            rule: Rule::ImplicitConversion,
                            message: format!(
                                "`return {written};` in a function that returns a float: GLSL ES 1.00 converts \
                                 no int to a float implicitly (§4.1.10); write `return {written}.0;`"
                            ),
                        });
                    }
                }
            }
            Statement::Block(ref b) => int_returns(b, expressions, text, refusals),
            Statement::If { ref accept, ref reject, .. } => {
                int_returns(accept, expressions, text, refusals);
                int_returns(reject, expressions, text, refusals);
            }
            Statement::Loop { ref body, ref continuing, .. } => {
                int_returns(body, expressions, text, refusals);
                int_returns(continuing, expressions, text, refusals);
            }
            _ => {}
        }
    }
}

/// Built-ins called with ints: GLSL ES 1.00's built-in functions take floats only (`abs`, `min`,
/// `max`, `clamp`, `sign`, `mod`... have no int forms before ES 3.00).
pub fn int_builtins(
    module: &naga::Module,
    info: &naga::valid::ModuleInfo,
    text: &Text,
    refusals: &mut Vec<Refusal>,
) {
    let functions =
        module.functions.iter().map(|(h, f)| (f, &info[h])).chain(
            module.entry_points.iter().enumerate().map(|(i, e)| (&e.function, info.get_entry_point(i))),
        );
    for (f, fi) in functions {
        for (_, e) in f.expressions.iter() {
            let Expression::Math { fun, arg, .. } = *e else { continue };
            let inner = fi[arg].ty.inner_with(&module.types);
            let int = matches!(inner.scalar_kind(), Some(ScalarKind::Sint | ScalarKind::Uint))
                && matches!(inner, TypeInner::Scalar(_) | TypeInner::Vector { .. });
            if !int {
                continue;
            }
            let span = f.expressions.get_span(arg);
            let Some(line) = text.line(span, false) else { continue };
            let name = format!("{fun:?}").to_lowercase();
            refusals.push(Refusal {
                line,
                rule: Rule::IntBuiltin,
                message: format!(
                    "`{name}` of the int `{}`: GLSL ES 1.00's built-in functions take floats only (no int {name} \
                     before ES 3.00); convert with float()",
                    text.of(span)
                ),
            });
        }
    }
}

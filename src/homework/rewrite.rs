//! The line-preserving rewrite of a WebGL1 (GLSL ES 1.00) homework shader to the Vulkan-style GLSL
//! 450 naga's GLSL front end reads.
//!
//! Why line for line: naga reads GLSL 440/450 only and ignores `#line`, so the only way its errors
//! can point at the student's own lines is to keep every one of them where it was. Each edit
//! replaces a byte range by text without line breaks and keeps the line breaks the range had;
//! whatever is new (the `#version`, the uniform blocks, the colour output) goes on a prelude of
//! `prelude_lines` lines, so rewritten line L is the student's line L - `prelude_lines`.
//!
//! Samplers: WebGL's `sampler2D` becomes a texture and a sampler, named `x` and `x_sampler`.
//! A function's `sampler2D p` parameter becomes `texture2D p, sampler p_sampler`, and wherever a
//! texture is passed to a function (`PCF(uShadowMap, c)`, `findBlocker(p, uv, z)`), its sampler
//! is passed after it (`PCF(uShadowMap, uShadowMap_sampler, c)`). `texture2D(t, uv)` becomes
//! `textureLod(sampler2D(t, t_sampler), uv, 0.0)`, so a parameter's texture is sampled with the
//! sampler its caller passed (the shadow map keeps its nearest filter inside `findBlocker` too),
//! and at level 0 explicitly (WGSL samples at an implicit level only in uniform control flow).
//!
//! Also: precision statements and qualifiers go, `const in` parameters become `in`, a non-void
//! function whose last statement is not a `return` gets `return <zero>;` before its closing brace
//! (naga's validator refuses one that can run off its end), and a prototype nothing calls before
//! its definition goes (naga orders a prototyped function wrongly).

use super::instrument::{
    POSITION_FROM_LIGHT, RECORDED_FUNCTIONS, STUDENT_MAIN, TAP, epilogue, recorded_name, recording_prelude,
    wrapper, wrapper_parameters,
};
use super::interface::{
    Binding, BindingKind, CLIP_Y_SIGN, FRAMEWORK_BLOCK_BINDING, FRAMEWORK_UNIFORMS, Interface,
    PER_LIGHT_NAMES, STUDENT_BLOCK_BINDING, attribute_location, declarations, is_glsl450_keyword,
    is_precision, resolve_sizes, texture_call,
};
use super::lex::{Kind, Token, check_size, depth_in, matching, matching_open, tokens};
use super::missing_return::{ends_with_return, zero_of};
use super::{HomeworkError, Stage};

/// The name the rewrite gives WebGL's `gl_FragColor`, declared at location 0 in the prelude.
pub const FRAG_COLOR: &str = "shadowlab_FragColor";
/// A student's shader rewritten to GLSL 450.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Rewritten {
    /// The GLSL 450 text: the prelude, then the student's lines, each on its own line number
    /// plus `prelude_lines`.
    pub glsl: String,
    pub stage: Stage,
    /// How many lines the rewrite put before the student's first line.
    pub prelude_lines: usize,
    /// Resources this shader declares, all in group 0.
    pub bindings: Vec<Binding>,
    /// The vertex attributes this shader declares, with their locations.
    pub attributes: Vec<(String, u32)>,
    /// The student's lines where a function got the `return` it lacked.
    pub added_returns: Vec<usize>,
    /// How many lines follow the student's: the `main` that calls theirs (and, in the fragment
    /// stage, writes what the recorded functions returned).
    pub epilogue_lines: usize,
    /// Which of `RECORDED_FUNCTIONS` the fragment stage records (defined, returning `float`).
    pub recorded: Vec<&'static str>,
    /// The student's shader defines `main` at file scope.
    pub has_main: bool,
}

impl Rewritten {
    /// The student's line for a line of the rewritten text (both 1-based), none in the prelude.
    pub fn student_line(&self, rewritten_line: usize) -> Option<usize> {
        rewritten_line.checked_sub(self.prelude_lines).filter(|l| *l >= 1)
    }
}

/// Edits to the source: a byte range and what replaces it (no line breaks in either's place:
/// the range's own line breaks are kept after the replacement).
#[derive(Default)]
struct Edits(Vec<(usize, usize, String)>);

impl Edits {
    fn replace(&mut self, start: usize, end: usize, with: impl Into<String>) {
        self.0.push((start, end, with.into()));
    }

    fn apply(mut self, source: &str) -> String {
        self.0.sort_by_key(|(start, end, _)| (*start, *end));
        let mut out = String::with_capacity(source.len() + 1024);
        let mut at = 0;
        for (start, end, with) in self.0 {
            if start < at {
                continue; // never made: every token is edited at most once
            }
            out.push_str(&source[at..start]);
            out.push_str(&with);
            out.extend(source[start..end].chars().filter(|c| *c == '\n'));
            at = end;
        }
        out.push_str(&source[at..]);
        out
    }
}

/// A function definition's body (token indices of its braces), its name's token, its parameter
/// list's parentheses, and its `sampler2D` parameters.
struct Body {
    name_at: usize,
    params: (usize, usize),
    open: usize,
    close: usize,
    samplers: Vec<String>,
}

/// Rewrite one stage of a student's WebGL1 shader to GLSL 450 against `layout` (see the module
/// documentation for what changes and why the lines stay where they were).
pub fn rewrite(source: &str, stage: Stage, layout: &Interface) -> Result<Rewritten, HomeworkError> {
    let copies_renamed = layout.copies_as_framework(source);
    let source = copies_renamed.as_str();
    let toks = tokens(source);
    check_size(source, &toks)?;
    let text = |i: usize| &source[toks[i].start..toks[i].end];
    let mut used = vec![false; toks.len()];
    let mut edits = Edits::default();
    let mut bindings = vec![Binding {
        name: "ShadowlabFramework".into(),
        binding: FRAMEWORK_BLOCK_BINDING,
        kind: BindingKind::UniformBlock,
    }];
    if !layout.extra_uniforms.is_empty() {
        bindings.push(Binding {
            name: "ShadowlabStudent".into(),
            binding: STUDENT_BLOCK_BINDING,
            kind: BindingKind::UniformBlock,
        });
    }

    // `#version 100` and `#extension`: gone, the prelude says `#version 450`.
    for (i, t) in toks.iter().enumerate() {
        let name = text(i).trim_start_matches('#').trim();
        if t.kind == Kind::Directive && (name == "version" || name == "extension") {
            let end = source[t.start..].find('\n').map_or(source.len(), |n| t.start + n);
            edits.replace(t.start, end, "");
            for (j, u) in toks.iter().enumerate().skip(i) {
                if u.start < end {
                    used[j] = true;
                }
            }
        }
    }

    // Globals: varyings and attributes get locations, uniforms go to the blocks, samplers split.
    let decls = declarations(source, &toks)?;
    let declares_position_from_light = decls.iter().any(|d| {
        d.qualifier == "varying"
            && d.glsl_type == "vec4"
            && d.names
                .iter()
                .any(|(n, s)| n == POSITION_FROM_LIGHT && (s.is_empty() || layout.is_per_light(n)))
    });
    let mut own_attributes: Vec<String> = decls
        .iter()
        .filter(|d| d.qualifier == "attribute")
        .flat_map(|d| d.names.iter().map(|(n, _)| n.clone()))
        .collect();
    own_attributes.sort();
    let mut attributes = Vec::new();
    let mut textures: Vec<String> = Vec::new();
    // A numbered copy for another light (`uShadowMap1`) is the framework's name by now: declared
    // once.
    let mut per_light_declared: Vec<&str> = Vec::new();
    for d in &decls {
        let fail = |message: String| HomeworkError::Rewrite { line: d.line, message };
        let mut parts = Vec::new();
        for (name, suffix) in &d.names {
            let name = name.as_str();
            if PER_LIGHT_NAMES.contains(&name) && d.qualifier != "attribute" {
                if per_light_declared.contains(&name) {
                    continue;
                }
                per_light_declared.push(name);
            }
            let ty = &d.glsl_type;
            // An array by light is declared as the framework's one (see `Interface::per_light`).
            let suffix = if layout.is_per_light(name) { "" } else { suffix.as_str() };
            match (d.qualifier.as_str(), stage) {
                ("varying", _) => {
                    let location = layout.varying_location(name).ok_or_else(|| {
                        fail(format!("varying {name} is not in the interface (gather it from both stages)"))
                    })?;
                    let dir = if stage == Stage::Vertex { "out" } else { "in" };
                    parts.push(format!("layout(location = {location}) {dir} {ty} {name}{suffix};"));
                }
                ("attribute", Stage::Vertex) => {
                    let location = attribute_location(name, &own_attributes);
                    attributes.push((name.to_string(), location));
                    parts.push(format!("layout(location = {location}) in {ty} {name}{suffix};"));
                }
                ("attribute", Stage::Fragment) => {
                    return Err(fail(format!("attribute {name} in a fragment shader")));
                }
                (_, _) if ty == "sampler2D" => {
                    let (binding, filter) = layout.texture_binding(name).ok_or_else(|| {
                        fail(format!("texture {name} is not in the interface (gather it from both stages)"))
                    })?;
                    let sampler = format!("{name}_sampler");
                    parts.push(format!(
                        "layout(set = 0, binding = {binding}) uniform texture2D {name}; \
                         layout(set = 0, binding = {}) uniform sampler {sampler};",
                        binding + 1
                    ));
                    bindings.push(Binding { name: name.to_string(), binding, kind: BindingKind::Texture });
                    bindings.push(Binding {
                        name: sampler,
                        binding: binding + 1,
                        kind: BindingKind::Sampler(filter),
                    });
                    textures.push(name.to_string());
                }
                (_, _) => {
                    let declared = format!("{ty}{}", resolve_sizes(source, suffix));
                    let framework = FRAMEWORK_UNIFORMS.iter().find(|f| f.name == name);
                    let known = match framework {
                        Some(f) => f.glsl_type == declared,
                        None => layout.extra_uniforms.iter().any(|(n, t)| n == name && *t == declared),
                    };
                    if !known {
                        return Err(fail(match framework {
                            Some(f) => format!(
                                "{name} is a {} in the framework, declared {declared} here",
                                f.glsl_type
                            ),
                            None => {
                                format!("uniform {name} is not in the interface (gather it from both stages)")
                            }
                        }));
                    }
                }
            }
        }
        edits.replace(toks[d.first].start, toks[d.last].end, parts.join(" "));
        used[d.first..=d.last].iter_mut().for_each(|u| *u = true);
    }

    // `precision mediump float;`: gone (GLSL 450 on the desktop has no precision).
    for i in 0..toks.len() {
        if !used[i] && text(i) == "precision" {
            let end = (i..toks.len()).find(|&j| text(j) == ";").unwrap_or(toks.len() - 1);
            edits.replace(toks[i].start, toks[end].end, "");
            used[i..=end].iter_mut().for_each(|u| *u = true);
        }
    }

    let bodies = functions(source, &toks, &mut used, &mut edits);
    let mut added_returns = Vec::new();
    for body in &bodies {
        let header = (0..body.open).rev().find(|&j| text(j) == ")").unwrap_or(0);
        let name_at = matching_open(source, &toks, header).saturating_sub(1);
        let return_type = (0..name_at).rev().find(|&j| !is_precision(text(j))).map(text).unwrap_or("void");
        if return_type == "void" || ends_with_return(source, &toks, body.open, body.close) {
            continue;
        }
        if let Some(value) = zero_of(return_type) {
            let close = &toks[body.close];
            edits.replace(close.start, close.start, format!("return {value}; "));
            added_returns.push(close.line);
        }
    }

    // `main` becomes the student's; the epilogue's `main` calls it (see `epilogue`). Without
    // one, naga says what it finds first (unbalanced braces hide `main` too), then
    // `translate` says `main` is missing.
    let main = bodies.iter().find(|b| text(b.name_at) == "main");
    if let Some(main) = main {
        edits.replace(toks[main.name_at].start, toks[main.name_at].end, STUDENT_MAIN);
        used[main.name_at] = true;
    }

    // The recorded functions: renamed, with a wrapper of the old name right after the body that
    // calls it and records what it returned (on the body's last line: no line moves).
    let mut recorded = Vec::new();
    if stage == Stage::Fragment {
        for (k, name) in RECORDED_FUNCTIONS.iter().enumerate() {
            // Under the student's own name where theirs differs (`averageBlockerDepth`).
            let Some(own) = recorded_name(source, &toks, name) else { continue };
            let Some(body) = bodies.iter().find(|b| text(b.name_at) == own) else { continue };
            let returns_float =
                (0..body.name_at).rev().find(|&j| !is_precision(text(j))).map(text) == Some("float");
            let Some((params, args)) =
                wrapper_parameters(source, &toks, body.params).filter(|_| returns_float)
            else {
                continue;
            };
            let student = format!("shadowlab_student_{own}");
            edits.replace(toks[body.name_at].start, toks[body.name_at].end, student.clone());
            used[body.name_at] = true;
            let after = toks[body.close].end;
            edits.replace(after, after, format!(" {}", wrapper(own, k, &student, &params, &args)));
            recorded.push(*name);
        }
    }

    // Token by token: precision qualifiers, `const in`, gl_FragColor, texture2D, passing samplers,
    // names GLSL 450 keeps for itself.
    let mut i = 0;
    while i < toks.len() {
        if used[i] {
            i += 1;
            continue;
        }
        let t = toks[i];
        let word = text(i);
        let next = |k: usize| (i + k < toks.len()).then(|| text(i + k));
        if is_precision(word) {
            edits.replace(t.start, t.end, "");
        } else if word == "const" && next(1) == Some("in") {
            edits.replace(t.start, toks[i + 1].start, "");
        } else if word == "gl_FragColor" && stage == Stage::Fragment {
            edits.replace(t.start, t.end, FRAG_COLOR);
        } else if layout.is_per_light(word) && next(1) == Some("[") {
            // `uLightMVP[l]` reads the light checked, as every element holds it.
            let close = matching(source, &toks, i + 1, "[", "]");
            let name = if textures.iter().any(|n| n == word) {
                format!("{word}, {word}_sampler")
            } else {
                word.into()
            };
            edits.replace(t.start, toks[close].end, name);
            i = close + 1;
            continue;
        } else if let Some(call) = texture_call(word)
            && next(1) == Some("(")
            && toks.get(i + 2).is_some_and(|t| t.kind == Kind::Ident)
            && let tex_last = layout.per_light_index_end(source, &toks, i + 2)
            && toks.get(tex_last + 1).is_some_and(|t| &source[t.start..t.end] == ",")
        {
            let tex = text(i + 2);
            // At level 0, explicitly: every texture here has one level, so the picture is the
            // same, and WGSL (unlike GLSL) allows implicit-level sampling only in uniform control
            // flow, which a lookup in findBlocker's loop is not (a browser refuses the shader).
            let close = matching(source, &toks, i + 1, "(", ")");
            let arguments = 1
                + (i + 2..close)
                    .filter(|&k| text(k) == "," && depth_in(source, &toks, i + 1, k) == 1)
                    .count();
            let call = match (call, arguments, text(close)) {
                ("texture", 2, ")") => "textureLod",
                ("textureProj", 2, ")") => "textureProjLod",
                (call, ..) => call,
            };
            // The uv of a 2D read goes through the tap (fragment stage: inside a recorded
            // function it records where the read lands).
            let uv_start =
                (tex_last + 1..close).find(|&k| text(k) == "," && depth_in(source, &toks, i + 1, k) == 1);
            if stage == Stage::Fragment
                && matches!(call, "texture" | "textureLod")
                && let Some(comma) = uv_start
            {
                let uv_end = (comma + 1..close)
                    .find(|&k| text(k) == "," && depth_in(source, &toks, i + 1, k) == 1)
                    .unwrap_or(close);
                edits.replace(toks[comma].end, toks[comma].end, format!(" {TAP}("));
                edits.replace(toks[uv_end].start, toks[uv_end].start, ")");
            }
            if call != texture_call(word).unwrap_or_default() {
                edits.replace(toks[close].start, toks[close].start, ", 0.0");
            }
            edits.replace(t.start, toks[tex_last].end, format!("{call}(sampler2D({tex}, {tex}_sampler)"));
            i = tex_last + 1;
            continue;
        } else if t.kind == Kind::Ident && is_glsl450_keyword(word) {
            edits.replace(t.start, t.end, format!("{word}_"));
        } else if t.kind == Kind::Ident
            && (textures.iter().any(|n| n == word)
                || bodies.iter().any(|b| b.open < i && i < b.close && b.samplers.iter().any(|s| s == word)))
        {
            edits.replace(t.start, t.end, format!("{word}, {word}_sampler"));
        }
        i += 1;
    }

    let mut body = edits.apply(source);
    if !body.ends_with('\n') {
        body.push('\n');
    }
    let prelude = prelude(stage, layout);
    let prelude_lines = prelude.lines().count();
    let epilogue = if main.is_some() { epilogue(stage, declares_position_from_light) } else { String::new() };
    let epilogue_lines = epilogue.lines().count();
    let glsl = format!("{prelude}{body}{epilogue}");
    debug_assert_eq!(
        glsl.lines().count(),
        prelude_lines + source.lines().count() + epilogue_lines,
        "the rewrite moved a line"
    );
    Ok(Rewritten {
        glsl,
        stage,
        prelude_lines,
        bindings,
        attributes,
        added_returns,
        epilogue_lines,
        recorded,
        has_main: main.is_some(),
    })
}

/// The lines before the student's: the version, the uniform blocks, the colour output.
fn prelude(stage: Stage, layout: &Interface) -> String {
    let fields: Vec<String> =
        FRAMEWORK_UNIFORMS.iter().map(|f| format!("{} {};", f.glsl_type, f.name)).collect();
    let mut out = format!(
        "#version 450\nlayout(set = 0, binding = {FRAMEWORK_BLOCK_BINDING}) uniform ShadowlabFramework {{ {} float {CLIP_Y_SIGN}; }};\n",
        fields.join(" ")
    );
    if !layout.extra_uniforms.is_empty() {
        let fields: Vec<String> = layout
            .extra_uniforms
            .iter()
            .map(|(name, ty)| match ty.find('[') {
                Some(at) => format!("{} {name}{};", &ty[..at], &ty[at..]),
                None => format!("{ty} {name};"),
            })
            .collect();
        out += &format!(
            "layout(set = 0, binding = {STUDENT_BLOCK_BINDING}) uniform ShadowlabStudent {{ {} }};\n",
            fields.join(" ")
        );
    }
    if stage == Stage::Fragment {
        out += &format!("layout(location = 0) out vec4 {FRAG_COLOR};\n");
        out += &recording_prelude();
    }
    out
}

/// Function headers at file scope: `sampler2D` parameters become a texture and a sampler; the
/// bodies of definitions are returned with the names of those parameters.
fn functions(source: &str, toks: &[Token], used: &mut [bool], edits: &mut Edits) -> Vec<Body> {
    let text = |i: usize| &source[toks[i].start..toks[i].end];
    let mut bodies = Vec::new();
    let mut prototypes = Vec::new(); // (name, first token, `;`)
    let mut definitions = Vec::new(); // (name, name's token)
    let mut depth = 0i32;
    let mut i = 0;
    while i < toks.len() {
        match text(i) {
            "{" => depth += 1,
            "}" => depth -= 1,
            _ => {}
        }
        let is_header = depth == 0
            && i > 0
            && !used[i]
            && !toks[i].in_directive
            && toks[i].kind == Kind::Ident
            && toks[i - 1].kind == Kind::Ident
            && i + 1 < toks.len()
            && text(i + 1) == "(";
        if !is_header {
            i += 1;
            continue;
        }
        let close = matching(source, toks, i + 1, "(", ")");
        let mut samplers = Vec::new();
        for p in i + 2..close {
            if text(p) != "sampler2D" || used[p] {
                continue;
            }
            edits.replace(toks[p].start, toks[p].end, "texture2D");
            used[p] = true;
            if toks[p + 1].kind == Kind::Ident {
                let name = text(p + 1);
                edits.replace(toks[p + 1].end, toks[p + 1].end, format!(", sampler {name}_sampler"));
                used[p + 1] = true;
                samplers.push(name.to_string());
            } else {
                edits.replace(toks[p].end, toks[p].end, ", sampler");
            }
        }
        if close + 1 < toks.len() && text(close + 1) == "{" {
            let end = matching(source, toks, close + 1, "{", "}");
            bodies.push(Body { name_at: i, params: (i + 1, close), open: close + 1, close: end, samplers });
            definitions.push((text(i), i));
            i = end + 1;
        } else {
            if close + 1 < toks.len() && text(close + 1) == ";" {
                prototypes.push((text(i), i - 1, close + 1));
            }
            i = close + 1;
        }
    }
    // naga's GLSL front end makes a prototype's function before the functions its definition
    // calls, which its validator then refuses (gfx-rs/naga#2225). A prototype that nothing
    // between it and its definition calls is not needed: it goes.
    for (name, first, semicolon) in prototypes {
        let defined = definitions.iter().find(|(n, at)| *n == name && *at > semicolon);
        if let Some(&(_, at)) = defined
            && !(semicolon..at).any(|j| text(j) == name)
        {
            edits.replace(toks[first].start, toks[semicolon].end, "");
            used[first..=semicolon].iter_mut().for_each(|u| *u = true);
        }
    }
    bodies
}

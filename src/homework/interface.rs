//! The framework's interface as the rewritten shaders declare it: the uniform block's fixed layout,
//! varying and attribute locations, texture and sampler bindings, and a student's additions
//! gathered from both stages so that both stages agree.

use super::HomeworkError;
use super::lex::{Kind, Token, tokens};

/// A member of the framework's uniform block (std140).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct UniformField {
    pub name: &'static str,
    pub glsl_type: &'static str,
    pub offset_bytes: u32,
}

/// The framework's uniforms, in the block's fixed order (binding 0). Every rewritten shader
/// declares all of them, whichever it uses, so one buffer serves both stages.
pub const FRAMEWORK_UNIFORMS: [UniformField; 9] = [
    UniformField { name: "uModelMatrix", glsl_type: "mat4", offset_bytes: 0 },
    UniformField { name: "uViewMatrix", glsl_type: "mat4", offset_bytes: 64 },
    UniformField { name: "uProjectionMatrix", glsl_type: "mat4", offset_bytes: 128 },
    UniformField { name: "uLightMVP", glsl_type: "mat4", offset_bytes: 192 },
    UniformField { name: "uCameraPos", glsl_type: "vec3", offset_bytes: 256 },
    UniformField { name: "uLightPos", glsl_type: "vec3", offset_bytes: 272 },
    UniformField { name: "uLightIntensity", glsl_type: "vec3", offset_bytes: 288 },
    UniformField { name: "uKs", glsl_type: "vec3", offset_bytes: 304 },
    UniformField { name: "uKd", glsl_type: "vec3", offset_bytes: 320 },
];

/// shadowlab's own member of the block, after the framework's (std140 packs it into uKd's
/// last four bytes): +1 in the camera pass, -1 in the
/// light pass (the vertex epilogue flips clip y by it so the map's rows lie as WebGL's do).
pub const CLIP_Y_SIGN: &str = "shadowlab_ClipYSign";
pub const CLIP_Y_SIGN_OFFSET_BYTES: u32 = 332;

/// The size of the framework's uniform block with shadowlab's member, std140.
pub const FRAMEWORK_UNIFORMS_SIZE_BYTES: u32 = 336;

/// The framework's varyings, at locations 0, 1, 2, 3; a student's own follow, sorted by name.
pub const FRAMEWORK_VARYINGS: [&str; 4] = ["vTextureCoord", "vFragPos", "vNormal", "vPositionFromLight"];

/// The framework's vertex attributes, at locations 0, 1, 2; a student's own follow, sorted by name.
pub const ATTRIBUTES: [&str; 3] = ["aVertexPosition", "aNormalPosition", "aTextureCoord"];

/// Binding of the framework's uniform block in group 0.
pub const FRAMEWORK_BLOCK_BINDING: u32 = 0;
/// Binding of the block of a student's own uniforms in group 0.
pub const STUDENT_BLOCK_BINDING: u32 = 1;
/// The framework's textures with their first binding (the sampler is the next one) and filter.
const FRAMEWORK_TEXTURES: [(&str, u32, SamplerFilter); 2] =
    [("uSampler", 2, SamplerFilter::Linear), ("uShadowMap", 4, SamplerFilter::Nearest)];
/// The first binding for a student's own textures.
const FIRST_STUDENT_TEXTURE_BINDING: u32 = 6;

/// How a sampler filters; every sampler repeats (the framework never changes WebGL's REPEAT).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SamplerFilter {
    Nearest,
    Linear,
}

/// What a binding of group 0 holds.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum BindingKind {
    UniformBlock,
    Texture,
    Sampler(SamplerFilter),
}

/// One resource a rewritten shader declares, in group 0.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Binding {
    /// The name in the rewritten GLSL (`uShadowMap`, `uShadowMap_sampler`, `ShadowlabFramework`).
    pub name: String,
    pub binding: u32,
    pub kind: BindingKind,
}

/// The interface both stages of one program are rewritten against: the framework's, plus what the
/// student added to either stage.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Interface {
    /// A student's own varyings, sorted by name; locations from 4 on.
    pub extra_varyings: Vec<String>,
    /// A student's own uniforms (name, declared type with any array suffix), sorted by name; they
    /// make the second block (binding 1) in this order.
    pub extra_uniforms: Vec<(String, String)>,
    /// A student's own `sampler2D` uniforms, sorted by name; bindings from 6 on, two each.
    pub extra_textures: Vec<String>,
    /// The framework's per-light names a student declared as arrays, one element per light
    /// (`uLightMVP[NUM_LIGHTS]`, `uShadowMap[2]`, `vPositionFromLight[2]`), sorted. shadowlab
    /// checks one light at a time: every element holds the light checked, so the rewrite reads
    /// each as the framework's single one (`uLightMVP[l]` is `uLightMVP`).
    pub per_light: Vec<String>,
    /// The framework's per-light names a student copied for another light under a number
    /// (`uShadowMap1`, `uLightMVP1`, `vPositionFromLight1`): (the copy, the framework's name),
    /// sorted. Like an array's elements, each copy holds the light checked: the rewrite reads it
    /// as the framework's one.
    pub per_light_copies: Vec<(String, String)>,
}

/// The framework's names that hold one light's data, which a page with several lights may turn
/// into arrays indexed by light.
pub const PER_LIGHT_NAMES: [&str; 5] =
    ["uLightMVP", "uLightPos", "uLightIntensity", "uShadowMap", "vPositionFromLight"];

/// The type the framework gives a per-light name (`uShadowMap` a sampler2D, `uLightMVP` a mat4).
fn per_light_type(name: &str) -> &'static str {
    match name {
        "uShadowMap" => "sampler2D",
        "vPositionFromLight" => "vec4",
        _ => FRAMEWORK_UNIFORMS.iter().find(|f| f.name == name).map_or("", |f| f.glsl_type),
    }
}

/// The framework's per-light name `name` is a numbered copy of (`uShadowMap1` of `uShadowMap`).
fn numbered_copy_of(name: &str) -> Option<&'static str> {
    PER_LIGHT_NAMES.iter().copied().find(|base| {
        name.strip_prefix(base).is_some_and(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()))
    })
}

/// The types a student's own uniform may have (WGSL allows no `bool` in a uniform buffer).
const BLOCK_TYPES: [&str; 13] = [
    "float", "int", "vec2", "vec3", "vec4", "ivec2", "ivec3", "ivec4", "mat2", "mat3", "mat4", "uint",
    "uvec2",
];

/// One `uniform`, `varying` or `attribute` declaration of a source.
pub(super) struct Declaration {
    pub qualifier: String,
    pub glsl_type: String,
    /// Each declared name with its array suffix (`[4]`, or empty).
    pub names: Vec<(String, String)>,
    /// Token indices of the qualifier and of the closing `;`.
    pub first: usize,
    pub last: usize,
    pub line: usize,
}

pub(super) fn is_precision(word: &str) -> bool {
    matches!(word, "highp" | "mediump" | "lowp")
}

/// Words GLSL ES 1.00 leaves free for names (WebGL compiles `vec2 sample;`) that GLSL 450 with
/// Vulkan's additions keeps for itself: a student's name of this kind is renamed (`sample_`).
pub(super) fn is_glsl450_keyword(word: &str) -> bool {
    matches!(
        word,
        "sample"
            | "patch"
            | "subroutine"
            | "buffer"
            | "shared"
            | "coherent"
            | "restrict"
            | "readonly"
            | "writeonly"
            | "precise"
            | "smooth"
            | "centroid"
            | "noperspective"
            | "layout"
            | "atomic_uint"
            | "sampler"
            | "subpassInput"
            | "demote"
    )
}

/// The global `uniform` / `varying` / `attribute` declarations of a source, from its tokens.
pub(super) fn declarations(source: &str, toks: &[Token]) -> Result<Vec<Declaration>, HomeworkError> {
    let text = |t: &Token| &source[t.start..t.end];
    let mut out = Vec::new();
    let mut depth = 0i32;
    let mut i = 0;
    while i < toks.len() {
        let t = &toks[i];
        match text(t) {
            "{" => depth += 1,
            "}" => depth -= 1,
            q @ ("uniform" | "varying" | "attribute") if depth == 0 && !t.in_directive => {
                let line = t.line;
                let fail = |message: String| HomeworkError::Rewrite { line, message };
                let end = (i..toks.len())
                    .find(|&j| text(&toks[j]) == ";")
                    .ok_or_else(|| fail(format!("`{q}` declaration without `;`")))?;
                let words: Vec<&Token> = toks[i + 1..end].iter().filter(|t| !is_precision(text(t))).collect();
                let glsl_type = words.first().map(|t| text(t)).unwrap_or_default().to_string();
                let mut names = Vec::new();
                let mut k = 1;
                while k < words.len() {
                    let name = words[k];
                    if name.kind != Kind::Ident {
                        return Err(fail(format!("cannot read this `{q}` declaration")));
                    }
                    k += 1;
                    let suffix_start = k;
                    while k < words.len() && text(words[k]) != "," {
                        k += 1;
                    }
                    let suffix = match (words.get(suffix_start), words.get(k.saturating_sub(1))) {
                        (Some(a), Some(b)) if k > suffix_start => source[a.start..b.end].to_string(),
                        _ => String::new(),
                    };
                    if !suffix.is_empty() && !suffix.starts_with('[') {
                        return Err(fail(format!("`{q}` {} with an initializer or qualifier", text(name))));
                    }
                    names.push((text(name).to_string(), suffix));
                    k += 1;
                }
                if glsl_type.is_empty() || names.is_empty() {
                    return Err(fail(format!("cannot read this `{q}` declaration")));
                }
                out.push(Declaration {
                    qualifier: q.to_string(),
                    glsl_type,
                    names,
                    first: i,
                    last: end,
                    line,
                });
                i = end;
            }
            _ => {}
        }
        i += 1;
    }
    Ok(out)
}

impl Interface {
    /// The framework's interface with nothing added.
    pub fn framework() -> Interface {
        Interface::default()
    }

    /// The framework's interface plus every uniform, varying and texture the given sources (both
    /// stages of one program) add to it. The same name declared with two types is an error.
    pub fn gather(sources: &[&str]) -> Result<Interface, HomeworkError> {
        let mut out = Interface::default();
        for source in sources {
            for d in declarations(source, &tokens(source))? {
                for (name, suffix) in &d.names {
                    // `[NUM]` with `#define NUM 4` in this stage is `[4]` in both (the other
                    // stage, which declares the block too, may not define NUM).
                    let written = suffix;
                    let resolved = resolve_sizes(source, suffix);
                    let suffix = &resolved;
                    let fail = |message: String| HomeworkError::Rewrite { line: d.line, message };
                    if let Some(base) = numbered_copy_of(name)
                        && suffix.is_empty()
                        && d.glsl_type == per_light_type(base)
                    {
                        out.per_light_copies.push((name.clone(), base.to_string()));
                        continue;
                    }
                    if !suffix.is_empty() && PER_LIGHT_NAMES.contains(&name.as_str()) {
                        let framework_type = per_light_type(name);
                        if d.glsl_type != framework_type {
                            return Err(fail(format!(
                                "{name} is a {framework_type} in the framework, declared {}{written} here",
                                d.glsl_type
                            )));
                        }
                        out.per_light.push(name.clone());
                        continue;
                    }
                    match d.qualifier.as_str() {
                        "varying" if !FRAMEWORK_VARYINGS.contains(&name.as_str()) => {
                            out.extra_varyings.push(name.clone())
                        }
                        "uniform" if d.glsl_type == "sampler2D" && texture_binding(name, &[]).is_none() => {
                            out.extra_textures.push(name.clone());
                        }
                        "uniform" if d.glsl_type == "sampler2D" => {} // the framework's
                        "uniform" => {
                            if let Some(field) = FRAMEWORK_UNIFORMS.iter().find(|f| f.name == name) {
                                if field.glsl_type != d.glsl_type || !suffix.is_empty() {
                                    return Err(fail(format!(
                                        "{name} is a {} in the framework, declared {}{written} here",
                                        field.glsl_type, d.glsl_type
                                    )));
                                }
                                continue;
                            }
                            if !BLOCK_TYPES.contains(&d.glsl_type.as_str()) {
                                return Err(fail(format!(
                                    "uniform {name}: a {} uniform is not supported (use float, int, vecN, ivecN or matN)",
                                    d.glsl_type
                                )));
                            }
                            let declared = format!("{}{suffix}", d.glsl_type);
                            match out.extra_uniforms.iter().find(|(n, _)| n == name) {
                                Some((_, other)) if *other != declared => {
                                    return Err(fail(format!(
                                        "uniform {name} is declared {declared} here and {other} in the other stage"
                                    )));
                                }
                                Some(_) => {}
                                None => out.extra_uniforms.push((name.clone(), declared)),
                            }
                        }
                        _ => {}
                    }
                }
            }
        }
        out.extra_varyings.sort();
        out.extra_varyings.dedup();
        out.extra_uniforms.sort();
        out.extra_textures.sort();
        out.extra_textures.dedup();
        out.per_light.sort();
        out.per_light.dedup();
        out.per_light_copies.sort();
        out.per_light_copies.dedup();
        Ok(out)
    }

    /// The framework's name a numbered copy for another light stands for (`uShadowMap1`:
    /// `uShadowMap`).
    pub fn copied_from(&self, name: &str) -> Option<&str> {
        self.per_light_copies.iter().find(|(copy, _)| copy == name).map(|(_, base)| base.as_str())
    }

    /// `source` with every numbered copy of a per-light name (`uShadowMap1`, see
    /// `per_light_copies`) written as the framework's (`uShadowMap`): each holds the light
    /// checked. Only names change, so no line moves.
    pub(super) fn copies_as_framework(&self, source: &str) -> String {
        if self.per_light_copies.is_empty() {
            return source.to_string();
        }
        let mut out = String::with_capacity(source.len());
        let mut at = 0;
        for t in tokens(source) {
            if t.kind == Kind::Ident
                && let Some(base) = self.copied_from(&source[t.start..t.end])
            {
                out.push_str(&source[at..t.start]);
                out.push_str(base);
                at = t.end;
            }
        }
        out.push_str(&source[at..]);
        out
    }

    /// The last token of a texture argument at `at`: the name, or the `]` of a per-light
    /// array's index after it.
    pub(super) fn per_light_index_end(&self, source: &str, toks: &[Token], at: usize) -> usize {
        let text = |i: usize| &source[toks[i].start..toks[i].end];
        if self.is_per_light(text(at)) && at + 1 < toks.len() && text(at + 1) == "[" {
            super::lex::matching(source, toks, at + 1, "[", "]")
        } else {
            at
        }
    }

    /// `name` is one of the framework's per-light names declared as an array by light.
    pub fn is_per_light(&self, name: &str) -> bool {
        self.per_light.iter().any(|n| n == name)
    }

    /// The location of a varying, shared by both stages.
    pub fn varying_location(&self, name: &str) -> Option<u32> {
        let framework = FRAMEWORK_VARYINGS.iter().position(|v| *v == name);
        let extra =
            || self.extra_varyings.iter().position(|v| v == name).map(|i| i + FRAMEWORK_VARYINGS.len());
        framework.or_else(extra).map(|i| i as u32)
    }

    /// The binding of a `sampler2D` uniform's texture (its sampler is the next binding), and how
    /// its sampler filters.
    pub fn texture_binding(&self, name: &str) -> Option<(u32, SamplerFilter)> {
        texture_binding(name, &self.extra_textures)
    }
}

fn texture_binding(name: &str, extra_textures: &[String]) -> Option<(u32, SamplerFilter)> {
    let framework = FRAMEWORK_TEXTURES.iter().find(|(n, ..)| *n == name).map(|&(_, b, f)| (b, f));
    let extra = || {
        let i = extra_textures.iter().position(|t| t == name)? as u32;
        Some((FIRST_STUDENT_TEXTURE_BINDING + 2 * i, SamplerFilter::Linear))
    };
    framework.or_else(extra)
}

/// An array suffix of a declaration in `source` with its `#define`d sizes written out
/// (`[NUM]` with `#define NUM 4` is `[4]`).
pub(super) fn resolve_sizes(source: &str, suffix: &str) -> String {
    integer_defines(source).iter().fold(suffix.to_string(), |s, (name, value)| replace_word(&s, name, value))
}

/// A source's `#define NAME <integer>` lines: (name, value), the last definition of a name last.
fn integer_defines(source: &str) -> Vec<(String, String)> {
    source
        .lines()
        .filter_map(|line| {
            let rest = line.trim_start().strip_prefix('#')?.trim_start().strip_prefix("define")?;
            let mut words = rest.split_whitespace();
            let (name, value) = (words.next()?, words.next()?);
            (words.next().is_none() && value.parse::<u32>().is_ok())
                .then(|| (name.to_string(), value.to_string()))
        })
        .collect()
}

/// `text` with each whole word `word` replaced by `with`.
fn replace_word(text: &str, word: &str, with: &str) -> String {
    let is_name = |c: char| c.is_ascii_alphanumeric() || c == '_';
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(at) = rest.find(word) {
        let before = rest[..at].chars().next_back();
        let after = rest[at + word.len()..].chars().next();
        out.push_str(&rest[..at]);
        if before.is_some_and(is_name) || after.is_some_and(is_name) {
            out.push_str(word);
        } else {
            out.push_str(with);
        }
        rest = &rest[at + word.len()..];
    }
    out.push_str(rest);
    out
}

/// The location of a vertex attribute: the framework's first, then the source's own by name.
pub(super) fn attribute_location(name: &str, own_sorted: &[String]) -> u32 {
    match ATTRIBUTES.iter().position(|a| *a == name) {
        Some(i) => i as u32,
        None => (ATTRIBUTES.len() + own_sorted.iter().position(|a| a == name).unwrap_or(0)) as u32,
    }
}

/// GLSL 450's name for a WebGL texture lookup.
pub(super) fn texture_call(word: &str) -> Option<&'static str> {
    match word {
        "texture2D" => Some("texture"),
        "texture2DProj" => Some("textureProj"),
        "texture2DLod" => Some("textureLod"),
        _ => None,
    }
}

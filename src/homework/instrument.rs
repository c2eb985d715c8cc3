//! What the rewrite adds around a student's code so that shadowlab can run it and see into it:
//! a `main` of its own that calls theirs (converting the framework's GL clip space in the vertex
//! stage) and, in the fragment stage, a wrapper around each of `useShadowMap`, `PCF`, `PCSS` and
//! `findBlocker` that records what it returned, and a tap on every texture read inside them that
//! records where it read: how many reads, how far from the receiver's own uv (the mean offset,
//! its root mean square, the farthest), what shows a search radius, a filter radius, and samples
//! that are not around the receiver.

use super::Stage;
use super::interface::{CLIP_Y_SIGN, is_precision};
use super::lex::{Kind, Token};

/// What the student's `main` is renamed to: the `main` the epilogue adds calls it.
pub(super) const STUDENT_MAIN: &str = "shadowlab_student_main";
/// The student's functions whose results the fragment stage records at every call, in the
/// order of the `Returned` output's channels. The first three give a visibility.
pub const RECORDED_FUNCTIONS: [&str; 4] = ["useShadowMap", "PCF", "PCSS", "findBlocker"];
/// The fragment outputs the instrumentation adds: the last value each recorded function returned
/// (`vec4`, channels in `RECORDED_FUNCTIONS` order) and what ran (`uvec4`: a bit per function that
/// ran, the visibility function + 1 (the last of the first three called from `main`'s level),
/// calls in all (at most 255), 1: the shader ran here).
pub const RETURNED_OUTPUT: u32 = 1;
pub const CALLS_OUTPUT: u32 = 2;
/// The first of four outputs with where the recorded functions read the map (a read counts for
/// the innermost recorded function running), offsets in uv of the map from the receiver's own uv
/// (`vPositionFromLight.xy / w * 0.5 + 0.5`): for PCF, PCSS and findBlocker in turn (reads,
/// |mean offset|, root mean square offset, largest offset), then PCF's and PCSS's stretch: the
/// two components of the offsets' second moments without their trace, over it, ((xx - yy),
/// 2 xy) / (xx + yy): (0, 0) for a disk, a unit vector at twice the angle of a line.
pub const TAPS_OUTPUT: u32 = 3;
/// The varying the receiver's uv comes from (a shader that does not declare it, the light pass's,
/// reads at offsets from uv 0).
pub(super) const POSITION_FROM_LIGHT: &str = "vPositionFromLight";
/// The function a texture read's uv goes through.
pub(super) const TAP: &str = "shadowlab_tap";

/// The student's own name for the recorded function `role` (one of `RECORDED_FUNCTIONS`): the
/// function of that name where the shader defines one. A blocker search under a name of the
/// student's (`averageBlockerDepth`) is recorded as `findBlocker`: the first function PCSS
/// calls whose name says "blocker" and that returns a float (a search radius is not one).
pub(crate) fn recorded_name<'s>(source: &'s str, toks: &[Token], role: &str) -> Option<&'s str> {
    let bodies = super::lex::function_bodies(source, toks);
    let text = |i: usize| toks.get(i).map_or("", |t| &source[t.start..t.end]);
    let returns_float =
        |name_at: usize| (0..name_at).rev().find(|&j| !is_precision(text(j))).map(text) == Some("float");
    if let Some(b) = bodies.iter().find(|b| b.name == role) {
        return Some(b.name);
    }
    let pcss = bodies.iter().find(|b| b.name == "PCSS").filter(|_| role == "findBlocker")?;
    (pcss.open..pcss.close).find_map(|k| {
        let name = text(k);
        let lower = name.to_ascii_lowercase();
        let searches = lower.contains("blocker") && !lower.contains("radius") && !lower.contains("size");
        let body = bodies.iter().find(|b| b.name == name && text(k + 1) == "(" && searches)?;
        returns_float(body.name_at).then_some(body.name)
    })
}

/// A recorded function's wrapper: the student's definition renamed to `student`, called with
/// the same arguments; the result recorded as function `k` and returned. One line.
pub(super) fn wrapper(name: &str, k: usize, student: &str, params: &str, args: &str) -> String {
    format!(
        "float {name}({params}) {{ shadowlab_depth += 1; uint shadowlab_caller = shadowlab_current; \
         shadowlab_current = {current}u; float shadowlab_result = {student}({args}); \
         shadowlab_current = shadowlab_caller; shadowlab_depth -= 1; \
         return shadowlab_record({k}u, shadowlab_result); }}",
        current = k + 1
    )
}

/// The fragment stage's prelude lines for the recording: the outputs, the state,
/// `shadowlab_record` (the visibility is the last of the first three called at `main`'s level)
/// and the tap.
pub(super) fn recording_prelude() -> String {
    let taps: Vec<String> = (0..4)
        .map(|k| format!("layout(location = {}) out vec4 shadowlab_Taps{k};", TAPS_OUTPUT + k))
        .collect();
    format!(
        "layout(location = {RETURNED_OUTPUT}) out vec4 shadowlab_Returned; \
         layout(location = {CALLS_OUTPUT}) out uvec4 shadowlab_Calls; {taps}\n\
         vec4 shadowlab_returned; uint shadowlab_ran; uint shadowlab_visibility_function; \
         uint shadowlab_calls; int shadowlab_depth; uint shadowlab_current; \
         vec4 shadowlab_tap_sums[4]; vec4 shadowlab_tap_moments[4]; vec2 shadowlab_receiver_uv;\n\
         float shadowlab_record(uint k, float r) {{ shadowlab_ran |= 1u << k; shadowlab_calls += 1u; \
         shadowlab_returned[k] = r; if (shadowlab_depth == 0 && k < 3u) {{ shadowlab_visibility_function = k + 1u; }} \
         return r; }}\n\
         vec2 {TAP}(vec2 uv) {{ if (shadowlab_current > 0u) {{ uint k = shadowlab_current - 1u; \
         vec2 d = uv - shadowlab_receiver_uv; shadowlab_tap_sums[k] += vec4(1.0, d, dot(d, d)); \
         shadowlab_tap_moments[k] += vec4(d.x * d.x, d.y * d.y, d.x * d.y, 0.0); \
         shadowlab_tap_moments[k].w = max(shadowlab_tap_moments[k].w, length(d)); }} return uv; }}\n\
         vec4 shadowlab_taps(uint k) {{ vec4 s = shadowlab_tap_sums[k]; float n = max(s.x, 1.0); \
         return vec4(s.x, length(s.yz) / n, sqrt(s.w / n), shadowlab_tap_moments[k].w); }}\n\
         vec2 shadowlab_stretch(uint k) {{ vec4 m = shadowlab_tap_moments[k]; float t = m.x + m.y; \
         return t > 0.0 ? vec2(m.x - m.y, 2.0 * m.z) / t : vec2(0.0); }}\n",
        taps = taps.join(" ")
    )
}

/// A recorded function's wrapper: its parameter list (as the rewrite declares it: a `sampler2D`
/// is a texture and a sampler, no precision) and the arguments that pass them on. None where a
/// parameter has no name.
pub(super) fn wrapper_parameters(
    source: &str,
    toks: &[Token],
    (open, close): (usize, usize),
) -> Option<(String, String)> {
    let text = |i: usize| &source[toks[i].start..toks[i].end];
    let mut params = Vec::new();
    let mut args = Vec::new();
    let mut start = open + 1;
    let mut depth = 0;
    for j in open + 1..=close {
        match text(j) {
            "(" | "[" => depth += 1,
            ")" | "]" if j < close => depth -= 1,
            "," | ")" if depth == 0 => {
                let words: Vec<usize> =
                    (start..j).filter(|&w| !is_precision(text(w)) && text(w) != "const").collect();
                start = j + 1;
                if words.is_empty() || (words.len() == 1 && text(words[0]) == "void") {
                    continue;
                }
                let name_at = words.iter().rev().find(|&&w| toks[w].kind == Kind::Ident && text(w) != "]")?;
                let name_index = words.iter().position(|w| w == name_at)?;
                if name_index == 0 {
                    return None;
                }
                let name = text(*name_at);
                let declared: Vec<&str> = words.iter().map(|&w| text(w)).collect();
                if declared.contains(&"sampler2D") {
                    params.push(format!("texture2D {name}, sampler {name}_sampler"));
                    args.push(format!("{name}, {name}_sampler"));
                } else {
                    params.push(declared.join(" ").replace(" [", "[").replace("[ ", "[").replace(" ]", "]"));
                    args.push(name.to_string());
                }
            }
            _ => {}
        }
    }
    Some((params.join(", "), args.join(", ")))
}

/// The lines after the student's: a `main` that calls theirs. The vertex stage's converts the
/// framework's GL clip space to wgpu's (z from -w..w to 0..w; y flipped where the block says, so
/// that the light pass writes its map the way WebGL lays it out); the fragment stage's finds the
/// receiver's uv first (where the student's shader declares `vPositionFromLight`) and writes
/// what the recorded functions returned and where they read.
pub(super) fn epilogue(stage: Stage, declares_position_from_light: bool) -> String {
    let receiver = if declares_position_from_light {
        format!("shadowlab_receiver_uv = {POSITION_FROM_LIGHT}.xy / {POSITION_FROM_LIGHT}.w * 0.5 + 0.5;")
    } else {
        String::new()
    };
    match stage {
        Stage::Vertex => format!(
            "void main() {{ {STUDENT_MAIN}(); gl_Position.z = (gl_Position.z + gl_Position.w) * 0.5; \
             gl_Position.y *= {CLIP_Y_SIGN}; }}\n"
        ),
        Stage::Fragment => format!(
            "void main() {{ {receiver} {STUDENT_MAIN}(); shadowlab_Returned = shadowlab_returned; \
             shadowlab_Calls = uvec4(shadowlab_ran, shadowlab_visibility_function, min(shadowlab_calls, 255u), 1u); \
             shadowlab_Taps0 = shadowlab_taps(1u); shadowlab_Taps1 = shadowlab_taps(2u); \
             shadowlab_Taps2 = shadowlab_taps(3u); \
             shadowlab_Taps3 = vec4(shadowlab_stretch(1u), shadowlab_stretch(2u)); }}\n"
        ),
    }
}

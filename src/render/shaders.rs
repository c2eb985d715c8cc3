//! WGSL sources, composed from shaders/*.wgsl (one concern per file; no preprocessor).

const COMMON: &str = include_str!("../../shaders/common.wgsl");
const SHADOW_SAMPLING: &str = include_str!("../../shaders/shadow_sampling.wgsl");
const SHADOW_PASS: &str = include_str!("../../shaders/shadow_pass.wgsl");
const CAMERA: &str = include_str!("../../shaders/camera.wgsl");
const REFERENCE: &str = include_str!("../../shaders/reference.wgsl");

/// A composed shader module: its name (for errors and labels) and its full source.
pub struct ShaderSource {
    pub name: &'static str,
    pub source: String,
}

fn compose(name: &'static str, parts: &[&str]) -> ShaderSource {
    ShaderSource { name, source: parts.join("\n") }
}

pub fn shadow_pass() -> ShaderSource {
    compose("shadow_pass", &[COMMON, SHADOW_PASS])
}

pub fn camera() -> ShaderSource {
    compose("camera", &[COMMON, SHADOW_SAMPLING, CAMERA])
}

pub fn reference() -> ShaderSource {
    compose("reference", &[COMMON, SHADOW_SAMPLING, REFERENCE])
}

/// Every module the renderer builds (the naga validation test walks this list).
pub fn all() -> Vec<ShaderSource> {
    vec![shadow_pass(), camera(), reference()]
}

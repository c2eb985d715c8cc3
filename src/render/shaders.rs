//! WGSL sources, composed from shaders/*.wgsl (one concern per file; no preprocessor).

const COMMON: &str = include_str!("../../shaders/common.wgsl");
const SPECIALISATION: &str = include_str!("../../shaders/specialisation.wgsl");
const SHADOW_LOOKUP: &str = include_str!("../../shaders/shadow_lookup.wgsl");
const SHADOW_FILTER: &str = include_str!("../../shaders/shadow_filter.wgsl");
const SHADOW_PASS: &str = include_str!("../../shaders/shadow_pass.wgsl");
const CAMERA_FAST_PATHS: &str = include_str!("../../shaders/camera_fast_paths.wgsl");
const CAMERA: &str = include_str!("../../shaders/camera.wgsl");
const MOMENTS: &str = include_str!("../../shaders/moments.wgsl");
const REFERENCE: &str = include_str!("../../shaders/reference.wgsl");

/// A composed shader module: its name (for errors and labels) and its full source.
pub struct ShaderSource {
    pub name: &'static str,
    pub source: String,
}

fn compose(name: &'static str, parts: &[(&str, &'static str)]) -> ShaderSource {
    let dir = std::env::var_os(SHADER_DIR_VAR);
    let text = |(file, built_in): &(&str, &'static str)| match &dir {
        // Shader work without a rebuild: read the files from disk, the built-in copy where one is missing.
        Some(dir) => std::fs::read_to_string(std::path::Path::new(dir).join(file))
            .unwrap_or_else(|_| built_in.to_string()),
        None => built_in.to_string(),
    };
    ShaderSource { name, source: parts.iter().map(text).collect::<Vec<_>>().join("\n") }
}

/// Set to a folder (such as `shaders`) to load the WGSL files from there instead of the copies
/// built into the binary.
pub const SHADER_DIR_VAR: &str = "SHADOWLAB_SHADER_DIR";

pub fn shadow_pass() -> ShaderSource {
    compose("shadow_pass", &[("common.wgsl", COMMON), ("shadow_pass.wgsl", SHADOW_PASS)])
}

pub fn camera() -> ShaderSource {
    compose(
        "camera",
        &[
            ("common.wgsl", COMMON),
            ("specialisation.wgsl", SPECIALISATION),
            ("shadow_lookup.wgsl", SHADOW_LOOKUP),
            ("shadow_filter.wgsl", SHADOW_FILTER),
            ("camera_fast_paths.wgsl", CAMERA_FAST_PATHS),
            ("camera.wgsl", CAMERA),
        ],
    )
}

pub fn moments() -> ShaderSource {
    compose("moments", &[("moments.wgsl", MOMENTS)])
}

pub fn reference() -> ShaderSource {
    compose(
        "reference",
        &[
            ("common.wgsl", COMMON),
            ("specialisation.wgsl", SPECIALISATION),
            ("shadow_lookup.wgsl", SHADOW_LOOKUP),
            ("shadow_filter.wgsl", SHADOW_FILTER),
            ("reference.wgsl", REFERENCE),
        ],
    )
}

/// Every module the renderer builds (the naga validation test walks this list).
pub fn all() -> Vec<ShaderSource> {
    vec![shadow_pass(), camera(), moments(), reference()]
}

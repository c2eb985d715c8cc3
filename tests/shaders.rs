//! Every composed shader module parses and validates with naga, and the GPU structs have the
//! same size in WGSL as in Rust.

use shadowlab::render::shaders;
use shadowlab::shadow::{LightGpu, ShadowParamsGpu};

fn validate(source: &shaders::ShaderSource) -> (naga::Module, naga::valid::ModuleInfo) {
    let module = naga::front::wgsl::parse_str(&source.source)
        .unwrap_or_else(|e| panic!("{}: {}", source.name, e.emit_to_string(&source.source)));
    let info =
        naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::empty())
            .validate(&module)
            .unwrap_or_else(|e| panic!("{}: {}", source.name, e.emit_to_string(&source.source)));
    (module, info)
}

#[test]
fn every_shader_module_validates() {
    let all = shaders::all();
    assert!(all.len() >= 3);
    for source in &all {
        validate(source);
    }
}

fn struct_size(module: &naga::Module, name: &str) -> u32 {
    module
        .types
        .iter()
        .find(|(_, ty)| ty.name.as_deref() == Some(name))
        .map(|(_, ty)| ty.inner.size(module.to_ctx()))
        .unwrap_or_else(|| panic!("struct {name} not found"))
}

#[test]
fn gpu_structs_match_their_rust_mirrors() {
    let (module, _) = validate(&shaders::camera());
    assert_eq!(struct_size(&module, "LightGpu") as usize, std::mem::size_of::<LightGpu>());
    assert_eq!(struct_size(&module, "ShadowParamsGpu") as usize, std::mem::size_of::<ShadowParamsGpu>());
    assert_eq!(struct_size(&module, "FrameGpu"), 112);
    assert_eq!(struct_size(&module, "ObjectGpu"), 160);
}

#[test]
fn visibility_functions_have_their_lesson_names() {
    let source = shaders::camera().source;
    for name in [
        "fn visibility_hard",
        "fn visibility_pcf",
        "fn search_blockers",
        "fn estimate_penumbra",
        "fn visibility_pcss",
        "fn receiver_bias_ndc",
        "fn light_space_lookup",
    ] {
        assert!(source.contains(name), "shaders/shadow_lookup.wgsl or shadow_filter.wgsl lost `{name}`");
    }
}

#[test]
fn wgsl_numbering_matches_the_shadow_models() {
    // Techniques, bias modes, kernels and light-size models are numbered once, in
    // src/shadow/gpu.rs; shaders/common.wgsl must say the same numbers.
    let (module, _) = validate(&shaders::camera());
    for (name, value) in shadowlab::shadow::gpu::SHARED_CONSTANTS {
        let (_, constant) = module
            .constants
            .iter()
            .find(|(_, c)| c.name.as_deref() == Some(name))
            .unwrap_or_else(|| panic!("shaders/common.wgsl has no `{name}`"));
        let wgsl = match module.global_expressions[constant.init] {
            naga::Expression::Literal(naga::Literal::U32(v)) => v,
            ref other => panic!("`{name}` is not a u32 literal: {other:?}"),
        };
        assert_eq!(wgsl, value, "`{name}`: WGSL says {wgsl}, the shadow model {value}");
    }
}

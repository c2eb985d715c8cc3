//! Every composed shader module parses and validates with naga, and the GPU structs have the
//! same size in WGSL as in Rust.

use shadowlab::render::shaders;
use shadowlab::shadow::{LightGpu, LightViewGpu, ShadowParamsGpu, ShadowViewGpu};

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
    assert_eq!(struct_size(&module, "ShadowViewGpu") as usize, std::mem::size_of::<ShadowViewGpu>());
    let (reference, _) = validate(&shaders::reference());
    assert_eq!(struct_size(&reference, "LightViewGpu") as usize, std::mem::size_of::<LightViewGpu>());
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

/// Both dispatchers name every technique the shadow model numbers, and send an id they do not
/// know to an impossible visibility, never to hard shadows: a technique added on one side only
/// cannot pass the GPU = twin test as a hard shadow.
#[test]
fn every_technique_is_dispatched_and_an_unknown_id_is_visible_on_both_sides() {
    use shadowlab::shadow::{DepthImage, Twin, VISIBILITY_UNKNOWN_TECHNIQUE, gpu::SHARED_CONSTANTS};
    let techniques: Vec<(&str, u32)> =
        SHARED_CONSTANTS.iter().copied().filter(|(n, _)| n.starts_with("TECHNIQUE_")).collect();
    // The shader: a case per technique in `shadow_visibility`, and the same impossible value.
    let camera = shaders::camera();
    let start = camera.source.find("fn shadow_visibility(").expect("the dispatcher");
    let body = &camera.source[start..][..camera.source[start..].find("\n}\n").expect("its end")];
    for (name, _) in &techniques {
        assert!(body.contains(&format!("case {name}:")), "shadow_visibility has no case {name}");
    }
    assert!(body.contains("default: {\n            out.visibility = VISIBILITY_UNKNOWN_TECHNIQUE;"));
    let (module, _) = validate(&camera);
    let (_, constant) = module
        .constants
        .iter()
        .find(|(_, c)| c.name.as_deref() == Some("VISIBILITY_UNKNOWN_TECHNIQUE"))
        .expect("the constant");
    match module.global_expressions[constant.init] {
        naga::Expression::Literal(naga::Literal::F32(v)) => assert_eq!(v, VISIBILITY_UNKNOWN_TECHNIQUE),
        ref other => panic!("not an f32 literal: {other:?}"),
    }
    // The twin: every technique gives a visibility, an unknown id the impossible one.
    let scene = shadowlab::scene::load_scene(&shadowlab::shipped_path("assets/scenes/games202.toml"), &[])
        .expect("the scene");
    let light = LightViewGpu::single(&scene.lights[0], 0.0, 64);
    let map = DepthImage { size: 64, depth_ndc: vec![1.0; 64 * 64] };
    let visibility_of = |technique: u32| {
        let params = ShadowParamsGpu { technique, ..ShadowParamsGpu::new(&scene.shadow) };
        let mut twin = Twin::new(&light.light, &light.view, &params, &map);
        let coord = twin.light_space_lookup(glam::Vec3::ZERO, glam::Vec3::Y);
        twin.shadow_visibility(&coord, 0).visibility
    };
    for (name, id) in &techniques {
        let v = visibility_of(*id);
        assert!((0.0..=1.0).contains(&v), "{name}: the twin's visibility {v}");
    }
    assert_eq!(visibility_of(99), VISIBILITY_UNKNOWN_TECHNIQUE);
}

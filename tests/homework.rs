//! A student's WebGL1 homework shader through the rewrite and naga: the project's own sample
//! shaders (tests/data/homework, written against the GAMES202 framework's interface) each rewrite
//! to GLSL 450 with every student line where it was, translate to WGSL that validates, and an
//! error names the student's file and line.

use shadowlab::homework::{
    BindingKind, CLIP_Y_SIGN_OFFSET_BYTES, FRAMEWORK_UNIFORMS, FRAMEWORK_UNIFORMS_SIZE_BYTES, HomeworkError,
    Interface, SamplerFilter, Stage, Translated, rewrite, translate,
};

fn data(name: &str) -> String {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/homework").join(name);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Both stages of a program, gathered into one interface and translated.
fn program(vertex: &str, fragment: &str) -> (Translated, Translated) {
    let (vs, fs) = (data(vertex), data(fragment));
    let layout = Interface::gather(&[&vs, &fs]).expect("an interface");
    let v = translate(vertex, &vs, Stage::Vertex, &layout).unwrap_or_else(|e| panic!("{e}"));
    let f = translate(fragment, &fs, Stage::Fragment, &layout).unwrap_or_else(|e| panic!("{e}"));
    (v, f)
}

/// The rewrite's line property: the student's part has exactly the source's lines, each at its
/// own number plus the prelude; lines the rewrite has nothing to change are the same text.
fn assert_lines_kept(name: &str, stage: Stage, translated: &Translated) {
    let source = data(name);
    let r = &translated.rewritten;
    let lines: Vec<&str> = r.glsl.split('\n').collect();
    let source_lines: Vec<&str> = source.split('\n').collect();
    assert_eq!(lines.len(), r.prelude_lines + source_lines.len() + r.epilogue_lines, "{name}: line count");
    assert_eq!(lines[0], "#version 450", "{name}");
    assert_eq!(r.stage, stage);
    for (n, line) in source.lines().enumerate() {
        let untouched = ["//", "}", "#define", "#ifdef", "#endif", "for (", "if ("]
            .iter()
            .any(|start| line.trim_start().starts_with(start))
            || line.trim().is_empty();
        let rewritten = lines[n + r.prelude_lines];
        if untouched && !r.added_returns.contains(&(n + 1)) {
            // A recorded function's wrapper follows its closing brace on the same line.
            let wrapped = line.trim() == "}" && rewritten.starts_with("} float ");
            assert!(rewritten == line || wrapped, "{name}:{}: {rewritten}", n + 1);
        }
    }
    for gone in [
        "precision",
        "varying",
        "attribute",
        "gl_FragColor",
        "highp",
        "mediump",
        "texture2D(",
        "#version 100",
    ] {
        assert!(!r.glsl.contains(gone), "{name}: `{gone}` left in\n{}", r.glsl);
    }
}

/// naga reads its own WGSL back and validates it: the translation is a shader wgpu can take.
fn assert_wgsl_valid(name: &str, wgsl: &str) {
    let module = naga::front::wgsl::parse_str(wgsl).unwrap_or_else(|e| panic!("{name}: {e}\n{wgsl}"));
    naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::default())
        .validate(&module)
        .unwrap_or_else(|e| panic!("{name}: {e:?}"));
}

fn check_program(vertex: &str, fragment: &str) -> (Translated, Translated) {
    let (v, f) = program(vertex, fragment);
    assert_lines_kept(vertex, Stage::Vertex, &v);
    assert_lines_kept(fragment, Stage::Fragment, &f);
    assert_wgsl_valid(vertex, &v.wgsl);
    assert_wgsl_valid(fragment, &f.wgsl);
    assert!(v.wgsl.contains("@vertex") && f.wgsl.contains("@fragment"));
    (v, f)
}

#[test]
fn the_template_filled_in_translates_with_its_lines_kept() {
    let (v, f) = check_program("phongVertex.glsl", "phongFragment.glsl");
    let glsl = &f.rewritten.glsl;
    // Varyings by name, the framework's in its fixed order; the colour output at location 0.
    assert!(glsl.contains("layout(location = 0) in vec2 vTextureCoord;"));
    assert!(glsl.contains("layout(location = 3) in vec4 vPositionFromLight;"));
    assert!(v.rewritten.glsl.contains("layout(location = 3) out vec4 vPositionFromLight;"));
    assert!(glsl.contains("layout(location = 0) out vec4 shadowlab_FragColor;"));
    // Attributes in the framework's order.
    let attributes: Vec<(&str, u32)> = v.rewritten.attributes.iter().map(|(n, l)| (n.as_str(), *l)).collect();
    assert_eq!(attributes, [("aVertexPosition", 0), ("aNormalPosition", 1), ("aTextureCoord", 2)]);
    // Textures split, the shadow map's sampler nearest, the colour's linear; parameters carry both.
    assert!(glsl.contains("uniform texture2D uShadowMap;"));
    assert!(glsl.contains("float findBlocker(texture2D shadowMap, sampler shadowMap_sampler, vec2 uv"));
    // At level 0 explicitly: a lookup in a loop is not in uniform control flow (WGSL refuses
    // implicit levels there).
    // Every 2D read's uv goes through the tap that records where the student's functions read.
    assert!(
        glsl.contains(
            "textureLod(sampler2D(shadowMap, shadowMap_sampler), shadowlab_tap( uv + poissonDisk[i]"
        )
    );
    assert!(glsl.contains("PCSS(uShadowMap, uShadowMap_sampler, vec4(shadowCoord, 1.0))"));
    assert!(glsl.contains("void poissonDiskSamples(in vec2 randomSeed)"), "`const in` becomes `in`");
    let sampler = |name: &str| f.rewritten.bindings.iter().find(|b| b.name == name).map(|b| b.kind.clone());
    assert_eq!(sampler("uShadowMap_sampler"), Some(BindingKind::Sampler(SamplerFilter::Nearest)));
    assert_eq!(sampler("uSampler_sampler"), Some(BindingKind::Sampler(SamplerFilter::Linear)));
    assert!(f.rewritten.added_returns.is_empty());
    assert!(f.wgsl.contains("textureSample"));
}

#[test]
fn the_light_pass_with_pack_translates() {
    let (_, f) = check_program("shadowVertex.glsl", "shadowFragment.glsl");
    assert!(f.rewritten.glsl.contains("shadowlab_FragColor = pack(gl_FragCoord.z);"));
}

#[test]
fn changed_signatures_and_ndc_coordinates_translate() {
    let (_, f) = check_program("phongVertex.glsl", "phongFragment_signatures.glsl");
    let glsl = &f.rewritten.glsl;
    assert!(glsl.contains(
        "float PCF(texture2D shadowMap, sampler shadowMap_sampler, vec4 coordsNdc, float filterRadiusUV, float biasNdc)"
    ));
    assert!(glsl.contains("return PCF(shadowMap, shadowMap_sampler, coordsNdc, penumbraUV, biasNdc);"));
    assert!(!glsl.contains("#extension"));
}

#[test]
fn helpers_taking_sampler2d_and_missing_returns_translate() {
    let (_, f) = check_program("phongVertex.glsl", "phongFragment_helpers.glsl");
    let source = data("phongFragment_helpers.glsl");
    let glsl = &f.rewritten.glsl;
    let lines: Vec<&str> = source.split('\n').collect();
    // The prototype nothing calls before its definition is gone, its line left empty.
    let at =
        lines.iter().position(|l| l.starts_with("float PCF(sampler2D shadowMap, vec4 coords);")).expect("it");
    assert_eq!(glsl.split('\n').nth(at + f.rewritten.prelude_lines), Some(""));
    assert!(
        glsl.contains("return unpack(textureLod(sampler2D(map, map_sampler), shadowlab_tap( uv), 0.0));")
    );
    assert!(glsl.contains("depthAt(map, map_sampler, uv + radius"));
    // findBlocker and noBlockerYet lack a final return: each gets one before its closing brace.
    let closing = |header: &str| {
        let start = lines.iter().position(|l| l.starts_with(header)).expect("the function");
        start + lines[start..].iter().position(|l| *l == "}").expect("its end") + 1
    };
    assert_eq!(f.rewritten.added_returns, [closing("float findBlocker("), closing("vec2 noBlockerYet(")]);
    let line =
        |n: usize| glsl.split('\n').nth(n - 1 + f.rewritten.prelude_lines).unwrap_or_default().to_string();
    // findBlocker's closing line also carries the wrapper that records what it returns.
    assert!(line(f.rewritten.added_returns[0]).starts_with("return 0.0; } float findBlocker("));
    assert_eq!(f.rewritten.recorded, ["PCF", "findBlocker"]);
    assert_eq!(line(f.rewritten.added_returns[1]), "return vec2(0.0); }");
}

#[test]
fn a_students_own_uniforms_and_varyings_translate_and_agree_between_stages() {
    let (v, f) = check_program("phongVertex_additions.glsl", "phongFragment_additions.glsl");
    let layout =
        Interface::gather(&[&data("phongVertex_additions.glsl"), &data("phongFragment_additions.glsl")])
            .expect("an interface");
    assert_eq!(layout.extra_varyings, ["vDepthView", "vOffsetFromLight"]);
    assert_eq!(layout.varying_location("vDepthView"), Some(4));
    assert_eq!(layout.varying_location("vOffsetFromLight"), Some(5));
    for (r, dir) in [(&v.rewritten, "out"), (&f.rewritten, "in")] {
        assert!(r.glsl.contains(&format!("layout(location = 4) {dir} float vDepthView;")));
        assert!(r.glsl.contains(&format!("layout(location = 5) {dir} vec4 vOffsetFromLight;")));
        // The same second block in both stages, in the order of the names.
        assert!(r.glsl.contains(
            "uniform ShadowlabStudent { vec2 uBiasMinMax; float uLightWidthUV; float uNormalOffsetWorld; int uTechnique; };"
        ));
        assert!(r.bindings.iter().any(|b| b.name == "ShadowlabStudent" && b.binding == 1));
    }
}

/// Line 40 of a sample broken two ways: the error names the file and the student's line 40.
#[test]
fn an_error_names_the_students_file_and_line() {
    for (fragment, broken) in [
        ("phongFragment.glsl", "  highp float wrapped = mod(along, PI) +;"),
        ("phongFragment.glsl", "  highp float wrapped = mod(notDeclaredAnywhere, PI);"),
        ("phongFragment_additions.glsl", "      lit += useShadowMap(shadowMap, coords.xy, bias);"),
    ] {
        let source = data(fragment);
        let mut lines: Vec<&str> = source.split('\n').collect();
        let n = if fragment == "phongFragment.glsl" { 40 } else { 33 };
        lines[n - 1] = broken;
        let source = lines.join("\n");
        let layout =
            Interface::gather(&[&data("phongVertex_additions.glsl"), &source]).expect("an interface");
        let error = translate(fragment, &source, Stage::Fragment, &layout).expect_err("a broken shader");
        let shown = error.to_string();
        assert_eq!(error.line(), Some(n), "{shown}");
        assert!(shown.starts_with(&format!("{fragment}:{n}: ")), "{shown}");
        assert!(!shown.contains('\n'), "{shown}");
    }
}

#[test]
fn a_framework_uniform_with_the_wrong_type_is_an_error_on_its_line() {
    let source = data("phongFragment.glsl").replace("uniform vec3 uKs;", "uniform vec4 uKs;");
    let error = Interface::gather(&[&source]).expect_err("a wrong type");
    assert_eq!(error.line(), Some(8));
    assert!(error.to_string().contains("uKs is a vec3 in the framework"), "{error}");
    // Rewritten against the framework alone, a student's own uniform is named as missing.
    let own = data("phongFragment_additions.glsl");
    let error = rewrite(&own, Stage::Fragment, &Interface::framework()).expect_err("not gathered");
    assert!(matches!(error, HomeworkError::Rewrite { line: 9, .. }), "{error}");
    assert!(error.in_file("f.glsl").to_string().starts_with("f.glsl:9: uniform uLightWidthUV"));
}

/// A student's own texture gets the next bindings (texture, then its linear sampler) and samples.
#[test]
fn a_students_own_texture_gets_its_own_bindings() {
    let source = data("phongFragment_helpers.glsl")
        .replace("uniform vec3 uLightPos;", "uniform vec3 uLightPos; uniform sampler2D uNoise;")
        .replace("float light = max(", "float light = texture2D(uNoise, coords.xy).r * max(");
    let layout = Interface::gather(&[&source]).expect("an interface");
    assert_eq!(layout.texture_binding("uNoise"), Some((6, SamplerFilter::Linear)));
    let f =
        translate("phongFragment.glsl", &source, Stage::Fragment, &layout).unwrap_or_else(|e| panic!("{e}"));
    assert!(
        f.rewritten
            .glsl
            .contains("textureLod(sampler2D(uNoise, uNoise_sampler), shadowlab_tap( coords.xy), 0.0)")
    );
    let binding = |name: &str| {
        f.rewritten.bindings.iter().find(|b| b.name == name).map(|b| (b.binding, b.kind.clone()))
    };
    assert_eq!(binding("uNoise"), Some((6, BindingKind::Texture)));
    assert_eq!(binding("uNoise_sampler"), Some((7, BindingKind::Sampler(SamplerFilter::Linear))));
    assert_wgsl_valid("phongFragment.glsl", &f.wgsl);
}

/// The framework's block as naga lays it out (std140) is where the renderer writes it: every
/// member at the offset `FRAMEWORK_UNIFORMS` gives, shadowlab's clip sign packed after uKd.
#[test]
fn the_framework_block_is_laid_out_where_the_renderer_writes_it() {
    let (v, _) = program("phongVertex.glsl", "phongFragment.glsl");
    let module = naga::front::wgsl::parse_str(&v.wgsl).expect("WGSL");
    let mut layouter = naga::proc::Layouter::default();
    layouter.update(module.to_ctx()).expect("a layout");
    let block = module
        .global_variables
        .iter()
        .find(|(_, g)| g.binding.as_ref().is_some_and(|b| b.group == 0 && b.binding == 0))
        .expect("the framework block")
        .1;
    let naga::TypeInner::Struct { members, .. } = &module.types[block.ty].inner else {
        panic!("the block is a struct")
    };
    for field in FRAMEWORK_UNIFORMS {
        let member = members.iter().find(|m| m.name.as_deref() == Some(field.name)).expect(field.name);
        assert_eq!(member.offset, field.offset_bytes, "{}", field.name);
    }
    let sign = members.iter().find(|m| m.name.as_deref() == Some("shadowlab_ClipYSign")).expect("the sign");
    assert_eq!(sign.offset, CLIP_Y_SIGN_OFFSET_BYTES);
    assert_eq!(layouter[block.ty].size, FRAMEWORK_UNIFORMS_SIZE_BYTES);
}

/// The bonus's lights in arrays indexed by light: shadowlab checks one light at a time, every
/// element holding it, so each array reads as the framework's single name, on the same lines.
#[test]
fn the_frameworks_per_light_names_declared_as_arrays_read_the_light_checked() {
    let (v, f) = check_program("phongVertex_lights.glsl", "phongFragment_lights.glsl");
    let layout = Interface::gather(&[&data("phongVertex_lights.glsl"), &data("phongFragment_lights.glsl")])
        .expect("an interface");
    assert_eq!(
        layout.per_light,
        ["uLightIntensity", "uLightMVP", "uLightPos", "uShadowMap", "vPositionFromLight"]
    );
    assert!(layout.extra_uniforms.is_empty() && layout.extra_varyings.is_empty(), "{layout:?}");
    let line = |r: &shadowlab::homework::Rewritten, n: usize| {
        r.glsl.split('\n').nth(r.prelude_lines + n - 1).map(str::trim).map(String::from)
    };
    assert_eq!(
        line(&v.rewritten, 24).as_deref(),
        Some("vPositionFromLight = uLightMVP * vec4(aVertexPosition, 1.0);")
    );
    assert_eq!(
        line(&f.rewritten, 49).as_deref(),
        Some("float visibility = useShadowMap(uShadowMap, uShadowMap_sampler, vec4(shadowCoord, 1.0));")
    );
    assert_eq!(
        line(&f.rewritten, 50).as_deref(),
        Some("sum += visibility * radiance(albedo, uLightPos, uLightIntensity);")
    );
    // The varying is the framework's one location, and the receiver's uv is read from it.
    assert!(f.rewritten.glsl.contains("layout(location = 3) in vec4 vPositionFromLight;"));
    assert!(f.rewritten.glsl.contains("shadowlab_receiver_uv = vPositionFromLight.xy"));
    // The light pass picks its matrix by the page's uLightIndex: a uniform of the student's own.
    let shadow = data("shadowVertex_lights.glsl");
    let layout = Interface::gather(&[&shadow, &data("shadowFragment.glsl")]).expect("an interface");
    assert_eq!(layout.extra_uniforms, [("uLightIndex".to_string(), "int".to_string())]);
    let s = translate("shadowVertex.glsl", &shadow, Stage::Vertex, &layout).unwrap_or_else(|e| panic!("{e}"));
    assert_wgsl_valid("shadowVertex_lights.glsl", &s.wgsl);
    // A per-light name of another type is still refused on its line.
    let wrong = data("phongVertex_lights.glsl").replace("uniform mat4 uLightMVP[", "uniform mat3 uLightMVP[");
    let error = Interface::gather(&[&wrong]).expect_err("a wrong type");
    assert_eq!(error.line(), Some(10));
    assert!(
        error.to_string().contains("uLightMVP is a mat4 in the framework, declared mat3[NUM_LIGHTS]"),
        "{error}"
    );
}

/// A second light's names copied under a number (`uLightMVP1`, `uShadowMap1`,
/// `vPositionFromLight1`): like an array's elements, each copy holds the light checked, so the
/// rewrite reads it as the framework's one, declared once, on the same lines.
#[test]
fn the_frameworks_per_light_names_copied_under_a_number_read_the_light_checked() {
    let vertex = data("phongVertex.glsl")
        .replace("uniform mat4 uLightMVP;", "uniform mat4 uLightMVP; uniform mat4 uLightMVP1;")
        .replace(
            "varying highp vec4 vPositionFromLight;",
            "varying highp vec4 vPositionFromLight; varying highp vec4 vPositionFromLight1;",
        )
        .replace(
            "  vPositionFromLight = uLightMVP * vec4(aVertexPosition, 1.0);",
            "  vPositionFromLight = uLightMVP * vec4(aVertexPosition, 1.0); vPositionFromLight1 = uLightMVP1 * vec4(aVertexPosition, 1.0);",
        );
    let fragment = data("phongFragment.glsl")
        .replace("uniform sampler2D uShadowMap;", "uniform sampler2D uShadowMap; uniform sampler2D uShadowMap1;")
        .replace("varying vec4 vPositionFromLight;", "varying vec4 vPositionFromLight; varying vec4 vPositionFromLight1;")
        .replace(
            "  visibility = PCSS(uShadowMap, vec4(shadowCoord, 1.0));",
            "  visibility = PCSS(uShadowMap, vec4(shadowCoord, 1.0)) * texture2D(uShadowMap1, vPositionFromLight1.xy).r;",
        );
    let layout = Interface::gather(&[&vertex, &fragment]).expect("an interface");
    let copies: Vec<(&str, &str)> =
        layout.per_light_copies.iter().map(|(c, b)| (c.as_str(), b.as_str())).collect();
    assert_eq!(
        copies,
        [
            ("uLightMVP1", "uLightMVP"),
            ("uShadowMap1", "uShadowMap"),
            ("vPositionFromLight1", "vPositionFromLight")
        ]
    );
    assert!(layout.extra_uniforms.is_empty() && layout.extra_varyings.is_empty(), "{layout:?}");
    assert!(layout.extra_textures.is_empty(), "{layout:?}");
    let v = translate("phongVertex.glsl", &vertex, Stage::Vertex, &layout).unwrap_or_else(|e| panic!("{e}"));
    let f = translate("phongFragment.glsl", &fragment, Stage::Fragment, &layout)
        .unwrap_or_else(|e| panic!("{e}"));
    assert_wgsl_valid("phongVertex.glsl", &v.wgsl);
    assert_wgsl_valid("phongFragment.glsl", &f.wgsl);
    let line = |r: &shadowlab::homework::Rewritten, n: usize| {
        r.glsl.split('\n').nth(r.prelude_lines + n - 1).map(str::trim).map(String::from).unwrap_or_default()
    };
    assert_eq!(
        line(&v.rewritten, 21),
        "vPositionFromLight = uLightMVP * vec4(aVertexPosition, 1.0); vPositionFromLight = uLightMVP * vec4(aVertexPosition, 1.0);"
    );
    assert!(
        line(&f.rewritten, 138)
            .contains("(sampler2D(uShadowMap, uShadowMap_sampler), shadowlab_tap( vPositionFromLight.xy)"),
        "{}",
        line(&f.rewritten, 138)
    );
    assert_eq!(f.rewritten.glsl.matches("uniform texture2D uShadowMap;").count(), 1);
    assert_eq!(f.rewritten.glsl.matches("in vec4 vPositionFromLight;").count(), 1);
}

/// A uniform of the student's own sized by a `#define` of one stage: the block both stages declare
/// has the size written out (the other stage may not define the name).
#[test]
fn an_array_uniform_sized_by_a_define_is_declared_with_its_size_in_both_stages() {
    let fragment = data("phongFragment.glsl").replace(
        "uniform vec3 uKs;",
        "uniform vec3 uKs;\n#define NUM_WEIGHTS 3\nuniform vec4 uWeights[NUM_WEIGHTS];",
    );
    let vertex = data("phongVertex.glsl");
    let layout = Interface::gather(&[&vertex, &fragment]).expect("an interface");
    assert_eq!(layout.extra_uniforms, [("uWeights".to_string(), "vec4[3]".to_string())]);
    let v = translate("phongVertex.glsl", &vertex, Stage::Vertex, &layout).unwrap_or_else(|e| panic!("{e}"));
    let f = translate("phongFragment.glsl", &fragment, Stage::Fragment, &layout)
        .unwrap_or_else(|e| panic!("{e}"));
    for t in [&v, &f] {
        assert!(
            t.rewritten.glsl.contains("uniform ShadowlabStudent { vec4 uWeights[3]; };"),
            "{}",
            t.rewritten.glsl
        );
    }
    assert_wgsl_valid("phongVertex.glsl", &v.wgsl);
    assert_wgsl_valid("phongFragment.glsl", &f.wgsl);
}

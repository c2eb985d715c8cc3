//! The student's page in a real engine: the light their engine.js makes, its CalcLightMVP against
//! the same matrices composed here with glam, a light built with three.js, and hostile scripts
//! that each end in one line naming the file.

use std::time::Duration;

use super::*;

pub(super) const EXAMPLE_LIGHT: &str = include_str!("../../../assets/homework/DirectionalLight.js");
pub(super) const FRAMEWORK_ENGINE: &str = include_str!("../../../assets/homework/framework/src/engine.js");

pub(super) fn source(name: &str, text: &str) -> ShaderSource {
    ShaderSource { name: name.into(), path: None, text: text.into() }
}

/// The objects the tests ask matrices for: (translate, scale), world units.
pub(super) const OBJECTS: [Placed; 4] = [
    ([0.0; 3], [1.0; 3]),
    ([40.0, 0.0, -40.0], [10.0; 3]),
    ([0.0, 0.0, -30.0], [4.0; 3]),
    ([1.0, 2.0, 3.0], [2.0; 3]),
];

fn load(light: &str, engine: Option<&str>) -> Result<(PageRun, EngineLight), ScriptError> {
    let engine = engine.map(|e| source("engine.js", e));
    let run = PageRun::run(
        &source("DirectionalLight.js", light),
        engine.as_ref(),
        &[],
        &OBJECTS,
        Limits::default(),
    )?;
    let light = run.engine_light.clone();
    Ok((run, light))
}

pub(super) fn line_of(text: &str, needle: &str) -> usize {
    text.lines().position(|l| l.contains(needle)).map_or(0, |i| i + 1)
}

#[test]
fn the_light_engine_js_makes_is_recorded_with_its_line() {
    let engine = FRAMEWORK_ENGINE.replace("const lightPos = [0, 80, 80];", "const lightPos = [10, 90, 70];");
    let (page, light) = load(EXAMPLE_LIGHT, Some(&engine)).expect("the page runs");
    assert_eq!(light.position.value, [10.0, 90.0, 70.0]);
    assert_eq!(light.intensity.value, 5000.0);
    assert_eq!(light.focal_point.value, [0.0; 3]);
    assert_eq!(light.position.file, "engine.js");
    assert_eq!(light.position.line, line_of(&engine, "new DirectionalLight("));
    assert!(page.notes().is_empty(), "{:?}", page.notes());
}

#[test]
fn calc_light_mvp_is_the_matrix_its_gl_matrix_calls_compose() {
    // The example light: ortho(-100, 100, -100, 100, 0.01, 400) * lookAt(light, focal, up) *
    // translate * scale, composed here in f64 by glam (gl-matrix computes in f64 and stores each
    // matrix in a Float32Array: a few f32 ulps apart at most).
    let (page, light) = load(EXAMPLE_LIGHT, None).expect("the page runs");
    let [eye, focal, up] =
        [light.position.value, light.focal_point.value, light.up.value].map(glam::DVec3::from);
    let view_clip = glam::DMat4::orthographic_rh_gl(-100.0, 100.0, -100.0, 100.0, 0.01, 400.0)
        * glam::DMat4::look_at_rh(eye, focal, up);
    for (t, s) in [([0.0; 3], [1.0; 3]), ([40.0, 0.0, -40.0], [10.0; 3]), ([0.0, 0.0, -30.0], [4.0; 3])] {
        let expected = view_clip
            * glam::DMat4::from_translation(glam::DVec3::from(t))
            * glam::DMat4::from_scale(glam::DVec3::from(s));
        let got = page.light_matrix(t, s).expect("a matrix");
        for (a, b) in got.clip_from_object.iter().zip(expected.to_cols_array()) {
            assert!((f64::from(*a) - b).abs() <= 1e-6 * b.abs().max(1.0), "{t:?} {s:?}: {a} vs {b}");
        }
        let names: Vec<(String, usize)> = got.calls.iter().map(|c| (c.name.clone(), c.line)).collect();
        let at = |needle: &str| line_of(EXAMPLE_LIGHT, needle);
        let expected_calls = [
            ("mat4.translate", at("mat4.translate(")),
            ("mat4.scale", at("mat4.scale(")),
            ("mat4.lookAt", at("mat4.lookAt(")),
            ("mat4.ortho", at("mat4.ortho(")),
            ("mat4.multiply", at("mat4.multiply(mvp, projection")),
            ("mat4.multiply", at("mat4.multiply(mvp, mvp")),
        ];
        let calls: Vec<(String, usize)> =
            names.into_iter().filter(|(name, _)| name != "mat4.create").collect();
        assert_eq!(calls, expected_calls.map(|(n, l)| (n.to_string(), l)).to_vec());
        assert_eq!(got.return_line, line_of(EXAMPLE_LIGHT, "return mvp;"));
    }
}

#[test]
fn a_light_built_with_three_js_runs() {
    let light = "class DirectionalLight {
  constructor(i, c, pos, focal, up, shadow, gl) {
    this.lightPos = pos; this.focalPoint = focal; this.lightUp = up;
  }
  CalcLightMVP(translate, scale) {
    const camera = new THREE.OrthographicCamera(-100, 100, 100, -100, 0.01, 400);
    camera.position.set(...this.lightPos);
    camera.up.set(...this.lightUp);
    camera.lookAt(...this.focalPoint);
    camera.updateMatrixWorld();
    const model = new THREE.Matrix4().compose(new THREE.Vector3(...translate), new THREE.Quaternion(), new THREE.Vector3(...scale));
    return new THREE.Matrix4().multiplyMatrices(camera.projectionMatrix, camera.matrixWorldInverse).multiply(model).elements;
  }
}";
    let (page, _) = load(light, None).expect("the page runs");
    let three = page.light_matrix([40.0, 0.0, -40.0], [10.0; 3]).expect("a matrix");
    let (reference, _) = load(EXAMPLE_LIGHT, None).expect("the page runs");
    let gl_matrix = reference.light_matrix([40.0, 0.0, -40.0], [10.0; 3]).expect("a matrix");
    for (a, b) in three.clip_from_object.iter().zip(gl_matrix.clip_from_object) {
        assert!((a - b).abs() < 1e-5, "{:?} vs {:?}", three.clip_from_object, gl_matrix.clip_from_object);
    }
    let camera =
        three.calls.iter().find(|c| c.name == "THREE.OrthographicCamera").expect("the camera is logged");
    assert_eq!(camera.line, line_of(light, "new THREE.OrthographicCamera"));
    assert_eq!(camera.args, vec![-100.0, 100.0, 100.0, -100.0, 0.01, 400.0]);
}

/// The error of loading `light` (or of its first matrix), which must be one line.
fn error_of(light: &str, engine: Option<&str>, limits: Limits) -> ScriptError {
    let e = match PageRun::run(
        &source("DirectionalLight.js", light),
        engine.map(|e| source("engine.js", e)).as_ref(),
        &[],
        &OBJECTS,
        limits,
    ) {
        Err(e) => e,
        Ok(page) => match page.light_matrix([0.0; 3], [1.0; 3]) {
            Err(e) => e,
            Ok(m) => panic!("expected an error, got {m:?}"),
        },
    };
    assert!(!e.to_string().contains('\n'), "{e}");
    e
}

fn with_body(body: &str) -> String {
    format!(
        "class DirectionalLight {{\n  constructor() {{}}\n  CalcLightMVP(translate, scale) {{\n{body}\n  }}\n}}\n"
    )
}

#[test]
fn hostile_scripts_each_end_in_one_line_naming_the_file() {
    let short = Limits { time: Duration::from_millis(300), ..Limits::default() };
    let cases: [(&str, &str, &str); 6] = [
        // QuickJS places an interrupted loop on its function's line; the message names the function.
        ("    while (true) {}", "CalcLightMVP(", "time bound of 0.3 s in CalcLightMVP"),
        ("    const a = []; for (;;) a.push(new Array(100000).fill(1));", "const a = []", "memory bound"),
        ("    const f = (n) => f(n + 1) + 1; return f(0);", "const f", "stack bound"),
        ("    throw new Error('no light today');", "throw new Error", "no light today"),
        ("    return fetch('http://example.com/light');", "fetch(", "fetch is not available"),
        ("    document.body.innerHTML = ''; return window.location.href;", "", "returned a string"),
    ];
    for (body, needle, message) in cases {
        let light = with_body(body);
        // Only the endless loop waits for the time bound; the others end long before it.
        let limits = if message.contains("time bound") { short } else { Limits::default() };
        let e = error_of(&light, None, limits);
        assert_eq!(e.file, "DirectionalLight.js", "{e}");
        if !needle.is_empty() {
            assert_eq!(e.line, line_of(&light, needle), "{e}");
        }
        assert!(e.message.contains(message), "{body}: {e}");
    }
}

#[test]
fn a_prototype_trick_cannot_change_what_shadowlab_reads() {
    // Replacing the built-ins shadowlab reads the result with changes nothing it reads.
    let light = EXAMPLE_LIGHT.replace(
        "class DirectionalLight {",
        "JSON.stringify = () => '{}'; Array.isArray = () => false; Object.prototype.matrix = null;\nclass DirectionalLight {",
    );
    let (page, _) = load(&light, None).expect("the page runs");
    let (reference, _) = load(EXAMPLE_LIGHT, None).expect("the page runs");
    let a = page.light_matrix([1.0, 2.0, 3.0], [2.0; 3]).expect("a matrix");
    let b = reference.light_matrix([1.0, 2.0, 3.0], [2.0; 3]).expect("a matrix");
    assert_eq!(a.clip_from_object, b.clip_from_object);
}

#[test]
fn a_failing_engine_js_is_a_note_and_the_framework_light_is_used() {
    let engine = "const canvas = document.querySelector('#glcanvas');\nundefinedFunction();\n";
    let (page, light) = load(EXAMPLE_LIGHT, Some(engine)).expect("the page runs");
    assert_eq!(light.position.value, [0.0, 80.0, 80.0]);
    assert!(page.notes().iter().any(|n| n.starts_with("engine.js:2: ")), "{:?}", page.notes());
    assert!(page.notes().iter().any(|n| n.contains("makes no DirectionalLight")), "{:?}", page.notes());
    page.light_matrix([0.0; 3], [1.0; 3]).expect("the framework's light still has a matrix");
}

#[test]
fn a_constructor_that_throws_gets_the_template_fields() {
    let light = EXAMPLE_LIGHT
        .replace("this.fbo = new FBO(gl);", "this.fbo = new FBO(gl);\n    throw new Error('no gl');");
    let (page, engine_light) = load(&light, None).expect("the page runs");
    assert_eq!(engine_light.position.value, [0.0, 80.0, 80.0]);
    assert!(
        page.notes().iter().any(|n| n.contains("constructor failed") && n.contains("no gl")),
        "{:?}",
        page.notes()
    );
    page.light_matrix([0.0; 3], [1.0; 3]).expect("CalcLightMVP runs on the template's fields");
}

#[test]
fn a_script_without_the_class_or_method_says_so() {
    let e = error_of("class Light {}", None, Limits::default());
    assert_eq!(e.to_string(), "DirectionalLight.js: no class or function named DirectionalLight");
    let e = error_of("class DirectionalLight { constructor() {} }", None, Limits::default());
    assert_eq!(e.to_string(), "DirectionalLight.js: DirectionalLight has no CalcLightMVP method");
    let e = error_of(
        "class DirectionalLight {\n  CalcLightMVP() {\n    return [1, 2];\n  }\n}",
        None,
        Limits::default(),
    );
    assert_eq!(
        e.to_string(),
        "DirectionalLight.js:2: CalcLightMVP returned an array of 2 elements, not a 4x4 matrix"
    );
    let e = error_of(
        "class DirectionalLight {\n  CalcLightMVP() {\n    let x = (1 + ;\n  }\n}",
        None,
        Limits::default(),
    );
    assert_eq!((e.file.as_str(), e.line), ("DirectionalLight.js", 3), "{e}");
}

#[test]
fn the_last_return_of_a_method_is_found_past_strings_and_comments() {
    let text = "class L {\n  CalcLightMVP(t, s) {\n    const a = '}'; // return }\n    /* { return */\n    if (t) { return 1; }\n    return `}`;\n  }\n  other() { return 2; }\n}";
    assert_eq!(last_return(text, 2), Some(6));
    assert_eq!(last_return(text, 8), Some(8));
    assert_eq!(last_return("function f() {}", 1), None);
    assert_eq!(method_line(text), Some(2));
    assert_eq!(
        method_line("// CalcLightMVP(x)\nx.CalcLightMVP(1);\nL.prototype.CalcLightMVP = function () {};"),
        Some(3)
    );
}

const FRAMEWORK_PHONG: &str =
    include_str!("../../../assets/homework/framework/src/materials/PhongMaterial.js");

#[test]
fn the_whole_page_runs_and_its_own_uniforms_are_recorded_by_name() {
    // A page whose PhongMaterial sets uniforms of its own, as many students do: one the same
    // for every object, one that differs between their floor (scale 4) and their models.
    let phong = FRAMEWORK_PHONG.replace(
        "uLightMVP: { type: 'matrix4fv', value: lightMVP },",
        "uLightMVP: { type: 'matrix4fv', value: lightMVP },\n            uFrustumSize: { type: '1f', value: 340 },\n            uReceiveShadow: { type: '1f', value: scale[0] === 4 ? 1 : 0 },",
    );
    let fragment = "uniform float uFrustumSize;\nuniform float uReceiveShadow;\nvoid main() { gl_FragColor = vec4(uFrustumSize * uReceiveShadow); }\n";
    let page = [
        source("hw/src/engine.js", FRAMEWORK_ENGINE),
        source("hw/src/materials/PhongMaterial.js", &phong),
        source("hw/src/shaders/phongShader/phongFragment.glsl", fragment),
    ];
    let page_light = PageRun::run(
        &source("hw/src/lights/DirectionalLight.js", EXAMPLE_LIGHT),
        Some(&page[0]),
        &page,
        &OBJECTS,
        Limits::default(),
    )
    .expect("the page runs");
    assert!(page_light.notes().is_empty(), "{:?}", page_light.notes());
    let camera = page_light.draws().uniforms_for(fragment);
    for kind in [&camera.floor, &camera.other] {
        assert_eq!(kind.get("uFrustumSize"), Some(&vec![340.0]), "{camera:?}");
        assert_eq!(kind.get("uLightPos"), Some(&vec![0.0, 80.0, 80.0]));
    }
    // Their floor's value goes to shadowlab's floor, their models' to every other object.
    assert_eq!(camera.floor.get("uReceiveShadow"), Some(&vec![1.0]), "{camera:?}");
    assert_eq!(camera.other.get("uReceiveShadow"), Some(&vec![0.0]), "{camera:?}");
    let (lights, checked) = page_light.lights();
    assert_eq!(lights.len(), 1);
    assert_eq!(checked, Some(0));
    assert_eq!(
        lights[0].made_at,
        format!("hw/src/engine.js:{}", line_of(FRAMEWORK_ENGINE, "new DirectionalLight("))
    );
}

#[test]
fn an_endless_frame_or_promise_ends_in_one_line_naming_its_file() {
    let short = Limits { time: Duration::from_millis(300), ..Limits::default() };
    for engine in [
        "requestAnimationFrame(function spin() {\n  while (true) {}\n});\n",
        "Promise.resolve().then(function wait() {\n  for (;;) {}\n});\n",
    ] {
        let e = error_of(EXAMPLE_LIGHT, Some(engine), short);
        assert_eq!(e.file, "engine.js", "{e}");
        assert!(e.message.contains("time bound of 0.3 s"), "{e}");
    }
}

/// The framework's engine.js whose main loop moves the light as `moving` says each frame.
fn animated_engine(moving: &str) -> String {
    let engine = FRAMEWORK_ENGINE
        .replace("        renderer.render();", &format!("        renderer.render();\n        {moving}"));
    assert_ne!(engine, FRAMEWORK_ENGINE, "the main loop's render call is where it was");
    engine
}

#[test]
fn a_light_the_page_moves_is_looked_at_again_where_it_moved() {
    // An orbit about y, its angle from the page's clock (Date.now, as real homework writes it).
    let engine = animated_engine(
        "const a = Date.now() * 0.001; directionLight.lightPos = [80 * Math.sin(a), 80, 80 * Math.cos(a)];",
    );
    let (mut page, _) = load(EXAMPLE_LIGHT, Some(&engine)).expect("the page runs");
    let times = page.times_of(0);
    assert_eq!(times, vec![0.5, 1.0, 2.0]);
    for t in times {
        let light = page.select(0, Some(t)).expect("the light then");
        // The frame that reaches t runs at a whole number of 60 Hz frames.
        let seconds = (t * 60.0).ceil() / 60.0;
        let expected = [80.0 * seconds.sin(), 80.0, 80.0 * seconds.cos()];
        for (got, want) in light.position.value.iter().zip(expected) {
            assert!((got - want).abs() < 1e-9, "at {t} s: {:?} vs {expected:?}", light.position.value);
        }
        // Its matrices are the light's there: the origin lies on its axis, at its distance.
        let m = page.light_matrix([0.0; 3], [1.0; 3]).expect("a matrix").clip_from_object;
        let origin = glam::Mat4::from_cols_array(&m) * glam::Vec4::W;
        assert!(origin.x.abs() < 1e-5 && origin.y.abs() < 1e-5, "{origin}");
    }
    // Back to the light as the page drew its first frames (two, at 60 Hz: the last at 1/60 s),
    // where the matrices of those frames put it, with a note that it was made elsewhere.
    let light = page.select(0, None).expect("the light");
    let first = 1.0f64 / 60.0;
    let expected = [80.0 * first.sin(), 80.0, 80.0 * first.cos()];
    for (got, want) in light.position.value.iter().zip(expected) {
        assert!((got - want).abs() < 1e-9, "{:?} vs {expected:?}", light.position.value);
    }
    assert!(
        page.notes().iter().any(|n| n.contains("at (0, 80, 80) was at (1.3, 80.0, 80.0)")),
        "{:?}",
        page.notes()
    );
    // A page that moves nothing is not looked at again.
    let (still, _) = load(EXAMPLE_LIGHT, None).expect("the page runs");
    assert!(still.times_of(0).is_empty());
}

//! Reading the light from engine.js-style files (written fresh for these tests).

use super::*;

const ENGINE: &str = r#"var cameraPosition = [30, 30, 30]

// 阴影贴图的分辨率
var resolution = 2048;

GAMES202Main();

function GAMES202Main() {
	const canvas = document.querySelector('#glcanvas');
	const gl = canvas.getContext('webgl');
	const camera = new THREE.PerspectiveCamera(75, gl.canvas.clientWidth / gl.canvas.clientHeight, 1e-2, 1000);
	const renderer = new WebGLRenderer(gl, camera);

	// Add lights
	let lightPos = [0, 80, 80];
	let focalPoint = [0, 0, 0];
	let lightUp = [0, 1, 0]
	const directionLight = new DirectionalLight(5000, [1, 1, 1], lightPos, focalPoint, lightUp, true, renderer.gl);
	renderer.addLight(directionLight);

	let floorTransform = setTransform(0, 0, -30, 4, 4, 4);
	loadOBJ(renderer, 'assets/floor/', 'floor', 'PhongMaterial', floorTransform);
	window.addEventListener('resize', () => setSize(canvas.clientWidth, canvas.clientHeight));
}
"#;

fn line_of(src: &str, needle: &str) -> usize {
    src.lines().position(|l| l.contains(needle)).map_or(0, |i| i + 1)
}

#[test]
fn framework_style_engine() {
    let light = engine_light(ENGINE, "engine.js", Limits::default());
    assert!(light.notes.is_empty(), "{:?}", light.notes);
    let call = line_of(ENGINE, "new DirectionalLight");
    assert_eq!(light.intensity, Sourced { value: 5000.0, file: "engine.js".into(), line: call });
    assert_eq!(light.color.value, [1.0, 1.0, 1.0]);
    assert_eq!(light.color.line, call);
    assert_eq!(
        light.position,
        Sourced { value: [0.0, 80.0, 80.0], file: "engine.js".into(), line: line_of(ENGINE, "let lightPos") }
    );
    assert_eq!(light.focal_point.line, line_of(ENGINE, "let focalPoint"));
    assert_eq!(light.up.value, [0.0, 1.0, 0.0]);
    assert_eq!(light.up.line, line_of(ENGINE, "let lightUp"));
}

#[test]
fn literal_arrays_in_the_call() {
    let src =
        ENGINE.replace("lightPos, focalPoint, lightUp, true", "[10, 60, 30], [0, 5, 0], [0, 1, 0], true");
    let light = engine_light(&src, "engine.js", Limits::default());
    assert!(light.notes.is_empty(), "{:?}", light.notes);
    assert_eq!(light.position.value, [10.0, 60.0, 30.0]);
    assert_eq!(light.position.line, line_of(&src, "new DirectionalLight"));
    assert_eq!(light.focal_point.value, [0.0, 5.0, 0.0]);
}

#[test]
fn arithmetic_and_names_in_definitions() {
    let src = ENGINE.replace("let lightPos = [0, 80, 80];", "let lightPos = [0, 40 * 2, 80];");
    assert_eq!(engine_light(&src, "engine.js", Limits::default()).position.value, [0.0, 80.0, 80.0]);
    let src = ENGINE.replace(
        "let lightPos = [0, 80, 80];",
        "const h = 50, d = h / 2;\n\tlet lightPos = [0, h + d, Math.sqrt(d * d)];",
    );
    let light = engine_light(&src, "engine.js", Limits::default());
    assert_eq!(light.position.value, [0.0, 75.0, 25.0]);
    assert!(light.notes.is_empty(), "{:?}", light.notes);
    let src = ENGINE.replace("new DirectionalLight(5000,", "new DirectionalLight(2500 * 2 + 1,");
    assert_eq!(engine_light(&src, "engine.js", Limits::default()).intensity.value, 5001.0);
}

#[test]
fn nearest_preceding_definition_wins() {
    let src = ENGINE.replace(
        "let lightPos = [0, 80, 80];",
        "let lightPos = [0, 80, 80];\n\tlightPos = [5, 6, 7]\n\tcamera.lightPos = [9, 9, 9];",
    );
    let light = engine_light(&src, "engine.js", Limits::default());
    assert_eq!(light.position.value, [5.0, 6.0, 7.0]);
    assert_eq!(light.position.line, line_of(&src, "lightPos = [5, 6, 7]"));
}

#[test]
fn missing_call_uses_the_framework() {
    let src = ENGINE.replace("new DirectionalLight(", "new PointLight(");
    let light = engine_light(&src, "engine.js", Limits::default());
    let fw = EngineLight::framework();
    assert_eq!(
        (light.intensity.clone(), light.position.clone(), light.up.clone()),
        (fw.intensity, fw.position, fw.up)
    );
    assert_eq!(light.notes.len(), 1);
    assert!(light.notes[0].contains("no `new DirectionalLight"), "{:?}", light.notes);
}

#[test]
fn unreadable_arguments_fall_back_one_by_one() {
    let src = ENGINE
        .replace("[1, 1, 1], lightPos", "getColor(), lightPos")
        .replace("let lightUp = [0, 1, 0]", "let lightUp = [0, 1]");
    let light = engine_light(&src, "engine.js", Limits::default());
    assert_eq!(light.position.value, [0.0, 80.0, 80.0]);
    assert_eq!(light.position.file, "engine.js");
    assert_eq!(light.color, EngineLight::framework().color);
    assert_eq!(light.up, EngineLight::framework().up);
    assert_eq!(light.notes.len(), 2, "{:?}", light.notes);
    assert!(light.notes[0].contains("color") && light.notes[0].contains("getColor"), "{}", light.notes[0]);
    assert!(
        light.notes[1].contains("up vector") && light.notes[1].contains("2 elements"),
        "{}",
        light.notes[1]
    );
    assert!(light.notes.iter().all(|n| !n.contains('\n')));
}

#[test]
fn undefined_name_and_broken_files() {
    let src = ENGINE.replace("let focalPoint = [0, 0, 0];", "");
    let light = engine_light(&src, "engine.js", Limits::default());
    assert_eq!(light.notes.len(), 1, "{:?}", light.notes);
    assert!(light.notes[0].contains("focalPoint"));
    // A lexing error after the call does not hide the call.
    let src = format!("{ENGINE}\nlet broken = 'unterminated\n");
    let light = engine_light(&src, "engine.js", Limits::default());
    assert_eq!(light.position.line, line_of(ENGINE, "let lightPos"));
    // Nothing readable at all.
    for junk in [
        "",
        "\"",
        "new DirectionalLight(",
        "new DirectionalLight(lightPos",
        "let a = a; new DirectionalLight(a, a, a, a, a)",
    ] {
        let light = engine_light(junk, "engine.js", Limits::default());
        assert_eq!(light.position.value, [0.0, 80.0, 80.0], "{junk}");
        assert!(!light.notes.is_empty(), "{junk}");
    }
}

#[test]
fn two_lights_note_the_first_is_used() {
    let src = ENGINE.replace("renderer.addLight(directionLight);", "renderer.addLight(directionLight);\n\tnew DirectionalLight(1, [1, 1, 1], [1, 2, 3], focalPoint, lightUp, true, renderer.gl);");
    let light = engine_light(&src, "engine.js", Limits::default());
    assert_eq!(light.position.value, [0.0, 80.0, 80.0]);
    assert_eq!(light.notes.len(), 1);
}

#[test]
fn hostile_engine_files_stay_bounded() {
    let names: Vec<String> = (0..5000).map(|i| format!("n{i}")).collect();
    let defs: String = names.iter().map(|n| format!("let {n} = 1;\n")).collect();
    let src = format!("{defs}let lightPos = [[{}].length, 0, 0];\n{ENGINE}", names.join(", "));
    let src = src.replace("\tlet lightPos = [0, 80, 80];\n", "");
    let t0 = std::time::Instant::now();
    let light = engine_light(&src, "engine.js", Limits::default());
    assert!(t0.elapsed() < std::time::Duration::from_secs(10));
    assert_eq!(light.position.value, [0.0, 80.0, 80.0]);
    assert!(light.notes[0].contains("more than 64 names"), "{:?}", light.notes);
    let src = ENGINE.replace("let lightPos = [0, 80, 80];", "let lightPos = (() => { while (true) {} })();");
    let light = engine_light(&src, "engine.js", Limits { steps: 10_000, ..Limits::default() });
    assert!(light.notes[0].contains("did not finish within 10000 steps"), "{:?}", light.notes);
}

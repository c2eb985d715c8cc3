//! `shadowlab homework` on a student's whole page, as a process: their own scripts run in order
//! with shadowlab's copy of the framework where they have none; a light uniform renamed in their
//! materials and shaders is fed as their page feeds it; a page with several lights lists each
//! with the line of their code that made it, and checks each DirectionalLight on its own, and
//! again at the times of their animation where it had moved.

mod common;

use common::{Run, repo_path};
use serde_json::Value;
use std::path::Path;

const SIZE: &str = "480x270";

fn shadowlab<S: AsRef<std::ffi::OsStr>>(args: &[S]) -> Run {
    common::run(common::shadowlab_command().args(args))
}

fn read(path: &str) -> String {
    std::fs::read_to_string(repo_path(path)).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// `text` with `from` replaced by `to`, which must be in it.
fn edit(text: &str, from: &str, to: &str) -> String {
    assert!(text.contains(from), "{from:?} is not in the text");
    text.replace(from, to)
}

fn line_of(text: &str, needle: &str) -> usize {
    text.lines().position(|l| l.contains(needle)).map_or(0, |i| i + 1)
}

/// Writes `files` (path in the submission, text) as `root/student/homework1/...` and checks the
/// folder into `root/out`.
fn run_folder(root: &Path, files: &[(&str, String)]) -> Run {
    for (path, text) in files {
        let to = root.join("student/homework1").join(path);
        std::fs::create_dir_all(to.parent().expect("a parent")).expect("folders");
        std::fs::write(&to, text).expect("write");
    }
    let out = root.join("out");
    shadowlab(&[
        "homework",
        &root.join("student").display().to_string(),
        "--size",
        SIZE,
        "--out",
        &out.display().to_string(),
        "--json",
    ])
}

/// The report of checking `files` (see `run_folder`), which must succeed.
fn check_folder(root: &Path, files: &[(&str, String)]) -> Value {
    let run = run_folder(root, files);
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    serde_json::from_str(&run.stdout).expect("the report is JSON")
}

/// The correct example's light with a `CalcLightVP()` (projection * view, no model matrix).
fn light_with_vp() -> String {
    edit(
        &read("assets/homework/DirectionalLight.js"),
        "  CalcLightMVP(translate, scale) {",
        "  CalcLightVP() {
    const view = mat4.create();
    const projection = mat4.create();
    const vp = mat4.create();
    mat4.lookAt(view, this.lightPos, this.focalPoint, this.lightUp);
    mat4.ortho(projection, -100, 100, -100, 100, 0.01, 400);
    mat4.multiply(vp, projection, view);
    return vp;
  }

  CalcLightMVP(translate, scale) {",
    )
}

#[test]
fn a_renamed_light_uniform_is_fed_as_the_students_page_feeds_it() {
    // Their materials set `uLightVP` (no model matrix) and their vertex shaders apply the model
    // matrix themselves: the framework's `uLightMVP` is never set. A correct solution otherwise.
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let material = |name: &str| {
        edit(
            &read(&format!("assets/homework/framework/src/materials/{name}.js")),
            "uLightMVP: { type: 'matrix4fv', value: lightMVP },",
            "uLightVP: { type: 'matrix4fv', value: light.CalcLightVP() },",
        )
    };
    let phong_vertex = edit(
        &edit(
            &read("assets/homework/framework/phongVertex.glsl"),
            "uniform mat4 uLightMVP;",
            "uniform mat4 uLightVP;",
        ),
        "uLightMVP * vec4(aVertexPosition, 1.0)",
        "uLightVP * world",
    );
    let shadow_vertex = edit(
        &edit(
            &read("assets/homework/framework/shadowVertex.glsl"),
            "uniform mat4 uLightMVP;",
            "uniform mat4 uModelMatrix;\nuniform mat4 uLightVP;",
        ),
        "uLightMVP * vec4(aVertexPosition, 1.0)",
        "uLightVP * uModelMatrix * vec4(aVertexPosition, 1.0)",
    );
    let files = [
        ("src/shaders/phongShader/phongFragment.glsl", read("assets/homework/phongFragment.glsl")),
        ("src/shaders/phongShader/phongVertex.glsl", phong_vertex),
        ("src/shaders/shadowShader/shadowVertex.glsl", shadow_vertex),
        ("src/lights/DirectionalLight.js", light_with_vp()),
        ("src/materials/PhongMaterial.js", material("PhongMaterial")),
        ("src/materials/ShadowMaterial.js", material("ShadowMaterial")),
        ("src/engine.js", read("assets/homework/framework/src/engine.js")),
    ];
    let report = check_folder(scratch.path(), &files);
    assert_eq!(report["findings"], serde_json::json!([]), "{:#}", report["findings"]);
    let light = &report["light"];
    assert_eq!(light["error"], Value::Null, "{light:#}");
    for pass in ["camera", "shadow"] {
        let vp = light["page_uniforms"][pass]["other"]["uLightVP"].as_array().expect("uLightVP was recorded");
        assert_eq!(vp.len(), 16, "{pass}");
    }
}

#[test]
fn each_light_of_a_page_with_several_is_listed_and_checked_on_its_own() {
    // The bonus: a second light behind the scene (sound) that orbits the y axis, its angle from
    // the page's clock, and a third so high that the framework's far plane (400) leaves the floor
    // out of its map.
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let engine = edit(
        &edit(
            &read("assets/homework/framework/src/engine.js"),
            "    renderer.addLight(directionLight);",
            "    renderer.addLight(directionLight);
    const secondLight = new DirectionalLight(2500, [1, 1, 1], [0, 80, -80], focalPoint, lightUp, true, renderer.gl);
    renderer.addLight(secondLight);
    const highLight = new DirectionalLight(2500, [1, 1, 1], [0, 420, 1], focalPoint, lightUp, true, renderer.gl);
    renderer.addLight(highLight);",
        ),
        "        renderer.render();",
        "        renderer.render();
        const angle = Date.now() * 0.001;
        secondLight.lightPos = [-80 * Math.sin(angle), 80, -80 * Math.cos(angle)];",
    );
    let files = [
        ("src/shaders/phongShader/phongFragment.glsl", read("assets/homework/phongFragment.glsl")),
        ("src/lights/DirectionalLight.js", read("assets/homework/DirectionalLight.js")),
        ("src/engine.js", engine.clone()),
    ];
    let report = check_folder(scratch.path(), &files);
    let lights = report["lights"].as_array().expect("the page's lights");
    assert_eq!(lights.len(), 3, "{lights:#?}");
    let made_at = |needle: &str| format!("homework1/src/engine.js:{}", line_of(&engine, needle));
    assert_eq!(lights[0]["made_at"], made_at("const directionLight = new DirectionalLight("));
    assert_eq!(lights[0]["checked"], true);
    assert_eq!(lights[0]["from"], report["light"]["from"]);
    assert_eq!(lights[1]["made_at"], made_at("const secondLight = new DirectionalLight("));
    assert_eq!(lights[1]["checked"], false);
    assert_eq!(lights[1]["position"], serde_json::json!([0.0, 80.0, -80.0]));
    let ids = |light: &Value| -> Vec<String> {
        light["findings"]
            .as_array()
            .unwrap_or_else(|| panic!("no findings of its own: {light:#}"))
            .iter()
            .map(|f| f.as_str().expect("an id").to_string())
            .collect()
    };
    // The first light's are the report's own. The second is sound but for one thing: the
    // framework's materials compute the first light's matrix only, so the page never draws with
    // the second's (nor the third's).
    let report_ids: Vec<String> = report["findings"]
        .as_array()
        .expect("findings")
        .iter()
        .map(|f| f["id"].as_str().expect("an id").to_string())
        .collect();
    assert_eq!(ids(&lights[0]), report_ids);
    assert_eq!(ids(&lights[1]), ["light_not_drawn"]);
    assert!(ids(&lights[2]).contains(&"light_not_drawn".to_string()), "{:?}", ids(&lights[2]));
    assert!(ids(&lights[2]).contains(&"light_frustum_clips".to_string()), "{:?}", ids(&lights[2]));
    // The orbiting light is checked again where it had moved: at 0.5, 1 and 2 s of the page's
    // animation (the first 60 Hz frame at or after each), each with its position and findings.
    assert_eq!(lights[1]["moved_at_s"], serde_json::json!([0.5, 1.0, 2.0]));
    let at_times = lights[1]["at_times"].as_array().expect("its checks at those times");
    assert_eq!(at_times.len(), 3, "{at_times:#?}");
    for check in at_times {
        let t = check["time_s"].as_f64().expect("a time");
        let x = check["position"][0].as_f64().expect("a position");
        assert!((x + 80.0 * t.sin()).abs() < 1e-3, "at {t} s the light is at x = {x}");
        assert!(check["findings"].is_array(), "{check:#}");
    }
    assert!(lights[0].get("moved_at_s").is_none() && lights[2].get("moved_at_s").is_none());
    for picture in [
        "student_light1.png",
        "student_light2.png",
        "student_light1_t0.5s.png",
        "student_light1_t2.0s.png",
        "student_map.png",
        "student_light1_map.png",
    ] {
        assert!(scratch.path().join("out").join(picture).is_file(), "{picture} is missing");
    }
}

/// The bonus in arrays indexed by light (`uLightMVP[NUM_LIGHTS]`, `uShadowMap[NUM_LIGHTS]`, a
/// light pass that picks its matrix by `uLightIndex`): each light is checked on its own, every
/// element holding it, and a mistake in the loop they share is found on each.
#[test]
fn lights_in_arrays_indexed_by_light_are_each_checked() {
    let engine = edit(
        &read("assets/homework/framework/src/engine.js"),
        "    renderer.addLight(directionLight);",
        "    renderer.addLight(directionLight);
    const secondLight = new DirectionalLight(2500, [1, 1, 1], [0, 80, -80], focalPoint, lightUp, true, renderer.gl);
    renderer.addLight(secondLight);",
    );
    // Their materials set each element by name, from the page's list of lights.
    let engine = edit(
        &engine,
        "    renderer.addLight(secondLight);",
        "    renderer.addLight(secondLight);\n    window.pageLights = [directionLight, secondLight];",
    );
    let material = |name: &str| {
        edit(
            &read(&format!("assets/homework/framework/src/materials/{name}.js")),
            "uLightMVP: { type: 'matrix4fv', value: lightMVP },",
            "'uLightMVP[0]': { type: 'matrix4fv', value: window.pageLights[0].CalcLightMVP(translate, scale) },
            'uLightMVP[1]': { type: 'matrix4fv', value: window.pageLights[1].CalcLightMVP(translate, scale) },",
        )
    };
    let fragment = read("tests/data/homework/phongFragment_lights.glsl");
    let files = |fragment: String| {
        [
            ("src/materials/PhongMaterial.js", material("PhongMaterial")),
            ("src/materials/ShadowMaterial.js", material("ShadowMaterial")),
            ("src/shaders/phongShader/phongFragment.glsl", fragment),
            ("src/shaders/phongShader/phongVertex.glsl", read("tests/data/homework/phongVertex_lights.glsl")),
            (
                "src/shaders/shadowShader/shadowVertex.glsl",
                read("tests/data/homework/shadowVertex_lights.glsl"),
            ),
            ("src/lights/DirectionalLight.js", read("assets/homework/DirectionalLight.js")),
            ("src/engine.js", engine.clone()),
        ]
    };
    let findings_of_each = |report: &Value| -> Vec<Vec<String>> {
        let lights = report["lights"].as_array().expect("the page's lights");
        assert_eq!(lights.len(), 2, "{lights:#?}");
        lights
            .iter()
            .map(|l| {
                let ids = l["findings"].as_array().unwrap_or_else(|| panic!("not checked: {l:#}"));
                ids.iter().map(|f| f.as_str().expect("an id").to_string()).collect()
            })
            .collect()
    };
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let sound = check_folder(scratch.path(), &files(fragment.clone()));
    assert_eq!(findings_of_each(&sound), [Vec::<String>::new(), Vec::new()]);
    let notes = sound["submission"]["notes"].to_string();
    assert!(
        notes.contains("uLightMVP, uLightPos, uShadowMap, vPositionFromLight are arrays by light"),
        "{notes}"
    );
    assert!(scratch.path().join("out/student_light1.png").is_file());
    // No bias in the loop both lights run: each shadows itself.
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let unbiased =
        check_folder(scratch.path(), &files(edit(&fragment, "#define BIAS 0.003", "#define BIAS 0.0")));
    for (light, ids) in findings_of_each(&unbiased).iter().enumerate() {
        assert!(ids.contains(&"self_shadowing".to_string()), "light {light}: {ids:?}");
    }
}

/// A lamp: a PointLight whose CalcLightMVP is a perspective projection, a map of distances to it
/// (over a far plane of the page's own uniform), the object's model matrix sent under a name of
/// the page's own (`uLightModel`), lookups outside its frustum taken as lit. The check runs it
/// as their page does: the lamp is the light checked, named where its projection is built, its
/// model-matrix uniform gets each check object's own, the map's distances are sound, and the
/// framework's floor outside the frustum is named as unshadowed, not as a black band.
#[test]
fn a_lamp_with_a_map_of_distances_is_checked_as_the_page_draws_it() {
    // The correct example's light made a lamp: a class of its own with a 90-degree perspective.
    let lamp = edit(
        &edit(&read("assets/homework/DirectionalLight.js"), "class DirectionalLight {", "class PointLight {"),
        "mat4.ortho(projection, -halfWidth, halfWidth, -halfWidth, halfWidth, 0.01, 400);",
        "mat4.perspective(projection, Math.PI / 2, 1, 1, 300);",
    );
    let engine = edit(
        &read("assets/homework/framework/src/engine.js"),
        "const directionLight = new DirectionalLight(5000, [1, 1, 1], lightPos,",
        "const directionLight = new PointLight(5000, [1, 1, 1], [0, 60, 40],",
    );
    let far = "uLightFarPlane: { type: '1f', value: 300 },";
    let shadow_material = edit(
        &read("assets/homework/framework/src/materials/ShadowMaterial.js"),
        "uLightMVP: { type: 'matrix4fv', value: lightMVP },",
        &format!(
            "uLightMVP: {{ type: 'matrix4fv', value: lightMVP }}, {far}
            uLightModel: {{ type: 'matrix4fv', value: mat4.scale(mat4.create(), mat4.fromTranslation(mat4.create(), translate), scale) }},"
        ),
    );
    let phong_material = edit(
        &read("assets/homework/framework/src/materials/PhongMaterial.js"),
        "uLightMVP: { type: 'matrix4fv', value: lightMVP },",
        &format!("uLightMVP: {{ type: 'matrix4fv', value: lightMVP }}, {far}"),
    );
    let fragment = read("tests/data/homework/phongFragment_lamp.glsl");
    let files = [
        ("src/shaders/phongShader/phongFragment.glsl", fragment.clone()),
        ("src/shaders/shadowShader/shadowVertex.glsl", read("tests/data/homework/shadowVertex_lamp.glsl")),
        (
            "src/shaders/shadowShader/shadowFragment.glsl",
            read("tests/data/homework/shadowFragment_lamp.glsl"),
        ),
        ("src/lights/DirectionalLight.js", read("assets/homework/DirectionalLight.js")),
        ("src/lights/PointLight.js", lamp.clone()),
        ("src/materials/ShadowMaterial.js", shadow_material),
        ("src/materials/PhongMaterial.js", phong_material),
        ("src/engine.js", engine),
    ];
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let report = check_folder(scratch.path(), &files);
    let light = &report["light"];
    assert_eq!(light["error"], Value::Null, "{light:#}");
    assert_eq!(
        light["from"],
        format!("homework1/src/lights/PointLight.js:{}", line_of(&lamp, "mat4.perspective("))
    );
    assert_eq!(light["frustum"]["kind"], "perspective", "{:#}", light["frustum"]);
    assert_eq!(report["lights"][0]["kind"], "PointLight");
    assert_eq!(report["lights"][0]["checked"], true);
    assert_eq!(light["page_uniforms"]["shadow"]["model_matrices"], serde_json::json!(["uLightModel"]));
    let ids: Vec<&str> =
        report["findings"].as_array().expect("findings").iter().filter_map(|f| f["id"].as_str()).collect();
    assert!(!ids.contains(&"depth_round_trip_wrong"), "{:#}", report["findings"]);
    let clips = report["findings"]
        .as_array()
        .and_then(|f| f.iter().find(|f| f["id"] == "light_frustum_clips"))
        .unwrap_or_else(|| panic!("the floor outside the lamp's frustum: {:#}", report["findings"]));
    let said = clips["explanation"].as_str().expect("an explanation");
    assert!(
        said.contains(&format!(
            "Your line {} takes whatever lies outside the map as lit",
            line_of(&fragment, "if (coord.x < 0.0")
        )),
        "{said}"
    );
    assert_eq!(ids, ["light_frustum_clips"], "{:#}", report["findings"]);
    // The same guard under the framework's own light, whose box leaves only the floor's x edges
    // out (where nothing stands): sound, nothing to say.
    let guarded = edit(
        &read("assets/homework/phongFragment.glsl"),
        "  visibility = PCSS(uShadowMap, vec4(shadowCoord, 1.0));",
        "  if (shadowCoord.x < 0.0 || shadowCoord.x > 1.0 || shadowCoord.y < 0.0 || shadowCoord.y > 1.0) {
    visibility = 1.0;
  } else {
    visibility = PCSS(uShadowMap, vec4(shadowCoord, 1.0));
  }",
    );
    let files = [
        ("src/shaders/phongShader/phongFragment.glsl", guarded),
        ("src/lights/DirectionalLight.js", read("assets/homework/DirectionalLight.js")),
        ("src/engine.js", read("assets/homework/framework/src/engine.js")),
    ];
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let report = check_folder(scratch.path(), &files);
    assert_eq!(report["findings"], serde_json::json!([]), "{:#}", report["findings"]);
}

/// The ids of a report's findings.
fn finding_ids(report: &Value) -> Vec<String> {
    report["findings"]
        .as_array()
        .expect("findings")
        .iter()
        .filter_map(|f| f["id"].as_str().map(String::from))
        .collect()
}

/// The explanation of the report's finding `id`.
fn explanation_of<'r>(report: &'r Value, id: &str) -> &'r str {
    report["findings"]
        .as_array()
        .and_then(|f| f.iter().find(|f| f["id"] == id))
        .and_then(|f| f["explanation"].as_str())
        .unwrap_or_else(|| panic!("no {id}: {:#}", report["findings"]))
}

/// Things that move in the page's animation, and the `uLightMVP` its draws get: computed once
/// in the framework's materials (as they load), it does not follow a light or an object that
/// the main loop moves; computed again each frame, it does. A second light the materials never
/// compute a matrix for is never drawn with.
#[test]
fn what_moves_is_checked_against_the_light_matrices_the_page_draws_with() {
    let framework_engine = read("assets/homework/framework/src/engine.js");
    let in_main_loop = |moving: &str| {
        edit(
            &framework_engine,
            "        renderer.render();",
            &format!("        {moving}\n        renderer.render();"),
        )
    };
    let check = |engine: String| {
        let files = [
            ("src/shaders/phongShader/phongFragment.glsl", read("assets/homework/phongFragment.glsl")),
            ("src/lights/DirectionalLight.js", read("assets/homework/DirectionalLight.js")),
            ("src/engine.js", engine),
        ];
        let scratch = tempfile::tempdir().expect("a scratch folder");
        check_folder(scratch.path(), &files)
    };
    // The small Mary slides up and down; its uLightMVP is the one its material computed.
    let slide = "for (const m of renderer.meshes) { if (m.mesh.transform.translate[2] === -40) m.mesh.transform.translate[1] = 10 * Math.sin(Date.now() * 0.002); }";
    let stale_object = check(in_main_loop(slide));
    assert_eq!(finding_ids(&stale_object), ["light_matrix_stale"], "{:#}", stale_object["findings"]);
    let said = explanation_of(&stale_object, "light_matrix_stale");
    assert!(said.contains("From 0.5 s of your page's animation assets/mary/Marry.obj moves"), "{said}");
    let material = read("assets/homework/framework/src/materials/PhongMaterial.js");
    let line = line_of(&material, "light.CalcLightMVP(");
    assert!(
        said.contains(&format!(
            "only while it loads (src/materials/PhongMaterial.js:{line} (the framework's)"
        )),
        "{said}"
    );
    // Computed again each frame, for both passes: sound.
    let recomputed = format!(
        "{slide} for (const m of renderer.meshes.concat(renderer.shadowMeshes)) m.material.uniforms.uLightMVP.value = directionLight.CalcLightMVP(m.mesh.transform.translate, m.mesh.transform.scale);"
    );
    let followed = check(in_main_loop(&recomputed));
    assert_eq!(finding_ids(&followed), Vec::<String>::new(), "{:#}", followed["findings"]);
    // The one light orbits; the materials keep the matrix of where it was.
    let orbit =
        "const a = Date.now() * 0.001; directionLight.lightPos = [80 * Math.sin(a), 80, 80 * Math.cos(a)];";
    let stale_light = check(in_main_loop(orbit));
    assert!(
        finding_ids(&stale_light).contains(&"light_matrix_stale".to_string()),
        "{:#}",
        stale_light["findings"]
    );
    let said = explanation_of(&stale_light, "light_matrix_stale");
    assert!(said.contains("From 0.5 s of your page's animation the light has moved"), "{said}");
    // A second light added to the framework: its materials compute the first light's matrix
    // only, so no draw is ever made with the second's.
    let second = edit(
        &framework_engine,
        "    renderer.addLight(directionLight);",
        "    renderer.addLight(directionLight);
    const secondLight = new DirectionalLight(2500, [1, 1, 1], [0, 80, -80], focalPoint, lightUp, true, renderer.gl);
    renderer.addLight(secondLight);",
    );
    let report = check(second);
    let lights = report["lights"].as_array().expect("lights");
    assert_eq!(lights[0]["findings"], serde_json::json!([]), "{lights:#?}");
    assert_eq!(lights[1]["findings"], serde_json::json!(["light_not_drawn"]), "{lights:#?}");
}

#[test]
fn a_page_that_renders_into_float_textures_is_refused_in_one_line_naming_where() {
    // Its maps (moments, a summed-area table) are not the framework's RGBA8 ones the check
    // builds: judging the picture the check would build instead would blame the wrong things.
    // A WebGL2 context alone is no reason: with RGBA8 maps it is checked as usual.
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let engine = edit(
        &read("assets/homework/framework/src/engine.js"),
        "canvas.getContext('webgl')",
        "canvas.getContext('webgl2')",
    );
    let files = |fbo: &str| {
        [
            ("src/shaders/phongShader/phongFragment.glsl", read("assets/homework/phongFragment.glsl")),
            ("src/lights/DirectionalLight.js", read("assets/homework/DirectionalLight.js")),
            ("src/engine.js", engine.clone()),
            ("src/textures/FBO.js", fbo.to_string()),
        ]
    };
    let rgba8 = read("assets/homework/framework/src/textures/FBO.js");
    let report = check_folder(&scratch.path().join("webgl2"), &files(&rgba8));
    assert_eq!(report["findings"], serde_json::json!([]), "{:#}", report["findings"]);

    let float = edit(
        &rgba8,
        "gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA, this.width, this.height, 0, gl.RGBA, gl.UNSIGNED_BYTE, null);",
        "gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA32F, this.width, this.height, 0, gl.RGBA, gl.FLOAT, null);",
    );
    let root = scratch.path().join("float");
    let run = run_folder(&root, &files(&float));
    assert_eq!(run.code, Some(2), "{}", run.stderr);
    let line = line_of(&float, "gl.RGBA32F");
    assert_eq!(
        run.stderr.trim(),
        format!(
            "shadowlab: homework1/src/textures/FBO.js:{line}: the page renders into float textures; the check builds the framework's RGBA8 shadow maps only, so it does not judge this submission"
        )
    );
    assert!(!root.join("out/report.json").exists(), "nothing is written for a refused submission");
}

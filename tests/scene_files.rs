//! Scene files at the library level: the shipped scenes, defaults, `--set` overrides and the
//! validation of lights. Fixture scenes live in tests/data/scenes/ (their mesh paths are
//! relative to that folder).

use shadowlab::scene::{
    LightKind, LightSize, MAX_LIGHTS, Projection, Scene, SceneError, ShadowSettings, Technique, load_scene,
    parse_scene_str,
};
use std::path::{Path, PathBuf};

fn repo_path(relative: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(relative)
}

fn fixture(name: &str) -> PathBuf {
    repo_path("tests/data/scenes").join(name)
}

fn overrides(pairs: &[(&str, &str)]) -> Vec<(String, String)> {
    pairs.iter().map(|(k, v)| (k.to_string(), v.to_string())).collect()
}

fn load_fixture(name: &str, pairs: &[(&str, &str)]) -> Scene {
    let path = fixture(name);
    load_scene(&path, &overrides(pairs)).unwrap_or_else(|e| panic!("{} should load: {e}", path.display()))
}

/// Parse inline scene text; mesh paths resolve against tests/data/obj.
fn parse(text: &str, pairs: &[(&str, &str)]) -> Result<Scene, SceneError> {
    parse_scene_str(text, &repo_path("tests/data/obj"), "inline.toml", &overrides(pairs))
}

fn parse_ok(text: &str) -> Scene {
    parse(text, &[]).unwrap_or_else(|e| panic!("scene should parse: {e}\n{text}"))
}

fn parse_err(text: &str, pairs: &[(&str, &str)]) -> String {
    match parse(text, pairs) {
        Ok(_) => panic!("scene should be rejected:\n{text}\noverrides: {pairs:?}"),
        Err(e) => e.to_string(),
    }
}

fn assert_one_line_naming(message: &str, needles: &[&str]) {
    assert_eq!(message.lines().count(), 1, "error should be one line: {message:?}");
    for needle in needles {
        assert!(message.contains(needle), "error should mention {needle:?}: {message}");
    }
}

const CAMERA: &str = "[camera]\nposition = [0.0, 4.0, 10.0]\n";

/// A scene with the camera, a plane and the given `[[light]]` tables.
fn scene_with_lights(lights: &[&str]) -> String {
    let mut text = format!("{CAMERA}\n[[object]]\nmesh = \"plane\"\n");
    for light in lights {
        text.push_str("\n[[light]]\n");
        text.push_str(light);
        text.push('\n');
    }
    text
}

const SPOT: &str = "kind = \"spot\"\nposition = [0.0, 10.0, 0.0]\nfov_deg = 60.0";
const DIRECTIONAL: &str = "kind = \"directional\"\nposition = [5.0, 10.0, 0.0]\nextent = 10.0";

/// Every scene file shipped in assets/scenes, sorted (at least one).
fn shipped_scene_paths() -> Vec<PathBuf> {
    let dir = repo_path("assets/scenes");
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("assets/scenes is readable")
        .map(|entry| entry.expect("directory entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    paths.sort();
    assert!(!paths.is_empty(), "no scenes found in {}", dir.display());
    paths
}

#[test]
fn every_shipped_scene_loads_with_lights_and_triangles() {
    let paths = shipped_scene_paths();
    for path in &paths {
        let scene = load_scene(path, &[]).unwrap_or_else(|e| panic!("{} should load: {e}", path.display()));
        assert_eq!(scene.path.as_deref(), Some(path.as_path()));
        assert!(!scene.lights.is_empty(), "{}: a shipped scene needs a light", path.display());
        assert!(scene.lights.len() <= MAX_LIGHTS, "{}", path.display());
        assert!(!scene.objects.is_empty(), "{}: no objects", path.display());
        for object in &scene.objects {
            assert!(
                object.mesh.triangle_count() > 0,
                "{}: object `{}` has no triangles",
                path.display(),
                object.name
            );
            // The probe panel and the slides name the surface in the reader's language.
            let zh = object.name_zh.as_deref().unwrap_or_default();
            assert!(
                zh.chars().any(|c| ('\u{4e00}'..='\u{9fff}').contains(&c)),
                "{}: object `{}` has no Chinese `name_zh`",
                path.display(),
                object.name
            );
        }
        scene.shadow.validate().unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    }
}

#[test]
fn minimal_scene_gets_every_default() {
    let scene = load_fixture("minimal.toml", &[]);
    assert_eq!(scene.shadow, ShadowSettings::default());
    assert!(scene.lights.is_empty());
    assert_eq!(scene.ambient.to_array(), [0.08, 0.08, 0.1]);

    let camera = scene.camera;
    assert_eq!(camera.projection, Projection::Perspective { fov_deg: 45.0 });
    assert_eq!(camera.position.to_array(), [0.0, 4.0, 10.0]);
    assert_eq!(camera.target.to_array(), [0.0, 0.0, 0.0]);
    assert_eq!(camera.up.to_array(), [0.0, 1.0, 0.0]);
    assert_eq!((camera.near, camera.far), (0.1, 1000.0));

    assert_eq!(scene.objects.len(), 1);
    let object = &scene.objects[0];
    assert_eq!(object.name, "plane", "an unnamed object takes its mesh's name");
    assert_eq!(object.color.to_array(), [0.8, 0.8, 0.8]);
    assert_eq!(object.translate.to_array(), [0.0; 3]);
    assert_eq!(object.rotate_deg.to_array(), [0.0; 3]);
    assert_eq!(object.scale.to_array(), [1.0; 3]);
    assert_eq!(object.spin_deg_per_s.to_array(), [0.0; 3]);
}

#[test]
fn inline_minimal_scene_matches_the_fixture_file() {
    let text = std::fs::read_to_string(fixture("minimal.toml")).expect("fixture is readable");
    let scene = parse_ok(&text);
    assert_eq!(scene.path, None, "scenes parsed from text have no path");
    assert_eq!(scene.shadow, ShadowSettings::default());
}

#[test]
fn light_defaults_are_applied() {
    let scene = parse_ok(&scene_with_lights(&[SPOT, DIRECTIONAL]));
    let spot = scene.lights[0];
    assert_eq!(spot.kind, LightKind::Spot { fov_deg: 60.0 });
    assert_eq!(spot.shadow_map_size, 2048);
    assert_eq!((spot.near, spot.far), (1.0, 500.0));
    assert_eq!(spot.size, LightSize::Width { width_world: 0.0 });
    assert_eq!(spot.color.to_array(), [1.0; 3]);
    assert_eq!(spot.intensity, 1.0);
    assert_eq!(spot.orbit_deg_per_s, 0.0);
    let directional = scene.lights[1];
    assert_eq!(directional.kind, LightKind::Directional { extent_world: 10.0 });
    assert_eq!(directional.near, 0.01);
}

#[test]
fn overrides_reach_camera_light_object_and_shadow() {
    let scene = load_fixture(
        "one_light.toml",
        &[
            ("camera.fov_deg", "40"),
            ("light.0.width", "4"),
            ("object.0.spin_deg_per_s", "[0,90,0]"),
            ("technique", "pcf"),
        ],
    );
    assert_eq!(scene.camera.projection, Projection::Perspective { fov_deg: 40.0 });
    assert_eq!(scene.lights[0].size, LightSize::Width { width_world: 4.0 });
    assert_eq!(scene.objects[0].spin_deg_per_s.to_array(), [0.0, 90.0, 0.0]);
    assert_eq!(scene.objects[1].spin_deg_per_s.to_array(), [0.0; 3], "only object 0 changes");
    assert_eq!(scene.shadow.technique, Technique::Pcf);
    // Untouched values keep the file's.
    assert_eq!(scene.shadow.samples, 16);
    assert_eq!(scene.camera.position.to_array(), [0.0, 6.0, 12.0]);
}

#[test]
fn overrides_apply_in_order() {
    let scene = load_fixture(
        "one_light.toml",
        &[("technique", "hard"), ("samples", "8"), ("technique", "pcf"), ("samples", "64")],
    );
    assert_eq!(scene.shadow.technique, Technique::Pcf);
    assert_eq!(scene.shadow.samples, 64);

    let scene = load_fixture("one_light.toml", &[("technique", "pcf"), ("technique", "hard")]);
    assert_eq!(scene.shadow.technique, Technique::Hard);
}

#[test]
fn overrides_accept_section_prefixes_and_quoted_values() {
    let scene = load_fixture(
        "one_light.toml",
        &[
            ("shadow.bias_mode", "slope"),
            ("pcf_kernel", "\"vogel\""),
            ("ambient", "[0.2, 0.3, 0.4]"),
            ("camera.position", "[1, 2, 3]"),
            ("light.0.shadow_map_size", "512"),
            ("object.1.name", "\"crate\""),
        ],
    );
    assert_eq!(scene.shadow.bias_mode.name(), "slope");
    assert_eq!(scene.shadow.pcf_kernel.name(), "vogel");
    assert_eq!(scene.ambient.to_array(), [0.2, 0.3, 0.4]);
    assert_eq!(scene.camera.position.to_array(), [1.0, 2.0, 3.0]);
    assert_eq!(scene.lights[0].shadow_map_size, 512);
    assert_eq!(scene.objects[1].name, "crate");
}

#[test]
fn override_errors_name_the_key() {
    let path = fixture("one_light.toml");
    let cases: &[(&str, &str, &[&str])] = &[
        ("technique", "blurry", &["technique", "blurry", "hard", "pcf", "pcss"]),
        ("samples", "0", &["samples", "1..=128"]),
        ("samples", "500", &["samples", "1..=128"]),
        ("bias", "nan", &["bias"]),
        ("foo", "1", &["foo"]),
        ("light.7.width", "1", &["light.7", "no light 7"]),
        ("object.9.scale", "2", &["object.9", "no object 9"]),
        ("light.x.width", "1", &["light.x"]),
        ("camera.fov_deg", "400", &["camera.fov_deg", "1..=170"]),
        ("light.0.shadow_map_size", "100", &["light.0.shadow_map_size", "256..=8192"]),
        ("nosuch.key", "1", &["nosuch.key"]),
    ];
    for (key, value, needles) in cases {
        let err = load_scene(&path, &overrides(&[(key, value)]))
            .err()
            .unwrap_or_else(|| panic!("--set {key}={value} should be rejected"));
        assert_one_line_naming(&err.to_string(), needles);
    }
}

#[test]
fn a_bad_override_is_reported_even_after_good_ones() {
    let err =
        load_fixture_err("one_light.toml", &[("technique", "pcf"), ("samples", "0"), ("samples", "16")]);
    assert_one_line_naming(&err, &["samples", "out of range"]);
}

fn load_fixture_err(name: &str, pairs: &[(&str, &str)]) -> String {
    match load_scene(&fixture(name), &overrides(pairs)) {
        Ok(_) => panic!("{name} with {pairs:?} should be rejected"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn directional_angular_diameter_parses_as_angular_diameter() {
    let scene = load_fixture("sun.toml", &[]);
    assert_eq!(scene.lights.len(), 1);
    assert_eq!(scene.lights[0].kind, LightKind::Directional { extent_world: 15.0 });
    assert_eq!(scene.lights[0].size, LightSize::AngularDiameter { angular_diameter_deg: 0.53 });
}

#[test]
fn spot_light_with_angular_diameter_is_rejected() {
    let err = parse_err(&scene_with_lights(&[&format!("{SPOT}\nangular_diameter_deg = 0.5")]), &[]);
    assert_one_line_naming(&err, &["inline.toml", "angular_diameter_deg", "spot"]);
}

#[test]
fn width_and_angular_diameter_together_are_rejected() {
    let err = parse_err(
        &scene_with_lights(&[&format!("{DIRECTIONAL}\nwidth = 1.0\nangular_diameter_deg = 0.5")]),
        &[],
    );
    assert_one_line_naming(&err, &["inline.toml", "width", "angular_diameter_deg"]);
}

#[test]
fn angular_diameter_override_on_a_light_with_width_is_rejected() {
    let err = load_fixture_err("one_light.toml", &[("light.0.angular_diameter_deg", "1")]);
    assert_one_line_naming(&err, &["light.0.angular_diameter_deg"]);
}

#[test]
fn at_most_four_lights() {
    let four = scene_with_lights(&[SPOT; MAX_LIGHTS]);
    assert_eq!(parse_ok(&four).lights.len(), MAX_LIGHTS);
    let five = scene_with_lights(&[SPOT; MAX_LIGHTS + 1]);
    let err = parse_err(&five, &[]);
    assert_one_line_naming(&err, &["inline.toml", "5 lights", "at most 4"]);
}

#[test]
fn shadow_map_size_out_of_range_names_the_key() {
    for size in ["100", "255", "8193"] {
        let err = parse_err(&scene_with_lights(&[&format!("{SPOT}\nshadow_map_size = {size}")]), &[]);
        assert_one_line_naming(&err, &["inline.toml", "light.0.shadow_map_size", size, "256..=8192"]);
    }
    for size in [256, 8192] {
        let scene = parse_ok(&scene_with_lights(&[&format!("{SPOT}\nshadow_map_size = {size}")]));
        assert_eq!(scene.lights[0].shadow_map_size, size);
    }
}

#[test]
fn light_kind_specific_keys_are_checked() {
    let err = parse_err(&scene_with_lights(&[&format!("{SPOT}\nextent = 5.0")]), &[]);
    assert_one_line_naming(&err, &["light.0.extent"]);
    let err = parse_err(&scene_with_lights(&[&format!("{DIRECTIONAL}\nfov_deg = 30.0")]), &[]);
    assert_one_line_naming(&err, &["light.0.fov_deg"]);
    let err = parse_err(&scene_with_lights(&["kind = \"directional\"\nposition = [0.0, 9.0, 0.0]"]), &[]);
    assert_one_line_naming(&err, &["light.0.extent", "required"]);
    let err = parse_err(&scene_with_lights(&["kind = \"spot\"\nposition = [0.0, 9.0, 0.0]"]), &[]);
    assert_one_line_naming(&err, &["light.0.fov_deg", "required"]);
}

#[test]
fn an_object_may_carry_a_chinese_name_shown_only_in_chinese() {
    use shadowlab::i18n::Lang;
    let text = format!("{CAMERA}\n[[object]]\nname = \"floor\"\nname_zh = \"地面\"\nmesh = \"plane\"\n");
    let scene = parse_ok(&text);
    let floor = &scene.objects[0];
    assert_eq!((floor.name.as_str(), floor.name_zh.as_deref()), ("floor", Some("地面")));
    assert_eq!((floor.label(Lang::En), floor.label(Lang::Zh)), ("floor", "地面"));
    assert_eq!(scene.object_label("floor", Lang::Zh), "地面");
    assert_eq!(scene.object_label("floor", Lang::En), "floor");
    // Without a Chinese name, or for a name no object has, the name itself.
    let plain = parse_ok(&format!("{CAMERA}\n[[object]]\nname = \"floor\"\nmesh = \"plane\"\n"));
    assert_eq!(plain.object_label("floor", Lang::Zh), "floor");
    assert_eq!(scene.object_label("moon", Lang::Zh), "moon");
    // `--set` reaches it like any object key; a misspelt key is still refused.
    let scene = parse(&text, &[("object.0.name_zh", "地板")]).expect("override");
    assert_eq!(scene.objects[0].label(Lang::Zh), "地板");
    let err = parse_err(&text.replace("name_zh", "name_cn"), &[]);
    assert!(err.contains("name_cn"), "{err}");
}

#[test]
fn utf8_object_names_survive() {
    let scene = load_fixture("utf8_names.toml", &[]);
    assert_eq!(scene.objects[0].name, "Würfel 立方体 ✓");
    // An unnamed object takes its mesh's name (the file stem); the OBJ object and material
    // names keep their UTF-8 in the mesh parts and materials.
    let mesh = &scene.objects[1].mesh;
    assert_eq!(scene.objects[1].name, mesh.name);
    assert_eq!(mesh.triangle_count(), 12);
    assert!(mesh.parts.iter().any(|p| p.name.contains("Würfel_立方体")), "parts: {:?}", mesh.parts);
    assert!(mesh.materials.iter().any(|m| m.name == "材质_Matériel"), "materials: {:?}", mesh.materials);

    let scene = load_fixture("utf8_names.toml", &[("object.0.name", "\"Ωmega ☂\"")]);
    assert_eq!(scene.objects[0].name, "Ωmega ☂");
}

#[test]
fn mesh_paths_are_relative_to_the_scene_file() {
    let scene = load_fixture("relative_mesh.toml", &[]);
    assert_eq!(scene.objects[0].name, "polygons");
    assert_eq!(scene.objects[0].mesh.triangle_count(), 5, "a quad and a pentagon, fan-triangulated");

    // parse_scene_str resolves against the base folder it is given.
    let scene = parse_ok(&format!("{CAMERA}\n[[object]]\nmesh = \"quad_ngon.obj\"\n"));
    assert_eq!(scene.objects[0].mesh.triangle_count(), 5);
}

#[test]
fn objects_sharing_a_mesh_share_one_copy() {
    let scene = load_scene(&repo_path("assets/scenes/games202.toml"), &[]).expect("games202 loads");
    let bunnies: Vec<_> = scene.objects.iter().filter(|o| o.name.contains("bunny")).collect();
    assert_eq!(bunnies.len(), 2);
    assert!(std::sync::Arc::ptr_eq(&bunnies[0].mesh, &bunnies[1].mesh));
}

#[test]
fn missing_mesh_and_texture_errors_name_the_file() {
    let err = load_fixture_err("missing_mesh.toml", &[]);
    assert_one_line_naming(&err, &["no_such_mesh.obj"]);
    let err = load_fixture_err("missing_texture.toml", &[]);
    assert_one_line_naming(&err, &["does_not_exist.png", "missing_texture.mtl"]);
    let err = parse_err(&format!("{CAMERA}\n[[object]]\nmesh = \"blob\"\n"), &[]);
    assert_one_line_naming(&err, &["inline.toml", "blob", "plane", "cube"]);
}

#[test]
fn missing_scene_file_names_the_file() {
    let path = fixture("there_is_no_such_scene.toml");
    let err = load_scene(&path, &[]).expect_err("a missing file is an error").to_string();
    assert_one_line_naming(&err, &["there_is_no_such_scene.toml", "cannot read"]);
}

#[test]
fn file_errors_name_the_label_and_line() {
    // Unknown key on line 5 (CAMERA is two lines, then a blank line and `[shadow]`).
    let err = parse_err(&format!("{CAMERA}\n[shadow]\nfoo = 1\n"), &[]);
    assert_one_line_naming(&err, &["inline.toml:5:", "foo"]);
    // Wrong type on line 2.
    let err = parse_err("[camera]\nposition = \"here\"\n", &[]);
    assert_one_line_naming(&err, &["inline.toml:2:"]);
    // Syntax error on line 3.
    let err = parse_err("[camera]\nposition = [0.0, 1.0, 5.0]\nfov_deg = = 3\n", &[]);
    assert_one_line_naming(&err, &["inline.toml:3:"]);
    // No camera at all.
    let err = parse_err("[[object]]\nmesh = \"plane\"\n", &[]);
    assert_one_line_naming(&err, &["inline.toml", "camera"]);
}

#[test]
fn non_finite_and_degenerate_values_are_rejected() {
    let err = parse_err(&format!("{CAMERA}fov_deg = nan\n"), &[]);
    assert_one_line_naming(&err, &["camera.fov_deg"]);
    let err = parse_err("[camera]\nposition = [0.0, inf, 0.0]\n", &[]);
    assert_one_line_naming(&err, &["camera.position"]);
    let err = parse_err("[camera]\nposition = [0.0, 0.0, 0.0]\n", &[]);
    assert_one_line_naming(&err, &["camera.position", "camera.target"]);
    let err = parse_err(&format!("{CAMERA}\n[[object]]\nmesh = \"cube\"\nscale = 0.0\n"), &[]);
    assert_one_line_naming(&err, &["object.0.scale"]);
    let err = parse_err(&format!("{CAMERA}\n[shadow]\nbias = nan\n"), &[]);
    assert_one_line_naming(&err, &["inline.toml", "bias"]);
    let err = parse_err(&scene_with_lights(&[&format!("{SPOT}\ncolor = [1.0, -1.0, 1.0]")]), &[]);
    assert_one_line_naming(&err, &["light.0.color"]);
}

#[test]
fn shipped_scenes_and_lesson_steps_show_something() {
    let paths = shipped_scene_paths();
    for path in &paths {
        let scene = load_scene(path, &[]).unwrap_or_else(|e| panic!("{} should load: {e}", path.display()));
        assert_eq!(scene.warnings(0.0, 16.0 / 9.0), Vec::<String>::new(), "{}", path.display());
    }
    let lessons = shadowlab::lessons::load_all(&repo_path("lessons")).expect("the lessons load");
    for lesson in &lessons {
        for (i, step) in lesson.steps.iter().enumerate() {
            let scene = step.scene().expect("the step's scene loads");
            let warnings = scene.warnings(step.time_s, 16.0 / 9.0);
            assert_eq!(warnings, Vec::<String>::new(), "lesson {} step {}", lesson.id, i + 1);
            for t in 0..step.try_this.len() {
                let scene = step.scene_with_try_this(t).expect("the prompt's scene loads");
                let time = step.try_this[t].time_s.unwrap_or(step.time_s);
                let warnings = scene.warnings(time, 16.0 / 9.0);
                assert_eq!(
                    warnings,
                    Vec::<String>::new(),
                    "lesson {} step {} try_this {}",
                    lesson.id,
                    i + 1,
                    t + 1
                );
            }
        }
    }
}

/// `[camera]` (lines 1-2), a blank line, then `[[object]]` on line 4 with these lines.
fn scene_with_object(object: &str) -> String {
    format!("{CAMERA}\n[[object]]\n{object}\n")
}

#[test]
fn absurd_but_finite_values_are_errors_at_their_key_and_line() {
    let cases: Vec<(String, &[&str])> = vec![
        // The example: a scale of -1e38 rendered an empty frame without a word.
        (scene_with_object("mesh = \"cube\"\nscale = -1e38"), &["inline.toml:6:", "object.0.scale", "1e6"]),
        (
            scene_with_object("mesh = \"cube\"\nscale = [1.0, 2e6, 1.0]"),
            &["inline.toml:6:", "object.0.scale"],
        ),
        (
            scene_with_object("mesh = \"cube\"\nscale = [1.0, 0.0, 1.0]"),
            &["inline.toml:6:", "object.0.scale"],
        ),
        (
            scene_with_object("mesh = \"cube\"\ntranslate = [0.0, -2e6, 0.0]"),
            &["inline.toml:6:", "object.0.translate", "1e6 world units"],
        ),
        ("[camera]\nposition = [3.4e38, 4.0, 10.0]\n".into(), &["inline.toml:2:", "camera.position"]),
        (format!("{CAMERA}target = [0.0, 0.0, 1e7]\n"), &["inline.toml:3:", "camera.target"]),
        (
            format!("{CAMERA}far = 0.05\n"),
            &["inline.toml:3:", "`camera.far` = 0.05", "greater than `camera.near` = 0.1"],
        ),
        (
            scene_with_lights(&[&format!("{SPOT}\nnear = 10.0\nfar = 5.0")]),
            &["inline.toml:12:", "`light.0.far` = 5", "`light.0.near` = 10"],
        ),
        // `far` left out (500): the error points at the light's table.
        (scene_with_lights(&[SPOT, &format!("{SPOT}\nnear = 600.0")]), &["inline.toml:12:", "light.1.far"]),
        (
            scene_with_lights(&["kind = \"spot\"\nposition = [0.0, 1e7, 0.0]\nfov_deg = 60.0"]),
            &["inline.toml:9:", "light.0.position", "1e6"],
        ),
        (
            scene_with_lights(&[&format!("{SPOT}\ncolor = [1e5, 1.0, 1.0]")]),
            &["inline.toml:11:", "light.0.color"],
        ),
        (format!("ambient = [0.1, -0.1, 0.1]\n{CAMERA}"), &["inline.toml:1:", "ambient", "negative"]),
        (scene_with_lights(&[SPOT; MAX_LIGHTS + 1]), &["inline.toml:27:", "5 lights", "light.4"]),
        (
            scene_with_lights(&[&format!("{SPOT}\nshadow_map_size = 1")]),
            &["inline.toml:11:", "light.0.shadow_map_size"],
        ),
        (format!("{CAMERA}\n[shadow]\nbias = 7.0\n"), &["inline.toml:5:", "bias"]),
        (
            "[camera]\nposition = [0.0, 0.0, 0.0]\n".into(),
            &["inline.toml:1:", "camera.target", "camera.position"],
        ),
        (scene_with_object("mesh = \"blob\""), &["inline.toml:5:", "object.0.mesh", "blob"]),
    ];
    for (text, needles) in cases {
        assert_one_line_naming(&parse_err(&text, &[]), needles);
    }
    // A scale allowed on its own, but a model 1e5 units across scaled by 1e3 reaches 1e8.
    let dir = tempfile::tempdir().expect("temporary folder");
    std::fs::write(dir.path().join("far.obj"), "v 0 0 0\nv 1e5 0 0\nv 0 1e5 0\nf 1 2 3\n")
        .expect("write obj");
    let text = scene_with_object("mesh = \"far.obj\"\nscale = 1e3");
    let err = parse_scene_str(&text, dir.path(), "inline.toml", &[]).expect_err("too far").to_string();
    assert_one_line_naming(&err, &["inline.toml:6:", "object.0.scale", "mesh `far`", "reaches 1.4"]);
    // An override names the key (its value has no line in the file).
    let err = parse_err(&scene_with_object("mesh = \"cube\""), &[("object.0.scale", "-1e38")]);
    assert_one_line_naming(&err, &["--set object.0.scale", "1e6"]);
}

#[test]
fn large_but_sane_values_still_load() {
    let scene = parse_ok(&scene_with_object(
        "mesh = \"plane\"\nscale = [1e5, 1.0, 1e5]\ntranslate = [0.0, 0.0, -9e5]",
    ));
    assert_eq!(scene.objects[0].scale.to_array(), [1e5, 1.0, 1e5]);
    let far_light =
        "kind = \"spot\"\nposition = [0.0, 1e6, 0.0]\nfov_deg = 60.0\nfar = 2e6\ncolor = [1e4, 0.0, 0.0]";
    let scene = parse_ok(&scene_with_lights(&[far_light]));
    assert_eq!(scene.lights[0].position.y, 1e6);
}

#[test]
fn scenes_that_show_nothing_say_so() {
    let warnings = |text: &str| parse_ok(text).warnings(0.0, 16.0 / 9.0);
    let light = "kind = \"spot\"\nposition = [0.0, 10.0, 0.0]\nfov_deg = 60.0";
    let cases: Vec<(String, &str)> = vec![
        (CAMERA.to_string(), "no objects"),
        (
            format!("{CAMERA}target = [0.0, 100.0, 10.0]\n\n[[object]]\nmesh = \"cube\"\n"),
            "no object is in the camera's view",
        ),
        (format!("{CAMERA}far = 2.0\n\n[[object]]\nmesh = \"cube\"\n"), "no object is in the camera's view"),
        (scene_with_object("mesh = \"cube\"\nscale = 100.0"), "the camera is inside object `cube`"),
        (
            format!(
                "{CAMERA}\n[[object]]\nname = \"box\"\nmesh = \"cube\"\nscale = 30.0\ntranslate = [0.0, 0.0, -40.0]\n\n\
                 [[light]]\nkind = \"spot\"\nposition = [0.0, 10.0, -40.0]\ntarget = [0.0, 0.0, -40.0]\nfov_deg = 60.0\n"
            ),
            "light 0 is inside object `box`",
        ),
        (
            format!(
                "{CAMERA}\n[[object]]\nmesh = \"cube\"\n\n[[light]]\n{light}\ntarget = [0.0, 20.0, 0.0]\n"
            ),
            "light 0's frustum (depths 1..500) holds no object",
        ),
        (
            format!(
                "ambient = [0.0, 0.0, 0.0]\n{CAMERA}\n[[object]]\nmesh = \"cube\"\n\n[[light]]\n{light}\nintensity = 0.0\n"
            ),
            "nothing lights the scene",
        ),
    ];
    for (text, needle) in cases {
        let found = warnings(&text);
        assert!(
            found.iter().any(|w| w.contains(needle)),
            "expected a warning with {needle:?}, got {found:?}\n{text}"
        );
        assert!(found.iter().all(|w| w.lines().count() == 1), "{found:?}");
    }
    // The plane under a light is no inside, and a scene that shows something says nothing.
    let text = scene_with_lights(&[SPOT]);
    assert_eq!(warnings(&text), Vec::<String>::new(), "{text}");
}

#[test]
fn errors_stay_on_one_line_whatever_the_file_holds() {
    // A carriage return in a key once went into the message as it was.
    let err = parse_err(&format!("{CAMERA}\n[[object]]\nm\rsh = \"plane\"\n"), &[]);
    assert_one_line_naming(&err, &["inline.toml:5:", "m\\rsh"]);
    assert!(!err.contains('\r'), "{err:?}");
    // A line break in a mesh name.
    let err = parse_err(&scene_with_object("mesh = \"line\\nbreak.obj\""), &[]);
    assert_one_line_naming(&err, &["line\\nbreak.obj"]);
    // serde spells out the float it did not want; a long one is given in exponent form.
    let err = parse_err(&scene_with_object("mesh = -1e38"), &[]);
    assert_one_line_naming(&err, &["inline.toml:5:", "mesh", "`-1e38`"]);
}

#[cfg(unix)]
#[test]
fn a_scene_path_that_is_not_a_regular_file_is_refused_at_once() {
    // /dev/zero never ends: reading it whole hung until the memory ran out.
    let err = load_scene(Path::new("/dev/zero"), &[]).expect_err("a device is not a scene").to_string();
    assert_one_line_naming(&err, &["/dev/zero", "not a regular file"]);
    let dir = tempfile::tempdir().expect("temporary folder");
    let err = load_scene(dir.path(), &[]).expect_err("a folder is not a scene").to_string();
    assert_one_line_naming(&err, &["is a folder"]);
}

/// A point light needs only where it is: six 90° faces, no aim, `width` its sphere's diameter;
/// the other kinds' keys are refused in one line naming the key, and its numbers keep their
/// ranges.
#[test]
fn a_point_light_takes_a_position_and_a_width_and_refuses_the_other_kinds_keys() {
    let lamp = "kind = \"point\"\nposition = [0.0, 6.0, 0.0]\nwidth = 0.5";
    let scene = parse_ok(&scene_with_lights(&[lamp]));
    let light = &scene.lights[0];
    assert_eq!(light.kind, shadowlab::scene::LightKind::Point);
    assert_eq!(light.size, shadowlab::scene::LightSize::Width { width_world: 0.5 });
    assert_eq!(light.near, 0.1, "the default near for a lamp");
    assert_eq!(shadowlab::shadow::views_needed(&scene.lights), 6);
    for (key, line) in [("fov_deg", "fov_deg = 60.0"), ("extent", "extent = 10.0")] {
        let err = parse_err(&scene_with_lights(&[&format!("{lamp}\n{line}")]), &[]);
        assert_one_line_naming(&err, &[&format!("light.0.{key}"), "point lights"]);
    }
    let err = parse_err(
        &scene_with_lights(&["kind = \"point\"\nposition = [0.0, 6.0, 0.0]\nangular_diameter_deg = 1.0"]),
        &[],
    );
    assert_one_line_naming(&err, &["light.0.angular_diameter_deg", "directional lights only"]);
    let err = parse_err(&scene_with_lights(&[lamp]), &[("light.0.width", "-1")]);
    assert_one_line_naming(&err, &["light.0.width"]);
    let err = parse_err(&scene_with_lights(&["kind = \"lamp\"\nposition = [0.0, 6.0, 0.0]"]), &[]);
    assert_one_line_naming(&err, &["lamp", "point"]);
}

/// A sun takes `cascades` (1..4), `cascade_lambda` (0..1) and `cascade_distance`; it renders one
/// map per cascade; the other kinds refuse the keys, and values out of range name their key.
#[test]
fn a_sun_takes_cascades_in_range_and_the_other_kinds_refuse_them() {
    let sun = "kind = \"directional\"\nposition = [20.0, 40.0, 10.0]\nextent = 30.0";
    let scene = parse_ok(&scene_with_lights(&[&format!(
        "{sun}\ncascades = 3\ncascade_lambda = 0.8\ncascade_distance = 50.0"
    )]));
    let cascades = scene.lights[0].cascades;
    assert_eq!((cascades.count, cascades.lambda, cascades.distance_world), (3, 0.8, 50.0));
    assert_eq!(shadowlab::shadow::views_needed(&scene.lights), 3);
    let plain = parse_ok(&scene_with_lights(&[sun]));
    assert_eq!(plain.lights[0].cascades, shadowlab::scene::Cascades::default());
    assert_eq!(shadowlab::shadow::views_needed(&plain.lights), 1);
    // `--set` turns them on for a scene that has none.
    let set = parse(&scene_with_lights(&[sun]), &[("light.0.cascades", "4")]).expect("scene");
    assert_eq!(set.lights[0].cascades.count, 4);
    for (key, value) in
        [("cascades", "0"), ("cascades", "5"), ("cascade_lambda", "1.5"), ("cascade_distance", "-2")]
    {
        let err = parse_err(&scene_with_lights(&[sun]), &[(&format!("light.0.{key}"), value)]);
        assert_one_line_naming(&err, &[&format!("light.0.{key}")]);
    }
    let lamp = "kind = \"point\"\nposition = [0.0, 6.0, 0.0]";
    let spot = "kind = \"spot\"\nposition = [0.0, 6.0, 4.0]\nfov_deg = 50.0";
    for light in [lamp, spot] {
        for line in ["cascades = 2", "cascade_lambda = 0.5", "cascade_distance = 10.0"] {
            let err = parse_err(&scene_with_lights(&[&format!("{light}\n{line}")]), &[]);
            let key = format!("light.0.{}", line.split(' ').next().expect("key"));
            assert_one_line_naming(&err, &[&key, "directional lights"]);
        }
    }
}

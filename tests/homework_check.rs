//! `shadowlab homework` as a student or a grader runs it: the binary as a process, on the shipped
//! example shaders (each gets exactly its own findings, the correct one none), on a shader that
//! does not compile (exit 2, the student's own line) and on bad input (nothing written).

mod common;
#[path = "../src/homework/submission/tests/writer.rs"]
#[allow(dead_code)]
mod zip_writer;

use common::{Run, repo_path};
use serde_json::Value;
use std::path::Path;

/// Small enough to be quick; the thresholds hold at this size as at 960x540.
const SIZE: &str = "480x270";

fn shadowlab<S: AsRef<std::ffi::OsStr>>(args: &[S]) -> Run {
    common::run(common::shadowlab_command().args(args))
}

fn example(name: &str) -> String {
    repo_path("assets/homework").join(name).display().to_string()
}

/// Run a check into `out` with `--json`; the report from stdout, which must equal report.json.
fn check(shader: &str, extra: &[&str], out: &Path) -> Value {
    let out_arg = out.display().to_string();
    let mut args = vec!["homework", shader, "--size", SIZE, "--out", &out_arg, "--json"];
    args.extend_from_slice(extra);
    let run = shadowlab(&args);
    assert_eq!(run.code, Some(0), "{shader}: {}", run.stderr);
    let report: Value = serde_json::from_str(&run.stdout).expect("the report is JSON");
    let written: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).expect("report.json"))
            .expect("report.json is JSON");
    assert_eq!(report, written, "{shader}: stdout and report.json differ");
    report
}

/// The correct solution with `from` replaced by `to` (a mistake made on purpose), written into
/// `scratch` and checked there into `out`: its report.
fn check_edited(scratch: &Path, from: &str, to: &str, out: &str) -> Value {
    let source = std::fs::read_to_string(example("phongFragment.glsl")).expect("the example");
    let edited = source.replace(from, to);
    assert_ne!(edited, source, "{from:?} is not in the example");
    let shader = scratch.join("phongFragment.glsl");
    std::fs::write(&shader, edited).expect("write the shader");
    check(&shader.display().to_string(), &[], &scratch.join(out))
}

fn finding_ids(report: &Value) -> Vec<String> {
    report["findings"]
        .as_array()
        .expect("findings")
        .iter()
        .map(|f| f["id"].as_str().expect("an id").to_string())
        .collect()
}

/// Each example's findings, in order, each `id` or `id (latent)`, with the extra arguments it is
/// checked with (see assets/homework/README.md).
fn example_cases() -> Vec<(&'static str, Vec<String>, &'static [&'static str])> {
    let script = |name: &str| vec!["--light-script".to_string(), example(name)];
    let shadow = |name: &str| vec!["--shadow-shader".to_string(), example(name)];
    vec![
        ("phongFragment.glsl", vec![], &[]),
        ("phongFragment.glsl", script("DirectionalLight.js"), &[]),
        ("phongFragment.glsl", script("DirectionalLight_three.js"), &[]),
        ("phongFragment.glsl", script("DirectionalLight_no_model.js"), &["light_model_matrix"]),
        ("phongFragment.glsl", script("DirectionalLight_narrow.js"), &["light_frustum_clips"]),
        ("phongFragment.glsl", script("DirectionalLight_identity_sum.js"), &["light_direction_off"]),
        ("phongFragment.glsl", script("DirectionalLight_low.js"), &["light_frustum_clips"]),
        ("phongFragment.glsl", shadow("shadowFragment_carry.glsl"), &["depth_round_trip_wrong"]),
        ("phongFragment_light_size_world.glsl", vec![], &["umbra_not_dark", "depends_on_uncleared_map"]),
        ("phongFragment_tiny_light.glsl", vec![], &["no_penumbra"]),
        ("phongFragment_nan_blocker.glsl", vec![], &["nan_blocker_depth"]),
        ("phongFragment_ndc_coordinates.glsl", vec![], &["shadows_missing"]),
        ("phongFragment_no_bias.glsl", shadow("shadowFragment_255.glsl"), &["self_shadowing"]),
        ("phongFragment_no_bias_hidden.glsl", vec![], &["round_trip_acne", "self_shadowing (latent)"]),
        ("phongFragment_bias_too_large.glsl", vec![], &["peter_panning"]),
        // The framework's floor leaves the low box; the check scene, which shows the bias, does not.
        (
            "phongFragment_bias_too_large.glsl",
            script("DirectionalLight_low.js"),
            &["light_frustum_clips", "peter_panning"],
        ),
        ("phongFragment_receiver_blocker.glsl", vec![], &["receiver_counts_as_blocker"]),
        (
            "phongFragment_red_only.glsl",
            vec![],
            &["depth_round_trip_wrong (latent)", "self_shadowing (latent)"],
        ),
        ("phongFragment_search_radius.glsl", vec![], &["search_radius_wrong (latent)"]),
        ("phongFragment_random_walk.glsl", vec![], &["samples_not_around_receiver"]),
        ("phongFragment_least_filter.glsl", vec![], &[]),
        ("phongFragment_constant_filter.glsl", vec![], &["filter_ignores_blocker"]),
        ("phongFragment_penumbra_unused.glsl", vec![], &["filter_ignores_blocker"]),
        ("phongFragment_partial_search.glsl", vec![], &["search_radius_wrong (latent)"]),
        ("phongFragment_count_radius.glsl", vec![], &["receiver_counts_as_blocker"]),
        ("phongFragment_filter_in_texels.glsl", vec![], &["search_and_filter_lights_differ"]),
        ("phongFragment_divided_twice.glsl", vec![], &["visibility_scaled"]),
        ("phongFragment_undivided.glsl", vec![], &["visibility_out_of_range"]),
        ("phongFragment_zero_blocker.glsl", vec![], &["filter_radius_not_finite"]),
        ("phongFragment_divided_by_blockers.glsl", vec![], &["nan_visibility", "visibility_out_of_range"]),
        ("phongFragment_blocker_early_return.glsl", vec![], &["blocker_depth_wrong"]),
        ("phongFragment_unfilled_samples.glsl", vec![], &["search_radius_wrong"]),
        ("phongFragment_grid_search.glsl", vec![], &["search_radius_wrong", "no_contact_hardening"]),
        ("phongFragment_receiver_from_map.glsl", vec![], &["penumbra_estimate_wrong"]),
        ("phongFragment_shadow_floor.glsl", vec![], &["umbra_not_dark"]),
        ("phongFragment_perspective_factor.glsl", vec![], &["penumbra_law_wrong"]),
        ("phongFragment_divided_by_receiver.glsl", vec![], &["penumbra_law_wrong"]),
    ]
}

/// A report's findings as `example_cases` writes them.
fn findings_with_severity(report: &Value) -> Vec<String> {
    report["findings"]
        .as_array()
        .expect("findings")
        .iter()
        .map(|f| match f["severity"].as_str() {
            Some("latent") => format!("{} (latent)", f["id"].as_str().expect("an id")),
            _ => f["id"].as_str().expect("an id").to_string(),
        })
        .collect()
}

#[test]
fn each_example_gets_exactly_its_findings_and_the_correct_one_none() {
    let scratch = tempfile::tempdir().expect("a scratch folder");
    for (k, (name, extra, expected)) in example_cases().into_iter().enumerate() {
        let what = format!("{name} {}", extra.join(" "));
        let out = scratch.path().join(format!("{k}"));
        let extra: Vec<&str> = extra.iter().map(String::as_str).collect();
        let report = check(&example(name), &extra, &out);
        assert_eq!(report["compiled"], true, "{what}");
        assert_eq!(findings_with_severity(&report), expected, "{what}: {report:#}");
        assert_eq!(report["visibility_function"], "PCSS", "{what}");
        assert_eq!(report["compared_with"], "pcss", "{what}");
        assert!(report["calls"].as_array().is_some_and(|c| c.contains(&Value::from("PCSS"))), "{what}");
        for finding in report["findings"].as_array().expect("findings") {
            assert!(finding["explanation"].as_str().is_some_and(|e| e.len() > 40), "{what}: {finding}");
            assert!(finding["figures"].as_object().is_some_and(|f| !f.is_empty()), "{what}: {finding}");
            assert!(finding["step"].as_u64().is_some_and(|s| s >= 1), "{what}: {finding}");
            if finding["severity"] == "latent" {
                assert!(
                    finding["explanation"].as_str().is_some_and(|e| e.starts_with("Hidden today")),
                    "{what}"
                );
            }
        }
        // The light the check drew with: the script's where one was given, the scene's otherwise.
        let from = report["light"]["from"].as_str().unwrap_or_else(|| panic!("{what}: {report:#}"));
        let script = extra.iter().position(|a| *a == "--light-script").map(|at| extra[at + 1]);
        match script {
            Some(path) => assert!(
                from.contains(Path::new(path).file_name().and_then(|n| n.to_str()).expect("a name")),
                "{what}: {from}"
            ),
            None => assert_eq!(from, "framework", "{what}"),
        }
        for picture in [
            "student.png",
            "student_lossless_map.png",
            "reference.png",
            "visibility.png",
            "ground_truth.png",
            "difference.png",
        ] {
            let image = image::open(out.join(picture)).unwrap_or_else(|e| panic!("{what}: {picture}: {e}"));
            assert_eq!((image.width(), image.height()), (480, 270), "{what}: {picture}");
        }
        // The map their light pass wrote, a texel a pixel.
        let map = image::open(out.join("student_map.png"))
            .unwrap_or_else(|e| panic!("{what}: student_map.png: {e}"));
        assert!(
            map.width() == map.height() && map.width() >= 512,
            "{what}: {}x{}",
            map.width(),
            map.height()
        );
        let figure =
            |key: &str| report[key].as_f64().unwrap_or_else(|| panic!("{what}: {key} in {report:#}"));
        assert!(figure("shaded_pixels") > 50_000.0, "{what}");
        if name == "phongFragment.glsl" && expected.is_empty() {
            // A correct solution agrees with the ground truth and with shadowlab's PCSS.
            assert!(figure("mean_abs_difference_to_ground_truth") < 0.02, "{report:#}");
            assert!(figure("mean_abs_difference") < 0.02, "{report:#}");
            assert!(figure("lit_area_mean") > 0.99 && figure("umbra_mean") < 0.1, "{report:#}");
            assert_eq!(figure("nan_fraction"), 0.0);
            // Its light width: LIGHT_WIDTH_UV 5/200 of a 200-unit map is 5 world units, and its
            // 20-sample spiral spans about three quarters of the nominal disk. The slabs' widths
            // follow similar triangles.
            let width = &report["light_width"];
            let implied = width["implied_light_width_world"].as_f64().expect("a width");
            assert!((2.5..5.0).contains(&implied), "{what}: {width:#}");
            assert_eq!(width["law_holds"], true, "{what}: {width:#}");
            assert_eq!(width["slabs"].as_array().map(Vec::len), Some(4), "{what}");
        }
        if name == "phongFragment_tiny_light.glsl" {
            // Its light, as its penumbrae show it, is far under the 5 world units of the scene's.
            let implied = report["light_width"]["implied_light_width_world"].as_f64();
            assert!(implied.is_none_or(|w| w < 0.5), "{what}: {:#}", report["light_width"]);
        }
    }
}

/// An example dropped into assets/homework ships by itself (build.rs); what it must be found to
/// be is stated here, in `example_cases`.
#[test]
fn every_example_in_the_folder_has_its_case() {
    let cases = example_cases();
    let named = |file: &str| {
        cases.iter().any(|(name, extra, _)| {
            *name == file || extra.iter().any(|a| Path::new(a).file_name().is_some_and(|n| n == file))
        })
    };
    let folder = repo_path("assets/homework");
    let mut files: Vec<String> = std::fs::read_dir(&folder)
        .expect("the examples' folder")
        .map(|entry| entry.expect("a folder entry").path())
        .filter(|p| p.is_file())
        .filter_map(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
        .filter(|name| shadowlab::built_in::ships(name) && name != "README.md")
        .collect();
    files.sort();
    assert!(!files.is_empty(), "no examples in {}", folder.display());
    let without: Vec<&String> = files.iter().filter(|f| !named(f)).collect();
    assert!(without.is_empty(), "examples without their case in example_cases: {without:?}");
}

/// The examples' table in assets/homework/README.md says what the test above checks.
#[test]
fn the_examples_readme_lists_every_example_with_its_findings() {
    let readme = std::fs::read_to_string(repo_path("assets/homework/README.md")).expect("the README");
    for (name, extra, expected) in example_cases() {
        let row = readme
            .lines()
            .find(|l| {
                l.starts_with("| `")
                    && l.contains(&format!("`{name}`"))
                    && extra.iter().skip(1).step_by(2).all(|a| {
                        let file = Path::new(a).file_name().and_then(|n| n.to_str()).expect("a name");
                        l.contains(file)
                    })
                    && (!extra.is_empty() || !l.contains("` with `"))
            })
            .unwrap_or_else(|| panic!("no row for {name} {extra:?}"));
        let listed = row.rsplit('|').nth(1).expect("a last column").trim();
        let wanted = if expected.is_empty() {
            "nothing".to_string()
        } else {
            expected.iter().map(|f| format!("`{f}`")).collect::<Vec<_>>().join(", ")
        };
        assert_eq!(listed, wanted, "{row}");
    }
}

/// A homework as the student hands it: their folder (the framework's layout, their light in
/// DirectionalLight.js) and the same folder zipped. The check finds the files and reads the light.
#[test]
fn a_homework_folder_and_its_zip_are_checked_with_the_students_own_light() {
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let files = [
        ("homework1/src/shaders/phongShader/phongFragment.glsl", example("phongFragment.glsl")),
        ("homework1/src/lights/DirectionalLight.js", example("DirectionalLight_narrow.js")),
        ("homework1/README.md", repo_path("assets/homework/README.md").display().to_string()),
    ];
    let folder = scratch.path().join("alice");
    let mut zip_entries = Vec::new();
    for (inside, from) in &files {
        let bytes = std::fs::read(from).expect("an example");
        let to = folder.join(inside);
        std::fs::create_dir_all(to.parent().expect("a parent")).expect("folders");
        std::fs::write(&to, &bytes).expect("write");
        zip_entries.push(zip_writer::deflated(&format!("alice/{inside}"), &bytes));
    }
    let zip = scratch.path().join("bob.zip");
    std::fs::write(&zip, zip_writer::build(&zip_entries)).expect("write the zip");
    for (path, name) in [(folder, "alice"), (zip, "bob")] {
        let report = check(&path.display().to_string(), &[], &scratch.path().join(format!("out_{name}")));
        assert_eq!(report["submission"]["name"], name, "{report:#}");
        // Each framework file with where it came from, a path inside the submission.
        let found: Vec<&str> = report["submission"]["files"]
            .as_array()
            .expect("files")
            .iter()
            .filter_map(|pair| pair[1].as_str())
            .collect();
        assert!(found.iter().any(|f| f.ends_with("phongShader/phongFragment.glsl")), "{found:?}");
        assert!(found.iter().any(|f| f.ends_with("lights/DirectionalLight.js")), "{found:?}");
        // Their own light: the narrow box (50 world units wide) the script builds, not the
        // scene's 200; it leaves part of the scene out, which is what they are told.
        let light = &report["light"];
        assert!(light["from"].as_str().is_some_and(|f| f.contains("DirectionalLight.js")), "{light:#}");
        assert!(
            (light["frustum"]["width_world"].as_f64().expect("a width") - 50.0).abs() < 1e-3,
            "{light:#}"
        );
        // The scene (about 141 world units deep along the light) spans about 35% of its 400-unit
        // depth range: no note that the precision is spent on empty space.
        let share = light["frustum"]["scene_depth_share"].as_f64().expect("a share");
        assert!((0.3..0.4).contains(&share), "{light:#}");
        assert!(!light["notes"].to_string().contains("empty space"), "{light:#}");
        assert_eq!(finding_ids(&report), ["light_frustum_clips"], "{report:#}");
    }
}

#[test]
fn a_hard_shadow_is_compared_with_shadowlabs_hard_shadow_and_has_no_penumbra_to_miss() {
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let report = check_edited(
        scratch.path(),
        "  visibility = PCSS(uShadowMap, vec4(shadowCoord, 1.0));",
        "  visibility = useShadowMap(uShadowMap, vec4(shadowCoord, 1.0));",
        "out",
    );
    assert_eq!(report["calls"], serde_json::json!(["useShadowMap"]));
    assert_eq!(report["compared_with"], "hard");
    assert_eq!(finding_ids(&report), Vec::<String>::new(), "{report:#}");
    assert!(report["mean_abs_difference"].as_f64().is_some_and(|d| d < 0.01), "{report:#}");
}

/// Peter panning is said in the student's own units: their light's depth range, the bias in [0, 1]
/// depth the lost shadows bound, and the constant in their code that is that bias (its line, the
/// function its test is in, its size in world units). Where the code writes nothing that large,
/// the finding says so instead of having the student shrink a bias that is not the cause.
#[test]
fn peter_panning_names_the_students_bias_with_its_line_in_their_own_units() {
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let report = check(&example("phongFragment_bias_too_large.glsl"), &[], &scratch.path().join("large"));
    let found = &report["findings"][0];
    assert_eq!(found["id"], "peter_panning", "{report:#}");
    let figure = |name: &str| found["figures"][name].as_f64().unwrap_or(f64::NAN);
    assert!((figure("light_depth_range_world") - 400.0).abs() < 1.0, "{found:#}");
    assert!(figure("bias_at_least_depth") <= 0.015 && 0.015 <= figure("bias_under_depth"), "{found:#}");
    assert_eq!((figure("bias_line"), figure("bias_written")), (30.0, 0.015), "{found:#}");
    assert_eq!(found["function"], "findBlocker", "{found:#}");
    let said = found["explanation"].as_str().unwrap_or_default();
    assert!(said.contains("`BIAS` (line 30, findBlocker: 6.0 world units)"), "{said}");
    assert!(said.contains("depth runs over 400 world units"), "{said}");

    // The same 6 world units, computed: `0.003 * 5.0` in each test. No constant is that large.
    let source = std::fs::read_to_string(example("phongFragment_bias_too_large.glsl")).expect("the example");
    let computed = source.replace("#define BIAS 0.015", "").replace("+ BIAS", "+ 0.003 * 5.0");
    let first_test = computed.lines().position(|l| l.contains("0.003 * 5.0")).expect("a test") + 1;
    let shader = scratch.path().join("phongFragment.glsl");
    std::fs::write(&shader, computed).expect("write the shader");
    let report = check(&shader.display().to_string(), &[], &scratch.path().join("computed"));
    assert_eq!(finding_ids(&report), ["peter_panning"], "{report:#}");
    let said = report["findings"][0]["explanation"].as_str().unwrap_or_default();
    let expected = format!("the largest, `0.003` on line {first_test}, is 1.2 world units");
    assert!(said.contains(&expected), "{said}");
    assert!(!said.contains("In your shader:"), "{said}");

    // The same bias set in a local by an expression in each function that tests: named where it
    // is set, the first of them.
    let local = source.replace("#define BIAS 0.015", "#define SCALE 5.0").replace("BIAS", "bias");
    let local = local.replace(
        "float findBlocker(sampler2D shadowMap, vec2 uv, float zReceiver) {",
        "float findBlocker(sampler2D shadowMap, vec2 uv, float zReceiver) {\n  float bias = 0.003 * SCALE;",
    );
    let local = local
        .replace(
            "float PCF(sampler2D shadowMap, vec4 coords, float radiusUV) {",
            "float PCF(sampler2D shadowMap, vec4 coords, float radiusUV) {\n  float bias = 0.003 * SCALE;",
        )
        .replace(
            "float useShadowMap(sampler2D shadowMap, vec4 shadowCoord) {",
            "float useShadowMap(sampler2D shadowMap, vec4 shadowCoord) {\n  float bias = 0.003 * SCALE;",
        );
    let set_at = local.lines().position(|l| l.contains("float bias = 0.003 * SCALE;")).expect("set") + 1;
    std::fs::write(&shader, local).expect("write the shader");
    let report = check(&shader.display().to_string(), &[], &scratch.path().join("local"));
    assert_eq!(finding_ids(&report), ["peter_panning"], "{report:#}");
    let found = &report["findings"][0];
    assert_eq!(found["function"], "findBlocker", "{found:#}");
    let said = found["explanation"].as_str().unwrap_or_default();
    let expected = format!("`bias = 0.003 * SCALE` (line {set_at}, findBlocker)");
    assert!(said.contains(&expected), "{said}");
}

/// Each of PCSS's steps judged on the student's own inputs names the function, its quantity
/// beside the expected one, and the line: the early return findBlocker always takes, the sample
/// array it reads before anything fills it, a search far smaller than the light the filter
/// behaves as, the map read that stands in for the receiver's depth, the constant that sets a
/// light as wide as the map.
#[test]
fn each_pcss_step_that_parts_from_the_twin_is_named_with_its_quantity_and_line() {
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let first = |name: &str| {
        let report = check(&example(name), &[], &scratch.path().join(name));
        report["findings"][0].clone()
    };
    let figure = |f: &Value, name: &str| f["figures"][name].as_f64().unwrap_or(f64::NAN);
    let said = |f: &Value| f["explanation"].as_str().unwrap_or_default().to_string();

    let early = first("phongFragment_blocker_early_return.glsl");
    assert_eq!(
        (early["id"].as_str(), early["function"].as_str()),
        (Some("blocker_depth_wrong"), Some("findBlocker"))
    );
    assert_eq!(figure(&early, "returned_median"), 0.0, "{early:#}");
    assert!((0.1..0.4).contains(&figure(&early, "twin_blocker_depth_median")), "{early:#}");
    assert!(
        said(&early).contains("the return on line 82, taken whenever the test on line 81 holds"),
        "{early:#}"
    );

    let unfilled = first("phongFragment_unfilled_samples.glsl");
    assert_eq!(unfilled["id"], "search_radius_wrong", "{unfilled:#}");
    assert_eq!(figure(&unfilled, "reads_at_receiver_share"), 1.0, "{unfilled:#}");
    assert!(said(&unfilled).contains("Line 69 reads `poissonDisk` before anything fills it"), "{unfilled:#}");

    let grid = first("phongFragment_grid_search.glsl");
    assert_eq!(grid["id"], "search_radius_wrong", "{grid:#}");
    assert!((2.0..3.5).contains(&figure(&grid, "search_radius_texels_median")), "{grid:#}");
    // The example's light: 5 world units, 5 / 200 of the 2048-texel map, half of it 25.6 texels.
    assert!((figure(&grid, "light_width_world") - 5.0).abs() < 0.25, "{grid:#}");
    assert!((figure(&grid, "light_half_width_texels_median") - 25.6).abs() < 1.0, "{grid:#}");

    let from_map = first("phongFragment_receiver_from_map.glsl");
    assert_eq!(
        (from_map["id"].as_str(), from_map["function"].as_str()),
        (Some("penumbra_estimate_wrong"), Some("PCSS"))
    );
    assert_eq!(figure(&from_map, "map_read_line"), 99.0, "{from_map:#}");
    assert!(figure(&from_map, "collapsed_share") > 0.3, "{from_map:#}");

    // A light size in world units (5) used as uv: a light five maps wide, and its #define.
    let wide = first("phongFragment_light_size_world.glsl");
    assert_eq!(wide["id"], "umbra_not_dark", "{wide:#}");
    assert!((figure(&wide, "light_width_uv") - 5.0).abs() < 0.1, "{wide:#}");
    assert_eq!(figure(&wide, "light_line"), 28.0, "{wide:#}");
    assert!(said(&wide).contains("That is `LIGHT_WIDTH_UV` on line 28."), "{wide:#}");

    // A blocked tap that counts 0.4: the umbra is that one number, and the #define that says so.
    let floor = first("phongFragment_shadow_floor.glsl");
    assert_eq!((floor["id"].as_str(), floor["function"].as_str()), (Some("umbra_not_dark"), Some("PCF")));
    assert!((figure(&floor, "umbra_value") - 0.4).abs() < 0.01, "{floor:#}");
    assert!(said(&floor).contains("That is `SHADOW_FLOOR` on line 33, in PCF."), "{floor:#}");

    // The correct solution: no step parts from the twin.
    let report = check(&example("phongFragment.glsl"), &[], &scratch.path().join("correct"));
    assert_eq!(finding_ids(&report), Vec::<String>::new(), "{report:#}");
}

/// A filter radius that scales with the depths beyond similar triangles is named by its law (the
/// powers of the receiver's and the blocker's depth the light's half width it implies follows),
/// by the line that divides, and by the light size the code sets against the one it behaves as;
/// a blocker search under a name of the student's is named by it.
#[test]
fn a_filter_radius_off_similar_triangles_is_named_by_its_law_its_line_and_the_light_it_behaves_as() {
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let first = |name: &str| {
        let report = check(&example(name), &[], &scratch.path().join(name));
        assert!(
            report["calls"].as_array().is_some_and(|c| c.iter().any(|f| f == "findBlocker")),
            "{report:#}"
        );
        report["findings"][0].clone()
    };
    let figure = |f: &Value, name: &str| f["figures"][name].as_f64().unwrap_or(f64::NAN);
    let said = |f: &Value| f["explanation"].as_str().unwrap_or_default().to_string();

    // NEAR_PLANE / zReceiver on the orthographic light: the half width goes as 1 / d_r.
    let near = first("phongFragment_perspective_factor.glsl");
    assert_eq!((near["id"].as_str(), near["function"].as_str()), (Some("penumbra_law_wrong"), Some("PCSS")));
    assert!((figure(&near, "receiver_depth_exponent") + 1.0).abs() < 0.05, "{near:#}");
    assert!(figure(&near, "blocker_depth_exponent").abs() < 0.05, "{near:#}");
    assert_eq!(figure(&near, "line"), 107.0, "{near:#}");
    assert!(said(&near).contains("near / z_r of the NVIDIA sample"), "{near:#}");
    // The light it behaves as against the 1 world unit its #define sets: 1 / d_r is 3-4 here.
    assert_eq!(figure(&near, "light_size_line"), 32.0, "{near:#}");
    assert!((2.0..6.0).contains(&figure(&near, "implied_light_width_world")), "{near:#}");
    assert!(said(&near).contains("where your LIGHT_WORLD_SIZE on line 32 is 1."), "{near:#}");
    assert!(!said(&near).contains("findBlocker"), "named as the student named it: {near:#}");

    // (d_r - d_b) / d_r: the half width goes as d_b / d_r.
    let receiver = first("phongFragment_divided_by_receiver.glsl");
    assert_eq!(receiver["id"], "penumbra_law_wrong", "{receiver:#}");
    assert!((figure(&receiver, "receiver_depth_exponent") + 1.0).abs() < 0.05, "{receiver:#}");
    assert!((figure(&receiver, "blocker_depth_exponent") - 1.0).abs() < 0.05, "{receiver:#}");
    assert_eq!(figure(&receiver, "line"), 99.0, "{receiver:#}");
    assert!(said(&receiver).contains("instead of the blocker's"), "{receiver:#}");
}

/// A filter radius that ignores the blocker is named with the penumbra the code computes and never
/// reads; a filter that behaves as another light than the search looks for, with the two lines
/// that turn one length into uv two ways; a blocker test's bias the wrong way round, with its line.
#[test]
fn a_filter_that_ignores_the_blocker_or_another_light_and_a_bias_the_wrong_way_are_named_by_line() {
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let first = |name: &str| check(&example(name), &[], &scratch.path().join(name))["findings"][0].clone();
    let figure = |f: &Value, name: &str| f["figures"][name].as_f64().unwrap_or(f64::NAN);
    let said = |f: &Value| f["explanation"].as_str().unwrap_or_default().to_string();

    // The search's radius (the receiver's depth alone) used to filter; the penumbra left unread.
    let unused = first("phongFragment_penumbra_unused.glsl");
    assert_eq!(
        (unused["id"].as_str(), unused["function"].as_str()),
        (Some("filter_ignores_blocker"), Some("PCSS"))
    );
    assert!(figure(&unused, "blocker_ratio_exponent").abs() < 0.1, "{unused:#}");
    assert_eq!(figure(&unused, "line"), 98.0, "{unused:#}");
    assert!(said(&unused).contains("computes `penumbraUV` from the blocker's depth"), "{unused:#}");
    // One radius everywhere: said so, with no line to name.
    let constant = first("phongFragment_constant_filter.glsl");
    assert_eq!(constant["id"], "filter_ignores_blocker", "{constant:#}");
    assert!(figure(&constant, "one_radius_share") > 0.9, "{constant:#}");
    assert!(constant["figures"].get("line").is_none(), "{constant:#}");

    // World units over the frustum's 200 for the search, over the map's 2048 texels for the filter.
    let texels = first("phongFragment_filter_in_texels.glsl");
    assert_eq!(texels["id"], "search_and_filter_lights_differ", "{texels:#}");
    assert!((9.0..11.5).contains(&figure(&texels, "search_over_filter")), "{texels:#}");
    assert_eq!((figure(&texels, "search_line"), figure(&texels, "line")), (73.0, 103.0), "{texels:#}");
    assert!(
        said(&texels).contains("`/ FRUSTUM_WIDTH`") && said(&texels).contains("`/ MAP_TEXELS`"),
        "{texels:#}"
    );

    // The first 8 of 32 samples: (8 / 32)^0.75 of the search's radius, on the loop's line.
    let part = first("phongFragment_partial_search.glsl");
    assert_eq!(
        (part["id"].as_str(), part["severity"].as_str()),
        (Some("search_radius_wrong"), Some("latent"))
    );
    assert_eq!(
        (figure(&part, "line"), figure(&part, "samples_read"), figure(&part, "samples_in_disk")),
        (69.0, 8.0, 32.0)
    );
    assert!(said(&part).contains("reach 35% of its radius"), "{part:#}");

    // A view summed into the identity: the map projects 22.5 degrees off the light's axis.
    let script = example("DirectionalLight_identity_sum.js");
    let args = ["--light-script", script.as_str()];
    let skewed =
        check(&example("phongFragment.glsl"), &args, &scratch.path().join("skewed"))["findings"][0].clone();
    assert_eq!(skewed["id"], "light_direction_off", "{skewed:#}");
    assert!((figure(&skewed, "angle_degrees") - 22.5).abs() < 0.5, "{skewed:#}");
    assert!(said(&skewed).contains("(DirectionalLight_identity_sum.js:"), "{skewed:#}");

    // A flat bias under the slope across a disk sized by a sample count: both lines.
    let wide = first("phongFragment_count_radius.glsl");
    assert_eq!(wide["id"], "receiver_counts_as_blocker", "{wide:#}");
    assert_eq!((figure(&wide, "bias_line"), figure(&wide, "radius_line")), (32.0, 71.0), "{wide:#}");
    assert!(figure(&wide, "receiver_spread_depth_median") > 2.0 * figure(&wide, "bias_depth"), "{wide:#}");

    // `depth - BIAS < zReceiver`: the wrong way round, on the `#define`'s line.
    let wrong_way = first("phongFragment_receiver_blocker.glsl");
    assert_eq!(wrong_way["id"], "receiver_counts_as_blocker", "{wrong_way:#}");
    assert_eq!(
        (figure(&wrong_way, "bias_line"), figure(&wrong_way, "test_line")),
        (31.0, 71.0),
        "{wrong_way:#}"
    );
    assert!(said(&wrong_way).contains("is the wrong way round"), "{wrong_way:#}");
}

/// A light whose box fits shadowlab's check scene but not the framework's own floor (±80 tall:
/// the far floor wraps to rows nothing was drawn in) is judged on that floor: the finding names
/// the band it leaves dark, in world units, and why it is dark.
#[test]
fn a_light_that_fits_the_check_scene_but_not_the_frameworks_floor_is_named_with_the_band() {
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let light = example("DirectionalLight_low.js");
    let report = check(&example("phongFragment.glsl"), &["--light-script", &light], scratch.path());
    assert_eq!(finding_ids(&report), ["light_frustum_clips"], "{report:#}");
    let found = &report["findings"][0];
    let figure = |name: &str| found["figures"][name].as_f64().unwrap_or(f64::NAN);
    // The floor reaches v = 0.707 * 141.7 = 100.2 up the map; the box ends at 80: z < -113.
    assert!((figure("framework_floor_dark_z_min") + 141.0).abs() < 2.0, "{found:#}");
    assert!((figure("framework_floor_dark_z_max") + 114.0).abs() < 3.0, "{found:#}");
    assert!((0.08..0.16).contains(&figure("framework_floor_dark_share")), "{found:#}");
    assert_eq!(figure("framework_floor_beyond_far_share"), 0.0, "{found:#}");
    let said = found["explanation"].as_str().unwrap_or_default();
    assert!(said.contains("wrap (REPEAT) to texels the floor never wrote"), "{said}");
}

/// No bias in PCF, the framework's packing: shadowlab's check scene hides the acne (its depths
/// lie under 0.5, where the round trip reads a little too far), but the framework's own floor
/// reaches depth 0.53 under its light, where the round trip reads up to 1/510 too near: the far
/// floor acnes, and the finding says that the round trip is why, with the band and the figures.
#[test]
fn the_round_trip_that_acnes_the_frameworks_far_floor_is_named_as_the_cause() {
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let report = check(&example("phongFragment_no_bias_hidden.glsl"), &[], scratch.path());
    let found = &report["findings"][0];
    assert_eq!(
        (found["id"].as_str(), found["severity"].as_str()),
        (Some("round_trip_acne"), Some("mistake"))
    );
    let figure = |name: &str| found["figures"][name].as_f64().unwrap_or(f64::NAN);
    assert_eq!(figure("bias_depth"), 0.0, "{found:#}");
    assert!((figure("round_trip_error_depth") - 1.0 / 510.0).abs() < 1e-4, "{found:#}");
    assert!(figure("acne_depth_from") >= 0.5 && figure("acne_z_min") < -135.0, "{found:#}");
    let said = found["explanation"].as_str().unwrap_or_default();
    assert!(said.contains("stored in 8-bit channels (k/255) and read back with 1/256 steps"), "{said}");
    // The correct solution's bias, 0.003, is over the round trip's 0.002: nothing.
    let correct = check(&example("phongFragment.glsl"), &[], &scratch.path().join("correct"));
    assert_eq!(finding_ids(&correct), Vec::<String>::new(), "{correct:#}");
}

/// A correct PCSS whose filter never goes under 2 texels: its penumbrae are the light's over that
/// floor, so they still follow similar triangles and give back a light near the 2 world units its
/// code sets (not a filter of one width, no_contact_hardening).
#[test]
fn a_narrow_light_over_a_least_filter_radius_is_measured_not_called_a_constant_filter() {
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let report = check(&example("phongFragment_least_filter.glsl"), &[], scratch.path());
    assert_eq!(finding_ids(&report), Vec::<String>::new(), "{report:#}");
    let width = &report["light_width"];
    assert_eq!(width["law_holds"], true, "{width:#}");
    let implied = width["implied_light_width_world"].as_f64().unwrap_or(f64::NAN);
    assert!((1.5..=2.5).contains(&implied), "{width:#}");
    assert_eq!(width["narrower_than_world"], Value::Null, "{width:#}");
}

/// A PCF whose sum of 32 tests is divided by another count (24), or not at all: visibility above
/// 1, and that finding alone (not missing shadows, a missing penumbra or acne).
#[test]
fn a_pcf_sum_divided_by_the_wrong_count_is_out_of_range_and_only_that() {
    let scratch = tempfile::tempdir().expect("a scratch folder");
    for (what, divided, max) in [
        ("PCF_NUM_SAMPLES - 8", "  return lit / float(PCF_NUM_SAMPLES - 8);", 32.0 / 24.0),
        ("no division", "  return lit;", 32.0),
    ] {
        let out = what.replace(' ', "_");
        let report = check_edited(scratch.path(), "  return lit / float(PCF_NUM_SAMPLES);", divided, &out);
        assert_eq!(finding_ids(&report), ["visibility_out_of_range"], "{what}: {report:#}");
        let finding = &report["findings"][0];
        let figure = |key: &str| finding["figures"][key].as_f64().unwrap_or_else(|| panic!("{what}: {key}"));
        // Most lit pixels ran the filter with every tap lit.
        assert!(figure("out_of_range_share") > 0.5, "{what}: {finding}");
        assert!(
            (figure("visibility_max") - max).abs() < 1e-3 && figure("visibility_min") >= 0.0,
            "{what}: {finding}"
        );
        assert!(figure("lit_area_mean") > 1.2, "{what}: {finding}");
        assert_eq!((finding["lesson"].as_str(), finding["step"].as_u64()), (Some("pcf"), Some(2)), "{what}");
    }
}

/// A PCF sum of 32 tests divided by PCF_NUM_SAMPLES twice: visibility 1/32 of shadowlab's
/// wherever the filter ran, and that finding alone (not a missing penumbra or acne).
#[test]
fn a_pcf_sum_divided_twice_is_scaled_and_only_that() {
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let report = check_edited(
        scratch.path(),
        "  return lit / float(PCF_NUM_SAMPLES);",
        "  return lit / float(PCF_NUM_SAMPLES) / float(PCF_NUM_SAMPLES);",
        "out",
    );
    assert_eq!(finding_ids(&report), ["visibility_scaled"], "{report:#}");
    let finding = &report["findings"][0];
    let figure = |key: &str| finding["figures"][key].as_f64().unwrap_or_else(|| panic!("{key}: {finding}"));
    // The correct solution's own scale against shadowlab's PCSS is 1 within 0.1% (noise of the
    // sample pattern); 2% keeps 32 apart from 31 and 33.
    assert!((32.0 * figure("scale") - 1.0).abs() < 0.02, "{finding}");
    assert!((figure("one_over_scale") - 32.0).abs() < 0.64, "{finding}");
    assert!(figure("fit_mean_abs_error") < 0.01 * figure("unscaled_mean_abs_error"), "{finding}");
    // Where findBlocker finds no blocker PCSS returns 1 unfiltered: the lit area reads a little
    // above 1/32.
    assert!(figure("lit_area_mean") < 0.2, "{finding}");
    assert_eq!((finding["lesson"].as_str(), finding["step"].as_u64()), (Some("pcf"), Some(2)));
}

#[test]
fn a_shader_that_does_not_compile_exits_2_on_the_students_own_line() {
    let source = std::fs::read_to_string(example("phongFragment.glsl")).expect("the example");
    let mut lines: Vec<&str> = source.lines().collect();
    let line = lines.iter().position(|l| l.contains("float depthSum = 0.0;")).expect("the line") + 1;
    lines[line - 1] = "  float depthSum = 0.0 +;";
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let shader = scratch.path().join("phongFragment.glsl");
    std::fs::write(&shader, lines.join("\n")).expect("write the shader");
    let out = scratch.path().join("out");
    let run = shadowlab(&["homework", &shader.display().to_string(), "--out", &out.display().to_string()]);
    assert_eq!(run.code, Some(2), "{}", run.stderr);
    assert_eq!(run.stderr.lines().count(), 1, "{}", run.stderr);
    assert!(run.stderr.starts_with(&format!("shadowlab: phongFragment.glsl:{line}: ")), "{}", run.stderr);
    let report: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).expect("report.json"))
            .expect("JSON");
    assert_eq!(report["compiled"], false);
    assert_eq!(report["error"]["line"], line);
    assert_eq!(report["findings"], serde_json::json!([]));
    assert!(!out.join("student.png").exists(), "no picture for a shader that did not compile");
}

#[test]
fn bad_input_is_one_line_exit_2_and_nothing_written() {
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let out = scratch.path().join("out");
    let out_arg = out.display().to_string();
    let correct = example("phongFragment.glsl");
    let missing = scratch.path().join("nope.glsl").display().to_string();
    let cases: [(Vec<&str>, &str); 4] = [
        (vec!["homework", &missing, "--out", &out_arg], "nope.glsl"),
        (vec!["homework", &correct, "--out", &out_arg, "--set", "light.0.nonsense=1"], "nonsense"),
        (vec!["homework", &correct, "--out", &out_arg, "--light", "3"], "--light 3"),
        (vec!["homework", &correct, "--out", "/no/such/folder/out"], "/no/such/folder"),
    ];
    for (args, named) in cases {
        let run = shadowlab(&args);
        assert_eq!(run.code, Some(2), "{args:?}: {}", run.stderr);
        assert_eq!(run.stderr.lines().count(), 1, "{args:?}: {}", run.stderr);
        assert!(
            run.stderr.starts_with("shadowlab: ") && run.stderr.contains(named),
            "{args:?}: {}",
            run.stderr
        );
        assert!(!out.exists(), "{args:?}: wrote {}", out.display());
    }
}

/// Bad shaders are bad input: each a clear one-line error on the student's own line (exit 2, no
/// picture), or, for an endless loop, a check that ends (wgpu bounds every loop).
#[test]
fn bad_shaders_are_one_line_errors_on_their_line_and_an_endless_loop_ends() {
    let source = std::fs::read_to_string(example("phongFragment.glsl")).expect("the example");
    let line_of = |text: &str, needle: &str| text.lines().position(|l| l.contains(needle)).expect(needle) + 1;
    let deep = format!("  float lit = {}0.0{};", "(".repeat(500), ")".repeat(500));
    let cases: Vec<(&str, String, &str, &str)> = vec![
        (
            "syntax error",
            source.replacen("float depthSum = 0.0;", "float depthSum = 0.0 +;", 1),
            "0.0 +;",
            "",
        ),
        (
            "unknown function",
            source.replacen("blinnPhong();", "blinnPhongg();", 1),
            "blinnPhongg",
            "blinnPhongg",
        ),
        ("no main", source.replacen("void main(void) {", "void notMain(void) {", 1), "", "main"),
        (
            "a sample count of 100000",
            source.replacen("#define NUM_SAMPLES 32", "#define NUM_SAMPLES 100000", 1),
            "vec2 poissonDisk[NUM_SAMPLES];",
            "100000",
        ),
        (
            "NaN everywhere",
            source.replacen("vec4(phongColor * visibility, 1.0)", "vec4(phongColor * (0.0 / 0.0), 1.0)", 1),
            "(0.0 / 0.0)",
            "NaN",
        ),
        ("nested too deep", source.replacen("  float lit = 0.0;", &deep, 1), "float lit = ((", "nested"),
        // What WebGL 1 refuses and GLSL 450 accepts: refused as the student's browser refused it.
        (
            "an int where WebGL wants a float",
            source.replacen("lit / float(PCF_NUM_SAMPLES)", "lit / PCF_NUM_SAMPLES", 1),
            "lit / PCF_NUM_SAMPLES",
            "WebGL 1 refuses this: `NUM_SAMPLES` (#define NUM_SAMPLES 32",
        ),
        (
            "a while loop",
            source.replacen(
                "  float lit = 0.0;",
                "  float lit = 0.0;\n  while (lit > 1.0) { lit -= 1.0; }",
                1,
            ),
            "while (lit",
            "`while` loop",
        ),
    ];
    let scratch = tempfile::tempdir().expect("a scratch folder");
    for (what, text, at, says) in cases {
        let shader = scratch.path().join("phongFragment.glsl");
        std::fs::write(&shader, &text).expect("write");
        let out = scratch.path().join(what.replace(' ', "_"));
        let run = shadowlab(&[
            "homework",
            &shader.display().to_string(),
            "--size",
            "64x36",
            "--out",
            &out.display().to_string(),
        ]);
        assert_eq!(run.code, Some(2), "{what}: {}", run.stderr);
        assert_eq!(run.stderr.lines().count(), 1, "{what}: {}", run.stderr);
        let line = if at.is_empty() { text.lines().count() } else { line_of(&text, at) };
        assert!(
            run.stderr.starts_with(&format!("shadowlab: phongFragment.glsl:{line}: ")),
            "{what}: {}",
            run.stderr
        );
        assert!(run.stderr.contains(says), "{what}: {}", run.stderr);
        assert!(!out.join("student.png").exists(), "{what}");
    }
    // An endless loop in findBlocker: the check still ends and reports.
    let endless = source.replacen(
        "  float depthSum = 0.0;",
        "  float depthSum = 0.0;\n  for (int k = 0; k >= 0; k += 0) { depthSum += 1.0; }",
        1,
    );
    let shader = scratch.path().join("phongFragment.glsl");
    std::fs::write(&shader, endless).expect("write");
    let report = check(&shader.display().to_string(), &[], &scratch.path().join("endless"));
    assert_eq!(report["compiled"], true);
}

/// A lesson 7 step renders the student's picture (as the app shows it), the one `shadowlab
/// homework` writes for the same shader.
#[test]
fn a_lesson_step_that_checks_a_homework_renders_the_students_picture() {
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let step = scratch.path().join("step.png");
    let run = shadowlab(&[
        "render",
        "--lesson",
        "homework",
        "--step",
        "4",
        "--size",
        SIZE,
        "--out",
        &step.display().to_string(),
    ]);
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    let out = scratch.path().join("check");
    check(&example("phongFragment_nan_blocker.glsl"), &[], &out);
    let a = image::open(&step).expect("the step").to_rgba8();
    let b = image::open(out.join("student.png")).expect("the student's picture").to_rgba8();
    assert_eq!(a.dimensions(), b.dimensions());
    let differing = a
        .pixels()
        .zip(b.pixels())
        .filter(|(p, q)| p.0.iter().zip(q.0).any(|(x, y)| x.abs_diff(y) > 2))
        .count();
    assert!(differing * 1000 <= (a.width() * a.height()) as usize, "{differing} pixels differ");
}

/// A student's own vertex shader (with varyings and uniforms of their own) runs with their
/// fragment shader: `--vertex` as the framework would link them.
#[test]
fn a_students_own_vertex_shader_runs_with_their_fragment_shader() {
    let data = |name: &str| repo_path("tests/data/homework").join(name).display().to_string();
    let scratch = tempfile::tempdir().expect("a scratch folder");
    let vertex = data("phongVertex_additions.glsl");
    let report =
        check(&data("phongFragment_additions.glsl"), &["--vertex", &vertex], &scratch.path().join("out"));
    assert_eq!(report["compiled"], true);
    assert!(
        report["calls"].as_array().is_some_and(|c| c.contains(&Value::from("useShadowMap"))),
        "{report:#}"
    );
    assert!(report["mean_abs_difference_to_ground_truth"].as_f64().is_some_and(|d| d < 0.05), "{report:#}");
}

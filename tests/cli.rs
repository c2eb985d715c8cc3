//! The command line as a user meets it: the `shadowlab` binary run as a process.
//!
//! Bad input must exit with code 2, print exactly one line on stderr starting `shadowlab: `
//! that names the file or key at fault, never panic, and leave no output (nor a temporary
//! file) behind. The positive tests render at small sizes with few reference samples.

mod common;

use common::Run;
use serde_json::Value;
use std::path::{Path, PathBuf};
use tempfile::TempDir;

fn repo_path(relative: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(relative)
}

fn contact() -> String {
    repo_path("assets/scenes/contact.toml").display().to_string()
}

fn fixture(name: &str) -> String {
    repo_path("tests/data/scenes").join(name).display().to_string()
}

fn shadowlab<S: AsRef<std::ffi::OsStr>>(args: &[S]) -> Run {
    common::run(common::shadowlab_command().args(args))
}

/// A scratch folder for outputs and hand-written scenes.
struct Scratch {
    dir: TempDir,
}

impl Scratch {
    fn new() -> Self {
        Self { dir: tempfile::tempdir().expect("temporary folder") }
    }

    fn path(&self, name: &str) -> PathBuf {
        self.dir.path().join(name)
    }

    fn arg(&self, name: &str) -> String {
        self.path(name).display().to_string()
    }

    /// Write a scene file into the folder and return its path.
    fn scene(&self, name: &str, text: &str) -> String {
        let path = self.path(name);
        std::fs::write(&path, text).expect("write scene");
        path.display().to_string()
    }

    /// Temporary files the atomic writer may have left behind.
    fn stray_temp_files(&self) -> Vec<String> {
        std::fs::read_dir(self.dir.path())
            .expect("read scratch folder")
            .map(|e| e.expect("directory entry").file_name().to_string_lossy().into_owned())
            .filter(|name| name.starts_with('.') && name.contains(".tmp-"))
            .collect()
    }

    fn assert_no_output(&self, out: &str) {
        assert!(!self.path(out).exists(), "{out} must not be written");
        assert_eq!(self.stray_temp_files(), Vec::<String>::new(), "stray temporary files");
    }
}

/// Exit code 2, one `shadowlab: ` line on stderr mentioning every needle, nothing on stdout.
#[track_caller]
fn assert_bad_input(run: &Run, needles: &[&str]) {
    assert_eq!(run.code, Some(2), "bad input should exit with 2:\n{run}");
    assert!(!run.stderr.contains("panicked"), "panicked:\n{run}");
    let lines: Vec<&str> = run.stderr.lines().collect();
    assert_eq!(lines.len(), 1, "exactly one line on stderr:\n{run}");
    assert!(lines[0].starts_with("shadowlab: "), "stderr should start with `shadowlab: `:\n{run}");
    for needle in needles {
        assert!(lines[0].contains(needle), "stderr should mention {needle:?}:\n{run}");
    }
    assert!(run.stdout.is_empty(), "nothing on stdout for bad input:\n{run}");
}

/// A usage error reported by the argument parser: exit code 2, the argument named.
#[track_caller]
fn assert_usage_error(run: &Run, needles: &[&str]) {
    assert_eq!(run.code, Some(2), "usage errors exit with 2:\n{run}");
    assert!(!run.stderr.contains("panicked"), "panicked:\n{run}");
    for needle in needles {
        assert!(run.stderr.contains(needle), "stderr should mention {needle:?}:\n{run}");
    }
    assert!(run.stdout.is_empty(), "nothing on stdout for bad input:\n{run}");
}

/// `render` of `scene` with extra arguments into scratch/out.png (at 32x18 unless `extra`
/// gives a size); returns the run.
fn render(scratch: &Scratch, scene: &str, extra: &[&str]) -> Run {
    let out = scratch.arg("out.png");
    let mut args = vec!["render", "--scene", scene, "--out", &out];
    if !extra.contains(&"--size") {
        args.extend_from_slice(&["--size", "32x18"]);
    }
    args.extend_from_slice(extra);
    shadowlab(&args)
}

#[track_caller]
fn render_rejected(scene: &str, extra: &[&str], needles: &[&str]) {
    let scratch = Scratch::new();
    let run = render(&scratch, scene, extra);
    assert_bad_input(&run, needles);
    scratch.assert_no_output("out.png");
}

#[track_caller]
fn render_usage_error(extra: &[&str], needles: &[&str]) {
    let scratch = Scratch::new();
    let run = render(&scratch, &contact(), extra);
    assert_usage_error(&run, needles);
    scratch.assert_no_output("out.png");
}

fn decode_png(path: &Path) -> image::RgbaImage {
    image::open(path).unwrap_or_else(|e| panic!("{} should be a PNG: {e}", path.display())).to_rgba8()
}

/// Render `view` of contact.toml at 160x90 and return the image and stdout.
fn render_view(view: &str, extra: &[&str]) -> (image::RgbaImage, String) {
    let scratch = Scratch::new();
    let out = scratch.arg("view.png");
    let scene = contact();
    let mut args = vec!["render", "--scene", &scene, "--size", "160x90", "--view", view, "--out", &out];
    args.extend_from_slice(extra);
    let run = shadowlab(&args);
    assert_eq!(run.code, Some(0), "render --view {view} should succeed:\n{run}");
    assert!(run.stderr.is_empty(), "nothing on stderr for a good render:\n{run}");
    assert!(run.stdout.contains("wrote "), "{run}");
    assert_eq!(scratch.stray_temp_files(), Vec::<String>::new());
    (decode_png(&scratch.path("view.png")), run.stdout)
}

/// The two numbers of a legend line `label: MIN .. MAX unit ...`.
fn legend_range(stdout: &str, label: &str) -> (f64, f64) {
    let line = stdout
        .lines()
        .find(|l| l.starts_with(label))
        .unwrap_or_else(|| panic!("no `{label}` legend line in:\n{stdout}"));
    let rest = line[label.len()..].trim_start_matches(':').trim();
    let mut words = rest.split_whitespace();
    let min: f64 =
        words.next().and_then(|w| w.parse().ok()).unwrap_or_else(|| panic!("no minimum in {line:?}"));
    assert_eq!(words.next(), Some(".."), "{line:?}");
    let max: f64 =
        words.next().and_then(|w| w.parse().ok()).unwrap_or_else(|| panic!("no maximum in {line:?}"));
    (min, max)
}

/// The app benches drive the whole app in a process of their own and wait for it to settle; on a
/// two-core machine three at once starve each other past that wait. They take turns.
fn app_bench_turn() -> std::sync::MutexGuard<'static, ()> {
    static TURN: std::sync::Mutex<()> = std::sync::Mutex::new(());
    TURN.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}

fn probe_json(extra: &[&str]) -> Value {
    let scene = contact();
    let mut args = vec!["probe", "--scene", &scene, "--size", "160x90"];
    args.extend_from_slice(extra);
    let run = shadowlab(&args);
    assert_eq!(run.code, Some(0), "probe should succeed:\n{run}");
    assert!(!run.stderr.contains("panicked"), "{run}");
    serde_json::from_str(&run.stdout).unwrap_or_else(|e| panic!("probe prints JSON ({e}):\n{run}"))
}

// ---------------------------------------------------------------------------------------------
// Bad input: scene files.

#[test]
fn missing_scene_file_names_the_file() {
    let scratch = Scratch::new();
    let scene = scratch.arg("no_such_scene.toml");
    let run = render(&scratch, &scene, &[]);
    assert_bad_input(&run, &["no_such_scene.toml", "cannot read"]);
    scratch.assert_no_output("out.png");
}

#[test]
fn scene_path_that_is_a_folder_is_rejected() {
    let scratch = Scratch::new();
    let folder = scratch.path("folder.toml");
    std::fs::create_dir(&folder).expect("create folder");
    let run = render(&scratch, &folder.display().to_string(), &[]);
    assert_bad_input(&run, &["folder.toml"]);
    scratch.assert_no_output("out.png");
}

#[test]
fn scene_file_that_is_not_utf8_is_rejected() {
    let scratch = Scratch::new();
    let path = scratch.path("binary.toml");
    std::fs::write(&path, b"\xff\xfe[camera]\n").expect("write");
    let run = render(&scratch, &path.display().to_string(), &[]);
    assert_bad_input(&run, &["binary.toml"]);
    scratch.assert_no_output("out.png");
}

#[test]
fn toml_syntax_error_names_file_and_line() {
    let scratch = Scratch::new();
    let scene = scratch.scene("syntax.toml", "[camera]\nposition = [0.0, 4.0, 10.0]\nfov_deg = = 40\n");
    let run = render(&scratch, &scene, &[]);
    assert_bad_input(&run, &["syntax.toml:3:"]);
    scratch.assert_no_output("out.png");
}

#[test]
fn unclosed_array_names_file_and_line() {
    let scratch = Scratch::new();
    let scene = scratch.scene("unclosed.toml", "# comment\n[camera]\nposition = [0, 1, 5\n");
    let run = render(&scratch, &scene, &[]);
    assert_bad_input(&run, &["unclosed.toml:3:"]);
    scratch.assert_no_output("out.png");
}

#[test]
fn unknown_shadow_key_names_file_key_and_line() {
    let scratch = Scratch::new();
    let scene = scratch.scene(
        "unknown_key.toml",
        "[camera]\nposition = [0.0, 4.0, 10.0]\n\n[shadow]\ntechnique = \"pcf\"\nfoo = 1\n",
    );
    let run = render(&scratch, &scene, &[]);
    assert_bad_input(&run, &["unknown_key.toml:6:", "foo"]);
    scratch.assert_no_output("out.png");
}

#[test]
fn unknown_light_key_names_file_key_and_line() {
    let scratch = Scratch::new();
    let scene = scratch.scene(
        "unknown_light_key.toml",
        "[camera]\nposition = [0.0, 4.0, 10.0]\n\n[[light]]\nkind = \"spot\"\nposition = [0.0, 9.0, 0.0]\nfov_deg = 50.0\nradius = 2.0\n",
    );
    let run = render(&scratch, &scene, &[]);
    assert_bad_input(&run, &["unknown_light_key.toml:8:", "radius"]);
    scratch.assert_no_output("out.png");
}

#[test]
fn wrong_value_type_in_file_names_file_and_line() {
    let scratch = Scratch::new();
    let scene = scratch
        .scene("wrong_type.toml", "[camera]\nposition = [0.0, 4.0, 10.0]\n\n[shadow]\nsamples = \"many\"\n");
    let run = render(&scratch, &scene, &[]);
    assert_bad_input(&run, &["wrong_type.toml:5:"]);
    scratch.assert_no_output("out.png");
}

#[test]
fn out_of_range_value_in_file_names_file_and_key() {
    let scratch = Scratch::new();
    let scene =
        scratch.scene("range.toml", "[camera]\nposition = [0.0, 4.0, 10.0]\n\n[shadow]\nsamples = 1000\n");
    let run = render(&scratch, &scene, &[]);
    assert_bad_input(&run, &["range.toml", "samples", "1..=128"]);
    scratch.assert_no_output("out.png");
}

#[test]
fn nan_in_file_names_file_and_key() {
    let scratch = Scratch::new();
    let scene = scratch.scene("nan.toml", "[camera]\nposition = [0.0, 4.0, 10.0]\n\n[shadow]\nbias = nan\n");
    let run = render(&scratch, &scene, &[]);
    assert_bad_input(&run, &["nan.toml", "bias"]);
    scratch.assert_no_output("out.png");
}

#[test]
fn too_many_lights_names_the_file() {
    let scratch = Scratch::new();
    let mut text = String::from("[camera]\nposition = [0.0, 4.0, 10.0]\n");
    for _ in 0..5 {
        text.push_str("\n[[light]]\nkind = \"spot\"\nposition = [0.0, 9.0, 0.0]\nfov_deg = 50.0\n");
    }
    let scene = scratch.scene("five_lights.toml", &text);
    let run = render(&scratch, &scene, &[]);
    assert_bad_input(&run, &["five_lights.toml", "at most 4"]);
    scratch.assert_no_output("out.png");
}

#[test]
fn missing_texture_names_the_texture() {
    render_rejected(&fixture("missing_texture.toml"), &[], &["does_not_exist.png", "missing_texture.mtl"]);
}

#[test]
fn missing_obj_names_the_mesh_file() {
    render_rejected(&fixture("missing_mesh.toml"), &[], &["no_such_mesh.obj"]);
}

#[test]
fn malformed_obj_names_the_mesh_file() {
    let scratch = Scratch::new();
    let obj = repo_path("tests/data/obj/malformed.obj");
    let scene = scratch.scene(
        "malformed_mesh.toml",
        &format!(
            "[camera]\nposition = [0.0, 4.0, 10.0]\n\n[[object]]\nmesh = {:?}\n",
            obj.display().to_string()
        ),
    );
    let run = render(&scratch, &scene, &[]);
    assert_bad_input(&run, &["malformed.obj"]);
    scratch.assert_no_output("out.png");
}

#[test]
fn unknown_primitive_names_the_mesh() {
    let scratch = Scratch::new();
    let scene =
        scratch.scene("blob.toml", "[camera]\nposition = [0.0, 4.0, 10.0]\n\n[[object]]\nmesh = \"blob\"\n");
    let run = render(&scratch, &scene, &[]);
    assert_bad_input(&run, &["blob.toml", "blob", "plane"]);
    scratch.assert_no_output("out.png");
}

#[test]
fn absurd_scale_names_file_line_and_key() {
    // A scale of -1e38 rendered an empty frame without a word.
    let scratch = Scratch::new();
    let text = "[camera]\nposition = [0.0, 4.0, 10.0]\n\n[[object]]\nmesh = \"cube\"\nscale = -1e38\n";
    let scene = scratch.scene("huge.toml", text);
    let run = render(&scratch, &scene, &[]);
    assert_bad_input(&run, &["huge.toml:6:", "object.0.scale"]);
    scratch.assert_no_output("out.png");
}

#[cfg(unix)]
#[test]
fn scene_that_is_a_device_is_rejected_at_once() {
    // Reading /dev/zero whole never ended.
    render_rejected("/dev/zero", &[], &["/dev/zero", "not a regular file"]);
}

#[test]
fn scene_that_shows_nothing_renders_with_a_warning() {
    let scratch = Scratch::new();
    let text =
        "[camera]\nposition = [0.0, 4.0, 10.0]\ntarget = [0.0, 100.0, 10.0]\n\n[[object]]\nmesh = \"cube\"\n";
    let scene = scratch.scene("away.toml", text);
    let run = render(&scratch, &scene, &[]);
    assert_eq!(run.code, Some(0), "a legal scene renders:\n{run}");
    let lines: Vec<&str> = run.stderr.lines().collect();
    assert_eq!(lines.len(), 1, "one warning:\n{run}");
    assert!(lines[0].starts_with("shadowlab: warning: "), "{run}");
    assert!(
        lines[0].contains("away.toml") && lines[0].contains("no object is in the camera's view"),
        "{run}"
    );
    assert!(scratch.path("out.png").exists(), "{run}");
}

// ---------------------------------------------------------------------------------------------
// Bad input: --set overrides.

#[test]
fn set_unknown_technique_lists_the_allowed_values() {
    render_rejected(
        &contact(),
        &["--set", "technique=blurry"],
        &["technique", "blurry", "hard", "pcf", "pcss"],
    );
}

#[test]
fn set_samples_zero_names_key_and_range() {
    render_rejected(&contact(), &["--set", "samples=0"], &["samples", "1..=128"]);
}

#[test]
fn set_samples_500_names_key_and_range() {
    render_rejected(&contact(), &["--set", "samples=500"], &["samples", "1..=128"]);
}

#[test]
fn set_bias_nan_names_bias() {
    render_rejected(&contact(), &["--set", "bias=nan"], &["bias"]);
}

#[test]
fn set_camera_fov_inf_names_the_key() {
    render_rejected(&contact(), &["--set", "camera.fov_deg=inf"], &["camera.fov_deg"]);
}

#[test]
fn set_missing_light_names_light_7() {
    render_rejected(&contact(), &["--set", "light.7.width=1"], &["light.7", "light 7"]);
}

#[test]
fn set_unknown_shadow_key_names_it() {
    render_rejected(&contact(), &["--set", "foo=1"], &["foo"]);
}

#[test]
fn set_unknown_section_names_the_key() {
    render_rejected(&contact(), &["--set", "lamp.0.width=1"], &["lamp.0.width"]);
}

#[test]
fn set_shadow_map_size_100_names_the_key() {
    render_rejected(
        &contact(),
        &["--set", "light.0.shadow_map_size=100"],
        &["light.0.shadow_map_size", "256..=8192"],
    );
}

#[test]
fn set_object_mesh_to_missing_obj_names_the_file() {
    render_rejected(&contact(), &["--set", "object.0.mesh=no_such_mesh.obj"], &["no_such_mesh.obj"]);
}

#[test]
fn set_without_equals_sign_is_a_usage_error() {
    render_usage_error(&["--set", "technique"], &["--set", "technique"]);
}

// ---------------------------------------------------------------------------------------------
// Bad input: command-line values.

#[test]
fn unknown_view_lists_the_views() {
    render_usage_error(
        &["--view", "sideways"],
        &["--view", "sideways", "shadow-map", "blocker-radius", "texel-density", "cascade-index"],
    );
}

#[test]
fn size_with_a_zero_side_is_rejected() {
    render_usage_error(&["--size", "0x10"], &["--size", "0x10"]);
}

#[test]
fn size_that_is_not_a_size_is_rejected() {
    render_usage_error(&["--size", "big"], &["--size", "big"]);
}

#[test]
fn time_nan_is_rejected() {
    render_usage_error(&["--time", "nan"], &["--time", "nan"]);
}

#[test]
fn negative_light_index_is_rejected() {
    render_usage_error(&["--light", "-1"], &["-1"]);
}

#[test]
fn probe_pixel_without_comma_is_rejected() {
    let run = shadowlab(&["probe", "--scene", &contact(), "--size", "32x18", "--pixel", "5"]);
    assert_usage_error(&run, &["--pixel", "5"]);
}

#[test]
fn probe_pixel_outside_the_image_is_rejected() {
    let run =
        shadowlab(&["probe", "--scene", &contact(), "--size", "32x18", "--pixel", "32,5", "--no-reference"]);
    assert_bad_input(&run, &["32,5", "32x18"]);
}

#[test]
fn probe_with_a_bad_override_prints_no_json() {
    let run = shadowlab(&[
        "probe",
        "--scene",
        &contact(),
        "--size",
        "32x18",
        "--pixel",
        "1,1",
        "--set",
        "samples=0",
    ]);
    assert_bad_input(&run, &["samples"]);
}

#[test]
fn out_path_not_png_is_rejected() {
    let scratch = Scratch::new();
    let out = scratch.arg("x.jpg");
    let run = shadowlab(&["render", "--scene", &contact(), "--size", "32x18", "--out", &out]);
    assert_bad_input(&run, &["x.jpg", ".png"]);
    scratch.assert_no_output("x.jpg");
}

#[test]
fn out_path_without_extension_is_rejected() {
    let scratch = Scratch::new();
    let out = scratch.arg("picture");
    let run = shadowlab(&["render", "--scene", &contact(), "--size", "32x18", "--out", &out]);
    assert_bad_input(&run, &["picture", ".png"]);
    scratch.assert_no_output("picture");
}

#[test]
fn out_folder_missing_is_rejected() {
    let scratch = Scratch::new();
    let out = scratch.path("missing").join("out.png");
    let run =
        shadowlab(&["render", "--scene", &contact(), "--size", "32x18", "--out", &out.display().to_string()]);
    assert_bad_input(&run, &["missing", "does not exist"]);
    assert!(!out.exists());
    assert!(!scratch.path("missing").exists(), "the folder must not be created");
    assert_eq!(scratch.stray_temp_files(), Vec::<String>::new());
}

#[test]
fn light_index_out_of_range_is_rejected() {
    render_rejected(&contact(), &["--light", "3"], &["--light 3", "contact.toml", "1 light"]);
}

#[test]
fn debug_view_of_a_scene_without_lights_is_rejected() {
    render_rejected(
        &fixture("minimal.toml"),
        &["--view", "shadow-map"],
        &["minimal.toml", "no lights", "shadow-map"],
    );
}

#[test]
fn bench_missing_scene_names_the_file() {
    let scratch = Scratch::new();
    let scene = scratch.arg("no_bench_scene.toml");
    let run = shadowlab(&["bench", "--scene", &scene, "--frames", "1", "--size", "32x18"]);
    assert_bad_input(&run, &["no_bench_scene.toml"]);
}

#[test]
fn bench_zero_frames_is_rejected() {
    let run = shadowlab(&["bench", "--frames", "0"]);
    assert_usage_error(&run, &["--frames", "0"]);
}

#[test]
fn no_arguments_without_a_display_exits_2_with_one_line() {
    // No arguments opens the app; with no display it must say so and point at the commands.
    let run = common::run(common::shadowlab_command().env_remove("DISPLAY").env_remove("WAYLAND_DISPLAY"));
    assert_eq!(run.code, Some(2), "{run}");
    assert!(!run.stderr.contains("panicked"), "{run}");
    let lines: Vec<&str> = run.stderr.lines().collect();
    assert_eq!(lines.len(), 1, "one line on stderr:\n{run}");
    assert!(lines[0].starts_with("shadowlab: no display"), "{run}");
    assert!(lines[0].contains("render"), "the message points at the commands:\n{run}");
}

// ---------------------------------------------------------------------------------------------
// Good input.

#[test]
fn render_final_writes_a_png_of_the_requested_size() {
    let (image, stdout) = render_view("final", &[]);
    assert_eq!(image.dimensions(), (160, 90));
    assert!(stdout.contains("160x90"), "{stdout}");
    let first = image.get_pixel(0, 0);
    assert!(image.pixels().any(|p| p != first), "the final image should not be one flat colour");
}

#[test]
fn render_visibility_writes_a_png_of_the_requested_size() {
    let (image, stdout) = render_view("visibility", &[]);
    assert_eq!(image.dimensions(), (160, 90));
    assert!(stdout.contains("visibility"), "{stdout}");
    // Surfaces are grey levels; contact.toml has both lit and shadowed surfaces in view.
    let greys: Vec<u8> = image.pixels().filter(|p| p[0] == p[1] && p[1] == p[2]).map(|p| p[0]).collect();
    assert!(greys.iter().any(|&g| g > 200), "some surface is lit");
    assert!(greys.iter().any(|&g| g < 50), "some surface is shadowed");
}

#[test]
fn render_shadow_map_is_the_size_of_the_light_map() {
    let scene = shadowlab::scene::load_scene(&repo_path("assets/scenes/contact.toml"), &[])
        .expect("contact.toml loads");
    let map = scene.lights[0].shadow_map_size;
    let (image, stdout) = render_view("shadow-map", &[]);
    assert_eq!(image.dimensions(), (map, map), "the shadow-map view ignores --size");
    let (near, far) = legend_range(&stdout, "light-space depth");
    assert!(0.0 < near && near <= far, "{stdout}");
}

#[test]
fn render_shadow_map_follows_a_shadow_map_size_override() {
    let (image, _) = render_view("shadow-map", &["--set", "light.0.shadow_map_size=512"]);
    assert_eq!(image.dimensions(), (512, 512));
}

#[test]
fn render_blocker_radius_prints_a_legend_in_texels() {
    let (image, stdout) = render_view("blocker-radius", &[]);
    assert_eq!(image.dimensions(), (160, 90));
    let line = stdout.lines().find(|l| l.starts_with("blocker-search radius")).unwrap_or_default();
    assert!(line.contains("texels"), "legend in texels:\n{stdout}");
    let (min, max) = legend_range(&stdout, "blocker-search radius");
    assert!(min.is_finite() && max.is_finite() && min <= max && max > 0.0, "{stdout}");
}

#[test]
fn render_penumbra_and_blockers_views_print_legends() {
    let (image, stdout) = render_view("penumbra", &[]);
    assert_eq!(image.dimensions(), (160, 90));
    let (min, max) = legend_range(&stdout, "penumbra width");
    assert!(min <= max, "{stdout}");
    let (image, stdout) = render_view("blockers", &["--set", "blocker_samples=8"]);
    assert_eq!(image.dimensions(), (160, 90));
    let (min, max) = legend_range(&stdout, "blockers found");
    assert!(min <= max && max <= 8.0, "at most blocker_samples blockers:\n{stdout}");
}

#[test]
fn render_reference_view_writes_a_png() {
    let (image, stdout) = render_view("reference", &["--set", "reference_samples=8"]);
    assert_eq!(image.dimensions(), (160, 90));
    assert!(stdout.contains("8 hard shadows"), "{stdout}");
}

#[test]
fn render_error_view_prints_the_mean_absolute_error() {
    let (image, stdout) = render_view("error", &["--set", "reference_samples=16"]);
    assert_eq!(image.dimensions(), (160, 90));
    let line = stdout
        .lines()
        .find(|l| l.starts_with("mean absolute error:"))
        .unwrap_or_else(|| panic!("no mean absolute error in:\n{stdout}"));
    let mae: f64 =
        line["mean absolute error:".len()..].trim().parse().unwrap_or_else(|e| panic!("{line:?}: {e}"));
    assert!((0.0..1.0).contains(&mae), "{line}");
}

/// The three numbers of the texel-density legend's second line, `on screen: MIN .. MAX, median M`.
fn densities_on_screen(stdout: &str) -> [f64; 3] {
    let line = stdout
        .lines()
        .find_map(|l| l.strip_prefix("on screen: "))
        .unwrap_or_else(|| panic!("no `on screen:` line in:\n{stdout}"));
    let numbers: Vec<f64> = line.split([' ', ',']).filter_map(|w| w.parse().ok()).collect::<Vec<_>>();
    let [min, max, median] = numbers[..] else { panic!("three numbers in {line:?}") };
    [min, median, max]
}

/// The texel-density view of the spot-lit contact scene: its legend gives the fixed log scale,
/// its unit and where 1 lies; the floor beyond the spot's cone is grey (no texels there); and a
/// map with four times the texels on a side has four times the density at every pixel.
#[test]
fn render_texel_density_prints_its_scale_and_follows_the_map_size() {
    let (image, stdout) = render_view("texel-density", &["--set", "light.0.shadow_map_size=512"]);
    assert_eq!(image.dimensions(), (160, 90));
    assert_eq!(legend_range(&stdout, "texel density"), (0.0625, 16.0), "{stdout}");
    let scale = stdout.lines().find(|l| l.starts_with("texel density")).unwrap_or_default();
    assert!(scale.contains("map texels per pixel") && scale.contains("red < 1 blocky"), "{stdout}");
    let off_the_map = image.pixels().filter(|p| p.0 == [120, 120, 120, 255]).count();
    assert!(off_the_map > 100, "the floor beyond the cone is grey: {off_the_map} pixels");
    let [min, median, max] = densities_on_screen(&stdout);
    assert!(0.0 < min && min <= median && median <= max, "{stdout}");
    let (_, larger) = render_view("texel-density", &["--set", "light.0.shadow_map_size=2048"]);
    let [_, larger_median, _] = densities_on_screen(&larger);
    assert!((larger_median / median - 4.0).abs() < 0.01, "{median} then {larger_median}");
}

/// A floor seen straight down by an orthographic camera, under a directional light shining
/// straight down: a texel is 2 * extent / map size world units wide and a pixel the camera's
/// height / the image's height, so the density is one number over the whole floor, the box's
/// top too: 1024 / 40 * (10.8 / 54) = 5.12 texels per pixel.
#[test]
fn render_texel_density_of_a_floor_seen_head_on_under_a_directional_light_is_one_number() {
    let scratch = Scratch::new();
    let scene = scratch.scene(
        "head_on.toml",
        "[camera]\nprojection = \"orthographic\"\nposition = [0.0, 40.0, 0.0]\ntarget = [0.0, 0.0, 0.0]\n\
         up = [0.0, 0.0, -1.0]\nheight = 10.8\nnear = 1.0\nfar = 100.0\n\n\
         [[object]]\nmesh = \"plane\"\nscale = [80.0, 1.0, 80.0]\n\n\
         [[object]]\nmesh = \"cube\"\ntranslate = [0.0, 2.0, 0.0]\nscale = [4.0, 4.0, 4.0]\n\n\
         [[light]]\nkind = \"directional\"\nposition = [0.0, 50.0, 0.0]\ntarget = [0.0, 0.0, 0.0]\n\
         up = [0.0, 0.0, -1.0]\nshadow_map_size = 1024\nextent = 20.0\nnear = 1.0\nfar = 100.0\n",
    );
    let run = render(&scratch, &scene, &["--view", "texel-density", "--size", "96x54"]);
    assert_eq!(run.code, Some(0), "{run}");
    assert!(run.stderr.is_empty(), "{run}");
    let expected = 1024.0 / 40.0 * (10.8 / 54.0);
    for density in densities_on_screen(&run.stdout) {
        assert!((density - expected).abs() < 0.002, "{density}, expected {expected}:\n{run}");
    }
    let image = decode_png(&scratch.path("out.png"));
    let first = *image.get_pixel(0, 0);
    assert!(image.pixels().all(|p| *p == first), "one colour over the floor and the box");
}

/// Which colour of the cascade-index palette a pixel shows (each is darkened by the surface's
/// lighting, to 0.65 at most; 0.6 leaves room for rounding), None for any other colour.
fn palette_index(pixel: image::Rgba<u8>) -> Option<usize> {
    let p = [0, 1, 2].map(|c| f32::from(pixel[c]));
    shadowlab::views::cascade_index::PALETTE.iter().position(|(colour, _)| {
        let c = colour.map(f32::from);
        let shade = (0..3).map(|k| p[k] * c[k]).sum::<f32>() / (0..3).map(|k| c[k] * c[k]).sum::<f32>();
        (0.6..=1.0).contains(&shade) && (0..3).all(|k| (p[k] - c[k] * shade).abs() <= 2.0)
    })
}

/// The cascade-index view of the avenue under a sun with four cascades: the legend names the
/// four colours, all four show on screen (the sharpest at the camera's feet) and no others.
#[test]
fn render_cascade_index_of_the_avenue_shows_four_cascades() {
    let scratch = Scratch::new();
    let scene = repo_path("assets/scenes/sun_avenue.toml").display().to_string();
    let run = render(&scratch, &scene, &["--view", "cascade-index", "--size", "320x180"]);
    assert_eq!(run.code, Some(0), "{run}");
    assert!(run.stderr.is_empty(), "{run}");
    assert!(run.stdout.contains("cascade index: which of the light's 4 shadow maps"), "{run}");
    let key = "orange: cascade 1, sky blue: cascade 2, green: cascade 3, yellow: cascade 4\n";
    assert!(run.stdout.contains(key), "{run}");
    let image = decode_png(&scratch.path("out.png"));
    let mut pixels = [0usize; 6];
    for p in image.pixels() {
        if let Some(k) = palette_index(*p) {
            pixels[k] += 1;
        }
    }
    assert!(pixels[..4].iter().all(|&n| n >= 20), "pixels per colour: {pixels:?}");
    assert_eq!(pixels[4..], [0, 0], "only the sun's four cascades: {pixels:?}");
    let (w, h) = image.dimensions();
    assert_eq!(palette_index(*image.get_pixel(w / 2, h - 1)), Some(0), "cascade 1 at the camera's feet");
}

#[test]
fn render_light_index_selects_the_light() {
    let scratch = Scratch::new();
    let scene = repo_path("assets/scenes/multi_light.toml").display().to_string();
    let run = render(&scratch, &scene, &["--view", "visibility", "--light", "1"]);
    assert_eq!(run.code, Some(0), "{run}");
    assert!(run.stdout.contains("light 1"), "{run}");
    assert_eq!(decode_png(&scratch.path("out.png")).dimensions(), (32, 18));
}

const LIGHT_KEYS: [&str; 15] = [
    "shadow_map_uv",
    "receiver_depth_ndc",
    "receiver_depth_linear",
    "stored_depth_ndc",
    "bias_ndc",
    "blocker_search_radius_uv",
    "blocker_search_radius_texels",
    "blockers_found",
    "avg_blocker_depth_linear",
    "penumbra_width_world",
    "filter_radius_uv",
    "filter_radius_texels",
    "visibility_gpu",
    "visibility_twin",
    "visibility_reference",
];

#[track_caller]
fn assert_light_report(light: &Value) {
    for key in LIGHT_KEYS {
        assert!(light.get(key).is_some(), "probe light report lacks `{key}`:\n{light:#}");
    }
    let number =
        |key: &str| light[key].as_f64().unwrap_or_else(|| panic!("`{key}` is not a number:\n{light:#}"));
    let gpu = number("visibility_gpu");
    let twin = number("visibility_twin");
    assert!((0.0..=1.0).contains(&gpu), "{light:#}");
    assert!((gpu - twin).abs() <= 1e-3, "GPU and CPU twin disagree: {gpu} vs {twin}");
    let uv = light["shadow_map_uv"].as_array().expect("shadow_map_uv is an array");
    assert_eq!(uv.len(), 2);
    assert!(number("receiver_depth_linear") > 0.0, "{light:#}");
}

#[test]
fn probe_at_the_centre_reports_a_hit_with_every_light_key() {
    let json = probe_json(&["--pixel", "80,45", "--set", "reference_samples=8"]);
    assert_eq!(json["hit"], Value::Bool(true), "{json:#}");
    assert_eq!(json["pixel"], serde_json::json!([80, 45]));
    assert!(json["object"].is_string(), "{json:#}");
    let lights = json["lights"].as_array().expect("lights is an array");
    assert_eq!(lights.len(), 1, "contact.toml has one light");
    assert_light_report(&lights[0]);
    let reference = lights[0]["visibility_reference"].as_f64().expect("visibility_reference is a number");
    assert!((0.0..=1.0).contains(&reference), "{reference}");
}

/// A point light's probe says which cube face the pixel read, and the distances it compared:
/// a floor pixel in the torus's shadow reads the -X face (the torus hangs to the lamp's -X side
/// and below it), where the stored distance is the torus's, nearer than the floor's.
#[test]
fn probe_of_a_lamp_names_the_cube_face_and_compares_distances() {
    let scene = repo_path("assets/scenes/point_lamp.toml").display().to_string();
    let run = shadowlab(&[
        "probe",
        "--scene",
        &scene,
        "--pixel",
        "300,360",
        "--no-reference",
        "--set",
        "technique=hard",
    ]);
    assert_eq!(run.code, Some(0), "{run}");
    let json: Value = serde_json::from_str(&run.stdout).expect("JSON");
    let light = &json["lights"][0];
    assert_light_report(light);
    assert_eq!(light["cube_face"], "-X", "{light:#}");
    assert_eq!(light["shadow_view"], 1, "the -X face is the lamp's second view: {light:#}");
    let number = |key: &str| light[key].as_f64().unwrap_or_else(|| panic!("{key}: {light:#}"));
    let lamp = glam::Vec3::new(0.0, 6.5, 0.0);
    let at: Vec<f32> = (0..3).map(|i| json["world_position"][i].as_f64().expect("position") as f32).collect();
    let distance = (glam::Vec3::from_slice(&at) - lamp).length();
    assert!((number("receiver_depth_linear") - f64::from(distance)).abs() < 1e-3, "{light:#}");
    assert!(number("stored_depth_linear") < number("receiver_depth_linear") - 1.0, "{light:#}");
    assert_eq!(number("visibility_gpu"), 0.0);
    assert_eq!(number("visibility_twin"), 0.0);
}

/// Far down the avenue the sun's sharper cascades do not hold the crate: the probe says which
/// cascade it read, its texel, and where the point fell off each sharper one.
#[test]
fn probe_of_a_cascaded_sun_says_which_cascade_and_why() {
    let scene = repo_path("assets/scenes/sun_avenue.toml").display().to_string();
    let probe = |pixel: &str| {
        let run = shadowlab(&["probe", "--scene", &scene, "--pixel", pixel, "--no-reference"]);
        assert_eq!(run.code, Some(0), "{run}");
        let json: Value = serde_json::from_str(&run.stdout).expect("JSON");
        assert_light_report(&json["lights"][0]);
        json
    };
    let near = probe("150,480");
    let cascade = &near["lights"][0]["cascade"];
    assert_eq!((cascade["index"].as_u64(), cascade["count"].as_u64()), (Some(0), Some(4)), "{near:#}");
    assert_eq!(cascade["uv_in_sharper"], serde_json::json!([]));
    let far = probe("478,228");
    assert_eq!(far["object"], "far crate", "{far:#}");
    let light = &far["lights"][0];
    let cascade = &light["cascade"];
    let index = cascade["index"].as_u64().expect("index");
    assert!(index >= 1, "{light:#}");
    assert_eq!(light["shadow_view"].as_u64(), Some(index), "the sun's views are its cascades");
    let misses = cascade["uv_in_sharper"].as_array().expect("misses");
    assert_eq!(misses.len() as u64, index);
    for uv in misses {
        let (u, v) = (uv[0].as_f64().expect("u"), uv[1].as_f64().expect("v"));
        let border = 4.0 / 1024.0;
        assert!(!(border..=1.0 - border).contains(&u) || !(border..=1.0 - border).contains(&v), "{uv}");
    }
    let width = |c: &Value| c["width_world"].as_f64().expect("width");
    assert!(width(cascade) > 2.0 * width(&near["lights"][0]["cascade"]), "farther cascades cover more");
    let texel = cascade["texel_world"].as_f64().expect("texel");
    assert!((texel - width(cascade) / 1024.0).abs() < 1e-6);
    assert!(cascade.get("view_depth_world").is_none(), "by map: {cascade:#}");
    // By interval the crate reads the cascade whose slice holds its depth along the view axis,
    // though a sharper map may hold it: the probe gives the depth and the slice, no misses.
    let run = shadowlab(&[
        "probe",
        "--scene",
        &scene,
        "--pixel",
        "478,228",
        "--no-reference",
        "--set",
        "light.0.cascade_selection=interval",
    ]);
    assert_eq!(run.code, Some(0), "{run}");
    let json: Value = serde_json::from_str(&run.stdout).expect("JSON");
    let cascade = &json["lights"][0]["cascade"];
    let depth = cascade["view_depth_world"].as_f64().expect("depth");
    let slice: Vec<f64> = (0..2).map(|i| cascade["slice_world"][i].as_f64().expect("slice")).collect();
    assert!(slice[0] <= depth && depth < slice[1], "{cascade:#}");
    assert_eq!(cascade["uv_in_sharper"], serde_json::json!([]));
    assert!(cascade["index"].as_u64().expect("index") > index, "the crate lies past its map's slice");
}

#[test]
fn probe_without_reference_leaves_the_reference_null() {
    let json = probe_json(&["--pixel", "80,45", "--no-reference"]);
    assert_eq!(json["hit"], Value::Bool(true), "{json:#}");
    let lights = json["lights"].as_array().expect("lights is an array");
    assert_eq!(lights.len(), 1);
    assert_light_report(&lights[0]);
    assert!(lights[0]["visibility_reference"].is_null());
}

#[test]
fn probe_at_the_sky_reports_no_hit() {
    let json = probe_json(&["--pixel", "0,0", "--no-reference", "--set", "camera.target=[0,100,0]"]);
    assert_eq!(json["hit"], Value::Bool(false), "{json:#}");
    assert_eq!(json["lights"], serde_json::json!([]));
    assert!(json.get("object").is_none(), "{json:#}");
}

#[test]
fn bench_json_has_a_row_per_technique_with_every_frame_and_the_adapter() {
    let scene = contact();
    let run = shadowlab(&["bench", "--scene", &scene, "--frames", "2", "--size", "160x90", "--json"]);
    assert_eq!(run.code, Some(0), "{run}");
    let json: Value =
        serde_json::from_str(&run.stdout).unwrap_or_else(|e| panic!("bench prints JSON ({e}):\n{run}"));
    let adapter = json["adapter"].as_str().expect("adapter is a string");
    assert!(!adapter.trim().is_empty());
    assert_eq!(json["frames"], serde_json::json!(2));
    assert_eq!(json["size"], serde_json::json!([160, 90]));
    assert_eq!(json["animated"], Value::Bool(true));
    let rows = json["rows"].as_array().expect("rows is an array");
    let labels: Vec<&str> = rows.iter().filter_map(|r| r["technique"].as_str()).collect();
    // contact.toml filters with 32 + 32 taps: no extra row for the scene's own counts; its
    // adaptive bias gets two rows with the receiver-plane bias; its spot light two as a lamp.
    assert_eq!(
        labels,
        [
            "none",
            "hard",
            "pcf 16",
            "pcf 32",
            "pcss 16+16",
            "pcss 32+32",
            "vsm",
            "vssm",
            "pcf 32 plane-bias",
            "pcss 32+32 plane-bias",
            "point-light hard",
            "point-light pcf 32"
        ],
        "{json:#}"
    );
    for row in rows {
        let plane = row["technique"].as_str().is_some_and(|l| l.ends_with("plane-bias"));
        let mode = if plane { "receiver_plane" } else { "adaptive" };
        assert_eq!(row["bias_mode"], Value::String(mode.into()), "{row}");
        for key in ["median_frame_ms", "min_frame_ms"] {
            let ms = row[key].as_f64().unwrap_or_else(|| panic!("`{key}` is not a number: {row}"));
            assert!(ms > 0.0 && ms.is_finite(), "{row}");
        }
        assert!(row["min_frame_ms"].as_f64() <= row["median_frame_ms"].as_f64(), "{row}");
        for key in ["shadow_pass_ms", "camera_pass_ms"] {
            let value = &row[key];
            assert!(value.is_null() || value.as_f64().is_some_and(|ms| ms >= 0.0), "{row}");
        }
        // Every timed frame, each 1/30 s of scene time after the one before.
        let frames = row["frames"].as_array().expect("frames is an array");
        assert_eq!(frames.len(), 2, "{row}");
        let t0 = frames[0]["time_s"].as_f64().expect("time_s");
        let t1 = frames[1]["time_s"].as_f64().expect("time_s");
        assert!((t1 - t0 - 1.0 / 30.0).abs() < 1e-4, "{row}");
    }
}

#[test]
fn bench_defaults_to_the_homework_workload_from_any_folder() {
    let scratch = Scratch::new();
    let run = common::run(
        common::shadowlab_command()
            .current_dir(scratch.dir.path())
            .args(["bench", "--only", "none", "--frames", "1", "--size", "64x36", "--json"]),
    );
    assert_eq!(run.code, Some(0), "{run}");
    let json: Value = serde_json::from_str(&run.stdout).unwrap_or_else(|e| panic!("JSON ({e}):\n{run}"));
    assert!(json["scene"].as_str().is_some_and(|s| s.ends_with("homework.toml")), "{json:#}");
    let labels: Vec<&str> =
        json["rows"].as_array().expect("rows").iter().filter_map(|r| r["technique"].as_str()).collect();
    assert_eq!(labels, ["none"]);
}

#[test]
fn bench_takes_overrides_a_fixed_time_and_picks_rows() {
    let run = shadowlab(&[
        "bench",
        "--set",
        "light.0.width=2",
        "--only",
        "pcss 50+50",
        "--time",
        "2",
        "--still",
        "--frames",
        "2",
        "--size",
        "64x36",
        "--json",
    ]);
    assert_eq!(run.code, Some(0), "{run}");
    let json: Value = serde_json::from_str(&run.stdout).unwrap_or_else(|e| panic!("JSON ({e}):\n{run}"));
    assert_eq!(json["overrides"], serde_json::json!(["light.0.width=2"]));
    assert_eq!(json["animated"], Value::Bool(false));
    let rows = json["rows"].as_array().expect("rows");
    assert_eq!(rows.len(), 1, "{json:#}");
    assert_eq!(rows[0]["technique"], "pcss 50+50");
    for frame in rows[0]["frames"].as_array().expect("frames") {
        assert_eq!(frame["time_s"].as_f64(), Some(2.0), "{frame}");
    }
}

/// A sun's cascades cost their maps: the homework's sun gets rows with four cascades, and a
/// scene whose sun has cascades gets rows with one map to hold them against.
#[test]
fn bench_holds_four_cascades_against_one_map() {
    let labels = |args: &[&str]| {
        let run = shadowlab(args);
        assert_eq!(run.code, Some(0), "{run}");
        let json: Value = serde_json::from_str(&run.stdout).unwrap_or_else(|e| panic!("JSON ({e}):\n{run}"));
        let rows = json["rows"].as_array().expect("rows").clone();
        for row in &rows {
            assert!(row["median_frame_ms"].as_f64().is_some_and(|ms| ms > 0.0), "{row}");
        }
        rows.iter().filter_map(|r| r["technique"].as_str().map(String::from)).collect::<Vec<_>>()
    };
    let quick = ["--frames", "1", "--size", "64x36", "--json"];
    assert_eq!(
        labels(&[&["bench", "--only", "4-cascade"][..], &quick].concat()),
        ["4-cascade hard", "4-cascade pcf 50"]
    );
    let avenue = common::repo_path("assets/scenes/sun_avenue.toml");
    let avenue = avenue.to_str().expect("path");
    assert_eq!(
        labels(&[&["bench", "--scene", avenue, "--only", "one-map"][..], &quick].concat()),
        ["one-map hard", "one-map pcf 16"]
    );
}

#[test]
fn bench_unknown_row_and_bad_override_are_refused() {
    let run = shadowlab(&["bench", "--only", "blurry", "--frames", "1"]);
    assert_bad_input(&run, &["--only blurry", "no such row", "pcss 50+50"]);
    let run = shadowlab(&["bench", "--set", "light.7.width=2", "--frames", "1"]);
    assert_bad_input(&run, &["light.7"]);
}

#[test]
fn bench_app_window_drives_the_real_window() {
    let _turn = app_bench_turn();
    // A real window needs a display: Xvfb stands in for one (the CI script installs it).
    let run = common::run_in_window(&["bench", "--app", "--window", "--seconds", "0.5", "--json"]);
    assert_eq!(run.code, Some(0), "{run}");
    let json: Value = serde_json::from_str(&run.stdout).unwrap_or_else(|e| panic!("JSON ({e}):\n{run}"));
    assert!(json["painter"].as_str().is_some_and(|p| p.ends_with("(window)")), "{json:#}");
    let phases = json["phases"].as_array().expect("phases");
    assert_eq!(phases.len(), 2, "{json:#}");
    // Each phase moved what it drives (the slider's width, the light) and the views showed it:
    // the bench fails rather than report a drag that missed.
    for (phase, moved) in phases.iter().zip(["light 0 width ", "light 0 position "]) {
        assert!(phase["ui_frames"].as_u64().is_some_and(|n| n > 0), "{phase}");
        assert!(phase["view_refreshes"].as_u64().is_some_and(|n| n > 0), "{phase}");
        assert!(
            phase["moved"].as_str().is_some_and(|m| m.starts_with(moved) && m.contains(" -> ")),
            "{phase}"
        );
        assert!(phase["release_to_full_quality_s"].as_f64().is_some_and(|s| s >= 0.0), "{phase}");
    }
}

/// The diagrams' own timing: every diagram in both languages, as JSON.
#[test]
fn bench_diagrams_times_every_diagram_in_both_languages() {
    let run = shadowlab(&["bench", "--diagrams", "--frames", "2", "--size", "320x180", "--json"]);
    assert_eq!(run.code, Some(0), "{run}");
    let json: Value =
        serde_json::from_str(&run.stdout).unwrap_or_else(|e| panic!("bench prints JSON ({e}):\n{run}"));
    assert_eq!(json["size"], serde_json::json!([320, 180]));
    let rows = json["rows"].as_array().expect("rows");
    let ids = ["two-pass", "acne-bias", "pcf-kernel", "pcss", "multi-light", "chebyshev", "shadow-views"];
    let expected: Vec<(&str, &str)> = ids.iter().flat_map(|id| [(*id, "en"), (*id, "zh")]).collect();
    let got: Vec<(&str, &str)> = rows
        .iter()
        .map(|r| (r["diagram"].as_str().unwrap_or(""), r["lang"].as_str().unwrap_or("")))
        .collect();
    assert_eq!(got, expected, "{json:#}");
    for r in rows {
        let ms = |key: &str| r[key].as_f64().unwrap_or(-1.0);
        assert!(ms("drag_min_ms") > 0.0 && ms("drag_median_ms") >= ms("drag_min_ms"), "{r}");
        assert!(ms("still_median_ms") > 0.0, "{r}");
    }
    let table = shadowlab(&["bench", "--diagrams", "--frames", "1", "--size", "320x180"]);
    assert_eq!(table.code, Some(0), "{table}");
    assert!(table.stdout.contains("drag median ms") && table.stdout.contains("chebyshev"), "{table}");
    let both = shadowlab(&["bench", "--diagrams", "--app"]);
    assert_eq!(both.code, Some(2), "{both}");
}

#[test]
fn bench_app_window_without_a_display_says_so() {
    let run =
        common::run(common::shadowlab_command().env_remove("DISPLAY").env_remove("WAYLAND_DISPLAY").args([
            "bench",
            "--app",
            "--window",
            "--seconds",
            "0.5",
        ]));
    assert_bad_input(&run, &["no display", "xvfb-run"]);
}

#[test]
fn bench_app_drives_the_app_and_reports_what_a_student_feels() {
    let _turn = app_bench_turn();
    let run = shadowlab(&["bench", "--app", "--seconds", "0.5", "--json"]);
    assert_eq!(run.code, Some(0), "{run}");
    let json: Value = serde_json::from_str(&run.stdout).unwrap_or_else(|e| panic!("JSON ({e}):\n{run}"));
    assert_eq!(json["lesson"], "pcss");
    let phases = json["phases"].as_array().expect("phases");
    assert_eq!(phases.len(), 2, "{json:#}");
    for phase in phases {
        assert!(phase["ui_frames"].as_u64().is_some_and(|n| n > 0), "{phase}");
        assert!(phase["view_refreshes"].as_u64().is_some_and(|n| n > 0), "{phase}");
        for key in
            ["ui_frames_per_s", "view_refreshes_per_s", "release_to_full_quality_s", "slowest_ui_frame_ms"]
        {
            assert!(phase[key].as_f64().is_some_and(|v| v >= 0.0 && v.is_finite()), "{key}: {phase}");
        }
    }
}

/// A VSM probe reports the moments it read, Chebyshev's bound (the visibility) and the true lit
/// share of the same footprint, which the bound never falls below.
#[test]
fn a_vsm_probe_reports_the_bound_and_the_true_share() {
    let mut shadowed = 0;
    for pixel in ["108,33", "70,40", "80,45", "95,50", "110,35"] {
        let json = probe_json(&[
            "--pixel",
            pixel,
            "--no-reference",
            "--set",
            "technique=vsm",
            "--set",
            "radius_texels=8",
        ]);
        let light = &json["lights"][0];
        let vsm = &light["vsm"];
        let number = |v: &Value| v.as_f64().unwrap_or_else(|| panic!("{pixel}: not a number in {vsm}"));
        let (bound, truth) = (number(&vsm["chebyshev_bound"]), number(&vsm["true_lit_fraction"]));
        assert_eq!(bound, number(&light["visibility_twin"]), "{pixel}: the bound is the visibility");
        assert!(bound >= truth - 1e-4, "{pixel}: bound {bound} below the true share {truth}");
        assert!(number(&vsm["variance_ndc2"]) >= -1e-6, "{vsm}");
        shadowed += usize::from(bound < 0.999);
    }
    assert!(shadowed > 0, "no probe landed in a VSM shadow");
}

/// The moments view: the level of the VSM moments the filter reads, as two square panels (mean
/// depth, standard deviation) with a legend naming the level; refused for techniques without
/// moments.
#[test]
fn the_moments_view_shows_the_level_the_filter_reads_and_needs_vsm() {
    let (image, stdout) = render_view("moments", &["--set", "technique=vsm", "--set", "radius_texels=6"]);
    // contact.toml's map is 2048 texels: radius 6 reads levels 2 and 3; the view shows level 2,
    // 512 texels a side.
    assert!(stdout.contains("VSM moments, level 2 (each texel averages 4x4 map texels)"), "{stdout}");
    assert_eq!((image.width(), image.height()), (2 * 512 + 8, 512));
    let right_panel_varies = (0..512).any(|y| image.get_pixel(520 + 256, y) != image.get_pixel(520 + 256, 0));
    assert!(right_panel_varies, "the standard deviation panel is flat");
    let scratch = Scratch::new();
    let run = render(&scratch, &contact(), &["--view", "moments", "--set", "technique=pcf"]);
    assert_bad_input(&run, &["moments", "vsm", "vssm"]);
    scratch.assert_no_output("out.png");
}

/// A VSSM probe sets its blocker estimate beside the true average of the same footprint and
/// PCSS's sampled average, each a depth between the light's near plane and the receiver.
#[test]
fn a_vssm_probe_compares_its_blocker_depth_with_the_footprint_and_pcss() {
    let mut estimated = 0;
    for pixel in ["108,33", "70,40", "80,45", "95,50", "110,35"] {
        let json = probe_json(&["--pixel", pixel, "--no-reference", "--set", "technique=vssm"]);
        let light = &json["lights"][0];
        let Some(vssm) = light.get("vssm") else { continue };
        estimated += 1;
        let receiver = light["receiver_depth_linear"].as_f64().expect("receiver depth");
        let estimate = vssm["estimated_blocker_depth_linear"].as_f64().expect("estimate");
        assert_eq!(Some(estimate), light["avg_blocker_depth_linear"].as_f64(), "{pixel}: {vssm}");
        assert!((20.0..=receiver).contains(&estimate), "{pixel}: estimate {estimate}, receiver {receiver}");
        if let Some(truth) = vssm["footprint_blocker_depth_linear"].as_f64() {
            assert!((20.0..=receiver).contains(&truth), "{pixel}: footprint average {truth}");
        }
        let bound = vssm["unoccluded_bound"].as_f64().expect("bound");
        assert!((0.0..1.0).contains(&bound), "{pixel}: blockers estimated with bound {bound}");
    }
    assert!(estimated > 0, "no probe found VSSM blockers");
}

// ---------------------------------------------------------------------------------------------
// The app's arguments: `shadowlab [FILE] [--lesson ID [--step N]] [--lang zh]`, checked before a
// window opens.

/// `shadowlab` with no display: the process the tests run has none, so a good argument ends at
/// the display check, a bad one before it.
fn app(args: &[&str]) -> Run {
    common::run(common::shadowlab_command().args(args).env_remove("DISPLAY").env_remove("WAYLAND_DISPLAY"))
}

#[test]
fn a_bad_app_argument_is_one_line_and_exit_2_before_any_window() {
    let scratch = Scratch::new();
    let broken = scratch.scene("broken.toml", "[camera\n");
    let notes = scratch.scene("notes.txt", "hello");
    let contact = contact();
    let cases: [(Vec<&str>, Vec<&str>); 7] = [
        (vec!["no_such_scene.toml"], vec!["no_such_scene.toml", "no such file", "pcss"]),
        (vec![&broken], vec!["broken.toml:1:", "unclosed table"]),
        (vec![&notes], vec!["notes.txt", ".toml", ".obj"]),
        (vec!["--lesson", "nope"], vec!["nope", "hard-shadows"]),
        (vec!["pcss", "--step", "99"], vec!["pcss", "1 to 8", "99"]),
        (vec![&contact, "--step", "2"], vec!["contact.toml", "--step"]),
        (vec!["--step", "2"], vec!["--step", "--lesson"]),
    ];
    for (args, needles) in cases {
        let run = app(&args);
        assert_bad_input(&run, &needles);
    }
    let run = app(&["--lang", "fr"]);
    assert_eq!(run.code, Some(2), "{run}");
    assert!(run.stderr.contains("fr") && run.stderr.contains("en or zh"), "{run}");
}

#[test]
fn a_good_app_argument_reaches_the_display_check() {
    let scratch = Scratch::new();
    let lesson = scratch.scene(
        "my_lesson.toml",
        &format!(
            r#"id = "mine"
order = 9
title = {{ en = "Mine", zh = "我的" }}
summary = {{ en = "One step.", zh = "一步。" }}

[[step]]
title = {{ en = "Poles", zh = "柱子" }}
text = {{ en = "Look at the poles.", zh = "看柱子。" }}
try_this = [ {{ en = "Set “radius” to 6.", zh = "把「半径」改成 6。", set = {{ radius_texels = 6 }} }} ]
scene = "{}"
probe = [480, 300]
"#,
            contact().replace('\\', "/")
        ),
    );
    let obj = repo_path("tests/data/obj/blender_export.obj").display().to_string();
    for args in [vec![contact()], vec![obj], vec![lesson], vec!["vsm".into(), "--step".into(), "3".into()]] {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let run = app(&args);
        assert_bad_input(&run, &["no display found", "xvfb-run"]);
    }
    let run = app(&["--lesson", "6", "--step", "2", "--lang", "zh"]);
    assert_bad_input(&run, &["no display found"]);
}

/// On a terminal, export and the ground truth show progress bars with a rate and the time left
/// (the tests' own output is not a terminal: `script` gives the command one).
#[test]
fn on_a_terminal_export_and_the_ground_truth_show_progress_bars() {
    let Ok(probe) = std::process::Command::new("script").arg("--version").output() else {
        panic!("`script` (util-linux) runs a command on a pseudo-terminal; install bsdutils");
    };
    assert!(probe.status.success());
    let scratch = Scratch::new();
    let out = scratch.arg("slides");
    let image = scratch.arg("truth.png");
    let exe = env!("CARGO_BIN_EXE_shadowlab");
    let on_terminal = |command: String| {
        let mut script = std::process::Command::new("script");
        script.args(["-qec", &command, "/dev/null"]);
        script.current_dir(env!("CARGO_MANIFEST_DIR")).env("XDG_RUNTIME_DIR", common::runtime_dir());
        let run = common::run(&mut script);
        assert_eq!(run.code, Some(0), "{command}:\n{run}");
        // Without the terminal's colour and cursor codes.
        let mut plain = String::new();
        let mut escape = false;
        for c in run.stdout.chars() {
            match (escape, c) {
                (false, '\u{1b}') => escape = true,
                (true, c) if c.is_ascii_alphabetic() => escape = false,
                (true, _) => {}
                (false, c) => plain.push(c),
            }
        }
        plain
    };
    let export = on_terminal(format!("{exe} export --lesson bias --size 640x360 --out {out}"));
    let bar = export.contains("6/7 slides · ") && export.contains("bias step 7/7");
    assert!(bar && export.contains("/s · ") && export.contains(" left · "), "{export}");
    assert!(!export.contains("[1/7]"), "a terminal gets the bar, not the log lines:\n{export}");
    let contact = contact();
    let truth =
        on_terminal(format!("{exe} render --scene {contact} --view reference --size 160x90 --out {image}"));
    assert!(truth.contains("ground truth ") && truth.contains("256/256 hard shadows · "), "{truth}");
}

/// `cargo install --path .` puts the binary elsewhere: run from another folder, it still finds
/// its lessons, scenes and meshes (beside it, or in the checkout it was built from).
#[test]
fn an_installed_binary_finds_its_lessons_and_scenes_from_any_folder() {
    let scratch = Scratch::new();
    let bin = scratch.path("bin");
    std::fs::create_dir(&bin).expect("bin folder");
    let installed = bin.join("shadowlab");
    std::fs::copy(env!("CARGO_BIN_EXE_shadowlab"), &installed).expect("copy the binary");
    let elsewhere = scratch.path("elsewhere");
    std::fs::create_dir(&elsewhere).expect("a folder of one's own");
    let run_there = |args: &[&str]| {
        let mut command = std::process::Command::new(&installed);
        command.args(args).current_dir(&elsewhere).env("XDG_RUNTIME_DIR", common::runtime_dir());
        common::run(&mut command)
    };
    let lessons = run_there(&["lessons"]);
    assert_eq!(lessons.code, Some(0), "{lessons}");
    assert!(lessons.stdout.contains("vsm") && lessons.stdout.contains("hard-shadows"), "{lessons}");
    let render = run_there(&["render", "--lesson", "multi-light", "--size", "160x90", "--out", "step.png"]);
    assert_eq!(render.code, Some(0), "{render}");
    assert!(elsewhere.join("step.png").is_file(), "{render}");

    // Without the checkout (forced here with SHADOWLAB_BUILT_IN_DATA=1), the copy built into the
    // binary is unpacked into the user's data folder and read from there.
    let data_home = scratch.path("data");
    let built_in = |args: &[&str]| {
        let mut command = std::process::Command::new(&installed);
        command
            .args(args)
            .current_dir(&elsewhere)
            .env("XDG_RUNTIME_DIR", common::runtime_dir())
            .env("XDG_DATA_HOME", &data_home)
            .env(shadowlab::shipped::BUILT_IN_ENV, "1");
        common::run(&mut command)
    };
    let lessons = built_in(&["lessons"]);
    assert_eq!(lessons.code, Some(0), "{lessons}");
    assert!(lessons.stdout.contains("vsm") && lessons.stdout.contains("hard-shadows"), "{lessons}");
    let unpacked: Vec<_> = std::fs::read_dir(data_home.join("shadowlab"))
        .expect("the unpacked copy")
        .map(|e| e.expect("entry").path())
        .collect();
    assert_eq!(unpacked.len(), 1, "{unpacked:?}");
    for relative in ["lessons/06_vsm.toml", "assets/scenes/games202.toml", "assets/meshes/bunny.obj"] {
        assert!(unpacked[0].join(relative).is_file(), "{relative} not unpacked");
    }
    // A lesson step renders from it: its scene, meshes and texture come from the copy.
    let render = built_in(&["render", "--lesson", "hard-shadows", "--size", "160x90", "--out", "copy.png"]);
    assert_eq!(render.code, Some(0), "{render}");
    assert!(elsewhere.join("copy.png").is_file(), "{render}");
}

#[test]
fn bench_soak_plays_the_lessons_in_the_real_window_and_keeps_moving() {
    let _turn = app_bench_turn();
    let run = common::run_in_window(&["bench", "--app", "--window", "--soak", "12", "--json"]);
    assert_eq!(run.code, Some(0), "{run}");
    let json: Value = serde_json::from_str(&run.stdout).unwrap_or_else(|e| panic!("JSON ({e}):\n{run}"));
    assert_eq!(json["moving_throughout"], Value::Bool(true), "{json:#}");
    assert!(json["frames_rendered"].as_u64().is_some_and(|n| n > 2), "{json:#}");
    assert!(json["full_detail_frames"].as_u64().is_some_and(|n| n >= 1), "{json:#}");
    assert!(json["view_switches"].as_u64().is_some_and(|n| n >= 1), "{json:#}");
    assert!(json["scene_time_advanced_s"].as_f64().is_some_and(|t| t > 1.0), "{json:#}");
    for key in ["rss_early_mb", "rss_end_mb"] {
        assert!(json[key].as_f64().is_some_and(|mb| mb > 10.0), "{key}: {json:#}");
    }
    // Too short to judge memory by.
    assert_eq!(json["memory_held"], Value::Null, "{json:#}");
    // Freed memory went back to the system along the way (glibc's arenas keep it otherwise).
    if cfg!(all(target_os = "linux", target_env = "gnu")) {
        assert!(json["pages_returned"].as_u64().is_some_and(|n| n >= 2), "{json:#}");
    }
}

#[test]
fn bench_soak_needs_the_window_and_a_sensible_length() {
    let run = shadowlab(&["bench", "--app", "--soak", "60"]);
    assert_bad_input(&run, &["--soak", "--window"]);
    // A lesson step that does not exist is named before any window opens.
    let run = shadowlab(&["bench", "--app", "--window", "--soak", "60", "--soak-lesson", "more-maps:9"]);
    assert_bad_input(&run, &["--soak-lesson more-maps:9", "7 steps"]);
    let run = shadowlab(&["bench", "--app", "--window", "--soak", "60", "--soak-lesson", "more-maps"]);
    assert_bad_input(&run, &["--soak-lesson more-maps", "LESSON:STEP"]);
    let run = shadowlab(&["bench", "--app", "--window", "--soak", "1"]);
    assert_bad_input(&run, &["--soak 1", "out of range"]);
}

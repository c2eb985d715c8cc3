//! Every user file fuzzed: seeded, mutation-based property tests that start from the shipped
//! scenes, lessons, OBJ/MTL files and textures (and the test fixtures), mutate them byte by byte
//! and with some knowledge of their structure, and feed them to the real loaders from a
//! temporary copy of the data tree, then to the `shadowlab render` process.
//!
//! What must hold for every input: the loader neither panics nor hangs (each case runs on a
//! thread of its own and must answer within a generous time); an error is one line and names
//! the file at fault; what loads is sane (finite transforms, indices in range, texture sizes
//! that match their pixels); nothing is written next to the inputs; the process exits with 0
//! or 2 (never a panic's 101 or a signal), on failure with one line on stderr naming the file
//! and no image or temporary file left behind.
//!
//! The random numbers come from a fixed seed, so a run is the same on every machine. The default
//! run takes about a minute in release mode on two cores; `cargo test --release --test fuzz --
//! --ignored` runs the same properties on six times as many cases from another seed (about five
//! minutes).
//! `SHADOWLAB_FUZZ_SEED=N` explores from another seed (a failure prints the seed it came from).

mod common;

use proptest::prelude::*;
use proptest::sample::{Index, select};
use proptest::test_runner::{Config, RngAlgorithm, TestCaseError, TestRng, TestRunner};
use shadowlab::scene::{Mesh, Scene, SceneError, load_scene, mesh::load_obj, parse_scene_str};
use std::collections::BTreeMap;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

// ---------------------------------------------------------------------------------------------
// Budgets and the runner.

/// Cases per target: the default run, and the long one behind `#[ignore]`.
#[derive(Clone, Copy)]
struct Budget {
    scenes: u32,
    lessons: u32,
    objs: u32,
    mtls: u32,
    textures: u32,
    cli: u32,
    /// Homework shaders through the rewrite and naga, and through `shadowlab homework`.
    shaders: u32,
    cli_homework: u32,
    /// Page addresses' queries through the app's link reader.
    links: u32,
    /// Mixed into every target's seed: the long run explores other cases than the default one.
    seed: u64,
}

const DEFAULT: Budget = Budget {
    scenes: 13_000,
    lessons: 1200,
    objs: 6000,
    mtls: 3000,
    textures: 6000,
    cli: 70,
    shaders: 3000,
    cli_homework: 8,
    links: 300,
    seed: 0x5EED_0001,
};
const LONG: Budget = Budget {
    scenes: 78_000,
    lessons: 7200,
    objs: 36_000,
    mtls: 18_000,
    textures: 36_000,
    cli: 420,
    shaders: 18_000,
    cli_homework: 48,
    links: 1800,
    seed: 0x5EED_0002,
};

/// The largest input a mutation makes (repeated lines stop here): big enough for huge counts,
/// small enough for two test threads on a small machine.
const MAX_INPUT: usize = 4 << 20;

/// A loader must answer within this; a normal case takes milliseconds.
const LOADER_LIMIT: Duration = Duration::from_secs(10);
/// A `shadowlab render` process must finish within this (lavapipe renders a 32x18 frame in a
/// second or two).
const PROCESS_LIMIT: Duration = Duration::from_secs(180);

fn base_seed(budget: Budget) -> u64 {
    std::env::var("SHADOWLAB_FUZZ_SEED").ok().and_then(|s| s.parse().ok()).unwrap_or(budget.seed)
}

/// A deterministic runner for `target`: its own ChaCha stream, so adding a target or changing
/// one's case count leaves the others' cases as they were. No failure files are written.
fn runner(target: &str, cases: u32, seed: u64) -> TestRunner {
    let mut bytes = [0u8; 32];
    bytes[..8].copy_from_slice(&seed.to_le_bytes());
    // FNV-1a of the target's name.
    let hash = target
        .bytes()
        .fold(0xcbf2_9ce4_8422_2325u64, |h, b| (h ^ u64::from(b)).wrapping_mul(0x100_0000_01b3));
    bytes[8..16].copy_from_slice(&hash.to_le_bytes());
    bytes[16..24].copy_from_slice(b"shadowla");
    bytes[24..].copy_from_slice(b"b fuzz!!");
    let config = Config {
        cases,
        failure_persistence: None,
        rng_algorithm: RngAlgorithm::ChaCha,
        // A failing case is shrunk for at most a minute (a hang costs LOADER_LIMIT per try).
        max_shrink_time: 60_000,
        max_shrink_iters: 512,
        ..Config::default()
    };
    TestRunner::new_with_rng(config, TestRng::from_seed(RngAlgorithm::ChaCha, &bytes))
}

/// How the cases of one target ended.
#[derive(Default)]
struct Tally {
    loaded: AtomicUsize,
    rejected: AtomicUsize,
    /// A case hung (see `guarded`).
    hung: std::sync::atomic::AtomicBool,
}

impl Tally {
    fn count(&self, ok: bool) {
        let counter = if ok { &self.loaded } else { &self.rejected };
        counter.fetch_add(1, Ordering::Relaxed);
    }
}

/// Run `check` on `cases` values of `strategy` and fail the test with the smallest failing
/// input proptest finds.
fn fuzz<S>(
    target: &str,
    cases: u32,
    budget: Budget,
    strategy: S,
    check: impl Fn(S::Value, &Tally) -> Result<(), TestCaseError>,
) where
    S: Strategy,
    S::Value: std::fmt::Debug,
{
    let seed = base_seed(budget);
    let tally = Tally::default();
    let started = Instant::now();
    let result = runner(target, cases, seed).run(&strategy, |case| {
        if tally.hung.load(Ordering::Relaxed) {
            return Ok(());
        }
        check(case, &tally)
    });
    let (loaded, rejected) = (tally.loaded.load(Ordering::Relaxed), tally.rejected.load(Ordering::Relaxed));
    eprintln!(
        "fuzz {target}: {cases} cases in {:.1} s ({loaded} loaded, {rejected} rejected), seed {seed:#x}",
        started.elapsed().as_secs_f64(),
    );
    if let Err(e) = result {
        panic!("fuzz {target} (SHADOWLAB_FUZZ_SEED={seed}): {e}");
    }
    // Both must be common: mutants that all fail to parse never reach the checks behind the
    // parser, and mutants that all load test nothing but the happy path.
    let cases = cases as usize;
    assert!(
        loaded * 40 >= cases && rejected * 40 >= cases,
        "fuzz {target}: {loaded} of {cases} cases loaded and {rejected} were rejected; the mutations \
         should give at least 1 in 40 of each"
    );
}

/// Run `work` on a thread of its own: a panic or no answer within `LOADER_LIMIT` fails the case.
///
/// A thread that hangs is left behind (it may keep reading or allocating), so after a hang the
/// target's remaining cases pass without running: proptest then reports the case that hung as
/// it was, instead of shrinking it through more hangs.
fn guarded<T: Send + 'static>(
    tally: &Tally,
    input: &[u8],
    work: impl FnOnce() -> T + Send + 'static,
) -> Result<T, TestCaseError> {
    let (send, receive) = std::sync::mpsc::channel();
    std::thread::Builder::new()
        .name("fuzz case".into())
        .spawn(move || {
            let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(work));
            let _ = send.send(result);
        })
        .map_err(|e| TestCaseError::fail(format!("cannot start a thread: {e}")))?;
    match receive.recv_timeout(LOADER_LIMIT) {
        Ok(Ok(value)) => Ok(value),
        Ok(Err(panic)) => {
            let message = panic
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            Err(fail(format!("panicked: {message}\n--- input\n{}", shown(input))))
        }
        Err(_) => {
            tally.hung.store(true, Ordering::Relaxed);
            Err(fail(format!(
                "no answer within {} s (a hang?)\n--- input\n{}",
                LOADER_LIMIT.as_secs(),
                shown(input)
            )))
        }
    }
}

fn fail(message: String) -> TestCaseError {
    TestCaseError::fail(message)
}

/// The input as text for a failure message (long inputs cut).
fn shown(bytes: &[u8]) -> String {
    let text = String::from_utf8_lossy(bytes);
    if text.len() > 3000 {
        let cut = (0..=3000).rev().find(|&i| text.is_char_boundary(i)).unwrap_or(0);
        format!("{}\n[... {} more bytes]", &text[..cut], text.len() - cut)
    } else {
        text.into_owned()
    }
}

/// An error message must be one non-empty line that names the file (one of `names`).
fn check_message(message: &str, names: &[&str], input: &[u8]) -> Result<(), TestCaseError> {
    let problem = if message.trim().is_empty() {
        Some("is empty")
    } else if message.lines().count() != 1 || message.contains(['\n', '\r']) {
        Some("is not one line")
    } else if !names.iter().any(|name| message.contains(name)) {
        Some("names none of the files")
    } else {
        None
    };
    match problem {
        None => Ok(()),
        Some(problem) => {
            Err(fail(format!("the error {problem} ({names:?}):\n{message:?}\n--- input\n{}", shown(input))))
        }
    }
}

// ---------------------------------------------------------------------------------------------
// The data tree: a temporary copy of everything the shipped files refer to.

fn repo_path(relative: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(relative)
}

/// One seed file: where its mutants are written (so relative paths inside resolve) and its bytes.
struct Seed {
    dir: PathBuf,
    bytes: Vec<u8>,
}

/// A temporary copy of the data tree:
/// root/assets/{scenes,meshes,textures}, root/lessons, root/obj (tests/data/obj) and
/// root/scenes (tests/data/scenes), laid out as in the repository.
struct Tree {
    root: tempfile::TempDir,
}

impl Tree {
    fn new() -> Self {
        let root = tempfile::tempdir().expect("temporary folder");
        let copies = [
            ("assets/scenes", "assets/scenes"),
            ("assets/meshes", "assets/meshes"),
            ("assets/textures", "assets/textures"),
            ("lessons", "lessons"),
            ("tests/data/obj", "obj"),
            ("tests/data/scenes", "scenes"),
        ];
        for (from, to) in copies {
            let target = root.path().join(to);
            std::fs::create_dir_all(&target).expect("create folder");
            for entry in std::fs::read_dir(repo_path(from)).expect("read folder") {
                let path = entry.expect("entry").path();
                if path.is_file() {
                    std::fs::copy(&path, target.join(path.file_name().expect("name"))).expect("copy");
                }
            }
        }
        // A folder whose name looks like a mesh.
        std::fs::create_dir_all(root.path().join("obj/folder.obj")).expect("folder.obj");
        Self { root }
    }

    fn path(&self, relative: &str) -> PathBuf {
        self.root.path().join(relative)
    }

    /// The files of `folder` (relative to the root) with `extension`, as seeds.
    fn seeds(&self, folder: &str, extension: &str) -> Vec<Seed> {
        let dir = self.path(folder);
        let mut paths: Vec<PathBuf> = std::fs::read_dir(&dir)
            .expect("read folder")
            .map(|e| e.expect("entry").path())
            .filter(|p| p.is_file() && p.extension().is_some_and(|e| e == extension))
            .collect();
        paths.sort();
        paths
            .into_iter()
            .map(|p| Seed { dir: dir.clone(), bytes: std::fs::read(&p).expect("read seed") })
            .collect()
    }

    /// Every file under the root with its size, but for the cases' own inputs (`fuzz-*`).
    fn listing(&self) -> BTreeMap<PathBuf, u64> {
        fn walk(dir: &Path, out: &mut BTreeMap<PathBuf, u64>) {
            let Ok(entries) = std::fs::read_dir(dir) else { return };
            for entry in entries.flatten() {
                let path = entry.path();
                let name = entry.file_name().to_string_lossy().into_owned();
                if path.is_dir() {
                    walk(&path, out);
                } else if !name.starts_with("fuzz-") {
                    out.insert(path, entry.metadata().map_or(0, |m| m.len()));
                }
            }
        }
        let mut out = BTreeMap::new();
        walk(self.root.path(), &mut out);
        out
    }
}

/// Checks that a case left the tree as it found it.
struct Untouched {
    before: BTreeMap<PathBuf, u64>,
}

impl Untouched {
    fn new(tree: &Tree) -> Self {
        Self { before: tree.listing() }
    }

    fn check(&self, tree: &Tree, input: &[u8]) -> Result<(), TestCaseError> {
        let after = tree.listing();
        if after == self.before {
            return Ok(());
        }
        let added: Vec<_> = after.keys().filter(|p| !self.before.contains_key(*p)).collect();
        Err(fail(format!("the loader changed the data tree (new: {added:?})\n--- input\n{}", shown(input))))
    }
}

/// Chunks any mutation may splice in: every seed file of every kind.
fn donors(tree: &Tree) -> Vec<Vec<u8>> {
    let mut out = Vec::new();
    for (folder, ext) in [
        ("assets/scenes", "toml"),
        ("lessons", "toml"),
        ("assets/meshes", "obj"),
        ("assets/meshes", "mtl"),
        ("obj", "obj"),
        ("obj", "mtl"),
        ("assets/textures", "png"),
    ] {
        out.extend(tree.seeds(folder, ext).into_iter().map(|s| s.bytes));
    }
    out
}

// ---------------------------------------------------------------------------------------------
// Byte-level mutations.

#[derive(Clone, Debug)]
enum ByteOp {
    Flip {
        at: Index,
        bit: u8,
    },
    Set {
        at: Index,
        byte: u8,
    },
    Insert {
        at: Index,
        bytes: Vec<u8>,
    },
    Delete {
        at: Index,
        len: u16,
    },
    /// Copy `len` bytes of another file (`donor`, from `from`) over `at..at + len`.
    Splice {
        at: Index,
        donor: Index,
        from: Index,
        len: u16,
    },
    /// Repeat `at..at + len` `times` times.
    Repeat {
        at: Index,
        len: u8,
        times: u16,
    },
    Truncate {
        at: Index,
    },
}

fn interesting_byte() -> impl Strategy<Value = u8> {
    prop_oneof![
        3 => any::<u8>(),
        2 => select(&b"\n\r\t \"'[]{}=,.#-+/\\0123456789eEnaif"[..]),
        1 => select(&[0u8, 0x7f, 0x80, 0xc3, 0xe4, 0xef, 0xbf, 0xff][..]),
    ]
}

fn byte_op() -> impl Strategy<Value = ByteOp> {
    prop_oneof![
        (any::<Index>(), 0u8..8).prop_map(|(at, bit)| ByteOp::Flip { at, bit }),
        (any::<Index>(), interesting_byte()).prop_map(|(at, byte)| ByteOp::Set { at, byte }),
        (any::<Index>(), prop::collection::vec(interesting_byte(), 1..12))
            .prop_map(|(at, bytes)| ByteOp::Insert { at, bytes }),
        (any::<Index>(), prop_oneof![1u16..8, 8u16..4096]).prop_map(|(at, len)| ByteOp::Delete { at, len }),
        (any::<Index>(), any::<Index>(), any::<Index>(), 1u16..2048)
            .prop_map(|(at, donor, from, len)| ByteOp::Splice { at, donor, from, len }),
        (any::<Index>(), 1u8..64, 2u16..2000).prop_map(|(at, len, times)| ByteOp::Repeat { at, len, times }),
        any::<Index>().prop_map(|at| ByteOp::Truncate { at }),
    ]
}

fn apply_byte_op(bytes: &mut Vec<u8>, op: &ByteOp, donors: &[Vec<u8>]) {
    let n = bytes.len();
    let pos = |at: &Index| if n == 0 { 0 } else { at.index(n + 1) };
    match op {
        ByteOp::Flip { at, bit } if n > 0 => bytes[at.index(n)] ^= 1 << bit,
        ByteOp::Set { at, byte } if n > 0 => bytes[at.index(n)] = *byte,
        ByteOp::Flip { .. } | ByteOp::Set { .. } => {}
        ByteOp::Insert { at, bytes: new } => {
            let at = pos(at);
            bytes.splice(at..at, new.iter().copied());
        }
        ByteOp::Delete { at, len } => {
            let at = pos(at).min(n);
            bytes.drain(at..(at + usize::from(*len)).min(n));
        }
        ByteOp::Splice { at, donor, from, len } => {
            let donor = donor.get(donors);
            if donor.is_empty() {
                return;
            }
            let from = from.index(donor.len());
            let chunk = &donor[from..(from + usize::from(*len)).min(donor.len())];
            let at = pos(at).min(n);
            let end = (at + chunk.len()).min(n);
            bytes.splice(at..end, chunk.iter().copied());
        }
        ByteOp::Repeat { at, len, times } if n > 0 => {
            let at = at.index(n);
            let chunk = bytes[at..(at + usize::from(*len)).min(n)].to_vec();
            let copies: Vec<u8> =
                chunk.iter().copied().cycle().take(chunk.len() * usize::from(*times)).collect();
            bytes.splice(at..at, copies);
        }
        ByteOp::Repeat { .. } => {}
        ByteOp::Truncate { at } => bytes.truncate(pos(at)),
    }
    bytes.truncate(MAX_INPUT);
}

// ---------------------------------------------------------------------------------------------
// TOML mutations: values replaced by extreme, non-finite, huge or mistyped ones, keys deleted or
// added, tables duplicated. They edit the text at the spans the parser reports, so the rest of
// the file (comments, lines) stays as it was.

/// A TOML value written into the file as it is.
#[derive(Clone, Debug)]
enum Raw {
    Token(&'static str),
    Float(f64),
    Int(i64),
    Vec3([f64; 3]),
    Text(String),
}

impl Raw {
    fn render(&self) -> String {
        fn float(f: f64) -> String {
            if f.is_nan() {
                "nan".into()
            } else if f.is_infinite() {
                (if f > 0.0 { "inf" } else { "-inf" }).into()
            } else {
                format!("{f:e}")
            }
        }
        match self {
            Raw::Token(t) => (*t).to_string(),
            Raw::Float(f) => float(*f),
            Raw::Int(i) => i.to_string(),
            Raw::Vec3(v) => format!("[{}, {}, {}]", float(v[0]), float(v[1]), float(v[2])),
            Raw::Text(s) => toml::Value::String(s.clone()).to_string(),
        }
    }
}

/// Values chosen for what they do to a loader: limits of f32 and of the integer types, what
/// overflows on conversion, zero and its sign, NaN and the infinities, wrong types.
const TOKENS: &[&str] = &[
    "1e38",
    "-1e38",
    "3.4e38",
    "3.5e38",
    "-3.5e38",
    "1e39",
    "-1e39",
    "1e308",
    "-1e308",
    "nan",
    "+nan",
    "-nan",
    "inf",
    "+inf",
    "-inf",
    "0",
    "0.0",
    "-0.0",
    "1e-45",
    "-1e-45",
    "1e-38",
    "1e-7",
    "-1",
    "-1.0",
    "1",
    "2",
    "0.5",
    "1e6",
    "1000001.0",
    "-1e6",
    "1e7",
    "1e9",
    "9223372036854775807",
    "-9223372036854775808",
    "4294967295",
    "4294967296",
    "2147483648",
    "-2147483649",
    "255",
    "256",
    "8192",
    "8193",
    "16384",
    "65536",
    "100000",
    "0x7fffffff",
    "0o777",
    "0b1",
    "1_000",
    "\"\"",
    "\"x\"",
    "\"nan\"",
    "\"1e38\"",
    "true",
    "false",
    "[]",
    "[1.0]",
    "[1.0, 2.0]",
    "[1.0, 2.0, 3.0, 4.0]",
    "[nan, nan, nan]",
    "[inf, 0.0, 0.0]",
    "[1e38, 1e38, 1e38]",
    "[-1e38, -1e38, -1e38]",
    "[-1e38, 1.0, 1.0]",
    "[0.0, 0.0, 0.0]",
    "[0.0, 1e-30, 0.0]",
    "[1e6, 0.0, 0.0]",
    "[1e7, 1e7, 1e7]",
    "[\"a\", \"b\", \"c\"]",
    "[[1.0]]",
    "{}",
    "{ x = 1 }",
    "1979-05-27",
    "1979-05-27T07:32:00Z",
];

/// Strings for string values: names of things that exist, things that do not, special files.
const STRINGS: &[&str] = &[
    "",
    " ",
    "plane",
    "cube",
    "sphere",
    "PLANE",
    "bunny.obj",
    "../meshes/bunny.obj",
    "../meshes/floor.obj",
    "../obj/multi_material.obj",
    "../obj/missing_texture.obj",
    "../obj/folder.obj",
    "../obj/empty.obj",
    "../obj/malformed.obj",
    "../obj/",
    "/dev/zero",
    "/dev/null.obj",
    ".",
    "..",
    "nan",
    "inf",
    "pcss",
    "hard",
    "vsm",
    "vssm",
    "pcf",
    "directional",
    "spot",
    "point",
    "texel-density",
    "../assets/scenes/sun_avenue.toml",
    "cascade-index",
    "orthographic",
    "perspective",
    "receiver_plane",
    "rgba8",
    "hardware",
    "grid",
    "shadow-map",
    "moments",
    "camera",
    "penumbra",
    "light-frustum",
    "pcss-triangles",
    "../assets/scenes/contact.toml",
    "../assets/scenes/missing.toml",
    "../assets/scenes/",
    "../lessons/01_hard_shadows.toml",
    "{probe.visibility}",
    "{probe.",
    "{probe.nosuch}",
    "💥 立方体 \u{202e}",
    "line\nbreak",
    "tab\there",
    "\u{0}",
];

/// Key names to add: every key of the scene and lesson files, override paths and unknown keys.
const KEYS: &[&str] = &[
    "position",
    "target",
    "up",
    "fov_deg",
    "height",
    "near",
    "far",
    "projection",
    "name",
    "mesh",
    "color",
    "translate",
    "rotate_deg",
    "scale",
    "spin_deg_per_s",
    "kind",
    "intensity",
    "shadow_map_size",
    "extent",
    "width",
    "angular_diameter_deg",
    "orbit_deg_per_s",
    "cascades",
    "cascade_lambda",
    "cascade_distance",
    "technique",
    "bias_mode",
    "bias",
    "slope_bias",
    "adaptive_c",
    "normal_offset_texels",
    "depth_bias_constant",
    "depth_bias_slope",
    "cull_front_faces",
    "pcf_kernel",
    "samples",
    "radius_texels",
    "rotate_per_pixel",
    "noise_seed",
    "blocker_samples",
    "min_filter_radius_texels",
    "search_radius_scale",
    "depth_storage",
    "ortho_near_factor",
    "vsm_min_variance",
    "vsm_bleed_reduction",
    "clamp_outside",
    "reference_samples",
    "ambient",
    "id",
    "order",
    "title",
    "summary",
    "text",
    "try_this",
    "scene",
    "set",
    "time",
    "play",
    "panels",
    "overlays",
    "probe",
    "diagram",
    "view",
    "light",
    "expect",
    "en",
    "zh",
    "\"light.0.position\"",
    "\"light.0.far\"",
    "\"object.0.scale\"",
    "\"camera.far\"",
    "\"light.9.width\"",
    "\"object.0.mesh\"",
    "foo",
    "name_zh",
    "\"\"",
    "\"a.b.c.d\"",
];

fn raw() -> impl Strategy<Value = Raw> {
    let floats = prop_oneof![
        select(&[1e38, -1e38, 3.4e38, -3.4e38, 1e6, -1e6, 1e-6, 1e-30, 0.0, -0.0][..]),
        -1e9f64..1e9,
        any::<f64>(),
    ];
    prop_oneof![
        4 => select(TOKENS).prop_map(Raw::Token),
        4 => floats.clone().prop_map(Raw::Float),
        1 => prop_oneof![any::<i64>(), -10i64..10_000].prop_map(Raw::Int),
        3 => [floats.clone(), floats.clone(), floats].prop_map(Raw::Vec3),
        2 => prop_oneof![
            4 => select(STRINGS).prop_map(str::to_string),
            1 => "[ -~]{0,40}",
            1 => (1usize..20_000).prop_map(|n| "x".repeat(n)),
        ]
        .prop_map(Raw::Text),
    ]
}

#[derive(Clone, Debug)]
enum TomlOp {
    /// Replace the value (or array element) at `node`.
    SetValue { node: Index, raw: Raw },
    /// Remove a `key = value` (or an array element).
    DeleteKey { node: Index },
    /// Add `key = raw` under a table header (or at the top).
    InsertKey { header: Index, key: &'static str, raw: Raw },
    /// Copy a `[table]` or `[[array]]` section, header and all, to the end.
    DuplicateSection { header: Index },
}

fn toml_op() -> impl Strategy<Value = TomlOp> {
    prop_oneof![
        6 => (any::<Index>(), raw()).prop_map(|(node, raw)| TomlOp::SetValue { node, raw }),
        2 => any::<Index>().prop_map(|node| TomlOp::DeleteKey { node }),
        2 => (any::<Index>(), select(KEYS), raw()).prop_map(|(header, key, raw)| TomlOp::InsertKey { header, key, raw }),
        1 => any::<Index>().prop_map(|header| TomlOp::DuplicateSection { header }),
    ]
}

/// A value in the text: its key's span (none for an array element) and its own.
struct Node {
    key: Option<Range<usize>>,
    value: Range<usize>,
}

fn toml_nodes(text: &str) -> Vec<Node> {
    use toml::de::{DeTable, DeValue};
    fn value(key: Option<Range<usize>>, v: &toml::Spanned<DeValue<'_>>, text: &str, out: &mut Vec<Node>) {
        let span = v.span();
        let Some(src) = text.get(span.clone()) else { return };
        match v.get_ref() {
            // A `[table]` or `[[array]]` section: only what is inside.
            DeValue::Table(t) if !src.starts_with('{') => return table(t, text, out),
            DeValue::Array(a)
                if src.starts_with("[[")
                    || a.iter().any(|e| {
                        matches!(e.get_ref(), DeValue::Table(_))
                            && !text.get(e.span()).is_some_and(|s| s.starts_with('{'))
                    }) =>
            {
                for element in a.iter() {
                    value(None, element, text, out);
                }
                return;
            }
            DeValue::Table(t) => table(t, text, out),
            DeValue::Array(a) => {
                for element in a.iter() {
                    value(None, element, text, out);
                }
            }
            _ => {}
        }
        if !span.is_empty() {
            out.push(Node { key, value: span });
        }
    }
    fn table(t: &DeTable<'_>, text: &str, out: &mut Vec<Node>) {
        for (k, v) in t.iter() {
            value(Some(k.span()), v, text, out);
        }
    }
    let Ok(doc) = DeTable::parse(text) else { return Vec::new() };
    let mut out = Vec::new();
    table(doc.get_ref(), text, &mut out);
    out
}

/// Byte offsets of the lines that start a `[table]` or `[[array]]` section.
fn headers(text: &str) -> Vec<usize> {
    let mut offset = 0;
    let mut out = Vec::new();
    for line in text.split_inclusive('\n') {
        if line.trim_start().starts_with('[') {
            out.push(offset);
        }
        offset += line.len();
    }
    out
}

fn apply_toml_op(text: &mut String, op: &TomlOp) {
    match op {
        TomlOp::SetValue { node, raw } => {
            let nodes = toml_nodes(text);
            if nodes.is_empty() {
                return;
            }
            let node = node.get(&nodes);
            // An array element takes a single value (its array is a node of its own).
            let raw = match raw {
                Raw::Vec3(v) if node.key.is_none() => Raw::Float(v[0]),
                other => other.clone(),
            };
            text.replace_range(node.value.clone(), &raw.render());
        }
        TomlOp::DeleteKey { node } => {
            let nodes = toml_nodes(text);
            if nodes.is_empty() {
                return;
            }
            let node = node.get(&nodes);
            let start = node.key.as_ref().map_or(node.value.start, |k| k.start.min(node.value.start));
            let mut end = node.value.end;
            // An array element takes its comma along.
            if node.key.is_none() {
                let rest = &text[end..];
                let skipped = rest.len() - rest.trim_start().len();
                if rest.trim_start().starts_with(',') {
                    end += skipped + 1;
                }
            }
            text.replace_range(start..end, "");
        }
        TomlOp::InsertKey { header, key, raw } => {
            let mut starts = headers(text);
            starts.insert(0, 0);
            let at = *header.get(&starts);
            // After the header line (or at the very top).
            let line_end = if at == 0 && !text.trim_start().starts_with('[') {
                0
            } else {
                text[at..].find('\n').map_or(text.len(), |i| at + i + 1)
            };
            let line = format!("{key} = {}\n", raw.render());
            if line_end == text.len() && !text.ends_with('\n') {
                text.push('\n');
                text.push_str(&line);
            } else {
                text.insert_str(line_end, &line);
            }
        }
        TomlOp::DuplicateSection { header } => {
            let starts = headers(text);
            if starts.is_empty() {
                return;
            }
            let i = header.index(starts.len());
            let end = starts.get(i + 1).copied().unwrap_or(text.len());
            let section = text[starts[i]..end].to_string();
            if !text.ends_with('\n') {
                text.push('\n');
            }
            text.push_str(&section);
        }
    }
}

#[derive(Clone, Debug)]
enum TextOp {
    Byte(ByteOp),
    Toml(TomlOp),
}

fn text_op() -> impl Strategy<Value = TextOp> {
    prop_oneof![6 => toml_op().prop_map(TextOp::Toml), 1 => byte_op().prop_map(TextOp::Byte)]
}

/// Mutations applied in order to one seed file. A TOML mutation of a file that no longer
/// parses does nothing.
fn mutate_toml(seed: &[u8], ops: &[TextOp], donors: &[Vec<u8>]) -> Vec<u8> {
    let mut bytes = seed.to_vec();
    for op in ops {
        match op {
            TextOp::Byte(op) => apply_byte_op(&mut bytes, op, donors),
            TextOp::Toml(op) => {
                if let Ok(mut text) = String::from_utf8(bytes.clone()) {
                    apply_toml_op(&mut text, op);
                    bytes = text.into_bytes();
                }
            }
        }
    }
    bytes
}

// ---------------------------------------------------------------------------------------------
// Scenes.

#[derive(Clone, Debug)]
struct SceneCase {
    seed: Index,
    ops: Vec<TextOp>,
    /// `--set` overrides on top.
    overrides: Vec<(String, String)>,
}

fn override_pair() -> impl Strategy<Value = (String, String)> {
    let key = prop_oneof![
        select(KEYS).prop_map(|k| k.trim_matches('"').to_string()),
        (select(&["light", "object"][..]), 0usize..6, select(KEYS))
            .prop_map(|(s, i, k)| format!("{s}.{i}.{}", k.trim_matches('"'))),
        select(KEYS).prop_map(|k| format!("camera.{}", k.trim_matches('"'))),
        "[a-z._0-9]{0,12}",
    ];
    (key, raw().prop_map(|r| r.render()))
}

fn scene_case(max_ops: usize) -> impl Strategy<Value = SceneCase> {
    (
        any::<Index>(),
        prop::collection::vec(text_op(), 1..=max_ops),
        prop_oneof![3 => Just(Vec::new()), 1 => prop::collection::vec(override_pair(), 1..3)],
    )
        .prop_map(|(seed, ops, overrides)| SceneCase { seed, ops, overrides })
}

/// What must hold for a scene that loaded: every transform the renderer builds is finite.
fn scene_problem(scene: &Scene) -> Option<String> {
    let camera = scene.camera.clip_from_world(16.0 / 9.0);
    if !camera.is_finite() {
        return Some(format!("the camera's matrix is not finite: {:?}", scene.camera));
    }
    for (i, object) in scene.objects.iter().enumerate() {
        if !object.world_from_object(0.0).is_finite() {
            return Some(format!("object {i}'s transform is not finite"));
        }
        let (lo, hi) = object.world_bounds(0.0);
        if !(lo.is_finite() && hi.is_finite()) {
            return Some(format!("object {i}'s world bounds are not finite: {lo} .. {hi}"));
        }
    }
    for (i, light) in scene.lights.iter().enumerate() {
        if !light.clip_from_world(0.0).is_finite() {
            return Some(format!("light {i}'s matrix is not finite: {light:?}"));
        }
    }
    // The checks for an empty picture run on anything that loads, and say one line each.
    if let Some(w) =
        scene.warnings(0.0, 16.0 / 9.0).into_iter().find(|w| w.is_empty() || w.contains(['\n', '\r']))
    {
        return Some(format!("a warning that is not one line: {w:?}"));
    }
    scene.shadow.validate().err()
}

/// Names an error about a scene may give: the scene itself, or a mesh file (whose own error
/// starts with its path).
fn scene_error_names(label: &str, error: &SceneError) -> Vec<String> {
    let mut names = vec![label.to_string()];
    if let SceneError::Mesh(e) = error {
        // A mesh's error starts with the OBJ, MTL or texture path it is about.
        let message = e.to_string();
        if let Some((path, _)) = message.split_once(": ") {
            names.push(path.to_string());
        }
    }
    names
}

fn check_scene_text(
    dir: &Path,
    bytes: &[u8],
    overrides: &[(String, String)],
    tally: &Tally,
) -> Result<(), TestCaseError> {
    let path = dir.join("fuzz-case.toml");
    std::fs::write(&path, bytes).map_err(|e| fail(format!("write: {e}")))?;
    let fuzz_input = || {
        let mut input = bytes.to_vec();
        if !overrides.is_empty() {
            input.extend(format!("\n--- overrides {overrides:?}").bytes());
        }
        input
    };
    let (file, list) = (path.clone(), overrides.to_vec());
    let loaded = guarded(tally, &fuzz_input(), move || {
        load_scene(&file, &list).map(|scene| scene_problem(&scene)).map_err(|e| {
            let names = scene_error_names("fuzz-case.toml", &e);
            (e.to_string(), names)
        })
    })?;
    match loaded {
        Ok(None) => tally.count(true),
        Ok(Some(problem)) => {
            return Err(fail(format!(
                "accepted a scene that cannot render: {problem}\n--- input\n{}",
                shown(&fuzz_input())
            )));
        }
        Err((message, names)) => {
            tally.count(false);
            let names: Vec<&str> = names.iter().map(String::as_str).collect();
            // An override's error names the key instead of the file.
            let mut names = names;
            let keys: Vec<String> = overrides.iter().map(|(k, _)| format!("--set {k}")).collect();
            names.extend(keys.iter().map(String::as_str));
            check_message(&message, &names, &fuzz_input())?;
        }
    }
    // The same text through parse_scene_str, under another label.
    if let Ok(text) = std::str::from_utf8(bytes) {
        let (text, base, list) = (text.to_string(), dir.to_path_buf(), overrides.to_vec());
        let parsed = guarded(tally, &fuzz_input(), move || {
            parse_scene_str(&text, &base, "inline label.toml", &list)
                .map(|scene| scene_problem(&scene))
                .map_err(|e| {
                    let names = scene_error_names("inline label.toml", &e);
                    (e.to_string(), names)
                })
        })?;
        match parsed {
            Ok(None) => {}
            Ok(Some(problem)) => return Err(fail(format!("parse_scene_str accepted: {problem}"))),
            Err((message, mut names)) => {
                names.extend(overrides.iter().map(|(k, _)| format!("--set {k}")));
                let names: Vec<&str> = names.iter().map(String::as_str).collect();
                check_message(&message, &names, &fuzz_input())?;
            }
        }
    }
    Ok(())
}

fn fuzz_scenes(budget: Budget) {
    let tree = Tree::new();
    let mut seeds = tree.seeds("assets/scenes", "toml");
    seeds.extend(tree.seeds("scenes", "toml"));
    let donors = donors(&tree);
    let untouched = Untouched::new(&tree);
    fuzz("scenes", budget.scenes, budget, scene_case(3), |case, tally| {
        let seed = case.seed.get(&seeds);
        let bytes = mutate_toml(&seed.bytes, &case.ops, &donors);
        check_scene_text(&seed.dir, &bytes, &case.overrides, tally)?;
        untouched.check(&tree, &bytes)
    });
}

#[test]
fn scenes() {
    fuzz_scenes(DEFAULT);
}

// ---------------------------------------------------------------------------------------------
// Lessons.

fn fuzz_lessons(budget: Budget) {
    let tree = Tree::new();
    let seeds = tree.seeds("lessons", "toml");
    let donors = donors(&tree);
    let untouched = Untouched::new(&tree);
    let strategy = (any::<Index>(), prop::collection::vec(text_op(), 1..=3));
    fuzz("lessons", budget.lessons, budget, strategy, |(seed, ops), tally| {
        let seed = seed.get(&seeds);
        let bytes = mutate_toml(&seed.bytes, &ops, &donors);
        let path = seed.dir.join("fuzz-case.toml");
        std::fs::write(&path, &bytes).map_err(|e| fail(format!("write: {e}")))?;
        let result = guarded(tally, &bytes, move || {
            shadowlab::lessons::load_lesson(&path).map(|lesson| lesson.steps.len()).map_err(|e| e.to_string())
        })?;
        match result {
            Ok(0) => {
                return Err(fail(format!("a lesson without steps loaded\n--- input\n{}", shown(&bytes))));
            }
            Ok(_) => tally.count(true),
            Err(message) => {
                tally.count(false);
                check_message(&message, &["fuzz-case.toml"], &bytes)?;
            }
        }
        untouched.check(&tree, &bytes)
    });
}

#[test]
fn lessons() {
    fuzz_lessons(DEFAULT);
}

// ---------------------------------------------------------------------------------------------
// OBJ and MTL files: line-level mutations that know the format.

#[derive(Clone, Debug)]
enum Line {
    Fixed(&'static str),
    /// `v`, `vt` or `vn` with these components.
    Vector(&'static str, Vec<f64>),
    /// `f` with these (position, texture, normal) indices.
    Face(Vec<(i64, Option<i64>, Option<i64>)>),
    /// `f 1 2 3 ... n`.
    HugeFace(u32),
    /// `Kd`/`Ka`/`Ks` with these components.
    Color(&'static str, Vec<f64>),
}

impl Line {
    fn render(&self) -> String {
        let numbers = |v: &[f64]| v.iter().map(|x| format!("{x}")).collect::<Vec<_>>().join(" ");
        match self {
            Line::Fixed(s) => (*s).to_string(),
            Line::Vector(kind, v) => format!("{kind} {}", numbers(v)),
            Line::Face(refs) => {
                let refs: Vec<String> = refs
                    .iter()
                    .map(|(v, t, n)| match (t, n) {
                        (None, None) => v.to_string(),
                        (Some(t), None) => format!("{v}/{t}"),
                        (None, Some(n)) => format!("{v}//{n}"),
                        (Some(t), Some(n)) => format!("{v}/{t}/{n}"),
                    })
                    .collect();
                format!("f {}", refs.join(" ")).trim_end().to_string()
            }
            Line::HugeFace(n) => {
                let mut s = String::from("f");
                for i in 1..=*n {
                    s.push(' ');
                    s.push_str(&i.to_string());
                }
                s
            }
            Line::Color(kind, v) => format!("{kind} {}", numbers(v)),
        }
    }
}

const OBJ_LINES: &[&str] = &[
    "f",
    "f 1",
    "f 1 2",
    "f 1 1 1",
    "f 0 0 0",
    "f -1 -2 -3",
    "f 1 2 3 4 5 6 7 8",
    "f a b c",
    "f 1/ 2/ 3/",
    "f 1// 2// 3//",
    "f //1 //2 //3",
    "f 1/1/1/1 2 3",
    "l 1 2",
    "p 1",
    "v",
    "v 1",
    "v 1 2",
    "v 1 2 3 4 5",
    "v nan nan nan",
    "v inf 0 0",
    "v 1e39 0 0",
    "v -3.4e38 3.4e38 0",
    "vt",
    "vt nan",
    "vt 1e39 -1e39",
    "vn 0 0 0",
    "vn nan nan nan",
    "mtllib",
    "mtllib missing.mtl",
    "mtllib folder.obj",
    "mtllib /dev/zero",
    "mtllib /dev/null",
    "mtllib ../meshes/floor.mtl",
    "mtllib multi_material.mtl",
    "mtllib blender_export.mtl",
    "mtllib missing_texture.mtl",
    "mtllib fuzz-case.obj",
    "usemtl",
    "usemtl nonexistent",
    "usemtl floor_checker",
    "o",
    "o 💥",
    "g",
    "s off",
    "s 1",
    "#",
    "",
    "\\",
];

const MTL_LINES: &[&str] = &[
    "newmtl",
    "newmtl x",
    "newmtl floor_checker",
    "Kd",
    "Kd 1",
    "Kd nan nan nan",
    "Kd inf -inf 0",
    "Kd 1e39 -1 2",
    "Ka -1 -1 -1",
    "d nan",
    "Ns -1e38",
    "illum 99999999999",
    "map_Kd",
    "map_Kd ",
    "map_Kd missing.png",
    "map_Kd /dev/zero",
    "map_Kd /dev/null",
    "map_Kd .",
    "map_Kd ..",
    "map_Kd -s 1 1 1",
    "map_Kd -o",
    "map_Kd -blendu",
    "map_Kd -s nan nan nan tex_2x2.png",
    "map_Kd -mm 0 1 tex_2x2.png",
    "map_Kd -clamp on tex_2x2.png",
    "map_Kd tex_2x2.png",
    "map_Kd ../textures/checker.png",
    "map_Kd ..\\textures\\checker.png",
    "map_Kd ../meshes/bunny.obj",
    "map_Kd fuzz-case.mtl",
    "map_Kd ../obj/folder.obj",
    "map_Ka tex_2x2.png",
    "map_Bump missing.png",
    "#",
    "",
];

fn extreme_f64() -> impl Strategy<Value = f64> {
    prop_oneof![
        select(&[f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 1e38, -1e38, 3.5e38, 1e-45, 0.0, -0.0, 1e6][..]),
        -10.0f64..10.0,
        any::<f64>(),
    ]
}

fn obj_line() -> BoxedStrategy<Line> {
    let index = prop_oneof![
        4 => 1i64..12,
        2 => -12i64..0,
        1 => select(&[0i64, 1_000_000, -1_000_000, i64::MAX, i64::MIN, 4_294_967_295, 4_294_967_296, 2_147_483_648][..]),
    ];
    let reference = (index.clone(), prop::option::of(index.clone()), prop::option::of(index));
    prop_oneof![
        4 => select(OBJ_LINES).prop_map(Line::Fixed),
        2 => (select(&["v", "vt", "vn"][..]), prop::collection::vec(extreme_f64(), 0..5))
            .prop_map(|(kind, v)| Line::Vector(kind, v)),
        3 => prop::collection::vec(reference, 0..6).prop_map(Line::Face),
        1 => prop_oneof![3u32..100, 1000u32..60_000].prop_map(Line::HugeFace),
    ]
    .boxed()
}

fn mtl_line() -> BoxedStrategy<Line> {
    prop_oneof![
        4 => select(MTL_LINES).prop_map(Line::Fixed),
        2 => (select(&["Kd", "Ka", "Ks"][..]), prop::collection::vec(extreme_f64(), 0..5))
            .prop_map(|(kind, v)| Line::Color(kind, v)),
    ]
    .boxed()
}

#[derive(Clone, Debug)]
enum LineOp {
    Replace {
        at: Index,
        line: Line,
    },
    Insert {
        at: Index,
        line: Line,
    },
    Delete {
        at: Index,
    },
    /// Repeat `len` lines from `at`, `times` times (huge counts).
    Repeat {
        at: Index,
        len: u8,
        times: u16,
    },
    Byte(ByteOp),
}

fn line_op(line: impl Strategy<Value = Line> + Clone) -> impl Strategy<Value = LineOp> {
    prop_oneof![
        3 => (any::<Index>(), line.clone()).prop_map(|(at, line)| LineOp::Replace { at, line }),
        3 => (any::<Index>(), line).prop_map(|(at, line)| LineOp::Insert { at, line }),
        1 => any::<Index>().prop_map(|at| LineOp::Delete { at }),
        1 => (any::<Index>(), 1u8..8, prop_oneof![2u16..20, 1000u16..20_000])
            .prop_map(|(at, len, times)| LineOp::Repeat { at, len, times }),
        2 => byte_op().prop_map(LineOp::Byte),
    ]
}

fn mutate_lines(seed: &[u8], ops: &[LineOp], donors: &[Vec<u8>]) -> Vec<u8> {
    let mut bytes = seed.to_vec();
    for op in ops {
        if let LineOp::Byte(op) = op {
            apply_byte_op(&mut bytes, op, donors);
            continue;
        }
        let text = String::from_utf8_lossy(&bytes).into_owned();
        let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
        let n = lines.len();
        match op {
            LineOp::Replace { at, line } if n > 0 => lines[at.index(n)] = line.render(),
            LineOp::Replace { line, .. } => lines.push(line.render()),
            LineOp::Insert { at, line } => lines.insert(at.index(n + 1), line.render()),
            LineOp::Delete { at } if n > 0 => {
                lines.remove(at.index(n));
            }
            LineOp::Repeat { at, len, times } if n > 0 => {
                let at = at.index(n);
                let chunk: Vec<String> = lines[at..(at + usize::from(*len)).min(n)].to_vec();
                let chunk_bytes: usize = chunk.iter().map(|l| l.len() + 1).sum();
                let times = usize::from(*times).min(MAX_INPUT / chunk_bytes.max(1));
                let copies: Vec<String> = (0..times).flat_map(|_| chunk.iter().cloned()).collect();
                lines.splice(at..at, copies);
            }
            LineOp::Delete { .. } | LineOp::Repeat { .. } | LineOp::Byte(_) => {}
        }
        bytes = (lines.join("\n") + "\n").into_bytes();
        bytes.truncate(MAX_INPUT);
    }
    bytes
}

/// What must hold for a mesh that loaded.
fn mesh_problem(mesh: &Mesh) -> Option<String> {
    let vertex_count = mesh.vertices.len();
    if mesh.indices.is_empty() || !mesh.indices.len().is_multiple_of(3) {
        return Some(format!("{} indices", mesh.indices.len()));
    }
    if let Some(i) = mesh.indices.iter().find(|&&i| i as usize >= vertex_count) {
        return Some(format!("index {i} of {vertex_count} vertices"));
    }
    for part in &mesh.parts {
        let end = u64::from(part.index_start) + u64::from(part.index_count);
        if end > mesh.indices.len() as u64 || part.material.is_some_and(|m| m >= mesh.materials.len()) {
            return Some(format!("part {part:?} out of range"));
        }
    }
    for v in &mesh.vertices {
        if !v.position.iter().chain(&v.normal).chain(&v.uv).all(|x| x.is_finite()) {
            return Some(format!("a vertex that is not finite: {v:?}"));
        }
    }
    for m in &mesh.materials {
        if !m.diffuse.is_finite() {
            return Some(format!("material `{}` has diffuse {}", m.name, m.diffuse));
        }
        if let Some(t) = &m.diffuse_texture {
            let texels = u64::from(t.width) * u64::from(t.height);
            if t.width == 0 || t.height == 0 || texels * 4 != t.rgba8.len() as u64 {
                return Some(format!("texture {}x{} with {} bytes", t.width, t.height, t.rgba8.len()));
            }
        }
    }
    None
}

/// Load `path` as an OBJ on a guarded thread: Ok(None) if it loaded and is sane.
fn check_obj(path: &Path, names: &[&str], input: &[u8], tally: &Tally) -> Result<(), TestCaseError> {
    let file = path.to_path_buf();
    let loaded =
        guarded(tally, input, move || load_obj(&file).map(|m| mesh_problem(&m)).map_err(|e| e.to_string()))?;
    match loaded {
        Ok(None) => {
            tally.count(true);
            Ok(())
        }
        Ok(Some(problem)) => {
            Err(fail(format!("loaded a broken mesh: {problem}\n--- input\n{}", shown(input))))
        }
        Err(message) => {
            tally.count(false);
            // Or a file the OBJ names (an MTL, a texture): the message then starts with its path
            // (every path here is absolute).
            let mut names = names.to_vec();
            names.extend(message.split_once(": ").map(|(path, _)| path).filter(|p| p.starts_with('/')));
            check_message(&message, &names, input)
        }
    }
}

fn fuzz_objs(budget: Budget) {
    let tree = Tree::new();
    let mut seeds = tree.seeds("assets/meshes", "obj");
    seeds.extend(tree.seeds("obj", "obj"));
    let donors = donors(&tree);
    let untouched = Untouched::new(&tree);
    let strategy = (any::<Index>(), prop::collection::vec(line_op(obj_line()), 1..=4));
    fuzz("obj", budget.objs, budget, strategy, |(seed, ops), tally| {
        let seed = seed.get(&seeds);
        let bytes = mutate_lines(&seed.bytes, &ops, &donors);
        let path = seed.dir.join("fuzz-case.obj");
        std::fs::write(&path, &bytes).map_err(|e| fail(format!("write: {e}")))?;
        check_obj(&path, &["fuzz-case.obj"], &bytes, tally)?;
        untouched.check(&tree, &bytes)
    });
}

#[test]
fn obj_files() {
    fuzz_objs(DEFAULT);
}

fn fuzz_mtls(budget: Budget) {
    let tree = Tree::new();
    // Each MTL with the OBJ that names it; the mutant is written as fuzz-case.mtl and a copy of
    // the OBJ (fuzz-mtl.obj) names that instead.
    let pairs = [
        ("assets/meshes", "floor.obj", "floor.mtl"),
        ("obj", "blender_export.obj", "blender_export.mtl"),
        ("obj", "multi_material.obj", "multi_material.mtl"),
        ("obj", "missing_texture.obj", "missing_texture.mtl"),
    ];
    let mut seeds = Vec::new();
    for (folder, obj, mtl) in pairs {
        let dir = tree.path(folder);
        let obj_text = std::fs::read_to_string(dir.join(obj)).expect("read obj");
        let obj_text = obj_text.replace(&format!("mtllib {mtl}"), "mtllib fuzz-case.mtl");
        assert!(obj_text.contains("mtllib fuzz-case.mtl"), "{obj} names {mtl}");
        let obj_path = dir.join(format!("fuzz-mtl-{obj}"));
        std::fs::write(&obj_path, &obj_text).expect("write obj");
        seeds.push((obj_path, dir.join("fuzz-case.mtl"), std::fs::read(dir.join(mtl)).expect("read mtl")));
    }
    let donors = donors(&tree);
    let untouched = Untouched::new(&tree);
    let strategy = (any::<Index>(), prop::collection::vec(line_op(mtl_line()), 1..=4));
    fuzz("mtl", budget.mtls, budget, strategy, |(seed, ops), tally| {
        let (obj, mtl, seed) = seed.get(&seeds);
        let bytes = mutate_lines(seed, &ops, &donors);
        std::fs::write(mtl, &bytes).map_err(|e| fail(format!("write: {e}")))?;
        check_obj(obj, &["fuzz-case.mtl"], &bytes, tally)?;
        untouched.check(&tree, &bytes)
    });
}

#[test]
fn mtl_files() {
    fuzz_mtls(DEFAULT);
}

// ---------------------------------------------------------------------------------------------
// Textures: PNG chunks rewritten (header fields with their CRC fixed, chunks dropped, doubled or
// cut) and bytes mutated, loaded through an MTL's map_Kd.

#[derive(Clone, Debug)]
enum PngOp {
    Byte(ByteOp),
    /// New width and height in IHDR (CRC fixed).
    Size {
        width: u32,
        height: u32,
    },
    /// New bit depth, colour type and interlace method in IHDR (CRC fixed).
    Format {
        depth: u8,
        color: u8,
        interlace: u8,
    },
    DropChunk {
        which: Index,
    },
    DuplicateChunk {
        which: Index,
    },
    /// Cut a chunk's data short (its length field kept, so the file ends early or misreads).
    CutChunk {
        which: Index,
        keep: Index,
    },
}

fn dimension() -> impl Strategy<Value = u32> {
    prop_oneof![
        select(&[0u32, 1, 2, 3, 255, 256, 8192, 8193, 16384, 65535, 1 << 20, (1 << 31) - 1, u32::MAX][..]),
        any::<u32>(),
    ]
}

fn png_op() -> impl Strategy<Value = PngOp> {
    prop_oneof![
        3 => byte_op().prop_map(PngOp::Byte),
        2 => (dimension(), dimension()).prop_map(|(width, height)| PngOp::Size { width, height }),
        2 => (select(&[0u8, 1, 2, 4, 8, 16, 3, 255][..]), select(&[0u8, 1, 2, 3, 4, 6, 7][..]), 0u8..3)
            .prop_map(|(depth, color, interlace)| PngOp::Format { depth, color, interlace }),
        1 => any::<Index>().prop_map(|which| PngOp::DropChunk { which }),
        1 => any::<Index>().prop_map(|which| PngOp::DuplicateChunk { which }),
        1 => (any::<Index>(), any::<Index>()).prop_map(|(which, keep)| PngOp::CutChunk { which, keep }),
    ]
}

fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = 0xffff_ffffu32;
    for &b in bytes {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 == 1 { (crc >> 1) ^ 0xedb8_8320 } else { crc >> 1 };
        }
    }
    !crc
}

/// The chunks of a PNG: (start of the length field, end of the CRC).
fn png_chunks(bytes: &[u8]) -> Vec<Range<usize>> {
    let mut out = Vec::new();
    let mut at = 8;
    while at + 12 <= bytes.len() {
        let len = u32::from_be_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]) as usize;
        let end = at.saturating_add(12).saturating_add(len);
        if end > bytes.len() {
            break;
        }
        out.push(at..end);
        at = end;
    }
    out
}

/// Rewrite IHDR's data (bytes 8.. of the file's first chunk) and fix its CRC.
fn edit_ihdr(bytes: &mut [u8], edit: impl FnOnce(&mut [u8])) {
    if bytes.len() < 33 || &bytes[12..16] != b"IHDR" {
        return;
    }
    edit(&mut bytes[16..29]);
    let crc = crc32(&bytes[12..29]);
    bytes[29..33].copy_from_slice(&crc.to_be_bytes());
}

fn mutate_png(seed: &[u8], ops: &[PngOp], donors: &[Vec<u8>]) -> Vec<u8> {
    let mut bytes = seed.to_vec();
    for op in ops {
        match op {
            PngOp::Byte(op) => apply_byte_op(&mut bytes, op, donors),
            PngOp::Size { width, height } => edit_ihdr(&mut bytes, |d| {
                d[0..4].copy_from_slice(&width.to_be_bytes());
                d[4..8].copy_from_slice(&height.to_be_bytes());
            }),
            PngOp::Format { depth, color, interlace } => edit_ihdr(&mut bytes, |d| {
                d[8] = *depth;
                d[9] = *color;
                d[12] = *interlace;
            }),
            PngOp::DropChunk { which } | PngOp::DuplicateChunk { which } | PngOp::CutChunk { which, .. } => {
                let chunks = png_chunks(&bytes);
                if chunks.is_empty() {
                    continue;
                }
                let chunk = which.get(&chunks).clone();
                match op {
                    PngOp::DropChunk { .. } => {
                        bytes.drain(chunk);
                    }
                    PngOp::DuplicateChunk { .. } => {
                        let copy = bytes[chunk.clone()].to_vec();
                        bytes.splice(chunk.end..chunk.end, copy);
                    }
                    PngOp::CutChunk { keep, .. } => {
                        let data = chunk.start + 8..chunk.end - 4;
                        let cut = data.start + keep.index(data.len() + 1);
                        bytes.drain(cut..data.end);
                    }
                    _ => {}
                }
            }
        }
    }
    bytes
}

/// Small images of odd shapes for the texture seeds: one texel, one row, one column, and one
/// row wider than any GPU's texture limit; a JPEG too.
fn generated_textures() -> Vec<(String, Vec<u8>)> {
    let encode = |w: u32, h: u32, format: image::ImageFormat| {
        let image =
            image::RgbaImage::from_fn(w, h, |x, y| image::Rgba([(x * 37) as u8, (y * 91) as u8, 200, 255]));
        let mut out = std::io::Cursor::new(Vec::new());
        let image = image::DynamicImage::ImageRgba8(image);
        let image = if format == image::ImageFormat::Jpeg {
            image::DynamicImage::ImageRgb8(image.to_rgb8())
        } else {
            image
        };
        image.write_to(&mut out, format).expect("encode");
        out.into_inner()
    };
    vec![
        ("1x1.png".into(), encode(1, 1, image::ImageFormat::Png)),
        ("7x1.png".into(), encode(7, 1, image::ImageFormat::Png)),
        ("1x300.png".into(), encode(1, 300, image::ImageFormat::Png)),
        ("16385x1.png".into(), encode(16_385, 1, image::ImageFormat::Png)),
        ("8x8.jpg".into(), encode(8, 8, image::ImageFormat::Jpeg)),
    ]
}

fn fuzz_textures(budget: Budget) {
    let tree = Tree::new();
    let meshes = tree.path("assets/meshes");
    let obj = std::fs::read_to_string(meshes.join("floor.obj")).expect("floor.obj");
    std::fs::write(meshes.join("fuzz-tex.obj"), obj.replace("mtllib floor.mtl", "mtllib fuzz-tex.mtl"))
        .expect("write obj");
    let mtl = std::fs::read_to_string(meshes.join("floor.mtl")).expect("floor.mtl");
    std::fs::write(meshes.join("fuzz-tex.mtl"), mtl.replace("checker.png", "fuzz-case.png"))
        .expect("write mtl");
    let mut seeds: Vec<Vec<u8>> = vec![
        std::fs::read(tree.path("assets/textures/checker.png")).expect("checker.png"),
        std::fs::read(tree.path("obj/tex_2x2.png")).expect("tex_2x2.png"),
    ];
    seeds.extend(generated_textures().into_iter().map(|(_, bytes)| bytes));
    let donors = donors(&tree);
    let untouched = Untouched::new(&tree);
    let obj = meshes.join("fuzz-tex.obj");
    let texture = tree.path("assets/textures/fuzz-case.png");
    let strategy = (any::<Index>(), prop::collection::vec(png_op(), 0..=3));
    fuzz("textures", budget.textures, budget, strategy, |(seed, ops), tally| {
        let seed: &Vec<u8> = seed.get(&seeds);
        let bytes = mutate_png(seed, &ops, &donors);
        std::fs::write(&texture, &bytes).map_err(|e| fail(format!("write: {e}")))?;
        let input = format!("PNG of {} bytes, ops {ops:?}", bytes.len());
        let file = obj.clone();
        let loaded = guarded(tally, input.as_bytes(), move || {
            load_obj(&file)
                .map(|m| match &m.materials[0].diffuse_texture {
                    Some(t) => mesh_problem(&m).or_else(|| {
                        (t.width > 8192 || t.height > 8192).then(|| {
                            format!("a {}x{} texture was accepted (GPUs take 8192)", t.width, t.height)
                        })
                    }),
                    None => Some("the texture is gone".into()),
                })
                .map_err(|e| e.to_string())
        })?;
        match loaded {
            Ok(None) => tally.count(true),
            Ok(Some(problem)) => return Err(fail(format!("{problem}: {input}"))),
            Err(message) => {
                tally.count(false);
                check_message(&message, &["fuzz-case.png"], input.as_bytes())?;
                check_message(&message, &["fuzz-tex.mtl"], input.as_bytes())?;
            }
        }
        untouched.check(&tree, input.as_bytes())
    });
}

#[test]
fn textures() {
    fuzz_textures(DEFAULT);
}

// ---------------------------------------------------------------------------------------------
// The process: `shadowlab render` on mutated scenes.

/// Run a command to completion or kill it after `limit`.
fn run_bounded(command: &mut std::process::Command, limit: Duration) -> Result<common::Run, TestCaseError> {
    use std::io::Read;
    let mut child = command
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .map_err(|e| fail(format!("cannot run shadowlab: {e}")))?;
    // Read both pipes on threads so a chatty child never blocks on a full pipe.
    let mut stdout = child.stdout.take().expect("stdout");
    let mut stderr = child.stderr.take().expect("stderr");
    let out = std::thread::spawn(move || {
        let mut s = Vec::new();
        let _ = stdout.read_to_end(&mut s);
        s
    });
    let err = std::thread::spawn(move || {
        let mut s = Vec::new();
        let _ = stderr.read_to_end(&mut s);
        s
    });
    let started = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().map_err(|e| fail(format!("wait: {e}")))? {
            break status;
        }
        if started.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            return Err(fail(format!("shadowlab did not finish within {} s", limit.as_secs())));
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let text = |bytes: Vec<u8>| String::from_utf8_lossy(&bytes).into_owned();
    let run = common::Run {
        code: status.code(),
        stdout: text(out.join().unwrap_or_default()),
        stderr: text(err.join().unwrap_or_default()),
    };
    #[cfg(unix)]
    if let Some(signal) = std::os::unix::process::ExitStatusExt::signal(&status) {
        return Err(fail(format!("shadowlab was killed by signal {signal}\n{run}")));
    }
    Ok(run)
}

fn fuzz_cli(budget: Budget) {
    let tree = Tree::new();
    let seeds = tree.seeds("assets/scenes", "toml");
    let donors = donors(&tree);
    let count = AtomicUsize::new(0);
    // Numbers replaced by numbers, mostly plausible ones, so most cases get past the parser and
    // many past the checks to the renderer.
    let number = prop_oneof![
        3 => (-100.0f64..100.0).prop_map(Raw::Float),
        1 => select(&[1e38, -1e38, 1e7, 0.0, -0.0, 1e-7, 1.0][..]).prop_map(Raw::Float),
        1 => (0i64..10_000).prop_map(Raw::Int),
        2 => [-50.0f64..50.0, -50.0f64..50.0, -50.0f64..50.0].prop_map(Raw::Vec3),
    ];
    let op = (any::<Index>(), number).prop_map(|(node, raw)| TextOp::Toml(TomlOp::SetValue { node, raw }));
    let strategy = (any::<Index>(), prop::collection::vec(op, 1..=2));
    fuzz("cli", budget.cli, budget, strategy, |(seed, ops), tally| {
        let seed = seed.get(&seeds);
        let bytes = mutate_toml(&seed.bytes, &ops, &donors);
        let scene = seed.dir.join("fuzz-case.toml");
        std::fs::write(&scene, &bytes).map_err(|e| fail(format!("write: {e}")))?;
        let out_dir = tree.path(&format!("fuzz-out-{}", count.fetch_add(1, Ordering::Relaxed)));
        std::fs::create_dir_all(&out_dir).map_err(|e| fail(format!("mkdir: {e}")))?;
        let out = out_dir.join("x.png");
        let mut command = common::shadowlab_command();
        command.args(["render", "--size", "32x18", "--scene"]).arg(&scene).arg("--out").arg(&out);
        let run = run_bounded(&mut command, PROCESS_LIMIT)?;
        let leftovers: Vec<String> = std::fs::read_dir(&out_dir)
            .map(|d| d.flatten().map(|e| e.file_name().to_string_lossy().into_owned()).collect())
            .unwrap_or_default();
        let context = || format!("{run}\n--- scene\n{}", shown(&bytes));
        match run.code {
            Some(0) => {
                tally.count(true);
                if leftovers != ["x.png"] {
                    return Err(fail(format!(
                        "a good render leaves x.png alone, found {leftovers:?}\n{}",
                        context()
                    )));
                }
                // Only warnings on stderr.
                if let Some(line) = run.stderr.lines().find(|l| !l.starts_with("shadowlab: warning: ")) {
                    return Err(fail(format!("unexpected stderr line {line:?}\n{}", context())));
                }
            }
            Some(2) => {
                tally.count(false);
                if !leftovers.is_empty() {
                    return Err(fail(format!("a failed render left {leftovers:?}\n{}", context())));
                }
                if !run.stderr.starts_with("shadowlab: ") || !run.stdout.is_empty() {
                    return Err(fail(format!(
                        "a refusal is one `shadowlab: ` line on stderr\n{}",
                        context()
                    )));
                }
                check_message(
                    run.stderr.trim_end(),
                    &["fuzz-case.toml", &tree.root.path().display().to_string()],
                    &bytes,
                )?;
            }
            _ => return Err(fail(format!("exit code must be 0 or 2\n{}", context()))),
        }
        let _ = std::fs::remove_dir_all(&out_dir);
        Ok(())
    });
}

#[test]
fn cli_render() {
    fuzz_cli(DEFAULT);
}

// ---------------------------------------------------------------------------------------------
// Homework shaders: the shipped examples and the test samples, mutated byte by byte and line by
// line, rewritten and translated (every error one line naming the student's file), and a few run
// whole by `shadowlab homework`.

/// A line-level or number-level edit of a shader.
#[derive(Clone, Debug)]
enum ShaderOp {
    Byte(ByteOp),
    DeleteLine(Index),
    DuplicateLine(Index),
    SwapLines(Index, Index),
    /// Replace a number in the text by another.
    Number(Index, &'static str),
}

const SHADER_NUMBERS: [&str; 12] =
    ["0", "0.0", "-1.0", "1e-9", "1e30", "100000", "4096", "2", "0.5", "-0.0", "255.0", "65536"];

fn shader_op() -> impl Strategy<Value = ShaderOp> {
    prop_oneof![
        3 => byte_op().prop_map(ShaderOp::Byte),
        1 => any::<Index>().prop_map(ShaderOp::DeleteLine),
        1 => any::<Index>().prop_map(ShaderOp::DuplicateLine),
        1 => (any::<Index>(), any::<Index>()).prop_map(|(a, b)| ShaderOp::SwapLines(a, b)),
        3 => (any::<Index>(), select(&SHADER_NUMBERS[..])).prop_map(|(at, n)| ShaderOp::Number(at, n)),
    ]
}

/// The byte ranges of the number literals in `text`.
fn numbers(text: &str) -> Vec<Range<usize>> {
    let bytes = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        let starts = bytes[i].is_ascii_digit()
            && (i == 0 || !(bytes[i - 1].is_ascii_alphanumeric() || bytes[i - 1] == b'_'));
        if starts {
            let start = i;
            while i < bytes.len() && (bytes[i].is_ascii_digit() || bytes[i] == b'.') {
                i += 1;
            }
            out.push(start..i);
        } else {
            i += 1;
        }
    }
    out
}

fn mutate_shader(seed: &[u8], ops: &[ShaderOp], donors: &[Vec<u8>]) -> Vec<u8> {
    let mut bytes = seed.to_vec();
    for op in ops {
        let text = String::from_utf8_lossy(&bytes).into_owned();
        let mut lines: Vec<&str> = text.split('\n').collect();
        let n = lines.len();
        match op {
            ShaderOp::Byte(op) => apply_byte_op(&mut bytes, op, donors),
            ShaderOp::DeleteLine(at) => {
                lines.remove(at.index(n));
                bytes = lines.join("\n").into_bytes();
            }
            ShaderOp::DuplicateLine(at) => {
                let at = at.index(n);
                lines.insert(at, lines[at]);
                bytes = lines.join("\n").into_bytes();
            }
            ShaderOp::SwapLines(a, b) => {
                lines.swap(a.index(n), b.index(n));
                bytes = lines.join("\n").into_bytes();
            }
            ShaderOp::Number(at, number) => {
                let found = numbers(&text);
                if !found.is_empty() {
                    let range = found[at.index(found.len())].clone();
                    let mut edited = text.clone();
                    edited.replace_range(range, number);
                    bytes = edited.into_bytes();
                }
            }
        }
    }
    bytes
}

fn shader_seeds() -> Vec<Vec<u8>> {
    let mut seeds = Vec::new();
    for dir in ["assets/homework", "tests/data/homework"] {
        let mut paths: Vec<PathBuf> = std::fs::read_dir(repo_path(dir))
            .expect("a shader folder")
            .flatten()
            .map(|e| e.path())
            .filter(|p| p.file_name().is_some_and(|n| n.to_string_lossy().starts_with("phongFragment")))
            .collect();
        paths.sort();
        seeds.extend(paths.iter().map(|p| std::fs::read(p).expect("a shader")));
    }
    seeds
}

fn fuzz_shaders(budget: Budget) {
    use shadowlab::homework::{HomeworkFiles, HomeworkProgram, ShaderSource};
    let seeds = shader_seeds();
    let dir = tempfile::tempdir().expect("a scratch folder");
    let path = dir.path().join("fuzz.glsl");
    let strategy = (any::<Index>(), prop::collection::vec(shader_op(), 1..=3));
    fuzz("shaders", budget.shaders, budget, strategy, |(seed, ops), tally| {
        let seed: &Vec<u8> = seed.get(&seeds);
        let bytes = mutate_shader(seed, &ops, &seeds);
        std::fs::write(&path, &bytes).map_err(|e| fail(format!("write: {e}")))?;
        let read_from = path.clone();
        let result = guarded(tally, &bytes, move || {
            let source = ShaderSource::read(&read_from)?;
            HomeworkProgram::translate(HomeworkFiles::with_framework(source))
                .map(|p| p.camera.fragment.wgsl.len())
        })?;
        match result {
            Ok(_) => tally.count(true),
            Err(e) => {
                tally.count(false);
                let message = e.to_string();
                // An error names the student's file (a framework stage's own errors would be ours).
                if !message.starts_with("fuzz.glsl") && !message.contains("fuzz.glsl:") {
                    return Err(fail(format!(
                        "the error does not name the file: {message}\n--- input\n{}",
                        shown(&bytes)
                    )));
                }
                check_message(&message, &["fuzz.glsl"], &bytes)?;
            }
        }
        Ok(())
    });
}

#[test]
fn homework_shaders() {
    fuzz_shaders(DEFAULT);
}

fn fuzz_cli_homework(budget: Budget) {
    let seeds: Vec<Vec<u8>> = shader_seeds().into_iter().take(2).collect();
    let dir = tempfile::tempdir().expect("a scratch folder");
    let count = AtomicUsize::new(0);
    // Numbers replaced, mostly: most cases compile and run.
    let op = prop_oneof![
        5 => (any::<Index>(), select(&SHADER_NUMBERS[..])).prop_map(|(at, n)| ShaderOp::Number(at, n)),
        1 => any::<Index>().prop_map(ShaderOp::DeleteLine),
    ];
    let strategy = (any::<Index>(), prop::collection::vec(op, 1..=2));
    fuzz("cli homework", budget.cli_homework, budget, strategy, |(seed, ops), tally| {
        let seed: &Vec<u8> = seed.get(&seeds);
        let bytes = mutate_shader(seed, &ops, &seeds);
        let case = count.fetch_add(1, Ordering::Relaxed);
        let shader = dir.path().join(format!("fuzz-{case}.glsl"));
        std::fs::write(&shader, &bytes).map_err(|e| fail(format!("write: {e}")))?;
        let out = dir.path().join(format!("out-{case}"));
        let mut command = common::shadowlab_command();
        command.args(["homework", "--size", "64x36"]).arg(&shader).arg("--out").arg(&out);
        let run = run_bounded(&mut command, PROCESS_LIMIT)?;
        let context = || format!("{run}\n--- shader\n{}", shown(&bytes));
        match run.code {
            Some(0) => {
                tally.count(true);
                if !out.join("report.json").is_file() || !out.join("student.png").is_file() {
                    return Err(fail(format!("a check writes report.json and the pictures\n{}", context())));
                }
            }
            Some(2) => {
                tally.count(false);
                if run.stderr.lines().count() != 1 || !run.stderr.starts_with("shadowlab: ") {
                    return Err(fail(format!(
                        "a refusal is one `shadowlab: ` line on stderr\n{}",
                        context()
                    )));
                }
                if out.join("student.png").exists() {
                    return Err(fail(format!("a shader that did not compile got a picture\n{}", context())));
                }
            }
            _ => return Err(fail(format!("exit code must be 0 or 2\n{}", context()))),
        }
        Ok(())
    });
}

#[test]
fn cli_homework() {
    fuzz_cli_homework(DEFAULT);
}

// ---------------------------------------------------------------------------------------------
// The long run.

#[test]
#[ignore = "long run: cargo test --release --test fuzz -- --ignored"]
fn long_run_scenes() {
    fuzz_scenes(LONG);
}

#[test]
#[ignore = "long run: cargo test --release --test fuzz -- --ignored"]
fn long_run_lessons() {
    fuzz_lessons(LONG);
}

#[test]
#[ignore = "long run: cargo test --release --test fuzz -- --ignored"]
fn long_run_obj_files() {
    fuzz_objs(LONG);
}

#[test]
#[ignore = "long run: cargo test --release --test fuzz -- --ignored"]
fn long_run_mtl_files() {
    fuzz_mtls(LONG);
}

#[test]
#[ignore = "long run: cargo test --release --test fuzz -- --ignored"]
fn long_run_textures() {
    fuzz_textures(LONG);
}

#[test]
#[ignore = "long run: cargo test --release --test fuzz -- --ignored"]
fn long_run_cli_render() {
    fuzz_cli(LONG);
}

#[test]
#[ignore = "long run: cargo test --release --test fuzz -- --ignored"]
fn long_run_homework_shaders() {
    fuzz_shaders(LONG);
}

#[test]
#[ignore = "long run: cargo test --release --test fuzz -- --ignored"]
fn long_run_cli_homework() {
    fuzz_cli_homework(LONG);
}

// ---------------------------------------------------------------------------------------------
// Page addresses: a link's query (`?lesson=pcss&step=3&lang=zh`) as a teacher, a student or a
// mangled copy-paste writes it.

const LINK_SEEDS: [&str; 6] = [
    "?lesson=pcss&step=3&lang=zh",
    "?scene=contact&technique=pcf",
    "?lesson=2&step=1&lang=en",
    "?backend=webgl2&lesson=multi-light&step=4",
    "?scene=games202&technique=pcss&lang=zh",
    "lesson=homework&step=6",
];
/// Values spliced in for a value: real names, numbers at the edges, escapes, other scripts.
const LINK_VALUES: [&str; 16] = [
    "pcss",
    "7",
    "0",
    "-1",
    "4294967296",
    "99999999999999999999",
    "%41",
    "%",
    "%zz",
    "%E4%B8%AD",
    "中文",
    "",
    "../../etc/passwd",
    "contact%00",
    "vsm",
    "+",
];

#[derive(Clone, Debug)]
enum LinkOp {
    Byte(ByteOp),
    /// Replace the value of the `n`th pair.
    Value(Index, &'static str),
    /// Repeat the query (many pairs, the same keys twice).
    Repeat(u8),
}

fn link_op() -> impl Strategy<Value = LinkOp> {
    prop_oneof![
        2 => byte_op().prop_map(LinkOp::Byte),
        4 => (any::<Index>(), select(&LINK_VALUES[..])).prop_map(|(at, v)| LinkOp::Value(at, v)),
        1 => (1u8..=200).prop_map(LinkOp::Repeat),
    ]
}

fn mutate_link(seed: &str, ops: &[LinkOp]) -> String {
    let donors: Vec<Vec<u8>> = LINK_SEEDS.iter().map(|s| s.as_bytes().to_vec()).collect();
    let mut query = seed.to_string();
    for op in ops {
        match op {
            LinkOp::Byte(op) => {
                let mut bytes = query.into_bytes();
                apply_byte_op(&mut bytes, op, &donors);
                query = String::from_utf8_lossy(&bytes).into_owned();
            }
            LinkOp::Value(at, value) => {
                let mut pairs: Vec<String> = query.split('&').map(str::to_owned).collect();
                let i = at.index(pairs.len());
                let key = pairs[i].split('=').next().unwrap_or_default().to_owned();
                pairs[i] = format!("{key}={value}");
                query = pairs.join("&");
            }
            LinkOp::Repeat(n) => query = vec![query.as_str(); usize::from(*n)].join("&"),
        }
    }
    query
}

fn fuzz_links(budget: Budget) {
    use shadowlab::app::{AppState, Settings, link};
    let strategy = (select(&LINK_SEEDS[..]), prop::collection::vec(link_op(), 1..=2));
    fuzz("links", budget.links, budget, strategy, |(seed, ops), tally| {
        let query = mutate_link(seed, &ops);
        let mut state = AppState::new(Settings::default());
        let (wanted, problems) = link::parse(&query);
        state.follow_link(&wanted, problems);
        let error = state.error.as_ref().map(|e| e.to_string());
        tally.count(error.is_none());
        if let Some(error) = &error
            && error.contains('\n')
        {
            return Err(fail(format!("not one line: {error}\n--- query\n{query}")));
        }
        // Wherever it went, the address the page then shows leads back to the same place.
        let address = state.link();
        let (again, problems) = link::parse(&address);
        if !problems.is_empty() {
            return Err(fail(format!("{query} led to {address}, which reads with {problems:?}")));
        }
        let mut followed = AppState::new(Settings::default());
        followed.follow_link(&again, problems);
        if followed.link() != address || followed.error.is_some() {
            return Err(fail(format!(
                "{query} led to {address}; following that gives {} ({:?})",
                followed.link(),
                followed.error.as_ref().map(|e| e.to_string())
            )));
        }
        Ok(())
    });
}

#[test]
fn links() {
    fuzz_links(DEFAULT);
}

#[test]
#[ignore = "long run: cargo test --release --test fuzz -- --ignored"]
fn long_run_links() {
    fuzz_links(LONG);
}

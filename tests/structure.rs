//! The shape ARCHITECTURE.md describes, held: the modules of each folder of src/ (the top-level
//! ones too) name each other without circles, no source file is past 500 lines (test code aside),
//! the twin's formulas and the GPU parameters are made in one place each, and every source a
//! comment cites is an entry of docs/REFERENCES.md.

mod module_graph;

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

const MAX_LINES: usize = 500;

fn sources() -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        for entry in std::fs::read_dir(dir).expect("src is readable").flatten() {
            let path = entry.path();
            if path.is_dir() {
                walk(&path, out);
            } else if path.extension().is_some_and(|e| e == "rs") {
                out.push(path);
            }
        }
    }
    let mut out = Vec::new();
    walk(&Path::new(env!("CARGO_MANIFEST_DIR")).join("src"), &mut out);
    out.sort();
    out
}

/// The file's code without its unit tests: a `tests.rs` file is all test code, and a
/// `#[cfg(test)]` module runs to the end of its file.
fn code_of(path: &Path) -> String {
    if path.file_name().is_some_and(|n| n == "tests.rs" || n == "mesh_tests.rs") {
        return String::new();
    }
    let text = std::fs::read_to_string(path).expect("a source file");
    match text.find("#[cfg(test)]\nmod tests") {
        Some(at) => text[..at].to_string(),
        None => text,
    }
}

#[test]
fn no_source_file_is_past_500_lines_of_code() {
    let long: Vec<String> = sources()
        .iter()
        .map(|p| (p, code_of(p).lines().count()))
        .filter(|(_, n)| *n > MAX_LINES)
        .map(|(p, n)| format!("{} ({n} lines)", p.display()))
        .collect();
    assert!(long.is_empty(), "split these by concern: {long:?}");
}

/// Within each folder of src/ (src itself too), its files and subfolders name each other without
/// a circle: a child naming its parent's own items, or the parent its children, is no edge.
#[test]
fn no_folder_has_an_import_circle() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let graph = module_graph::Graph::of_crate(&root.join("src/lib.rs"));
    let mut problems = Vec::new();
    for (folder, edges) in graph.sibling_edges() {
        let shown = if folder.is_empty() { "src".to_string() } else { folder.join("/") };
        for circle in module_graph::circles(&edges) {
            let mut lines = vec![format!("{shown}: {} -> {}", circle.join(" -> "), circle[0])];
            for (i, from) in circle.iter().enumerate() {
                let to = &circle[(i + 1) % circle.len()];
                let site = edges[from][to]
                    .strip_prefix(&format!("{}/", root.display()))
                    .unwrap_or(&edges[from][to])
                    .to_string();
                lines.push(format!("    {from} -> {to}: {site}"));
            }
            problems.push(lines.join("\n"));
        }
    }
    assert!(problems.is_empty(), "{} import circles:\n{}", problems.len(), problems.join("\n"));
}

/// The circle check on a crate made for it: a path in code, a parent's re-export and a glob
/// import each make an edge; a parent's own items, comments, strings and tests do not.
#[test]
fn the_circle_check_sees_what_siblings_name() {
    let dir = std::env::temp_dir().join(format!("shadowlab-module-graph-{}", std::process::id()));
    let files = [
        ("src/lib.rs", "pub mod a;\npub mod b;\n"),
        ("src/a/mod.rs", "mod w;\nmod x;\nmod y;\nmod z;\npub use z::Thing;\npub struct Parent;\n"),
        ("src/a/w.rs", "use super::*;\npub struct Inner(Parent);\nfn f(_: Thing) {}\n"),
        (
            "src/a/x.rs",
            "use super::Parent;\n// super::z::Thing\nfn f() -> &'static str { super::y::g(); \"super::z\" }\n\
             #[cfg(test)]\nmod tests {\n    use crate::a::z::Thing;\n}\n",
        ),
        ("src/a/y.rs", "pub fn g(thing: super::Thing) -> super::Thing {\n    thing\n}\n"),
        ("src/a/z.rs", "pub struct Thing(crate::a::w::Inner, super::x::X);\n"),
        ("src/b/mod.rs", "mod p;\nmod q;\npub struct Parent;\n"),
        ("src/b/p.rs", "use super::Parent;\nuse super::q::Q;\n"),
        ("src/b/q.rs", "pub struct Q(super::Parent);\n"),
    ];
    for (path, text) in files {
        std::fs::create_dir_all(dir.join(path).parent().expect("a folder")).expect("a temporary folder");
        std::fs::write(dir.join(path), text).expect("a fixture file");
    }
    let edges = module_graph::Graph::of_crate(&dir.join("src/lib.rs")).sibling_edges();
    let _ = std::fs::remove_dir_all(&dir);
    let (a, b) = (&edges[&vec!["a".to_string()]], &edges[&vec!["b".to_string()]]);
    let names = |m: &BTreeMap<String, String>| m.keys().cloned().collect::<Vec<_>>();
    assert_eq!(module_graph::circles(a), [vec!["w", "z"], vec!["x", "y", "z"]]);
    assert_eq!(names(&a["x"]), ["y"], "only the call in code counts");
    assert!(a["x"]["y"].ends_with("a/x.rs:3"), "{}", a["x"]["y"]);
    assert!(a["y"]["z"].ends_with("a/y.rs:1"), "through the parent's re-export: {}", a["y"]["z"]);
    assert!(a["w"]["z"].ends_with("a/w.rs:3"), "through `use super::*`: {}", a["w"]["z"]);
    assert_eq!(names(&a["z"]), ["w", "x"]);
    assert!(module_graph::circles(b).is_empty());
    assert_eq!(b.len(), 1);
    assert_eq!(names(&b["p"]), ["q"]);
    assert!(!edges.contains_key(&Vec::<String>::new()), "the top level names nothing across");
}

/// Where the code outside the twin names a formula the twin defines, it calls it: no second
/// definition of these functions anywhere in src.
#[test]
fn each_light_space_formula_is_defined_once() {
    let formulas = [
        "fn depth_linear_from_ndc",
        "fn depth_ndc_from_linear",
        "fn ndc_per_world",
        "fn off_axis_sec",
        "fn texel_world_at",
        "fn texel_world_bound",
        "fn outside_frustum",
        "fn read_texel_centre_uv",
        "fn receiver_bias_ndc",
        "fn blocker_search_radius_uv",
        "fn estimate_penumbra",
        "fn blocker_depth_from_penumbra",
        "fn filter_radius_texels",
        "fn search_kernel",
    ];
    for formula in formulas {
        let defined: Vec<String> = sources()
            .iter()
            .filter(|p| {
                code_of(p).lines().any(|l| l.trim_start().trim_start_matches("pub ").starts_with(formula))
            })
            .map(|p| p.display().to_string())
            .collect();
        // The twin's free function, and at most its method wrapper in the same folder.
        assert!(
            !defined.is_empty() && defined.iter().all(|p| p.contains("/src/shadow/")),
            "`{formula}` is defined outside src/shadow: {defined:?}"
        );
    }
}

/// A frame's shadow parameters are made from the scene's settings in one place, the renderer's
/// `prepare`; the ground truth makes its own from its own settings, and the pipeline cache its
/// placeholder. Everything downstream reads them from the frame.
#[test]
fn shadow_params_are_built_from_settings_in_the_known_places_only() {
    let allowed = [
        "src/render/prepare.rs",
        "src/render/reference_pass.rs",
        "src/render/pipelines.rs",
        "src/diagrams/live.rs",
    ];
    for path in sources() {
        let shown = path.display().to_string();
        if code_of(&path).contains("ShadowParamsGpu::new(") && !shown.contains("/src/shadow/") {
            assert!(allowed.iter().any(|a| shown.ends_with(a)), "{shown} builds ShadowParamsGpu itself");
        }
    }
}

/// The repository's text files under `dir` (relative to its root) with their text: what is not
/// UTF-8 (fonts, images) is left out, and so are build and package folders.
fn text_files(dir: &str) -> Vec<(String, String)> {
    fn walk(root: &Path, dir: &Path, out: &mut Vec<(String, String)>) {
        let Ok(entries) = std::fs::read_dir(dir) else { return };
        for entry in entries.flatten() {
            let path = entry.path();
            let name = entry.file_name().to_string_lossy().to_string();
            if path.is_dir() {
                if !["target", "node_modules", ".git"].contains(&name.as_str()) {
                    walk(root, &path, out);
                }
            } else if let Ok(text) = std::fs::read_to_string(&path) {
                let shown = path.strip_prefix(root).unwrap_or(&path).display().to_string();
                out.push((shown, text));
            }
        }
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut out = Vec::new();
    let path = root.join(dir);
    if path.is_file() {
        out.push((dir.to_string(), std::fs::read_to_string(&path).expect("a text file")));
    } else {
        walk(root, &path, &mut out);
    }
    out.sort();
    out
}

/// A citation key: an upper-case letter, then letters and digits in parts joined by hyphens, at
/// least one hyphen (`Fernando-2005`, `LearnOpenGL-ShadowMapping`). The hyphen keeps a key apart
/// from code (`taps[i][PCF]`, `&[Vec2]`) and from rustdoc links, which never contain one.
fn is_key(key: &str) -> bool {
    key.starts_with(|c: char| c.is_ascii_uppercase())
        && key.contains('-')
        && key.split('-').all(|part| !part.is_empty() && part.chars().all(|c| c.is_ascii_alphanumeric()))
}

/// The keys cited on one line, as `[Key]`.
fn citations(line: &str) -> Vec<&str> {
    let mut keys = Vec::new();
    for (at, _) in line.match_indices('[') {
        let rest = &line[at + 1..];
        let len = rest.find(|c: char| !(c.is_ascii_alphanumeric() || c == '-')).unwrap_or(rest.len());
        if rest[len..].starts_with(']') && is_key(&rest[..len]) {
            keys.push(&rest[..len]);
        }
    }
    keys
}

/// Every `[Key]` in src/, shaders/, lessons/ and assets/ (and README.md, ARCHITECTURE.md and
/// docs/REFERENCES.md itself) is the heading of an entry in docs/REFERENCES.md, and every entry
/// is cited somewhere in src/, shaders/, lessons/ or assets/.
#[test]
fn every_citation_has_its_entry_and_every_entry_is_cited() {
    const REFERENCES: &str = "docs/REFERENCES.md";
    let (_, references) = text_files(REFERENCES).pop().expect("docs/REFERENCES.md");
    let mut problems = Vec::new();
    let mut entries: BTreeMap<String, usize> = BTreeMap::new();
    for (i, line) in references.lines().enumerate() {
        let Some(heading) = line.strip_prefix("### [") else { continue };
        let key = heading.split(']').next().unwrap_or_default();
        if !is_key(key) {
            problems.push(format!(
                "{REFERENCES}:{}: `[{key}]` is not a key (Letters-and-digits-with-hyphens)",
                i + 1
            ));
        } else if entries.insert(key.to_string(), i + 1).is_some() {
            problems.push(format!("{REFERENCES}:{}: [{key}] has a second entry", i + 1));
        }
    }
    let citing = ["src", "shaders", "lessons", "assets"];
    let mut cited = BTreeSet::new();
    for dir in citing.iter().chain(&["README.md", "ARCHITECTURE.md", REFERENCES]) {
        for (path, text) in text_files(dir) {
            for (i, line) in text.lines().enumerate() {
                for key in citations(line) {
                    if !entries.contains_key(key) {
                        problems.push(format!("{path}:{}: [{key}] has no entry in {REFERENCES}", i + 1));
                    } else if citing.contains(dir) {
                        cited.insert(key.to_string());
                    }
                }
            }
        }
    }
    for (key, line) in &entries {
        if !cited.contains(key) {
            problems.push(format!(
                "{REFERENCES}:{line}: [{key}] is cited nowhere in src/, shaders/, lessons/ or assets/"
            ));
        }
    }
    assert!(problems.is_empty(), "{} citation problems:\n{}", problems.len(), problems.join("\n"));
}

/// Sources are cited from docs/REFERENCES.md, not from notes kept outside the repository.
#[test]
fn nothing_points_at_notes_outside_the_repository() {
    // Spelled in pieces so that this file does not match itself.
    let outside = [concat!("../", "shared"), concat!("REFERENCES", " \""), concat!("Seed", " 0")];
    let places =
        ["src", "shaders", "lessons", "assets", "tests", "web", "docs", "README.md", "ARCHITECTURE.md"];
    let mut problems = Vec::new();
    for place in places {
        for (path, text) in text_files(place) {
            for (i, line) in text.lines().enumerate() {
                for needle in outside.iter().filter(|n| line.contains(**n)) {
                    problems.push(format!("{path}:{}: mentions `{needle}`", i + 1));
                }
            }
        }
    }
    assert!(
        problems.is_empty(),
        "{} mentions of notes outside the repository:\n{}",
        problems.len(),
        problems.join("\n")
    );
}

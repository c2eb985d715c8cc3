//! The scripts of a student's page in the order their browser runs them: their index.html's
//! `<script src>` list where they have one, else the framework's; their own file where they have
//! it, shadowlab's copy of the framework's interface where they do not. The framework's libraries
//! are loaded before any of them (the prelude), so a page's own copies of them are skipped.

use crate::homework::program::ShaderSource;

/// The framework's `src/` scripts in index.html's order, with shadowlab's copy of each (None: the
/// student's file only).
pub(super) const FRAMEWORK: [(&str, Option<&str>); 16] = [
    ("shaders/Shader.js", Some(include_str!("../../../assets/homework/framework/src/shaders/Shader.js"))),
    (
        "shaders/InternalShader.js",
        Some(include_str!("../../../assets/homework/framework/src/shaders/InternalShader.js")),
    ),
    (
        "materials/Material.js",
        Some(include_str!("../../../assets/homework/framework/src/materials/Material.js")),
    ),
    (
        "materials/ShadowMaterial.js",
        Some(include_str!("../../../assets/homework/framework/src/materials/ShadowMaterial.js")),
    ),
    (
        "materials/PhongMaterial.js",
        Some(include_str!("../../../assets/homework/framework/src/materials/PhongMaterial.js")),
    ),
    ("textures/Texture.js", Some(include_str!("../../../assets/homework/framework/src/textures/Texture.js"))),
    ("textures/FBO.js", Some(include_str!("../../../assets/homework/framework/src/textures/FBO.js"))),
    ("objects/Mesh.js", Some(include_str!("../../../assets/homework/framework/src/objects/Mesh.js"))),
    ("loads/loadOBJ.js", Some(include_str!("../../../assets/homework/framework/src/loads/loadOBJ.js"))),
    ("loads/loadShader.js", Some(include_str!("../../../assets/homework/framework/src/loads/loadShader.js"))),
    ("lights/Light.js", Some(include_str!("../../../assets/homework/framework/src/lights/Light.js"))),
    ("lights/DirectionalLight.js", None),
    ("lights/PointLight.js", None),
    (
        "renderers/WebGLRenderer.js",
        Some(include_str!("../../../assets/homework/framework/src/renderers/WebGLRenderer.js")),
    ),
    (
        "renderers/MeshRender.js",
        Some(include_str!("../../../assets/homework/framework/src/renderers/MeshRender.js")),
    ),
    ("engine.js", Some(ENGINE_JS)),
];

/// The framework's shaders, answered where the page asks for one the submission does not hold.
pub(super) const FRAMEWORK_SHADERS: [(&str, &str); 3] = [
    ("src/shaders/phongShader/phongVertex.glsl", crate::homework::program::FRAMEWORK_PHONG_VERTEX),
    ("src/shaders/shadowShader/shadowVertex.glsl", crate::homework::program::FRAMEWORK_SHADOW_VERTEX),
    ("src/shaders/shadowShader/shadowFragment.glsl", crate::homework::program::FRAMEWORK_SHADOW_FRAGMENT),
];

/// Libraries the prelude (or its stand-ins) already provides: a page's own `<script>` for one is
/// skipped.
const PROVIDED_LIBRARIES: [&str; 10] = [
    "three.js",
    "three.min.js",
    "gl-matrix.js",
    "gl-matrix-min.js",
    "orbitcontrols.js",
    "mtlloader.js",
    "objloader.js",
    "dat.gui.js",
    "dat.gui.min.js",
    "stats.min.js",
];

/// One script of the page.
pub(super) enum Script<'a> {
    /// shadowlab's copy of a framework file.
    Ours { name: String, text: &'static str },
    /// One of the student's files (not their light or engine.js).
    Theirs(&'a ShaderSource),
    /// Their `DirectionalLight.js` (or the one the check was given instead).
    Light,
    /// Their `engine.js` (or the one given instead, or shadowlab's copy).
    Engine,
}

/// The page's scripts in order, with what could not be followed (one line each).
pub(super) struct ScriptList<'a> {
    pub scripts: Vec<Script<'a>>,
    pub notes: Vec<String>,
}

fn file_name(path: &str) -> &str {
    path.rsplit('/').next().unwrap_or(path)
}

/// Whether `name` (a path in the submission) is the framework's file `path`.
fn is_framework_file(name: &str, path: &str) -> bool {
    name == path || name.ends_with(&format!("/{path}"))
}

/// shadowlab's copy of the framework's file `path` (None: the framework's own has none).
fn our_copy(path: &str, text: Option<&'static str>) -> Option<Script<'static>> {
    text.map(|text| Script::Ours { name: format!("shadowlab/framework/{path}"), text })
}

fn ours(path: &str) -> Option<Script<'static>> {
    FRAMEWORK.iter().find(|(p, _)| is_framework_file(path, p)).and_then(|(p, text)| our_copy(p, *text))
}

/// shadowlab's copy of the framework's engine.js, for a submission without one.
pub(super) const ENGINE_JS: &str = include_str!("../../../assets/homework/framework/src/engine.js");

fn slot(path: &str) -> Option<Script<'static>> {
    match file_name(path) {
        n if n.eq_ignore_ascii_case("DirectionalLight.js") => Some(Script::Light),
        n if n.eq_ignore_ascii_case("engine.js") => Some(Script::Engine),
        _ => None,
    }
}

/// The `src` of each classic `<script>` of an HTML page, in order, and those loaded as modules.
fn script_sources(html: &str) -> (Vec<String>, Vec<String>) {
    let lower = html.to_lowercase();
    let (mut classic, mut modules) = (Vec::new(), Vec::new());
    let mut from = 0;
    while let Some(start) = lower[from..].find("<script").map(|i| i + from) {
        let end = lower[start..].find('>').map_or(lower.len(), |i| i + start);
        let tag = &html[start..end];
        let tag_lower = &lower[start..end];
        from = end;
        let Some(at) = tag_lower.find("src=") else { continue };
        let rest = &tag[at + 4..];
        let src = match rest.chars().next() {
            Some(q @ ('"' | '\'')) => rest[1..].split(q).next().unwrap_or_default(),
            _ => rest.split([' ', '>']).next().unwrap_or_default(),
        };
        if tag_lower.contains("type=\"module\"") || tag_lower.contains("type='module'") {
            modules.push(src.to_string());
        } else {
            classic.push(src.to_string());
        }
    }
    (classic, modules)
}

/// `src` relative to the folder `base` ('/'-separated), with `./` and `../` resolved.
fn resolve(base: &str, src: &str) -> String {
    let mut parts: Vec<&str> = base.split('/').filter(|p| !p.is_empty()).collect();
    for part in src.split(['?', '#']).next().unwrap_or_default().split('/') {
        match part {
            "" | "." => {}
            ".." => {
                parts.pop();
            }
            p => parts.push(p),
        }
    }
    parts.join("/")
}

/// The page's scripts: index.html's list where the submission has one, else the framework's.
pub(super) fn script_list(page: &[ShaderSource]) -> ScriptList<'_> {
    let theirs = |path: &str| page.iter().find(|f| f.name.eq_ignore_ascii_case(path));
    let index = page
        .iter()
        .filter(|f| file_name(&f.name).eq_ignore_ascii_case("index.html"))
        .min_by_key(|f| f.name.len());
    let mut notes = Vec::new();
    let Some(index) = index else {
        let scripts = FRAMEWORK
            .iter()
            .filter_map(|(path, text)| {
                slot(path).or_else(|| {
                    page.iter()
                        .find(|f| is_framework_file(&f.name, path))
                        .map(Script::Theirs)
                        .or_else(|| our_copy(path, *text))
                })
            })
            .collect();
        return ScriptList { scripts, notes };
    };
    let base = index.name.rsplit_once('/').map_or("", |(dir, _)| dir);
    let (classic, modules) = script_sources(&index.text);
    for m in &modules {
        notes.push(format!("{} loads {m} as a module, which the check does not run", index.name));
    }
    let mut scripts = Vec::new();
    let (mut light, mut engine) = (false, false);
    for src in classic {
        let path = resolve(base, &src);
        if PROVIDED_LIBRARIES.contains(&file_name(&path).to_lowercase().as_str()) {
            continue;
        }
        match slot(&path) {
            Some(Script::Light) if !light => {
                light = true;
                scripts.push(Script::Light);
            }
            Some(Script::Engine) if !engine => {
                engine = true;
                scripts.push(Script::Engine);
            }
            Some(_) => {}
            None => match theirs(&path).map(Script::Theirs).or_else(|| ours(&path)) {
                Some(script) => scripts.push(script),
                None => notes.push(format!("{} loads {src}, which the submission does not hold", index.name)),
            },
        }
    }
    // The check needs the light and engine.js even where index.html names them otherwise.
    if !light {
        let at = scripts.iter().position(|s| matches!(s, Script::Engine)).unwrap_or(scripts.len());
        scripts.insert(at, Script::Light);
    }
    if !engine {
        scripts.push(Script::Engine);
    }
    ScriptList { scripts, notes }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn file(name: &str, text: &str) -> ShaderSource {
        ShaderSource { name: name.into(), path: None, text: text.into() }
    }

    fn names(list: &ScriptList<'_>) -> Vec<String> {
        list.scripts
            .iter()
            .map(|s| match s {
                Script::Ours { name, .. } => name.clone(),
                Script::Theirs(f) => f.name.clone(),
                Script::Light => "LIGHT".into(),
                Script::Engine => "ENGINE".into(),
            })
            .collect()
    }

    #[test]
    fn without_index_html_the_framework_order_takes_their_files_where_they_have_them() {
        let page = [file("hw/src/renderers/WebGLRenderer.js", ""), file("hw/src/lights/PointLight.js", "")];
        let list = script_list(&page);
        let names = names(&list);
        assert_eq!(names.len(), 16, "{names:?}");
        assert_eq!(names[0], "shadowlab/framework/shaders/Shader.js");
        assert_eq!(
            names[11..],
            [
                "LIGHT",
                "hw/src/lights/PointLight.js",
                "hw/src/renderers/WebGLRenderer.js",
                "shadowlab/framework/renderers/MeshRender.js",
                "ENGINE"
            ]
            .map(String::from)
        );
    }

    #[test]
    fn index_html_gives_the_order_and_its_own_scripts() {
        let html = r#"<html><script src="lib/three.js" defer></script>
            <script src='./src/util/helpers.js'></script><SCRIPT SRC="src/lights/DirectionalLight.js"></SCRIPT>
            <script src="src/objects/Mesh.js"></script><script src="src/missing.js"></script>
            <script type="module" src="src/main.js"></script><script src="src/engine.js"></script>"#;
        let page = [file("hw/index.html", html), file("hw/src/util/helpers.js", "")];
        let list = script_list(&page);
        assert_eq!(
            names(&list),
            ["hw/src/util/helpers.js", "LIGHT", "shadowlab/framework/objects/Mesh.js", "ENGINE"]
                .map(String::from)
        );
        assert_eq!(
            list.notes,
            [
                "hw/index.html loads src/main.js as a module, which the check does not run",
                "hw/index.html loads src/missing.js, which the submission does not hold"
            ]
        );
    }

    #[test]
    fn paths_resolve_against_the_page() {
        assert_eq!(resolve("a/b", "./src/x.js?v=2"), "a/b/src/x.js");
        assert_eq!(resolve("a/b", "../lib/y.js"), "a/lib/y.js");
        assert_eq!(resolve("", "src/engine.js"), "src/engine.js");
    }
}

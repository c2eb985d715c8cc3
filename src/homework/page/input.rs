//! What driver.js is given: shadowlab's prelude (the stand-ins, the framework's libraries and the
//! driver itself), then one JSON input naming the student's scripts in their page's order, the
//! text files the loaders answer with, and the objects whose light matrices the check needs. The
//! same on both sides: the desktop's engine and the browser's Worker run exactly this.

use serde::Serialize;

use super::scripts::{ENGINE_JS, FRAMEWORK_SHADERS, Script, script_list};
use super::{Limits, Placed};
use crate::homework::page::ScriptError;
use crate::homework::program::ShaderSource;

/// A prelude script's text: in the program, or (in the page, for the framework's libraries, which
/// the page serves beside its wasm to keep them out of it) a file at this path under the page.
pub(super) enum Text {
    Included(&'static str),
    #[cfg_attr(not(target_arch = "wasm32"), allow(dead_code))]
    Served(&'static str),
}

/// One of the framework's libraries: in the desktop program, included; in the page, served from
/// `homework/lib/` beside the wasm (web/build.sh copies it there).
macro_rules! library {
    ($file:literal) => {{
        #[cfg(not(target_arch = "wasm32"))]
        let text = Text::Included(include_str!(concat!("../../../assets/homework/framework/lib/", $file)));
        #[cfg(target_arch = "wasm32")]
        let text = Text::Served(concat!("homework/lib/", $file));
        text
    }};
}

/// Shadowlab's stand-ins, the libraries and the driver, in the order they run, before the
/// student's scripts.
pub(super) const PRELUDE: [(&str, Text); 6] = [
    ("shadowlab/browser.js", Text::Included(include_str!("../../../assets/homework/page/browser.js"))),
    ("lib/three.js", library!("three.min.js")),
    ("lib/gl-matrix-min.js", library!("gl-matrix-min.js")),
    ("shadowlab/libraries.js", Text::Included(include_str!("../../../assets/homework/page/libraries.js"))),
    ("shadowlab/calls.js", Text::Included(include_str!("../../../assets/homework/page/calls.js"))),
    ("shadowlab/driver.js", Text::Included(include_str!("../../../assets/homework/page/driver.js"))),
];

/// Frames of the page run after it loads, and the time between them (ms, a 60 Hz display).
const FRAMES: usize = 2;
const FRAME_MS: f64 = 1000.0 / 60.0;

/// When the check looks at the page's lights again, seconds of their animation: a light that
/// moved by then gets a check of its own at that time.
const LOOK_AGAIN_S: [f64; 3] = [0.5, 1.0, 2.0];

/// The page's text files (shaders by path) as the loaders answer them: the framework's shaders
/// where the submission has none of the name.
fn page_files(page: &[ShaderSource]) -> std::collections::BTreeMap<String, &str> {
    let mut files: std::collections::BTreeMap<String, &str> =
        FRAMEWORK_SHADERS.iter().map(|(name, text)| ((*name).to_string(), *text)).collect();
    for file in page {
        let lower = file.name.to_lowercase();
        if [".glsl", ".vert", ".frag"].iter().any(|e| lower.ends_with(e)) {
            // The submission's own file replaces the framework's of the same place.
            files
                .retain(|name, _| !file.name.ends_with(name.as_str()) && !name.ends_with(file.name.as_str()));
            files.insert(file.name.clone(), &file.text);
        }
    }
    files
}

/// What the driver is given (driver.js's `input`).
#[derive(Serialize)]
struct DriverInput<'a> {
    light: NamedText<'a>,
    #[serde(rename = "engineName")]
    engine_name: &'a str,
    scripts: Vec<DriverScript<'a>>,
    files: std::collections::BTreeMap<String, &'a str>,
    objects: Vec<[f64; 6]>,
    frames: usize,
    #[serde(rename = "frameMs")]
    frame_ms: f64,
    /// For the message of a page that allocates past the bound.
    #[serde(rename = "memoryMiB")]
    memory_mib: usize,
    /// The time bound, ms: the page's animation is followed for half of it at most.
    #[serde(rename = "timeMs")]
    time_ms: f64,
    /// The times the check looks at the page's lights again, seconds (an orbit, a light moved).
    times: &'static [f64],
}

#[derive(Serialize)]
struct NamedText<'a> {
    name: &'a str,
    text: &'a str,
}

#[derive(Serialize)]
struct DriverScript<'a> {
    role: &'static str,
    name: &'a str,
    text: &'a str,
}

/// The page's input as JSON, and what reading its script list noticed (notes for the report).
pub(super) fn driver_input(
    light: &ShaderSource,
    engine_js: Option<&ShaderSource>,
    page: &[ShaderSource],
    objects: &[Placed],
    limits: Limits,
) -> Result<(String, Vec<String>), ScriptError> {
    let list = script_list(page);
    let engine_source =
        engine_js.map_or(NamedText { name: "shadowlab/framework/engine.js", text: ENGINE_JS }, |e| {
            NamedText { name: &e.name, text: &e.text }
        });
    let scripts = list
        .scripts
        .iter()
        .map(|s| match s {
            Script::Light => DriverScript { role: "light", name: &light.name, text: &light.text },
            Script::Engine => {
                DriverScript { role: "engine", name: engine_source.name, text: engine_source.text }
            }
            Script::Theirs(f) => DriverScript { role: "theirs", name: &f.name, text: &f.text },
            Script::Ours { name, text } => DriverScript { role: "ours", name, text },
        })
        .collect();
    let input = DriverInput {
        light: NamedText { name: &light.name, text: &light.text },
        engine_name: engine_js.map_or("engine.js", |e| e.name.as_str()),
        scripts,
        files: page_files(page),
        objects: objects.iter().map(|(t, s)| [t[0], t[1], t[2], s[0], s[1], s[2]]).collect(),
        frames: FRAMES,
        frame_ms: FRAME_MS,
        memory_mib: limits.memory_bytes >> 20,
        time_ms: limits.time.as_secs_f64() * 1000.0,
        times: &LOOK_AGAIN_S,
    };
    let json = serde_json::to_string(&input).map_err(|e| ScriptError {
        file: "shadowlab".into(),
        line: 0,
        message: format!("the page could not start (its input: {e})"),
    })?;
    Ok((json, list.notes))
}

//! A student's homework page run as their browser runs it, in a real JavaScript engine (`engine`:
//! QuickJS on the desktop), with stand-ins for what a browser gives a page
//! (assets/homework/page/browser.js: a window, a document with one canvas, a WebGL context that
//! records, loaders answered only from shadowlab) and the framework's libraries themselves
//! (assets/homework/framework/lib: gl-matrix 2.7.0 and three.js r125, as the framework's
//! index.html loads them).
//!
//! The scripts run in index.html's order. Where the submission has no file of its own, shadowlab's
//! copy of the framework's interface stands in (assets/homework/framework/src). Today the page
//! gives the check its light: every `new DirectionalLight(...)` the student's engine.js makes is
//! recorded with its arguments and the line that made it, and that light's own `CalcLightMVP`
//! builds each object's matrix.

mod engine;
mod record;
mod scripts;

#[cfg(test)]
mod tests;

use engine::Engine;
pub use engine::Limits;
use record::MadeLight;
pub use record::{FoundLight, PageDraws};
use scripts::{FRAMEWORK_SHADERS, Script, script_list};
use serde::Deserialize;

use super::light_script::{EngineLight, GlCall, LightMatrix, ScriptError, Sourced};
use super::program::ShaderSource;

/// Shadowlab's stand-ins and the libraries, in the order they run, before the student's scripts.
const PRELUDE: [(&str, &str); 5] = [
    ("shadowlab/browser.js", include_str!("../../../assets/homework/page/browser.js")),
    ("lib/three.js", include_str!("../../../assets/homework/framework/lib/three.min.js")),
    ("lib/gl-matrix-min.js", include_str!("../../../assets/homework/framework/lib/gl-matrix-min.js")),
    ("shadowlab/libraries.js", include_str!("../../../assets/homework/page/libraries.js")),
    ("shadowlab/calls.js", include_str!("../../../assets/homework/page/calls.js")),
];

/// Wraps the light classes after their scripts ran, so each construction is recorded.
const WATCH_LIGHTS: &str = "try { if (typeof DirectionalLight === 'function') DirectionalLight = __shadowlab.watchLight('DirectionalLight', DirectionalLight); } catch (e) {}\n\
    try { if (typeof PointLight === 'function') PointLight = __shadowlab.watchLight('PointLight', PointLight); } catch (e) {}";

/// Frames of the page run after it loads, and the time between them (ms, a 60 Hz display).
const FRAMES: usize = 2;
const FRAME_MS: f64 = 1000.0 / 60.0;

/// shadowlab's copy of the framework's engine.js, for a submission without one.
const ENGINE_JS: &str = include_str!("../../../assets/homework/framework/src/engine.js");

/// The script that hands the page its text files (shaders by path), the framework's shaders where
/// the submission has none of the name.
fn files_script(page: &[ShaderSource]) -> String {
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
    format!("__shadowlab.files = {};", serde_json::to_string(&files).unwrap_or_else(|_| "{}".into()))
}

/// The framework's light, made where the student's engine.js made none.
const FRAMEWORK_LIGHT: &str = "__shadowlab.light = new DirectionalLight(5000, [1, 1, 1], [0, 80, 80], [0, 0, 0], [0, 1, 0], true, document.querySelector('#glcanvas').getContext('webgl')); 'made'";

/// A light object with the template's fields, for a constructor that throws.
fn template_light(args: &str) -> String {
    format!(
        "(function (a) {{ const l = Object.create(DirectionalLight.prototype); \
         ['lightIntensity', 'lightColor', 'lightPos', 'focalPoint', 'lightUp', 'hasShadowMap'].forEach((k, i) => {{ l[k] = a[i]; }}); \
         l.mesh = {{}}; l.mat = {{}}; l.fbo = {{}}; __shadowlab.light = l; return 'made'; }})({args})"
    )
}

#[derive(Deserialize)]
struct CallJson {
    name: String,
    args: Vec<f64>,
    line: usize,
}

#[derive(Deserialize)]
struct MatrixJson {
    matrix: Option<Vec<serde_json::Value>>,
    what: Option<String>,
    calls: Vec<CallJson>,
}

/// The student's light, made by their page and kept alive in its engine.
pub struct PageLight {
    engine: Engine,
    file: String,
    /// The line that defines CalcLightMVP (where a report points when the matrix is wrong).
    method_line: usize,
    /// The line of its last `return` (where a matrix built by hand comes from).
    return_line: usize,
    notes: Vec<String>,
    /// Every light the page made, in order; the check's is `checked`.
    found: Vec<FoundLight>,
    checked: Option<usize>,
    draws: PageDraws,
    /// Where the page asked for a WebGL2 context (`file:line`), if it did.
    webgl2: Option<String>,
}

fn shadowlab_error(e: ScriptError) -> ScriptError {
    ScriptError { file: "shadowlab".into(), line: 0, message: format!("the page could not start ({e})") }
}

impl PageLight {
    /// Runs the page with the student's `DirectionalLight.js` and, where they have one, their
    /// `engine.js`; returns the light and what engine.js gave it. Err: the light's script fails
    /// to run or has no `DirectionalLight` with a `CalcLightMVP` (the check then uses the
    /// framework's light). A failing engine.js is a note, not an error.
    pub fn load(
        light: &ShaderSource,
        engine_js: Option<&ShaderSource>,
        page: &[ShaderSource],
        limits: Limits,
    ) -> Result<(PageLight, EngineLight), ScriptError> {
        let engine =
            Engine::new(limits).map_err(|m| ScriptError { file: "shadowlab".into(), line: 0, message: m })?;
        for (file, source) in PRELUDE {
            engine.run_script(file, source).map_err(shadowlab_error)?;
        }
        engine.run_script("shadowlab/files.js", &files_script(page)).map_err(shadowlab_error)?;
        let list = script_list(page);
        let mut notes = list.notes;
        let mut light_ran = false;
        for script in &list.scripts {
            match script {
                Script::Light => {
                    engine.run_script(&light.name, &light.text)?;
                    light_ran = true;
                }
                Script::Engine => {
                    if !light_ran {
                        engine.run_script(&light.name, &light.text)?;
                        light_ran = true;
                    }
                    Self::check_class(&engine, &light.name)?;
                    engine.run_script("shadowlab/watch.js", WATCH_LIGHTS).map_err(shadowlab_error)?;
                    let (name, text) = match engine_js {
                        Some(e) => (e.name.as_str(), e.text.as_str()),
                        None => ("shadowlab/framework/engine.js", ENGINE_JS),
                    };
                    if let Err(e) = engine.run_script(name, text) {
                        notes.push(format!("{e} (the rest of {name} did not run)"));
                    }
                }
                Script::Theirs(file) => {
                    if let Err(e) = engine.run_script(&file.name, &file.text) {
                        notes.push(format!("{e} (the rest of {} did not run)", file.name));
                    }
                }
                Script::Ours { name, text } => {
                    if let Err(e) = engine.run_script(name, text) {
                        notes.push(format!(
                            "shadowlab's copy of {name} failed beside the page's own scripts ({e})"
                        ));
                    }
                }
            }
        }
        match engine.eval_string("shadowlab", &format!("__shadowlab.runFrames({FRAMES}, {FRAME_MS})")) {
            Ok(error) if !error.is_empty() => {
                notes.push(format!("a frame of the page failed: {}", engine::one_line(&error)))
            }
            Ok(_) => {}
            Err(e) => notes.push(format!("the page's frames did not run to the end ({e})")),
        }
        let made: Vec<MadeLight> =
            serde_json::from_str(&engine.eval_string("shadowlab", "__shadowlab.lightsJson()")?).map_err(
                |e| shadowlab_error(ScriptError { file: "lights".into(), line: 0, message: e.to_string() }),
            )?;
        let directional: Vec<(usize, &MadeLight)> =
            made.iter().enumerate().filter(|(_, l)| l.kind == "DirectionalLight").collect();
        let engine_name = engine_js.map_or("engine.js", |e| e.name.as_str());
        let mut engine_light = EngineLight::framework();
        match directional.first() {
            None => {
                notes.push(format!("{engine_name} makes no DirectionalLight: used the framework's light"));
                if let Err(e) = engine.eval_string(&light.name, FRAMEWORK_LIGHT) {
                    notes.push(format!(
                        "the DirectionalLight constructor failed ({e}); used an object with the template's fields instead"
                    ));
                    engine.eval_string(
                        "shadowlab",
                        &template_light("[5000, [1, 1, 1], [0, 80, 80], [0, 0, 0], [0, 1, 0], true]"),
                    )?;
                }
            }
            Some(&(index, first)) => {
                if directional.len() > 1 {
                    notes.push(format!(
                        "{} makes {} DirectionalLights; the first (line {}) is used",
                        first.file,
                        directional.len(),
                        first.line
                    ));
                }
                engine_light = Self::engine_light(first, &mut notes);
                match &first.error {
                    None => {
                        engine.eval_string(
                            "shadowlab",
                            &format!("__shadowlab.light = __shadowlab.lights[{index}].object; 'made'"),
                        )?;
                    }
                    Some(why) => {
                        notes.push(format!(
                            "the DirectionalLight constructor failed ({}:{}: {why}); used an object with the template's fields instead",
                            first.file, first.line
                        ));
                        engine.eval_string(
                            "shadowlab",
                            &template_light(&format!("__shadowlab.lights[{index}].args")),
                        )?;
                    }
                }
            }
        }
        let method_line = method_line(&light.text).unwrap_or(0);
        let return_line = last_return(&light.text, method_line).unwrap_or(method_line);
        let draws: PageDraws = engine
            .eval_string("shadowlab", "__shadowlab.drawsJson()")
            .ok()
            .and_then(|json| serde_json::from_str(&json).ok())
            .unwrap_or_default();
        let found = made.iter().map(MadeLight::found).collect();
        let webgl2 = engine
            .eval_string("shadowlab", "__shadowlab.contextJson()")
            .ok()
            .and_then(|json| serde_json::from_str::<Option<record::Context>>(&json).ok().flatten())
            .filter(|c| c.kind == "webgl2")
            .map(|c| if c.line > 0 { format!("{}:{}", c.file, c.line) } else { c.file });
        let checked = directional.first().map(|(i, _)| *i);
        let page = PageLight {
            engine,
            file: light.name.clone(),
            method_line,
            return_line,
            notes,
            found,
            checked,
            draws,
            webgl2,
        };
        Ok((page, engine_light))
    }

    /// Err where the light's script defines no `DirectionalLight` with a `CalcLightMVP`.
    fn check_class(engine: &Engine, file: &str) -> Result<(), ScriptError> {
        let kind = engine.eval_string(
            file,
            "typeof DirectionalLight !== 'function' ? 'none' : (DirectionalLight.prototype && typeof DirectionalLight.prototype.CalcLightMVP === 'function') ? 'ok' : 'no method'",
        )?;
        let message = match kind.as_str() {
            "ok" => return Ok(()),
            "none" => "no class or function named DirectionalLight",
            _ => "DirectionalLight has no CalcLightMVP method",
        };
        Err(ScriptError { file: file.to_string(), line: 0, message: message.into() })
    }
}

/// `value` as made on `made`'s line.
fn sourced<T>(made: &MadeLight, value: T) -> Sourced<T> {
    Sourced { value, file: made.file.clone(), line: made.line }
}

impl PageLight {
    /// The light's arguments as engine.js gave them; an argument that is not what the framework
    /// passes keeps the framework's value, with a note.
    fn engine_light(made: &MadeLight, notes: &mut Vec<String>) -> EngineLight {
        let mut light = EngineLight::framework();
        let number = |v: &serde_json::Value| v.as_f64();
        let vec3 = |v: &serde_json::Value| -> Option<[f64; 3]> {
            let a = v.as_array()?;
            (a.len() == 3).then_some([a[0].as_f64()?, a[1].as_f64()?, a[2].as_f64()?])
        };
        let null = serde_json::Value::Null;
        let arg = |i: usize| made.args.get(i).unwrap_or(&null);
        let mut keep = |what: &str| {
            notes.push(format!(
                "{}:{}: the light's {what} is not what the framework passes: kept the framework's",
                made.file, made.line
            ))
        };
        match number(arg(0)) {
            Some(x) => light.intensity = sourced(made, x),
            None => keep("intensity"),
        }
        for (i, what) in [(1, "color"), (2, "position"), (3, "focal point"), (4, "up vector")] {
            match vec3(arg(i)) {
                Some(v) => match i {
                    1 => light.color = sourced(made, v),
                    2 => light.position = sourced(made, v),
                    3 => light.focal_point = sourced(made, v),
                    _ => light.up = sourced(made, v),
                },
                None => keep(what),
            }
        }
        light
    }

    /// What running the page noticed (a failing engine.js, several lights).
    pub fn notes(&self) -> &[String] {
        &self.notes
    }

    /// Every light the page made, and which of them the check uses (None: the framework's).
    pub fn lights(&self) -> (&[FoundLight], Option<usize>) {
        (&self.found, self.checked)
    }

    /// Where the page asked for a WebGL2 context (`file:line`), if it did: its passes are not the
    /// framework's WebGL1 ones the check builds.
    pub fn webgl2(&self) -> Option<&str> {
        self.webgl2.as_deref()
    }

    /// What the page drew on its first frames.
    pub fn draws(&self) -> &PageDraws {
        &self.draws
    }

    /// Calls the light's CalcLightMVP for an object placed by `translate` and `scale` (world
    /// units), as the framework's materials call it.
    pub fn light_matrix(&mut self, translate: [f64; 3], scale: [f64; 3]) -> Result<LightMatrix, ScriptError> {
        let list = |v: [f64; 3]| format!("[{:?}, {:?}, {:?}]", v[0], v[1], v[2]);
        let json = self.engine.eval_string(
            &self.file,
            &format!("__shadowlab.lightMatrix(__shadowlab.light, {}, {})", list(translate), list(scale)),
        )?;
        let read: MatrixJson = serde_json::from_str(&json).map_err(|e| ScriptError {
            file: self.file.clone(),
            line: self.method_line,
            message: e.to_string(),
        })?;
        let calls: Vec<GlCall> =
            read.calls.into_iter().map(|c| GlCall { name: c.name, args: c.args, line: c.line }).collect();
        let return_line = self.return_line;
        let Some(values) = read.matrix else {
            return Err(ScriptError {
                file: self.file.clone(),
                line: self.method_line,
                message: format!(
                    "CalcLightMVP returned {}, not a 4x4 matrix",
                    read.what.unwrap_or_else(|| "something else".into())
                ),
            });
        };
        let mut clip_from_object = [0.0f32; 16];
        for (slot, v) in clip_from_object.iter_mut().zip(&values) {
            *slot = match v {
                serde_json::Value::Number(n) => n.as_f64().unwrap_or(f64::NAN) as f32,
                serde_json::Value::String(s) if s == "Infinity" => f32::INFINITY,
                serde_json::Value::String(s) if s == "-Infinity" => f32::NEG_INFINITY,
                _ => f32::NAN,
            };
        }
        Ok(LightMatrix { clip_from_object, calls, return_line })
    }
}

/// The line that defines `CalcLightMVP` (a method, or an assignment of a function), not a
/// comment or a call.
fn method_line(text: &str) -> Option<usize> {
    const NAME: &str = "CalcLightMVP";
    text.lines()
        .position(|line| {
            let code = line.trim_start();
            if code.starts_with("//") || code.starts_with('*') || code.starts_with("/*") {
                return false;
            }
            code.match_indices(NAME).any(|(at, _)| {
                let after = code[at + NAME.len()..].trim_start();
                let called = code[..at].ends_with('.');
                after.starts_with('=') || (!called && (after.starts_with('(') || after.starts_with(':')))
            })
        })
        .map(|i| i + 1)
}

/// The line of the last `return` in the function whose definition starts on `from` (1-based):
/// its body's braces matched past strings, template literals and comments.
fn last_return(text: &str, from: usize) -> Option<usize> {
    let lines: Vec<&str> = text.lines().collect();
    let (mut depth, mut opened, mut found) = (0usize, false, None);
    let mut in_block_comment = false;
    for (index, line) in lines.iter().enumerate().skip(from.checked_sub(1)?) {
        let chars: Vec<char> = line.chars().collect();
        let mut i = 0;
        let mut quote: Option<char> = None;
        while i < chars.len() {
            let (c, next) = (chars[i], chars.get(i + 1).copied());
            if in_block_comment {
                if c == '*' && next == Some('/') {
                    in_block_comment = false;
                    i += 1;
                }
            } else if let Some(q) = quote {
                if c == '\\' {
                    i += 1;
                } else if c == q {
                    quote = None;
                }
            } else if c == '/' && next == Some('/') {
                break;
            } else if c == '/' && next == Some('*') {
                in_block_comment = true;
                i += 1;
            } else if matches!(c, '\'' | '"' | '`') {
                quote = Some(c);
            } else if c == '{' {
                depth += 1;
                opened = true;
            } else if c == '}' {
                depth = depth.saturating_sub(1);
                if opened && depth == 0 {
                    return found;
                }
            } else if opened
                && chars[i..].starts_with(&['r', 'e', 't', 'u', 'r', 'n'])
                && (i == 0 || !(chars[i - 1].is_alphanumeric() || chars[i - 1] == '_'))
                && !chars.get(i + 6).is_some_and(|c| c.is_alphanumeric() || *c == '_')
            {
                found = Some(index + 1);
            }
            i += 1;
        }
    }
    found
}

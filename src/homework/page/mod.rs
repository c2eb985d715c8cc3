//! A student's homework page run as their browser runs it, in a real JavaScript engine (`engine`:
//! QuickJS on the desktop), with stand-ins for what a browser gives a page
//! (assets/homework/page/browser.js: a window, a document with one canvas, a WebGL context that
//! records, loaders answered only from shadowlab) and the framework's libraries themselves
//! (assets/homework/framework/lib: gl-matrix 2.7.0 and three.js r125, as the framework's
//! index.html loads them).
//!
//! The scripts run in index.html's order (`scripts`). Where the submission has no file of its
//! own, shadowlab's copy of the framework's interface stands in (assets/homework/framework/src).
//! One script, assets/homework/page/driver.js, runs the whole page whichever engine hosts it:
//! the scripts, the first frames, then the light's `CalcLightMVP` for each object the check
//! draws. What it returns (`record`): every light the page made with the line that made it, the
//! matrices, and each draw's uniforms by the names the student's code uses.

mod answer;
#[cfg(not(target_arch = "wasm32"))]
mod engine;
mod input;
mod lines;
mod record;
mod scripts;
mod stale;
#[cfg(target_arch = "wasm32")]
mod worker;

#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_errors;
#[cfg(test)]
mod tests_fuzz;

use input::{PRELUDE, driver_input};
use lines::{last_return, method_line};
use record::MadeLight;
pub use record::{FoundLight, PageDraws};
use serde::Deserialize;

use super::program::ShaderSource;
pub use crate::homework::light::StaleMatrix;
pub use answer::{EngineLight, GlCall, LightMatrix, ScriptError, Sourced};

#[derive(Deserialize)]
struct Failed {
    file: String,
    line: usize,
    message: String,
}

impl From<Failed> for ScriptError {
    fn from(f: Failed) -> Self {
        ScriptError { file: f.file, line: f.line, message: f.message }
    }
}

#[derive(Deserialize)]
struct CallJson {
    name: String,
    args: Vec<f64>,
    #[serde(default)]
    file: String,
    line: usize,
}

/// One object's matrix as the driver returns it.
#[derive(Deserialize)]
struct MatrixJson {
    #[serde(default)]
    matrix: Option<Vec<serde_json::Value>>,
    #[serde(default)]
    what: Option<String>,
    #[serde(default)]
    calls: Vec<CallJson>,
    #[serde(default)]
    error: Option<Failed>,
}

#[derive(Deserialize)]
struct Place {
    file: String,
    line: usize,
}

impl Place {
    fn shown(&self) -> String {
        if self.line > 0 { format!("{}:{}", self.file, self.line) } else { self.file.clone() }
    }
}

/// The WebGL context the page asked for, and where it first made a float texture.
#[derive(Deserialize)]
struct ContextJson {
    #[serde(rename = "floatTexture")]
    float_texture: Option<Place>,
}

/// Another DirectionalLight's matrices, by its index among the lights the page made.
#[derive(Deserialize)]
struct OtherLightJson {
    index: usize,
    matrices: Vec<MatrixJson>,
    /// Its `lightPos` when the matrices were computed (after the first frames).
    #[serde(default)]
    position: Option<Vec<f64>>,
}

/// A light's matrices later in the page's animation, where they changed.
#[derive(Deserialize)]
struct TimedLightJson {
    index: usize,
    seconds: f64,
    #[serde(default)]
    position: Option<Vec<f64>>,
    matrices: Vec<MatrixJson>,
}

/// What the driver returns.
#[derive(Deserialize)]
struct DriverOutput {
    fatal: Option<Failed>,
    notes: Vec<String>,
    lights: Vec<MadeLight>,
    checked: Option<usize>,
    matrices: Vec<MatrixJson>,
    /// The checked light's `lightPos` when its matrices were computed (after the first frames).
    #[serde(default)]
    position: Option<Vec<f64>>,
    #[serde(default)]
    others: Vec<OtherLightJson>,
    #[serde(default)]
    timed: Vec<TimedLightJson>,
    draws: Option<PageDraws>,
    context: Option<ContextJson>,
    #[serde(default)]
    stale: Vec<stale::StaleJson>,
    #[serde(default, rename = "calcCalls")]
    calc_calls: Vec<stale::CalcCallJson>,
}

/// Bounds on one page. The browser bounds a Worker's memory and stack by its own limits; the
/// time bound holds on both sides.
#[derive(Clone, Copy, Debug)]
pub struct Limits {
    /// Bytes the engine may allocate in all (libraries included).
    pub memory_bytes: usize,
    /// Bytes of native stack the engine's recursion may use.
    #[cfg_attr(target_arch = "wasm32", allow(dead_code))]
    pub stack_bytes: usize,
    /// Wall-clock time one script (or one call into the page) may run.
    pub time: std::time::Duration,
}

impl Default for Limits {
    fn default() -> Self {
        Limits { memory_bytes: 192 << 20, stack_bytes: 512 << 10, time: std::time::Duration::from_secs(4) }
    }
}

/// Each object's (translate, scale) with its light matrix, or why there is none.
type Matrices = Vec<(Placed, Result<LightMatrix, ScriptError>)>;

/// An object's place as the framework gives it: (translate, scale), world units.
pub type Placed = ([f64; 3], [f64; 3]);

/// One light's matrix for each object asked, as the page loaded or at a time of its animation.
struct LightSet {
    /// The light's index among those the page made (None: the framework's light, used where the
    /// page made no DirectionalLight).
    index: Option<usize>,
    /// Seconds of the page's animation (None: as the page loaded).
    seconds: Option<f64>,
    /// The light as engine.js made it, moved where the animation had taken it.
    light: EngineLight,
    matrices: Matrices,
}

/// A student's page, run: their light, what their engine.js gave it, the matrix of each object
/// asked for, and what the page drew.
pub struct PageRun {
    pub engine_light: EngineLight,
    notes: Vec<String>,
    /// Every light the page made, in order; the check's is `checked`.
    found: Vec<FoundLight>,
    checked: Option<usize>,
    /// Each light's matrices the page computed: first the checked light's as the page loaded,
    /// then each other DirectionalLight's, then each light's where its animation had moved it.
    sets: Vec<LightSet>,
    /// The set `light_matrix` answers from (an index into `sets`).
    selected: usize,
    draws: PageDraws,
    /// Where the page first made a float texture (`file:line`), if it did.
    float_texture: Option<String>,
    /// Draws of its animation whose uLightMVP did not follow what moved.
    stale: Vec<StaleMatrix>,
}

fn shadowlab_error(e: ScriptError) -> ScriptError {
    ScriptError { file: "shadowlab".into(), line: 0, message: format!("the page could not start ({e})") }
}

impl PageRun {
    /// Runs the page with the student's `DirectionalLight.js`, their `engine.js` where they have
    /// one, and the rest of their `page`; then their light's `CalcLightMVP` for each object
    /// placed by (translate, scale) in `objects` (world units). Err: the light's script fails to
    /// run or has no `DirectionalLight` with a `CalcLightMVP` (the check then uses the
    /// framework's light), or the page ran past a bound. A failing engine.js is a note.
    #[cfg(not(target_arch = "wasm32"))]
    pub fn run(
        light: &ShaderSource,
        engine_js: Option<&ShaderSource>,
        page: &[ShaderSource],
        objects: &[Placed],
        limits: Limits,
    ) -> Result<PageRun, ScriptError> {
        let (input, notes) = driver_input(light, engine_js, page, objects, limits)?;
        let engine = engine::Engine::new(limits).map_err(|m| ScriptError {
            file: "shadowlab".into(),
            line: 0,
            message: m,
        })?;
        for (file, text) in &PRELUDE {
            let input::Text::Included(source) = text else {
                return Err(shadowlab_error(ScriptError {
                    file: (*file).into(),
                    line: 0,
                    message: "served to the page only".into(),
                }));
            };
            engine.run_script(file, source).map_err(shadowlab_error)?;
        }
        let output = engine.run_page(&light.name, &input)?;
        Self::from_output(&output, light, objects, notes)
    }

    /// The same run as the desktop's `run`, in the browser's own engine (a Worker of the page):
    /// Pending until the Worker answers; the answer is kept, so asking again for the same page
    /// and objects is Ready at once.
    #[cfg(target_arch = "wasm32")]
    pub fn poll(
        light: &ShaderSource,
        engine_js: Option<&ShaderSource>,
        page: &[ShaderSource],
        objects: &[Placed],
        limits: Limits,
    ) -> std::task::Poll<Result<PageRun, ScriptError>> {
        let (input, notes) = match driver_input(light, engine_js, page, objects, limits) {
            Ok(made) => made,
            Err(e) => return std::task::Poll::Ready(Err(e)),
        };
        worker::poll(&PRELUDE, &input, &light.name, limits.time)
            .map(|output| output.and_then(|output| Self::from_output(&output, light, objects, notes)))
    }

    /// The run from what driver.js returned (`output`, JSON), whichever engine ran it; `notes`
    /// come first (what reading the script list noticed).
    fn from_output(
        output: &str,
        light: &ShaderSource,
        objects: &[Placed],
        mut notes: Vec<String>,
    ) -> Result<PageRun, ScriptError> {
        let output: DriverOutput = serde_json::from_str(output).map_err(|e| {
            shadowlab_error(ScriptError { file: "driver".into(), line: 0, message: e.to_string() })
        })?;
        if let Some(fatal) = output.fatal {
            return Err(fatal.into());
        }
        notes.extend(output.notes);
        let mut engine_light = match output.checked.and_then(|i| output.lights.get(i)) {
            Some(made) => Self::engine_light(made, &mut notes),
            None => EngineLight::framework(),
        };
        if output.checked.is_some() {
            moved_by_first_frames(&mut engine_light, output.position.as_deref(), &mut notes);
        }
        let method_line = method_line(&light.text).unwrap_or(0);
        let return_line = last_return(&light.text, method_line).unwrap_or(method_line);
        let placed = |matrices: Vec<MatrixJson>| -> Matrices {
            objects
                .iter()
                .zip(matrices)
                .map(|(placed, m)| (*placed, matrix(m, &light.name, method_line, return_line)))
                .collect()
        };
        let mut sets = vec![LightSet {
            index: output.checked,
            seconds: None,
            light: engine_light.clone(),
            matrices: placed(output.matrices),
        }];
        for other in output.others {
            if let Some(made) = output.lights.get(other.index) {
                let mut light = Self::engine_light(made, &mut Vec::new());
                moved_by_first_frames(&mut light, other.position.as_deref(), &mut notes);
                sets.push(LightSet {
                    index: Some(other.index),
                    seconds: None,
                    light,
                    matrices: placed(other.matrices),
                });
            }
        }
        for timed in output.timed {
            let Some(loaded) = sets.iter().find(|s| s.index == Some(timed.index) && s.seconds.is_none())
            else {
                continue;
            };
            let mut light = loaded.light.clone();
            if let Some(p) = timed.position.filter(|p| p.len() == 3) {
                light.position.value = [p[0], p[1], p[2]];
            }
            let matrices = placed(timed.matrices);
            sets.push(LightSet { index: Some(timed.index), seconds: Some(timed.seconds), light, matrices });
        }
        let float_texture = output.context.and_then(|c| c.float_texture).map(|p| p.shown());
        Ok(PageRun {
            engine_light,
            notes,
            found: output.lights.iter().map(MadeLight::found).collect(),
            checked: output.checked,
            sets,
            selected: 0,
            stale: stale::stale_matrices(&output.stale, &output.calc_calls, output.draws.as_ref()),
            draws: output.draws.unwrap_or_default(),
            float_texture,
        })
    }

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

    /// Where the page first made a float texture (`file:line`), if it did: its maps are not the
    /// framework's RGBA8 ones the check builds (moments for VSM, a summed-area table, ...).
    pub fn float_texture(&self) -> Option<&str> {
        self.float_texture.as_deref()
    }

    /// What the page drew on its first frames.
    /// The draws of its animation whose uLightMVP did not follow what moved.
    pub fn stale(&self) -> &[StaleMatrix] {
        &self.stale
    }

    pub fn draws(&self) -> &PageDraws {
        &self.draws
    }

    /// The times (seconds) at which the page's animation changed light `index`'s matrices.
    pub fn times_of(&self, index: usize) -> Vec<f64> {
        self.sets.iter().filter(|s| s.index == Some(index)).filter_map(|s| s.seconds).collect()
    }

    /// Makes `light_matrix` answer for the page's light `index` (one it computed matrices for),
    /// as the page loaded or at `seconds` of its animation (one of `times_of`), and gives that
    /// light as engine.js made it, moved where the animation took it; None for a light or a time
    /// without matrices.
    pub fn select(&mut self, index: usize, seconds: Option<f64>) -> Option<EngineLight> {
        self.selected = self.sets.iter().position(|s| s.index == Some(index) && s.seconds == seconds)?;
        Some(self.sets[self.selected].light.clone())
    }

    /// The light's matrix for an object placed by `translate` and `scale`, as the page computed
    /// it when it ran (an object it was not asked for is an error).
    pub fn light_matrix(&self, translate: [f64; 3], scale: [f64; 3]) -> Result<LightMatrix, ScriptError> {
        self.sets[self.selected]
            .matrices
            .iter()
            .find(|((t, s), _)| *t == translate && *s == scale)
            .map(|(_, m)| m.clone())
            .unwrap_or_else(|| {
                Err(ScriptError {
                    file: "shadowlab".into(),
                    line: 0,
                    message: format!("no matrix was asked of the page for {translate:?} {scale:?}"),
                })
            })
    }
}

/// The light where the page's first frames left it (`at`, its `lightPos` then), with a note
/// where that is not where it was made: their uniforms and their matrices are the moved ones.
fn moved_by_first_frames(light: &mut EngineLight, at: Option<&[f64]>, notes: &mut Vec<String>) {
    let Some(&[x, y, z]) = at else { return };
    let made = light.position.value;
    if [x, y, z].iter().all(|v| v.is_finite())
        && made.iter().zip([x, y, z]).any(|(a, b)| (a - b).abs() > 1e-6)
    {
        notes.push(format!(
            "the light made on {}:{} at ({}, {}, {}) was at ({x:.1}, {y:.1}, {z:.1}) when the page drew its first frames: the check uses it there",
            light.position.file, light.position.line, made[0], made[1], made[2]
        ));
        light.position.value = [x, y, z];
    }
}

/// `value` as made on `made`'s line.
fn sourced<T>(made: &MadeLight, value: T) -> Sourced<T> {
    Sourced { value, file: made.file.clone(), line: made.line }
}

/// One object's matrix from what the driver returned.
fn matrix(
    m: MatrixJson,
    file: &str,
    method_line: usize,
    return_line: usize,
) -> Result<LightMatrix, ScriptError> {
    if let Some(error) = m.error {
        return Err(error.into());
    }
    let calls: Vec<GlCall> = m
        .calls
        .into_iter()
        .map(|c| GlCall { name: c.name, args: c.args, file: c.file, line: c.line })
        .collect();
    let Some(values) = m.matrix else {
        return Err(ScriptError {
            file: file.to_string(),
            line: method_line,
            message: format!(
                "CalcLightMVP returned {}, not a 4x4 matrix",
                m.what.unwrap_or_else(|| "something else".into())
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

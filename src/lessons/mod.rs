//! Lessons are data: one TOML file per lesson in `lessons/`, steps in order. A step names a
//! scene, overrides any scene value (the same keys as `--set`), and says what to show and what
//! to read, in English and Simplified Chinese. Parsed with `deny_unknown_fields`, so a typo is an
//! error naming the file, the line and the key.

pub mod live;

use crate::diagrams::DiagramKind;
use crate::files::OneLine;
use crate::i18n::Lang;
use crate::scene::{Override, Scene, SceneError, SceneSource};
use crate::views::View;
use crate::views::overlays::Overlay;
use serde::Deserialize;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use toml::Spanned;

#[derive(Debug, thiserror::Error)]
pub enum LessonError {
    #[error("{}: cannot read: {}", OneLine(path), OneLine(reason))]
    Io { path: String, reason: String },
    #[error("{}:{line}: {}", OneLine(path), OneLine(message))]
    Parse { path: String, line: usize, message: String },
    #[error("{}:{line}: step {step}: {}", OneLine(path), OneLine(message))]
    Step { path: String, line: usize, step: usize, message: String },
    #[error("{}", OneLine(.0))]
    NotFound(String),
}

/// Text in both languages; both are required.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Text {
    pub en: String,
    pub zh: String,
}

impl Text {
    pub fn get(&self, lang: Lang) -> &str {
        // Lesson text carries its own translation: not a table lookup.
        match lang {
            Lang::En => &self.en,
            Lang::Zh => &self.zh,
        }
    }
}

/// The frame a step's `probe` pixel is given in: the lesson's own frame. The app, the CLI and the
/// slides all probe in it, so they all quote the same numbers, whatever their views' sizes.
pub const PROBE_FRAME: (u32, u32) = (960, 540);

/// Panels a step can show.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Panel {
    Camera,
    ShadowMap,
    Diagram,
    KernelPlot,
    Probe,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LessonFile {
    id: String,
    order: u32,
    title: Text,
    summary: Text,
    #[serde(rename = "step")]
    steps: Vec<Spanned<StepFile>>,
}

fn default_panels() -> Vec<Panel> {
    vec![Panel::Camera, Panel::ShadowMap, Panel::Diagram]
}

/// A "Try this" prompt as written: its text and what its Apply button changes.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TryThisFile {
    en: String,
    zh: String,
    set: Option<toml::Table>,
    time: Option<f32>,
    view: Option<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct StepFile {
    title: Text,
    text: Text,
    #[serde(default)]
    try_this: Vec<Spanned<TryThisFile>>,
    scene: Spanned<String>,
    set: Option<Spanned<toml::Table>>,
    #[serde(default)]
    time: f32,
    #[serde(default)]
    play: bool,
    #[serde(default = "default_panels")]
    panels: Vec<Panel>,
    #[serde(default)]
    overlays: Vec<Overlay>,
    /// Probe pixel in the lesson's 960x540 frame (`PROBE_FRAME`).
    probe: Option<[u32; 2]>,
    diagram: Option<Spanned<String>>,
    view: Option<Spanned<String>>,
    #[serde(default)]
    light: usize,
    /// What the probe must find on the step's light, where the text claims it.
    expect: Option<live::Verdict>,
    /// A homework shader (a `phongFragment.glsl`) the step checks beside its scene, and the light
    /// pass's fragment shader it runs with (default: the framework's).
    homework: Option<Spanned<String>>,
    homework_shadow_shader: Option<Spanned<String>>,
}

/// A step's homework shader and the light pass's, where the step names its own.
#[derive(Clone, Debug, PartialEq)]
pub struct StepHomework {
    pub fragment: PathBuf,
    pub shadow_fragment: Option<PathBuf>,
}

/// A "Try this" prompt: text naming the app's controls, and the change its Apply button makes
/// on top of the step (`--set`-style overrides, a scene time, a view).
#[derive(Clone, Debug, PartialEq)]
pub struct TryThis {
    pub text: Text,
    pub overrides: Vec<Override>,
    pub time_s: Option<f32>,
    pub view: Option<View>,
}

impl TryThis {
    /// The prompt changes something the Apply button can set.
    pub fn applies_anything(&self) -> bool {
        !self.overrides.is_empty() || self.time_s.is_some() || self.view.is_some()
    }
}

/// One step of a lesson, checked: its scene loads with its overrides.
#[derive(Clone, Debug)]
pub struct Step {
    pub title: Text,
    pub text: Text,
    pub try_this: Vec<TryThis>,
    pub scene_path: PathBuf,
    /// The scene file, read once for every step of the lesson that names it.
    pub source: Arc<SceneSource>,
    /// The `set` table's values, typed, in file order.
    pub overrides: Vec<Override>,
    pub time_s: f32,
    pub play: bool,
    pub panels: Vec<Panel>,
    pub overlays: Vec<Overlay>,
    pub probe: Option<[u32; 2]>,
    pub diagram: Option<DiagramKind>,
    pub view: View,
    pub light: usize,
    /// The verdict the text claims for the probe on `light` (the tests hold the probe to it).
    pub expect: Option<live::Verdict>,
    /// The homework shader the step checks (lesson 7), opened as a student's would be.
    pub homework: Option<StepHomework>,
}

impl Step {
    /// The step's scene with its overrides applied.
    pub fn scene(&self) -> Result<Scene, SceneError> {
        self.source.build(&self.overrides)
    }

    /// The step's scene with prompt `index`'s changes on top (what its Apply button shows).
    pub fn scene_with_try_this(&self, index: usize) -> Result<Scene, SceneError> {
        let extra = self.try_this.get(index).map_or(&[][..], |t| &t.overrides[..]);
        let all: Vec<Override> = self.overrides.iter().chain(extra).cloned().collect();
        self.source.build(&all)
    }
}

#[derive(Clone, Debug)]
pub struct Lesson {
    pub id: String,
    pub order: u32,
    pub title: Text,
    pub summary: Text,
    pub path: PathBuf,
    pub steps: Vec<Step>,
}

/// The folder the lessons ship in (see [`crate::shipped_path`]).
pub fn default_dir() -> PathBuf {
    crate::shipped_path("lessons")
}

fn line_of(text: &str, byte: usize) -> usize {
    text.as_bytes()[..byte.min(text.len())].iter().filter(|&&b| b == b'\n').count() + 1
}

/// Flatten a `set` table into overrides, values kept as typed: `{ light = { 0 = { width = 4 } } }`
/// and `"light.0.width" = 4` both give `light.0.width` = 4.
fn flatten(prefix: &str, table: &toml::Table, out: &mut Vec<Override>) {
    for (key, value) in table {
        let full = if prefix.is_empty() { key.clone() } else { format!("{prefix}.{key}") };
        match value {
            toml::Value::Table(inner) => flatten(&full, inner, out),
            other => out.push(Override { key: full, value: other.clone() }),
        }
    }
}

/// The step's text quotes the probe (`{probe...}`) somewhere.
fn step_quotes_probe(step: &Step) -> bool {
    std::iter::once(&step.text)
        .chain(step.try_this.iter().map(|t| &t.text))
        .any(|t| t.en.contains("{probe.") || t.zh.contains("{probe."))
}

impl Step {
    /// The step's explanation in `lang` with the probe's and the frame's numbers filled in (see
    /// [`live`]); a probe report alone leaves the frame's numbers pending.
    pub fn text_filled<'a>(&self, lang: Lang, sources: impl Into<live::Sources<'a>>) -> String {
        live::fill(self.text.get(lang), sources, self.light, lang).0
    }

    /// The try-this prompts in `lang`, filled in.
    pub fn try_this_filled<'a>(&self, lang: Lang, sources: impl Into<live::Sources<'a>>) -> Vec<String> {
        let sources = sources.into();
        self.try_this.iter().map(|t| live::fill(t.text.get(lang), sources, self.light, lang).0).collect()
    }

    /// Every text of the step, in both languages: the explanation, then the prompts.
    pub fn texts(&self) -> impl Iterator<Item = &str> {
        std::iter::once(&self.text)
            .chain(self.try_this.iter().map(|t| &t.text))
            .flat_map(|t| [t.en.as_str(), t.zh.as_str()])
    }

    /// The step's explanation or a prompt quotes `{NAMESPACE.NAME}`, in either language.
    pub fn quotes(&self, namespace: live::Namespace, name: &str) -> bool {
        self.texts().any(|t| live::quotes(t, namespace, name))
    }

    /// The lights whose probe value `name` the step quotes (the step's own light where a
    /// placeholder names none), in order, each once.
    pub fn quoted_lights(&self, name: &str) -> Vec<usize> {
        let mut lights: Vec<usize> = self
            .texts()
            .filter_map(|t| live::placeholders(t).ok())
            .flatten()
            .filter(|p| p.namespace == live::Namespace::Probe && p.name == name)
            .map(|p| p.light.unwrap_or(self.light))
            .collect();
        lights.sort_unstable();
        lights.dedup();
        lights
    }
}

/// Load and check one lesson file.
pub fn load_lesson(path: &Path) -> Result<Lesson, LessonError> {
    let label = path.display().to_string();
    let text = crate::files::read_input_text(path, crate::files::MAX_TEXT_FILE_BYTES)
        .map_err(|reason| LessonError::Io { path: label.clone(), reason })?;
    let file: LessonFile = toml::from_str(&text).map_err(|e| {
        let (line, message) = crate::scene::describe_toml_error(&text, &e);
        LessonError::Parse { path: label.clone(), line, message }
    })?;
    if file.steps.is_empty() {
        return Err(LessonError::Parse {
            path: label,
            line: 1,
            message: "a lesson needs at least one [[step]]".into(),
        });
    }
    let base = path.parent().unwrap_or(Path::new("."));
    let mut steps = Vec::with_capacity(file.steps.len());
    let mut sources: HashMap<PathBuf, Arc<SceneSource>> = HashMap::new();
    for (index, spanned) in file.steps.into_iter().enumerate() {
        let step_line = line_of(&text, spanned.span().start);
        let s = spanned.into_inner();
        let error = |span: std::ops::Range<usize>, message: String| LessonError::Step {
            path: label.clone(),
            line: if span.is_empty() { step_line } else { line_of(&text, span.start) },
            step: index + 1,
            message,
        };
        let diagram = match &s.diagram {
            None => None,
            Some(d) => Some(DiagramKind::from_id(d.get_ref()).ok_or_else(|| {
                let ids: Vec<_> = DiagramKind::ALL.iter().map(|k| k.id()).collect();
                error(
                    d.span(),
                    format!("unknown diagram `{}` (expected one of {})", d.get_ref(), ids.join(", ")),
                )
            })?),
        };
        let view = match &s.view {
            None => View::Final,
            Some(v) => View::from_name(v.get_ref())
                .ok_or_else(|| error(v.span(), format!("unknown view `{}`", v.get_ref())))?,
        };
        if !s.time.is_finite() {
            return Err(error(0..0, "`time` must be a finite number of seconds".into()));
        }
        let mut overrides = Vec::new();
        if let Some(set) = &s.set {
            flatten("", set.get_ref(), &mut overrides);
        }
        let set_span = s.set.as_ref().map_or(0..0, |set| set.span());
        let mut try_this = Vec::with_capacity(s.try_this.len());
        // Each prompt's errors point at its own line.
        let prompt_spans: Vec<_> = s.try_this.iter().map(|t| t.span()).collect();
        for (i, (t, span)) in s.try_this.into_iter().zip(&prompt_spans).enumerate() {
            let t = t.into_inner();
            let mut overrides = Vec::new();
            if let Some(set) = &t.set {
                flatten("", set, &mut overrides);
            }
            let view =
                match &t.view {
                    None => None,
                    Some(v) => Some(View::from_name(v).ok_or_else(|| {
                        error(span.clone(), format!("try_this {}: unknown view `{v}`", i + 1))
                    })?),
                };
            if t.time.is_some_and(|t| !t.is_finite()) {
                return Err(error(
                    span.clone(),
                    format!("try_this {}: `time` must be a finite number of seconds", i + 1),
                ));
            }
            try_this.push(TryThis { text: Text { en: t.en, zh: t.zh }, overrides, time_s: t.time, view });
        }
        let scene_path = base.join(s.scene.get_ref());
        let source = match sources.get(&scene_path) {
            Some(source) => source.clone(),
            None => {
                let source = Arc::new(
                    SceneSource::read(&scene_path).map_err(|e| error(s.scene.span(), e.to_string()))?,
                );
                sources.insert(scene_path.clone(), source.clone());
                source
            }
        };
        // A homework the step checks: its files must be there (named at the key's line).
        let shader = |key: &Option<Spanned<String>>| -> Result<Option<PathBuf>, LessonError> {
            let Some(key) = key else { return Ok(None) };
            let path = base.join(key.get_ref());
            crate::files::check_regular_file(&path)
                .map_err(|e| error(key.span(), format!("homework shader {}: {e}", path.display())))?;
            Ok(Some(path))
        };
        let homework_shadow = shader(&s.homework_shadow_shader)?;
        let homework =
            shader(&s.homework)?.map(|fragment| StepHomework { fragment, shadow_fragment: homework_shadow });
        let step = Step {
            title: s.title,
            text: s.text,
            try_this,
            scene_path,
            source,
            overrides,
            time_s: s.time,
            play: s.play,
            panels: s.panels,
            overlays: s.overlays,
            probe: s.probe,
            diagram,
            view,
            light: s.light,
            expect: s.expect,
            homework,
        };
        // Live numbers: every `{probe.NAME}` and `{frame.NAME}` must name a value, in both
        // languages.
        for text in std::iter::once(&step.text).chain(step.try_this.iter().map(|t| &t.text)) {
            for lang_text in [&text.en, &text.zh] {
                if let Err(message) = live::placeholders(lang_text) {
                    return Err(error(0..0, message));
                }
            }
        }
        // A playing step's picture moves on from `time`: no claim about one moment can hold.
        if step.play && (step.expect.is_some() || step_quotes_probe(&step)) {
            return Err(error(
                0..0,
                "`play = true` but the step states what its probe shows (the picture moves on from \
                 `time`): drop `play`, or the `expect` and the probe values in the text"
                    .into(),
            ));
        }
        if (step.expect.is_some() || step_quotes_probe(&step)) && step.probe.is_none() {
            return Err(error(0..0, "the text quotes the probe but the step sets no `probe` pixel".into()));
        }
        // A lesson that cannot render is caught here, before anything is shown or written.
        let scene = step.scene().map_err(|e| match e {
            SceneError::Override { .. } => error(set_span.clone(), e.to_string()),
            _ => error(s.scene.span(), e.to_string()),
        })?;
        // Every Apply button works: the prompt's changes load on top of the step's.
        for (i, (t, span)) in step.try_this.iter().zip(&prompt_spans).enumerate() {
            if !t.overrides.is_empty() {
                step.scene_with_try_this(i)
                    .map_err(|e| error(span.clone(), format!("try_this {}: {e}", i + 1)))?;
            }
        }
        if step.light >= scene.lights.len().max(1) {
            return Err(error(
                0..0,
                format!("`light` = {} but the scene has {} light(s)", step.light, scene.lights.len()),
            ));
        }
        if let Some([x, y]) = step.probe
            && (x >= 960 || y >= 540)
        {
            return Err(error(0..0, format!("probe {x},{y} is outside the 960x540 frame")));
        }
        steps.push(step);
    }
    Ok(Lesson {
        id: file.id,
        order: file.order,
        title: file.title,
        summary: file.summary,
        path: path.to_path_buf(),
        steps,
    })
}

/// Every `*.toml` lesson in `dir` (an editor's hidden, backup or lock files left out, as the
/// built-in copy leaves them out), in their `order`.
pub fn load_all(dir: &Path) -> Result<Vec<Lesson>, LessonError> {
    let entries = crate::files::folder_entries(dir)
        .map_err(|e| LessonError::Io { path: dir.display().to_string(), reason: e.to_string() })?;
    let ships = |p: &Path| p.file_name().is_some_and(|n| crate::built_in::ships(&n.to_string_lossy()));
    let mut paths: Vec<PathBuf> =
        entries.into_iter().filter(|p| p.extension().is_some_and(|x| x == "toml") && ships(p)).collect();
    paths.sort();
    let mut lessons = paths.iter().map(|p| load_lesson(p)).collect::<Result<Vec<_>, _>>()?;
    let mut ids: Vec<&str> = lessons.iter().map(|l| l.id.as_str()).collect();
    ids.sort_unstable();
    if let Some(pair) = ids.windows(2).find(|pair| pair[0] == pair[1]) {
        return Err(LessonError::NotFound(format!(
            "two lessons in {} have the id `{}`",
            dir.display(),
            pair[0]
        )));
    }
    lessons.sort_by_key(|l| l.order);
    Ok(lessons)
}

/// Find a lesson by id (or by its 1-based position).
pub fn find<'a>(lessons: &'a [Lesson], id: &str) -> Result<&'a Lesson, LessonError> {
    lessons
        .iter()
        .find(|l| l.id == id)
        .or_else(|| id.parse::<usize>().ok().and_then(|n| n.checked_sub(1)).and_then(|i| lessons.get(i)))
        .ok_or_else(|| {
            let ids: Vec<_> = lessons.iter().map(|l| l.id.as_str()).collect();
            LessonError::NotFound(format!("no lesson `{id}` (lessons: {})", ids.join(", ")))
        })
}

//! A place in the app as a page address's query, so a teacher can put one step on a slide:
//! `?lesson=pcss&step=3&lang=zh`, `?scene=contact&technique=pcf`. Following a link applies what
//! it names and says, in one line each, what it could not (the rest still applies); the query of
//! where the student is now is what the page's address follows.

use crate::files::OneLine;
use crate::i18n::Lang;
use crate::scene::Technique;
use crate::shipped_path;
use std::fmt::Write;

/// The folder of the scenes a link can name (by file stem).
const SCENES: &str = "assets/scenes";
/// Keys the app reads elsewhere (the page's backend) and a link keeps.
const KEPT_KEYS: &[&str] = &["backend"];
/// Longest query read (a link on a slide is a few dozen characters).
const MAX_QUERY_BYTES: usize = 2048;

/// What a link asks for; `None`s leave that part as it is.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Link {
    /// A lesson's id or number.
    pub lesson: Option<String>,
    /// From 1.
    pub step: Option<u32>,
    /// A shipped scene's file stem (`contact`).
    pub scene: Option<String>,
    pub technique: Option<Technique>,
    pub lang: Option<Lang>,
}

/// Read a query (`?a=b&c=d`, the `?` optional): the link, and a line for each part that could not
/// be read (an unknown key, a bad value).
pub fn parse(query: &str) -> (Link, Vec<String>) {
    let mut link = Link::default();
    let mut problems = Vec::new();
    if query.len() > MAX_QUERY_BYTES {
        problems.push(format!(
            "the link's query is {} bytes long (at most {MAX_QUERY_BYTES} are read)",
            query.len()
        ));
        return (link, problems);
    }
    for pair in query.trim_start_matches('?').split('&').filter(|p| !p.is_empty()) {
        let (key, value) = pair.split_once('=').unwrap_or((pair, ""));
        let (key, value) = (decode(key), decode(value));
        let value = value.trim();
        // What is quoted back stays on its line, however the link was mangled.
        let (shown_key, shown) = (OneLine(&key), OneLine(value));
        match key.as_str() {
            "lesson" if !value.is_empty() => link.lesson = Some(value.to_owned()),
            "scene" if !value.is_empty() => link.scene = Some(value.to_owned()),
            "step" => match value.parse::<u32>() {
                Ok(step) if step >= 1 => link.step = Some(step),
                _ => problems.push(format!("step `{shown}` is not a step number (1, 2, ...)")),
            },
            "technique" => match Technique::from_name(value) {
                Some(t) => link.technique = Some(t),
                None => {
                    let names: Vec<&str> = Technique::ALL.iter().map(|t| t.name()).collect();
                    problems.push(format!("no technique `{shown}` (techniques: {})", names.join(", ")));
                }
            },
            "lang" => match Lang::from_code(value) {
                Some(lang) => link.lang = Some(lang),
                None => problems.push(format!("no language `{shown}` (languages: en, zh)")),
            },
            "lesson" | "scene" => problems.push(format!("`{shown_key}` names nothing")),
            k if KEPT_KEYS.contains(&k) => {}
            _ => problems.push(format!(
                "unknown part `{shown_key}` (a link names lesson, step, scene, technique, lang)"
            )),
        }
    }
    (link, problems)
}

/// `%XX` escapes and `+` as a space, as a form encodes them; malformed escapes stay as written.
fn decode(text: &str) -> String {
    let bytes = text.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let hex = |b: u8| (b as char).to_digit(16);
        match bytes[i] {
            b'+' => out.push(b' '),
            b'%' => {
                match (bytes.get(i + 1).copied().and_then(hex), bytes.get(i + 2).copied().and_then(hex)) {
                    (Some(h), Some(l)) => {
                        out.push((h * 16 + l) as u8);
                        i += 2;
                    }
                    _ => out.push(b'%'),
                }
            }
            b => out.push(b),
        }
        i += 1;
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// `%XX` for everything but unreserved characters.
fn encode(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for b in text.bytes() {
        if b.is_ascii_alphanumeric() || b"-_.~".contains(&b) {
            out.push(b as char);
        } else {
            let _ = write!(out, "%{b:02X}");
        }
    }
    out
}

/// The scene a link names by stem, if shadowlab ships it.
fn shipped_scene(name: &str) -> Option<std::path::PathBuf> {
    let valid = !name.is_empty() && name.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_' || b == b'-');
    let path = shipped_path(SCENES).join(format!("{name}.toml"));
    (valid && crate::files::is_file(&path)).then_some(path)
}

/// The stems of the shipped scenes, for a message.
fn scene_names() -> Vec<String> {
    let mut names: Vec<String> = crate::files::folder_entries(&shipped_path(SCENES))
        .unwrap_or_default()
        .iter()
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .filter_map(|p| Some(p.file_stem()?.to_string_lossy().into_owned()))
        .collect();
    names.sort();
    names
}

impl super::AppState {
    /// Go where `link` says; what could not be followed goes into the error line (one line per
    /// part, the rest applied).
    pub fn follow_link(&mut self, link: &Link, mut problems: Vec<String>) {
        if let Some(lang) = link.lang {
            self.lang = lang;
            self.settings.lang = lang;
        }
        match (&link.lesson, &link.scene) {
            (Some(id), scene) => {
                if scene.is_some() {
                    problems.push("a link opens a lesson or a scene, not both: the lesson is shown".into());
                }
                match crate::lessons::find(&self.lessons, id).map(|l| l.id.clone()) {
                    Ok(found) => {
                        let index = self.lessons.iter().position(|l| l.id == found).unwrap_or(0);
                        let steps = self.lessons[index].steps.len() as u32;
                        let step = link.step.unwrap_or(1);
                        if step > steps {
                            problems.push(format!("lesson `{found}` has steps 1 to {steps}, not {step}"));
                        }
                        self.go_to_step(index, step.clamp(1, steps.max(1)) as usize - 1);
                    }
                    Err(_) => {
                        let ids: Vec<&str> = self.lessons.iter().map(|l| l.id.as_str()).collect();
                        problems.push(format!("no lesson `{}` (lessons: {})", OneLine(id), ids.join(", ")));
                    }
                }
            }
            (None, Some(name)) => match shipped_scene(name) {
                Some(path) => {
                    self.open(&path);
                    self.settings.last_lesson = None;
                }
                None => problems.push(format!(
                    "no scene `{}` (scenes: {})",
                    OneLine(name),
                    scene_names().join(", ")
                )),
            },
            (None, None) if link.step.is_some() => {
                problems.push("`step` needs a lesson (`lesson=pcss&step=3`)".into())
            }
            (None, None) => {}
        }
        if let Some(technique) = link.technique
            && self.scene.shadow.technique != technique
        {
            self.scene.shadow.technique = technique;
            self.mark_dirty();
        }
        self.show_lesson_list &= link.lesson.is_none() && link.scene.is_none();
        if !problems.is_empty() {
            self.error = Some(super::AppError::new("could not follow all of the link", problems.join(" · ")));
        }
    }

    /// The query of where the student is (without `?`): the lesson and step, or the shipped scene;
    /// the technique where it is not the step's own (or always, on a scene); the language.
    pub fn link(&self) -> String {
        let mut query = String::new();
        let technique = self.scene.shadow.technique;
        match self.current_step() {
            Some((lesson, _, step)) => {
                let _ = write!(query, "lesson={}&step={}", encode(&lesson.id), step + 1);
                if technique != self.base_scene.shadow.technique {
                    let _ = write!(query, "&technique={}", technique.name());
                }
            }
            None => {
                let stem = match &self.source {
                    super::Source::Scene(path) => path.file_stem().map(|s| s.to_string_lossy().into_owned()),
                    super::Source::Lesson { .. } => None,
                };
                if let Some(stem) = stem.filter(|s| self.homework.is_none() && shipped_scene(s).is_some()) {
                    let _ = write!(query, "scene={}&", encode(&stem));
                }
                let _ = write!(query, "technique={}", technique.name());
            }
        }
        let _ = write!(query, "&lang={}", self.lang.code());
        query
    }
}

/// The parts of `query` a link keeps whatever the place (the page's `backend`), as `&k=v`.
pub fn kept_parts(query: &str) -> String {
    query
        .trim_start_matches('?')
        .split('&')
        .filter(|pair| KEPT_KEYS.contains(&pair.split_once('=').map_or(*pair, |(k, _)| k)))
        .map(|pair| format!("&{pair}"))
        .collect()
}

//! Scene files (TOML). Paths inside a scene are relative to the file.
//!
//! `--set key=value` overrides are applied to the parsed TOML table before the strict
//! (`deny_unknown_fields`) deserialisation, so an unknown key or a wrong type is reported
//! with the key's name. Bare keys mean `[shadow]` keys (`technique=pcss`); others are paths:
//! `camera.fov_deg=40`, `light.0.width=4`, `object.1.spin_deg_per_s=[0,90,0]`.

mod build;

use super::light::{CascadeSelection, Cascades, Light, LightKind, LightSize};
use super::mesh::{self, Mesh, MeshError};
use super::settings::ShadowSettings;
use super::{Camera, MAX_LIGHTS, Object, Projection, Scene};
use crate::files::OneLine;
use build::build_scene;
use glam::Vec3;
use serde::Deserialize;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    #[error("{}: cannot read: {}", OneLine(path), OneLine(reason))]
    Io { path: String, reason: String },
    #[error("{}:{line}: {}", OneLine(path), OneLine(message))]
    Parse { path: String, line: usize, message: String },
    #[error("{}: {}", OneLine(path), OneLine(message))]
    Invalid { path: String, message: String },
    #[error("--set {}: {}", OneLine(key), OneLine(message))]
    Override { key: String, message: String },
    #[error(transparent)]
    Mesh(#[from] MeshError),
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneFile {
    camera: CameraFile,
    #[serde(default, rename = "object")]
    objects: Vec<ObjectFile>,
    #[serde(default, rename = "light")]
    lights: Vec<LightFile>,
    #[serde(default)]
    shadow: ShadowSettings,
    #[serde(default = "default_ambient")]
    ambient: [f32; 3],
}

#[derive(Deserialize, Clone, Copy, PartialEq)]
#[serde(rename_all = "lowercase")]
enum ProjectionName {
    Perspective,
    Orthographic,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CameraFile {
    #[serde(default = "default_projection")]
    projection: ProjectionName,
    position: [f32; 3],
    #[serde(default)]
    target: [f32; 3],
    #[serde(default = "default_up")]
    up: [f32; 3],
    fov_deg: Option<f32>,
    height: Option<f32>,
    #[serde(default = "default_camera_near")]
    near: f32,
    #[serde(default = "default_camera_far")]
    far: f32,
}

#[derive(Deserialize)]
#[serde(untagged)]
enum ScaleFile {
    Uniform(f32),
    PerAxis([f32; 3]),
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ObjectFile {
    name: Option<String>,
    /// The name in Chinese, for the probe panel and the slides.
    name_zh: Option<String>,
    mesh: String,
    #[serde(default = "default_color")]
    color: [f32; 3],
    #[serde(default)]
    translate: [f32; 3],
    #[serde(default)]
    rotate_deg: [f32; 3],
    scale: Option<ScaleFile>,
    #[serde(default)]
    spin_deg_per_s: [f32; 3],
}

#[derive(Deserialize, Clone, Copy, PartialEq)]
#[serde(rename_all = "lowercase")]
enum LightKindName {
    Directional,
    Spot,
    Point,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LightFile {
    kind: LightKindName,
    position: [f32; 3],
    #[serde(default)]
    target: [f32; 3],
    #[serde(default = "default_up")]
    up: [f32; 3],
    #[serde(default = "default_light_color")]
    color: [f32; 3],
    #[serde(default = "default_intensity")]
    intensity: f32,
    #[serde(default = "default_map_size")]
    shadow_map_size: u32,
    extent: Option<f32>,
    fov_deg: Option<f32>,
    near: Option<f32>,
    #[serde(default = "default_light_far")]
    far: f32,
    width: Option<f32>,
    angular_diameter_deg: Option<f32>,
    #[serde(default)]
    orbit_deg_per_s: f32,
    cascades: Option<u32>,
    cascade_lambda: Option<f32>,
    cascade_distance: Option<f32>,
    /// `CascadeSelection::name`: "map" or "interval".
    cascade_selection: Option<String>,
}

fn default_ambient() -> [f32; 3] {
    [0.08, 0.08, 0.1]
}
fn default_projection() -> ProjectionName {
    ProjectionName::Perspective
}
fn default_up() -> [f32; 3] {
    [0.0, 1.0, 0.0]
}
fn default_camera_near() -> f32 {
    0.1
}
fn default_camera_far() -> f32 {
    1000.0
}
fn default_color() -> [f32; 3] {
    [0.8, 0.8, 0.8]
}
fn default_light_color() -> [f32; 3] {
    [1.0, 1.0, 1.0]
}
fn default_intensity() -> f32 {
    1.0
}
fn default_map_size() -> u32 {
    2048
}
fn default_light_far() -> f32 {
    500.0
}

/// One `--set` override with its value typed: TOML (`4`, `[0, 1, 0]`, `true`), or a bare word
/// taken as a string (`technique=pcss`).
#[derive(Clone, Debug, PartialEq)]
pub struct Override {
    pub key: String,
    pub value: toml::Value,
}

impl Override {
    /// `key=value` as the command line and the `set` tables give it.
    pub fn parse(key: &str, value: &str) -> Self {
        let value = match toml::from_str::<toml::Table>(&format!("v = {value}")) {
            Ok(mut t) => t.remove("v").unwrap_or(toml::Value::String(value.to_string())),
            Err(_) => toml::Value::String(value.to_string()),
        };
        Self { key: key.to_string(), value }
    }

    /// The value as `--set` would write it (a string without quotes).
    pub fn value_text(&self) -> String {
        match &self.value {
            toml::Value::String(s) => s.clone(),
            other => other.to_string(),
        }
    }
}

/// A scene file read and parsed once: each [`SceneSource::build`] applies its overrides to a
/// copy of the parsed table, and the meshes it names load once for all builds.
#[derive(Debug)]
pub struct SceneSource {
    path: Option<PathBuf>,
    label: String,
    base_dir: PathBuf,
    text: String,
    table: toml::Table,
    meshes: std::sync::Mutex<HashMap<PathBuf, Arc<Mesh>>>,
}

impl SceneSource {
    /// Read and parse a scene file (a syntax error names its line).
    pub fn read(path: &Path) -> Result<Self, SceneError> {
        let label = path.display().to_string();
        let text = crate::files::read_input_text(path, crate::files::MAX_TEXT_FILE_BYTES)
            .map_err(|reason| SceneError::Io { path: label.clone(), reason })?;
        let base_dir = path.parent().unwrap_or(Path::new("."));
        let mut source = Self::parse(text, base_dir, &label)?;
        source.path = Some(path.to_path_buf());
        Ok(source)
    }

    /// Parse scene text. `label` names the source in errors; mesh paths resolve against `base_dir`.
    pub fn parse(text: String, base_dir: &Path, label: &str) -> Result<Self, SceneError> {
        let table: toml::Table = toml::from_str(&text).map_err(|e| {
            let (line, message) = describe_toml_error(&text, &e);
            SceneError::Parse { path: label.to_string(), line, message }
        })?;
        Ok(Self {
            path: None,
            label: label.to_string(),
            base_dir: base_dir.to_path_buf(),
            text,
            table,
            meshes: Default::default(),
        })
    }

    /// The file it was read from, if any.
    pub fn path(&self) -> Option<&Path> {
        self.path.as_deref()
    }

    /// The scene with `overrides` applied in order. The file alone must be valid (its errors
    /// point at its lines), and each override is checked as it comes (its errors name its key).
    pub fn build(&self, overrides: &[Override]) -> Result<Scene, SceneError> {
        let (label, text) = (self.label.as_str(), self.text.as_str());
        let parse_error = |e: toml::de::Error| {
            let (line, message) = describe_toml_error(text, &e);
            SceneError::Parse { path: label.to_string(), line, message }
        };
        let mut meshes = self.meshes.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        let file: SceneFile = toml::from_str(text).map_err(parse_error)?;
        let mut scene =
            build_scene(file, &self.base_dir, &mut meshes).map_err(|e| e.with_path(label, Some(text)))?;
        if !overrides.is_empty() {
            let mut table = self.table.clone();
            for o in overrides {
                apply_override(&mut table, o)?;
                let file = SceneFile::deserialize(toml::Value::Table(table.clone())).map_err(|e| {
                    SceneError::Override { key: o.key.clone(), message: short_numbers(e.message().trim()) }
                })?;
                scene =
                    build_scene(file, &self.base_dir, &mut meshes).map_err(|e| e.with_override(&o.key))?;
            }
        }
        scene.path = self.path.clone();
        Ok(scene)
    }
}

/// Read a scene file and apply `--set` overrides (in order).
pub fn load_scene(path: &Path, overrides: &[(String, String)]) -> Result<Scene, SceneError> {
    SceneSource::read(path)?.build(&typed(overrides))
}

/// Parse scene text. `label` names the source in errors; mesh paths resolve against `base_dir`.
pub fn parse_scene_str(
    text: &str,
    base_dir: &Path,
    label: &str,
    overrides: &[(String, String)],
) -> Result<Scene, SceneError> {
    SceneSource::parse(text.to_string(), base_dir, label)?.build(&typed(overrides))
}

fn typed(overrides: &[(String, String)]) -> Vec<Override> {
    overrides.iter().map(|(k, v)| Override::parse(k, v)).collect()
}

/// Set one key in the scene table.
pub fn apply_override(table: &mut toml::Table, o: &Override) -> Result<(), SceneError> {
    let key = o.key.as_str();
    let err = |message: String| SceneError::Override { key: key.to_string(), message };
    let parsed = o.value.clone();
    let parts: Vec<&str> = key.split('.').collect();
    if parts.iter().any(|p| p.is_empty()) {
        return Err(err("malformed key".into()));
    }
    let (section, rest): (&str, &[&str]) = match parts[0] {
        "camera" | "shadow" | "light" | "object" | "ambient" => (parts[0], &parts[1..]),
        _ => ("shadow", &parts[..]),
    };
    let slot: &mut toml::Value = match section {
        "ambient" if rest.is_empty() => {
            table.insert("ambient".into(), parsed);
            return Ok(());
        }
        "camera" | "shadow" if rest.len() == 1 => {
            let entry =
                table.entry(section.to_string()).or_insert_with(|| toml::Value::Table(toml::Table::new()));
            entry
                .as_table_mut()
                .ok_or_else(|| err(format!("[{section}] is not a table")))?
                .insert(rest[0].to_string(), parsed);
            return Ok(());
        }
        "light" | "object" if rest.len() == 2 => {
            let index: usize =
                rest[0].parse().map_err(|_| err(format!("`{}` is not a {section} index", rest[0])))?;
            let list = table
                .get_mut(section)
                .and_then(|v| v.as_array_mut())
                .ok_or_else(|| err(format!("the scene has no [[{section}]]")))?;
            let count = list.len();
            list.get_mut(index).ok_or_else(|| err(format!("no {section} {index} (the scene has {count})")))?
        }
        _ => {
            return Err(err(
                "unknown key (use a [shadow] key, camera.KEY, light.N.KEY or object.N.KEY)".into()
            ));
        }
    };
    slot.as_table_mut()
        .ok_or_else(|| err(format!("{section} {} is not a table", rest[0])))?
        .insert(rest[1].to_string(), parsed);
    Ok(())
}

pub(crate) fn line_of(text: &str, byte: usize) -> usize {
    text.as_bytes()[..byte.min(text.len())].iter().filter(|&&b| b == b'\n').count() + 1
}

/// The line of a TOML error and its message, naming the key where serde's message does not
/// (`unknown variant 'blurry'` becomes "`technique`: unknown variant ...").
pub(crate) fn describe_toml_error(text: &str, e: &toml::de::Error) -> (usize, String) {
    let message = short_numbers(e.message().trim());
    let Some(span) = e.span() else { return (1, message) };
    let line = line_of(text, span.start);
    let line_text = text.lines().nth(line - 1).unwrap_or("");
    let key = line_text
        .split_once('=')
        .map(|(k, _)| k.trim().trim_matches('"'))
        .filter(|k| !k.is_empty() && !k.contains(['[', ']', '{']) && !message.contains(&format!("`{k}`")));
    match key {
        Some(key) => (line, format!("`{key}`: {message}")),
        None => (line, message),
    }
}

/// serde spells out a float it did not expect in full (`floating point
/// \`340000000000000000000000000000000000000.0\``): a quoted number that long is written in
/// exponent form instead.
fn short_numbers(message: &str) -> String {
    let mut out = String::with_capacity(message.len());
    for (i, part) in message.split('`').enumerate() {
        if i > 0 {
            out.push('`');
        }
        match part.parse::<f64>() {
            Ok(v) if i % 2 == 1 && part.len() > 24 => out.push_str(&format!("{v:e}")),
            _ => out.push_str(part),
        }
    }
    out
}

//! What the student's page did, as the recording stand-ins kept it: the lights it made (with the
//! line of their code that made each), the programs it built and, per draw, each uniform's value
//! by the name their code gave it.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::homework::light::ObjectUniforms;

/// One `new DirectionalLight(...)` or `new PointLight(...)` the page made.
#[derive(Clone, Debug, Deserialize)]
pub(super) struct MadeLight {
    pub kind: String,
    pub args: Vec<serde_json::Value>,
    pub file: String,
    pub line: usize,
    pub error: Option<String>,
}

/// A light the page made, as a report lists it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FoundLight {
    /// `DirectionalLight` or `PointLight`.
    pub kind: String,
    /// Where the student's code made it (`src/engine.js:47`); `framework` for shadowlab's copy.
    pub made_at: String,
    /// Its position as the constructor was given it (world units), where it was three numbers.
    pub position: Option<[f64; 3]>,
    /// Why its constructor failed, if it did.
    pub error: Option<String>,
}

impl MadeLight {
    pub(super) fn found(&self) -> FoundLight {
        let position = self.args.get(2).and_then(|v| {
            let a = v.as_array()?;
            (a.len() == 3).then_some([a[0].as_f64()?, a[1].as_f64()?, a[2].as_f64()?])
        });
        FoundLight {
            kind: self.kind.clone(),
            made_at: if self.line > 0 { format!("{}:{}", self.file, self.line) } else { "framework".into() },
            position,
            error: self.error.clone(),
        }
    }
}

#[derive(Clone, Debug, Default, Deserialize)]
struct Program {
    id: u64,
    fragment: Option<String>,
}

#[derive(Clone, Debug, Default, Deserialize)]
struct Draw {
    frame: i64,
    program: u64,
    /// The model request whose arrays were bound (None: arrays of the page's own, a light cube).
    #[serde(default)]
    request: Option<usize>,
    uniforms: BTreeMap<String, serde_json::Value>,
}

/// A file the page asked a loader for.
#[derive(Clone, Debug, Default, Deserialize)]
struct Request {
    url: String,
}

/// The programs the page built, the files it asked for and the draws of its first frames.
#[derive(Clone, Debug, Default, Deserialize)]
pub struct PageDraws {
    programs: Vec<Program>,
    draws: Vec<Draw>,
    #[serde(default)]
    requests: Vec<Request>,
}

/// Which kind of the framework's objects a draw drew.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Kind {
    Floor,
    Model,
    Unknown,
}

/// Each uniform's value most of `draws` had.
fn most_common<'a>(draws: impl Iterator<Item = &'a Draw>) -> BTreeMap<String, Vec<f64>> {
    let mut seen: BTreeMap<String, Vec<(Vec<f64>, usize)>> = BTreeMap::new();
    for draw in draws {
        for (name, value) in &draw.uniforms {
            let mut v = Vec::new();
            numbers(value, &mut v);
            let counts = seen.entry(name.clone()).or_default();
            match counts.iter_mut().find(|(seen, _)| *seen == v) {
                Some((_, n)) => *n += 1,
                None => counts.push((v, 1)),
            }
        }
    }
    seen.into_iter()
        .filter_map(|(name, counts)| {
            // The first of the most common: draws come in the page's order.
            let top = counts.iter().map(|(_, n)| *n).max()?;
            let best = counts.into_iter().find(|(_, n)| *n == top)?;
            Some((name, best.0))
        })
        .collect()
}

/// A uniform's value as numbers, in the order WebGL takes them (booleans as 0 and 1).
fn numbers(value: &serde_json::Value, out: &mut Vec<f64>) {
    match value {
        serde_json::Value::Number(n) => out.extend(n.as_f64()),
        serde_json::Value::Bool(b) => out.push(f64::from(u8::from(*b))),
        serde_json::Value::Array(items) => items.iter().for_each(|v| numbers(v, out)),
        _ => {}
    }
}

impl PageDraws {
    /// The file the page asked a loader for as request `index`.
    pub fn request_url(&self, index: usize) -> Option<String> {
        self.requests.get(index).map(|r| r.url.clone())
    }

    /// The uniforms the page set, by name, on the first frame's draws of the program whose
    /// fragment shader is `fragment`: for its floor and for its models.
    pub fn uniforms_for(&self, fragment: &str) -> ObjectUniforms {
        let wanted = fragment.trim();
        let programs: Vec<u64> = self
            .programs
            .iter()
            .filter(|p| p.fragment.as_deref().is_some_and(|f| f.trim() == wanted))
            .map(|p| p.id)
            .collect();
        let first_frame = self.draws.iter().filter(|d| programs.contains(&d.program)).map(|d| d.frame).min();
        let drawn: Vec<&Draw> = self
            .draws
            .iter()
            .filter(|d| programs.contains(&d.program) && Some(d.frame) == first_frame)
            .collect();
        let kind = |d: &Draw| match d.request.and_then(|r| self.requests.get(r)) {
            Some(r) if r.url.to_lowercase().contains("floor") => Kind::Floor,
            Some(_) => Kind::Model,
            None => Kind::Unknown,
        };
        let of_kind = |k: Kind| {
            let some: Vec<&Draw> = drawn.iter().copied().filter(|d| kind(d) == k).collect();
            if some.is_empty() { most_common(drawn.iter().copied()) } else { most_common(some.into_iter()) }
        };
        ObjectUniforms {
            floor: of_kind(Kind::Floor),
            other: of_kind(Kind::Model),
            model_matrices: model_matrices(&drawn),
        }
    }
}

/// The framework's names, which the check sets itself.
const FRAMEWORK_NAMES: [&str; 9] = [
    "uModelMatrix",
    "uViewMatrix",
    "uProjectionMatrix",
    "uLightMVP",
    "uCameraPos",
    "uLightPos",
    "uLightIntensity",
    "uKs",
    "uKd",
];

/// The uniforms of the page's own naming that hold the drawn object's model matrix: on every
/// draw that set both, the value was that draw's `uModelMatrix`, and on one at least it was
/// not the identity (which any matrix left alone is).
fn model_matrices(draws: &[&Draw]) -> Vec<String> {
    let matrix = |draw: &Draw, name: &str| {
        let mut v = Vec::new();
        numbers(draw.uniforms.get(name)?, &mut v);
        (v.len() == 16).then_some(v)
    };
    let same = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 1e-6 * (1.0 + y.abs()));
    let identity: Vec<f64> = (0..16).map(|k| if k % 5 == 0 { 1.0 } else { 0.0 }).collect();
    let names: std::collections::BTreeSet<&String> = draws
        .iter()
        .flat_map(|d| d.uniforms.keys())
        .filter(|n| !FRAMEWORK_NAMES.contains(&n.as_str()))
        .collect();
    names
        .into_iter()
        .filter(|name| {
            let pairs: Vec<(Vec<f64>, Vec<f64>)> =
                draws.iter().filter_map(|d| Some((matrix(d, name)?, matrix(d, "uModelMatrix")?))).collect();
            !pairs.is_empty()
                && pairs.iter().all(|(own, model)| same(own, model))
                && pairs.iter().any(|(own, _)| !same(own, &identity))
        })
        .cloned()
        .collect()
}

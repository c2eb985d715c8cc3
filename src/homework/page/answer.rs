//! What a student's page answers the check, whichever engine ran it: the light their engine.js
//! made (each value with the line it came from), each object's light matrix with the gl-matrix
//! and three.js calls that built it, and a failure as one line naming the file and line.

/// A script error on one line: `lights/DirectionalLight.js:37: near is not defined`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ScriptError {
    pub file: String,
    /// 1-based; 0 when no line applies.
    pub line: usize,
    pub message: String,
}

impl std::fmt::Display for ScriptError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.line == 0 {
            write!(f, "{}: {}", self.file, self.message)
        } else {
            write!(f, "{}:{}: {}", self.file, self.line, self.message)
        }
    }
}

impl std::error::Error for ScriptError {}

/// Where a value came from in the student's files.
#[derive(Clone, Debug, PartialEq)]
pub struct Sourced<T> {
    pub value: T,
    pub file: String,
    /// 0 (with file "framework") for the framework's defaults.
    pub line: usize,
}

impl<T> Sourced<T> {
    fn framework(value: T) -> Self {
        Sourced { value, file: "framework".into(), line: 0 }
    }
}

/// The light engine.js builds:
/// `new DirectionalLight(intensity, color, lightPos, focalPoint, lightUp, hasShadowMap, gl)`.
#[derive(Clone, Debug, PartialEq)]
pub struct EngineLight {
    pub intensity: Sourced<f64>,
    pub color: Sourced<[f64; 3]>,
    pub position: Sourced<[f64; 3]>,
    pub focal_point: Sourced<[f64; 3]>,
    pub up: Sourced<[f64; 3]>,
    pub notes: Vec<String>,
}

impl EngineLight {
    /// The framework's light: intensity 5000, white, at (0, 80, 80) looking at the origin, y up.
    pub fn framework() -> Self {
        EngineLight {
            intensity: Sourced::framework(5000.0),
            color: Sourced::framework([1.0, 1.0, 1.0]),
            position: Sourced::framework([0.0, 80.0, 80.0]),
            focal_point: Sourced::framework([0.0, 0.0, 0.0]),
            up: Sourced::framework([0.0, 1.0, 0.0]),
            notes: Vec::new(),
        }
    }
}

/// One gl-matrix or three.js call made while computing a matrix (what a report can show a TA).
#[derive(Clone, Debug, PartialEq)]
pub struct GlCall {
    /// "mat4.ortho", "THREE.OrthographicCamera".
    pub name: String,
    /// The numeric arguments only (vectors and matrices flattened), not the `out` array.
    pub args: Vec<f64>,
    /// The script of theirs the call was made from (`src/lights/PointLight.js`).
    pub file: String,
    pub line: usize,
}

/// A light matrix a student's CalcLightMVP returned.
#[derive(Clone, Debug, PartialEq)]
pub struct LightMatrix {
    /// Column-major, gl-matrix's layout; non-finite entries are kept for the caller to judge.
    pub clip_from_object: [f32; 16],
    /// The calls of this run, in order (at most the first 4096).
    pub calls: Vec<GlCall>,
    /// The line of the `return` that produced the matrix.
    pub return_line: usize,
}

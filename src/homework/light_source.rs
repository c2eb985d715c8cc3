//! Where a student's light is run: on the desktop, in their page (`page`, a real JavaScript
//! engine, which computes the matrix of each object it is given as it runs); in the browser page,
//! in `light_script`, shadowlab's own sandboxed interpreter, until the page runs them in the
//! browser's engine. Both answer each object's matrix.

use super::light_script::{EngineLight, LightMatrix, ScriptError};
use super::program::ShaderSource;
use serde::Serialize;

/// A student's light, loaded: each object's matrix, and what their page made and set.
pub(super) trait LightMatrices {
    fn notes(&self) -> &[String];
    fn light_matrix(&mut self, translate: [f64; 3], scale: [f64; 3]) -> Result<LightMatrix, ScriptError>;
    /// Every light the page made (the checked one marked) as the report lists them.
    fn lights(&self) -> Vec<LightEntry> {
        Vec::new()
    }
    /// Why the check cannot build this page's passes, if it cannot (one line naming where).
    fn refusal(&self) -> Option<String> {
        None
    }
    /// The values the page gave the uniforms of the program whose fragment shader is `fragment`.
    fn uniforms(&self, _fragment: &str) -> super::light::ObjectUniforms {
        super::light::ObjectUniforms::default()
    }
}

#[cfg(not(target_arch = "wasm32"))]
impl LightMatrices for super::page::PageRun {
    fn notes(&self) -> &[String] {
        self.notes()
    }
    fn light_matrix(&mut self, translate: [f64; 3], scale: [f64; 3]) -> Result<LightMatrix, ScriptError> {
        super::page::PageRun::light_matrix(self, translate, scale)
    }
    fn lights(&self) -> Vec<LightEntry> {
        let (found, checked) = self.lights();
        found
            .iter()
            .enumerate()
            .map(|(i, l)| LightEntry {
                kind: l.kind.clone(),
                from: l.made_at.clone(),
                made_at: l.made_at.clone(),
                position: l.position.map(|p| p.map(|x| x as f32)),
                checked: Some(i) == checked,
                error: l.error.clone(),
            })
            .collect()
    }
    fn uniforms(&self, fragment: &str) -> super::light::ObjectUniforms {
        self.draws().uniforms_for(fragment)
    }
    fn refusal(&self) -> Option<String> {
        self.float_texture().map(|at| {
            format!(
                "{at}: the page renders into float textures; the check builds the framework's RGBA8 shadow maps only, so it does not judge this submission"
            )
        })
    }
}

#[cfg(target_arch = "wasm32")]
impl LightMatrices for super::light_script::LightScript {
    fn notes(&self) -> &[String] {
        self.notes()
    }
    fn light_matrix(&mut self, translate: [f64; 3], scale: [f64; 3]) -> Result<LightMatrix, ScriptError> {
        self.light_matrix(translate, scale)
    }
}

/// The light engine.js makes and the student's `DirectionalLight.js` loaded: their page run in
/// a real engine, with their light's matrix for each object placed by (translate, scale).
#[cfg(not(target_arch = "wasm32"))]
pub(super) fn load_light(
    script: &ShaderSource,
    engine: Option<&ShaderSource>,
    page: &[ShaderSource],
    objects: &[super::page::Placed],
) -> (EngineLight, Result<Box<dyn LightMatrices>, ScriptError>) {
    match super::page::PageRun::run(script, engine, page, objects, super::page::Limits::default()) {
        Ok(run) => (run.engine_light.clone(), Ok(Box::new(run))),
        Err(e) => (EngineLight::framework(), Err(e)),
    }
}

/// The light engine.js makes (read without running it) and `DirectionalLight.js` in shadowlab's
/// own interpreter.
#[cfg(target_arch = "wasm32")]
pub(super) fn load_light(
    script: &ShaderSource,
    engine: Option<&ShaderSource>,
    _page: &[ShaderSource],
    _objects: &[([f64; 3], [f64; 3])],
) -> (EngineLight, Result<Box<dyn LightMatrices>, ScriptError>) {
    use super::light_script::{LightScript, Limits, engine_light};
    let limits = Limits::default();
    let light = match engine {
        Some(file) => engine_light(&file.text, &file.name, limits),
        None => EngineLight::framework(),
    };
    let loaded = LightScript::load(&script.text, &script.name, &light, limits);
    (light, loaded.map(|l| Box::new(l) as Box<dyn LightMatrices>))
}

/// One light the student's page made, as the report lists it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LightEntry {
    /// `DirectionalLight` or `PointLight`.
    pub kind: String,
    /// Where it comes from: for the checked light, the line its matrix is built on; else where
    /// the page made it.
    pub from: String,
    /// Where the student's code made it (`src/engine.js:47`), or `framework`.
    pub made_at: String,
    /// Its position as made, world units.
    pub position: Option<[f32; 3]>,
    /// Whether the check used it.
    pub checked: bool,
    /// Why its constructor or its matrix failed, if one did.
    pub error: Option<String>,
}

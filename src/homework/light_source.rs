//! Where a student's light is run: in their page (`page`), in a real JavaScript engine that
//! computes the matrix of each object it is given as it runs: QuickJS on the desktop, the
//! browser's own engine (a Worker) in the page.

use super::page::{EngineLight, LightMatrix, ScriptError};
use super::program::ShaderSource;
use serde::Serialize;
use std::task::Poll;

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
    /// Draws of the page's animation whose uLightMVP did not follow what moved.
    fn stale(&self) -> Vec<super::light::StaleMatrix> {
        Vec::new()
    }
    /// Makes `light_matrix` answer for the page's light `index` (as `lights` numbers them), as
    /// the page loaded or at `seconds` of its animation, and gives that light as engine.js made
    /// it (moved where the animation took it); None where it has no matrices then.
    fn select(&mut self, _index: usize, _seconds: Option<f64>) -> Option<EngineLight> {
        None
    }
}

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
                findings: None,
                light_width: None,
                moved_at_s: self.times_of(i),
                at_times: Vec::new(),
            })
            .collect()
    }
    fn uniforms(&self, fragment: &str) -> super::light::ObjectUniforms {
        self.draws().uniforms_for(fragment)
    }
    fn stale(&self) -> Vec<super::light::StaleMatrix> {
        super::page::PageRun::stale(self).to_vec()
    }
    fn select(&mut self, index: usize, seconds: Option<f64>) -> Option<EngineLight> {
        super::page::PageRun::select(self, index, seconds)
    }
    fn refusal(&self) -> Option<String> {
        self.float_texture().map(|at| {
            format!(
                "{at}: the page renders into float textures; the check builds the framework's RGBA8 shadow maps only, so it does not judge this submission"
            )
        })
    }
}

/// The light engine.js made (the framework's where the page failed), and each object's matrix or
/// why there is none.
pub(super) type LoadedLight = (EngineLight, Result<Box<dyn LightMatrices>, ScriptError>);

/// The light engine.js makes and the student's `DirectionalLight.js` loaded: their page run in
/// a real engine, with their light's matrix for each object placed by (translate, scale).
/// Pending in the browser until its Worker answers (the desktop answers at once).
pub(super) fn load_light(
    script: &ShaderSource,
    engine: Option<&ShaderSource>,
    page: &[ShaderSource],
    objects: &[super::page::Placed],
) -> Poll<LoadedLight> {
    use super::page::{Limits, PageRun};
    #[cfg(not(target_arch = "wasm32"))]
    let run = Poll::Ready(PageRun::run(script, engine, page, objects, Limits::default()));
    #[cfg(target_arch = "wasm32")]
    let run = PageRun::poll(script, engine, page, objects, Limits::default());
    run.map(|run| match run {
        Ok(run) => (run.engine_light.clone(), Ok(Box::new(run) as Box<dyn LightMatrices>)),
        Err(e) => (EngineLight::framework(), Err(e)),
    })
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
    /// Whether this check used it.
    pub checked: bool,
    /// Why its constructor or its matrix failed, if one did.
    pub error: Option<String>,
    /// The findings of its own check (ids), where it had one: each light of the page with a map
    /// is checked on its own by `shadowlab homework`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub findings: Option<Vec<String>>,
    /// What the slabs said of the light its check's shader behaves as; `law_holds` is null where
    /// too few of the check scene's slabs cast a measurable shadow under this light to judge.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub light_width: Option<super::LightWidthFit>,
    /// The times (seconds of the page's animation) at which the check looked again and found it
    /// moved: an orbit, a light their code moves each frame.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub moved_at_s: Vec<f64>,
    /// Its checks at those times, by `shadowlab homework`.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub at_times: Vec<TimedCheck>,
}

/// A light's check at one time of the page's animation.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TimedCheck {
    pub time_s: f64,
    /// Where the animation had taken the light, world units.
    pub position: [f32; 3],
    pub findings: Vec<String>,
}

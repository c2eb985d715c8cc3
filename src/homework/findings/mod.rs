//! What a homework gets wrong. The evidence: the visibility the student's shader returned at
//! every pixel (over the framework's map, a white one and a lossless one), what each of their
//! functions returned and where it read the map, shadowlab's own technique and the ground truth at
//! the same pixel, the light their penumbrae say, and the light they built. Each finding is a
//! function of its own in [`FINDINGS`], run in that order; it carries the figures that show it, a
//! sentence on the cause and the lesson step that teaches it.
//!
//! A finding is a mistake where it shows in the picture the framework draws. The same checks run
//! again over the lossless map (depth kept in floats, not rounded to 8 bits a channel): what shows
//! only there is latent, today hidden by the framework's packing (its 256-vs-255 rounding reads
//! depth about depth / 255 too far, a bias of its own). The thresholds are set from figures
//! across real submissions, never for one file (tests/homework_check.rs holds the project's own
//! example of each).

mod blocker_test;
mod filter_radius;
mod formula_lines;
mod framework_floor;
mod functions;
mod ids;
mod light;
mod pcss_steps;
mod penumbra;
mod penumbra_law;
mod round_trip;
pub(crate) mod shadows;
mod source_lines;
mod visibility;

pub use functions::TwinInputs;

use super::light_width::LightWidthFit;
use super::{HomeworkImages, TapImages};
use crate::i18n::Lang;
use glam::{Mat4, Vec2, Vec3};
use serde::Serialize;
use std::collections::BTreeMap;

/// Ground truth at or below this: the umbra; at or above `LIT`: fully lit.
pub(crate) const UMBRA: f32 = 0.02;
pub(crate) const LIT: f32 = 0.98;
/// A visibility strictly between these is soft (in a penumbra).
pub(crate) const SOFT: (f32, f32) = (0.05, 0.95);
/// A surface faces the light where N.L is above this.
pub(crate) const FACING: f32 = 0.3;

/// Figure names for the check scene's slabs, in the scene's order.
pub(crate) struct SlabKeys {
    pub core_visibility: &'static str,
    pub width_world: &'static str,
    pub law_width_world: &'static str,
}

pub(crate) const SLAB_KEYS: [SlabKeys; 4] = [
    SlabKeys {
        core_visibility: "slab_1_core_visibility",
        width_world: "slab_1_width_world",
        law_width_world: "slab_1_law_width_world",
    },
    SlabKeys {
        core_visibility: "slab_2_core_visibility",
        width_world: "slab_2_width_world",
        law_width_world: "slab_2_law_width_world",
    },
    SlabKeys {
        core_visibility: "slab_3_core_visibility",
        width_world: "slab_3_width_world",
        law_width_world: "slab_3_law_width_world",
    },
    SlabKeys {
        core_visibility: "slab_4_core_visibility",
        width_world: "slab_4_width_world",
        law_width_world: "slab_4_law_width_world",
    },
];

/// Whether a finding shows in the picture.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Severity {
    /// It shows in the picture the framework draws.
    Mistake,
    /// It does not show today: only over a lossless map, or in a value a later step discards.
    Latent,
}

/// One thing a check found.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Finding {
    pub id: &'static str,
    pub severity: Severity,
    /// The student's function it names first, where it names one.
    pub function: Option<&'static str>,
    /// The figures that show it, by name.
    pub figures: BTreeMap<&'static str, f64>,
    /// What was seen and its likely cause, one or two sentences.
    pub explanation: String,
    /// The lesson step that teaches it: the lesson's id and the step, from 1.
    pub lesson: &'static str,
    pub step: usize,
}

/// A finding's entry in the registry.
pub struct FindingKind {
    pub id: &'static str,
    /// The lesson step that teaches it.
    pub lesson: &'static str,
    pub step: usize,
    /// Judge the evidence; `earlier` holds what the entries before this one found.
    pub judge: fn(&Judged<'_>, &[Finding], Lang) -> Option<Found>,
}

/// What a finding's judge returns: the rest comes from its registry entry.
pub struct Found {
    pub function: Option<&'static str>,
    pub figures: BTreeMap<&'static str, f64>,
    pub explanation: String,
    /// The mistake is there but a later step discards it (a NaN PCSS guards against).
    pub latent: bool,
}

impl Found {
    pub fn new(
        function: Option<&'static str>,
        figures: BTreeMap<&'static str, f64>,
        explanation: String,
    ) -> Self {
        Self { function, figures, explanation, latent: false }
    }
}

/// Every finding, in the order they are judged (a later one may stand aside for an earlier one
/// that explains the same pixels).
pub const FINDINGS: &[FindingKind] = &[
    visibility::NAN_BLOCKER_DEPTH,
    visibility::NAN_VISIBILITY,
    visibility::VISIBILITY_OUT_OF_RANGE,
    visibility::VISIBILITY_SCALED,
    light::LIGHT_MODEL_MATRIX,
    light::LIGHT_DIRECTION_OFF,
    light::LIGHT_FRUSTUM_CLIPS,
    light::LIGHT_NOT_DRAWN,
    light::LIGHT_MATRIX_STALE,
    shadows::SHADOWS_MISSING,
    shadows::PETER_PANNING,
    shadows::UMBRA_NOT_DARK,
    functions::DEPTH_ROUND_TRIP_WRONG,
    functions::SEARCH_RADIUS_WRONG,
    functions::FILTER_RADIUS_NOT_FINITE,
    pcss_steps::SEARCH_MISSES_LIGHT,
    blocker_test::SEARCH_READS_PART_OF_DISK,
    blocker_test::RECEIVER_COUNTS_AS_BLOCKER,
    pcss_steps::BLOCKER_DEPTH_WRONG,
    pcss_steps::PENUMBRA_ESTIMATE_WRONG,
    functions::SAMPLES_NOT_AROUND_RECEIVER,
    filter_radius::FILTER_IGNORES_BLOCKER,
    penumbra_law::PENUMBRA_LAW_WRONG,
    filter_radius::SEARCH_AND_FILTER_LIGHTS_DIFFER,
    shadows::SELF_SHADOWING,
    pcss_steps::UNPACK_LOSES_DEPTH,
    round_trip::ROUND_TRIP_ACNE,
    penumbra::NO_PENUMBRA,
    penumbra::NO_CONTACT_HARDENING,
    shadows::DEPENDS_ON_UNCLEARED_MAP,
];

/// The light a homework's passes were drawn with, as the check reads it.
pub struct LightInputs<'a> {
    /// `uLightMVP` per scene object (GL clip conventions) and each object's model matrix.
    pub clip_from_object: &'a [Mat4],
    pub world_from_object: &'a [Mat4],
    /// The scene's object names, in order.
    pub object_names: &'a [String],
    /// Texels per side of the map.
    pub map_size: u32,
    /// The matrix an object at the origin gets (GL clip from world): the framework's floor
    /// under it.
    pub clip_from_world: Mat4,
    /// Where the light looks (unit, world: from its position to its focal point), and the
    /// script's line that made its matrix (`DirectionalLight.js:37`, or `framework`).
    pub look_direction: Vec3,
    pub from: String,
    /// The slabs' penumbrae and the light width they say.
    pub width: Option<&'a LightWidthFit>,
    /// What the student's model matrix does instead of translate-then-scale, where it is wrong.
    pub model_matrix: Option<super::ModelMatrixError>,
    /// Draws of the page's animation whose uLightMVP for this light did not follow what moved.
    pub stale: &'a [crate::homework::light::StaleMatrix],
}

/// The per-pixel inputs of a check, all of one view's size, rows top first.
pub struct Evidence<'a> {
    /// The student's pass over the map judged (the framework's, or the lossless one), and where
    /// their functions read.
    pub student: &'a HomeworkImages,
    /// The student's pass over the lossless map, and that map as their light pass packed it.
    pub lossless: &'a HomeworkImages,
    pub lossless_map: Option<&'a super::images::PackedMap>,
    pub taps: &'a TapImages,
    /// Per pixel, by how much the visibility over the framework's map changes over a white one
    /// (NaN where one of the two is not a finite number and the other is, or only one has one):
    /// what depends on the texels the framework never clears.
    pub white_map_change: &'a [f32],
    /// shadowlab's technique at the same settings, and the ground truth, per pixel.
    pub shadowlab: &'a [f32],
    pub ground_truth: &'a [f32],
    /// N.L towards the light per pixel (None: no surface).
    pub facing: &'a [Option<f32>],
    /// The function (1-based in `RECORDED_FUNCTIONS`) `main` takes its visibility from.
    pub visibility_function: Option<usize>,
    /// The world position and the scene object under each pixel (None: no surface).
    pub positions: &'a [Option<Vec3>],
    pub objects: &'a [Option<usize>],
    pub light: LightInputs<'a>,
    /// shadowlab's map of the same light, where the twin searches as the student's findBlocker did.
    pub twin: Option<&'a TwinInputs<'a>>,
    /// The student's fragment shader: the lines a finding can point at.
    pub fragment_source: &'a str,
}

/// Where a pixel's surface lies in the student's own light: their shadow coordinate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Receiver {
    /// uv of the map and depth in [0, 1], as `vPositionFromLight.xyz / w * 0.5 + 0.5` gives them.
    pub uv: Vec2,
    pub depth: f32,
}

impl Receiver {
    /// Inside the map and its depth range.
    pub fn inside(&self) -> bool {
        (0.0..=1.0).contains(&self.uv.x)
            && (0.0..=1.0).contains(&self.uv.y)
            && (0.0..=1.0).contains(&self.depth)
    }
}

/// The evidence with what every finding reads worked out once.
pub struct Judged<'a> {
    pub e: &'a Evidence<'a>,
    /// Pixels the student's shader ran at.
    pub shaded: Vec<usize>,
    /// Of those, with a finite visibility.
    pub finite: Vec<(usize, f32)>,
    /// Shaded pixels whose visibility is NaN or infinite.
    pub non_finite: usize,
    /// Each pixel's shadow coordinate in the student's light (None: no surface).
    pub receivers: Vec<Option<Receiver>>,
    /// The twin's searches where findBlocker searched, worked out on first use.
    twin: std::cell::OnceCell<Vec<(usize, functions::TwinSearch)>>,
}

impl<'a> Judged<'a> {
    pub fn new(e: &'a Evidence<'a>) -> Self {
        let student = e.student;
        let shaded: Vec<usize> = (0..student.calls.len()).filter(|&i| student.covered(i)).collect();
        let visible: Vec<(usize, f32)> =
            shaded.iter().filter_map(|&i| student.visibility(i).map(|v| (i, v))).collect();
        let finite: Vec<(usize, f32)> = visible.iter().copied().filter(|(_, v)| v.is_finite()).collect();
        let non_finite = visible.len() - finite.len();
        let inverses: Vec<Mat4> = e.light.world_from_object.iter().map(|m| m.inverse()).collect();
        let receivers = (0..e.positions.len())
            .map(|i| {
                let (p, o) = (e.positions[i]?, e.objects.get(i).copied().flatten()?);
                let clip = *e.light.clip_from_object.get(o)? * (*inverses.get(o)? * p.extend(1.0));
                let ndc = clip.truncate() / clip.w;
                Some(Receiver { uv: Vec2::new(ndc.x, ndc.y) * 0.5 + 0.5, depth: ndc.z * 0.5 + 0.5 })
            })
            .collect();
        Self { e, shaded, finite, non_finite, receivers, twin: std::cell::OnceCell::new() }
    }

    /// The twin's searches where the student's findBlocker searched (see `functions`).
    pub(crate) fn twin(&self) -> &[(usize, functions::TwinSearch)] {
        self.twin.get_or_init(|| functions::twin_searches(self))
    }

    pub fn truth(&self, i: usize) -> f32 {
        self.e.ground_truth[i]
    }

    /// No recorded function returned NaN here (NaN lookups land anywhere: such a pixel is
    /// explained by that, and left out of the other checks).
    pub fn sound(&self, i: usize) -> bool {
        let s = self.e.student;
        (0..4).all(|k| !s.ran(i, k) || s.returned[i][k].is_finite())
    }

    /// The visibility over the framework's map changes by more than `by` over a white one.
    pub fn changes_over_white(&self, i: usize, by: f32) -> bool {
        let change = self.e.white_map_change[i];
        change.is_nan() || change > by
    }

    /// The surface faces the light.
    pub fn faces_light(&self, i: usize) -> bool {
        self.e.facing[i].is_some_and(|c| c > FACING)
    }

    /// The student's visibility is through PCSS.
    pub fn pcss(&self) -> bool {
        self.e.visibility_function == Some(3)
    }

    pub fn share(&self, count: usize) -> f64 {
        count as f64 / self.shaded.len().max(1) as f64
    }
}

pub(crate) fn mean(values: impl Iterator<Item = f64>) -> Option<f64> {
    let (sum, n) = values.fold((0.0, 0u64), |(s, n), v| (s + v, n + 1));
    (n > 0).then(|| sum / n as f64)
}

/// The median of `values` (None: empty).
pub(crate) fn median(mut values: Vec<f32>) -> Option<f32> {
    values.retain(|v| !v.is_nan());
    values.sort_by(f32::total_cmp);
    values.get(values.len() / 2).copied()
}

pub(crate) fn has(earlier: &[Finding], id: &str) -> bool {
    earlier.iter().any(|f| f.id == id)
}

/// By how much each pixel's visibility changes from `student` to `white` (see
/// `Evidence::white_map_change`).
pub fn white_map_change(student: &HomeworkImages, white: &HomeworkImages) -> Vec<f32> {
    (0..student.calls.len())
        .map(|i| match (student.visibility(i), white.visibility(i)) {
            (Some(a), Some(b)) if a.is_finite() && b.is_finite() => (a - b).abs(),
            (Some(a), Some(b)) if a.is_finite() == b.is_finite() => 0.0,
            (None, None) => 0.0,
            _ => f32::NAN,
        })
        .collect()
}

/// Run every finding over the evidence, in order.
pub fn judge(evidence: &Evidence<'_>, lang: Lang) -> Vec<Finding> {
    let judged = Judged::new(evidence);
    // The blocker search is named as the student named it (`averageBlockerDepth`).
    let source = evidence.fragment_source;
    let blocker_search = super::instrument::recorded_name(source, &super::lex::tokens(source), "findBlocker")
        .filter(|name| *name != "findBlocker");
    let mut found: Vec<Finding> = Vec::new();
    for kind in FINDINGS {
        if let Some(mut f) = (kind.judge)(&judged, &found, lang) {
            if let Some(name) = blocker_search {
                f.explanation = f.explanation.replace("findBlocker", name);
            }
            found.push(Finding {
                id: kind.id,
                severity: if f.latent { Severity::Latent } else { Severity::Mistake },
                function: f.function,
                figures: f.figures,
                explanation: f.explanation,
                lesson: kind.lesson,
                step: kind.step,
            });
        }
    }
    found
}

/// The findings of a check: the mistakes the framework's map shows, then what shows only over
/// the lossless one (latent), each with why it does not show today.
pub fn findings(framework: &Evidence<'_>, lossless: &Evidence<'_>, lang: Lang) -> Vec<Finding> {
    let mut all = judge(framework, lang);
    let hidden: Vec<Finding> = judge(lossless, lang)
        .into_iter()
        .filter(|f| !has(&all, f.id) && f.id != ids::DEPENDS_ON_UNCLEARED_MAP)
        .map(|mut f| {
            f.severity = Severity::Latent;
            f.explanation = format!(
                "{} {}",
                crate::i18n::tr(lang, "Hidden today by the framework's packing (its 256-vs-255 rounding reads every depth a little too far, a bias of its own); it shows as soon as depth is kept exactly:"),
                f.explanation
            );
            f
        })
        .collect();
    // A latent mistake of a function already named shows its own figures too.
    all.extend(hidden);
    all
}

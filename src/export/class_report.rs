//! The class report `shadowlab homework --class` writes: `index.html` (English) and
//! `index_zh.html` (Chinese), each linking to the other (`page`), and `grades.csv`, from one row
//! per student: how their check ended and what their `report.json` says.
//!
//! Everything is built in memory before the first file is written, and each file is written
//! atomically: a failure leaves the last class report whole. Student-controlled text (names,
//! messages, explanations that quote file names) is escaped wherever it is written.

mod page;
mod saved;

pub use saved::{CLASS, MAX_REPORT_BYTES, is_class_report, read, read_report};

use crate::homework::findings::FINDINGS;
use crate::i18n::{Lang, tr};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;

/// The class report's files, in the order they are written.
pub const INDEX_EN: &str = "index.html";
pub const INDEX_ZH: &str = "index_zh.html";
pub const GRADES: &str = "grades.csv";

/// The pictures of a student's check the page shows, as their check names them.
pub const PICTURES: [&str; 4] =
    ["student.png", "student_lossless_map.png", "ground_truth.png", "difference.png"];

/// How a student's check ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// It ran and wrote its report.
    Checked,
    /// The shader did not compile (its report says where).
    DidNotCompile,
    /// The submission could not be read as a homework (exit 2).
    Refused,
    /// The check failed (exit 1) or crashed.
    Failed,
    /// It was stopped after the time allowed.
    TimedOut,
}

impl Status {
    pub const ALL: [Status; 5] =
        [Status::Checked, Status::DidNotCompile, Status::Refused, Status::Failed, Status::TimedOut];

    /// The status as the CSV, the summary and the English page say it.
    pub fn label(self) -> &'static str {
        tr(Lang::En, self.key())
    }

    /// The status in `lang`.
    pub fn shown(self, lang: Lang) -> &'static str {
        tr(lang, self.key())
    }

    fn key(self) -> &'static str {
        match self {
            Status::Checked => "checked@class",
            Status::DidNotCompile => "did not compile@class",
            Status::Refused => "refused@class",
            Status::Failed => "failed@class",
            Status::TimedOut => "timed out@class",
        }
    }

    /// A class name for the page's colours (no English word: the Chinese page holds none).
    fn css(self) -> &'static str {
        match self {
            Status::Checked => "s-ok",
            Status::DidNotCompile => "s-compile",
            Status::Refused => "s-refuse",
            Status::Failed => "s-fail",
            Status::TimedOut => "s-time",
        }
    }
}

/// Whether a finding shows in the picture (`report.json`'s `severity`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Severity {
    Mistake,
    Latent,
}

/// What the class report reads of a student's `report.json`; the rest of it is left alone.
#[derive(Clone, Debug, Default, PartialEq, Deserialize)]
pub struct StudentReport {
    pub compiled: bool,
    #[serde(default)]
    pub error: Option<ShaderError>,
    #[serde(default)]
    pub visibility_function: Option<String>,
    #[serde(default)]
    pub light: Option<LightPart>,
    #[serde(default)]
    pub light_width: Option<WidthPart>,
    #[serde(default)]
    pub findings: Vec<FindingPart>,
    /// Every light the student's page made (absent where the page did not run).
    #[serde(default)]
    pub lights: Vec<PageLightPart>,
}

/// One light the student's page made, and the findings of its own check where it had one.
#[derive(Clone, Debug, Default, PartialEq, Deserialize)]
pub struct PageLightPart {
    #[serde(default)]
    pub kind: String,
    #[serde(default)]
    pub made_at: String,
    #[serde(default)]
    pub findings: Option<Vec<String>>,
    /// Its checks where the page's animation had moved it.
    #[serde(default)]
    pub at_times: Vec<TimedPart>,
}

/// A light's check at one time of the page's animation.
#[derive(Clone, Debug, Default, PartialEq, Deserialize)]
pub struct TimedPart {
    #[serde(default)]
    pub time_s: f64,
    #[serde(default)]
    pub findings: Vec<String>,
}

impl PageLightPart {
    /// What its checks found, in one line: `no findings`, or the ids, then each time's.
    pub fn verdict(&self, no_findings: &str, not_checked: &str, at: impl Fn(f64) -> String) -> String {
        let list = |f: &[String]| if f.is_empty() { no_findings.to_string() } else { f.join(" ") };
        let mut verdict = self.findings.as_deref().map_or(not_checked.to_string(), list);
        for timed in &self.at_times {
            verdict.push_str(&format!("; {}: {}", at(timed.time_s), list(&timed.findings)));
        }
        verdict
    }
}

impl StudentReport {
    /// The bonus, where the page made several lights or moved one: (lights made, checks of
    /// them, of those how many without a finding).
    pub fn bonus(&self) -> Option<(usize, usize, usize)> {
        let moved = self.lights.iter().any(|l| !l.at_times.is_empty());
        (self.lights.len() > 1 || moved).then(|| {
            let checks: Vec<&[String]> = self
                .lights
                .iter()
                .flat_map(|l| {
                    l.findings.as_deref().into_iter().chain(l.at_times.iter().map(|t| &t.findings[..]))
                })
                .collect();
            (self.lights.len(), checks.len(), checks.iter().filter(|f| f.is_empty()).count())
        })
    }
}

#[derive(Clone, Debug, Default, PartialEq, Deserialize)]
pub struct ShaderError {
    #[serde(default)]
    pub file: String,
    #[serde(default)]
    pub line: Option<u64>,
    #[serde(default)]
    pub message: String,
}

#[derive(Clone, Debug, Default, PartialEq, Deserialize)]
pub struct LightPart {
    /// `DirectionalLight.js:37`, or `framework`.
    #[serde(default)]
    pub from: String,
    /// Why the student's light was not used.
    #[serde(default)]
    pub error: Option<String>,
    #[serde(default)]
    pub frustum: Option<FrustumPart>,
}

#[derive(Clone, Debug, Default, PartialEq, Deserialize)]
pub struct FrustumPart {
    #[serde(default)]
    pub kind: String,
    #[serde(default)]
    pub width_world: Option<f64>,
    #[serde(default)]
    pub fov_deg: Option<f64>,
    #[serde(default)]
    pub depth_range_world: Option<f64>,
}

#[derive(Clone, Debug, Default, PartialEq, Deserialize)]
pub struct WidthPart {
    #[serde(default)]
    pub implied_light_width_world: Option<f64>,
    /// Set where the penumbrae are too narrow to measure: the light is narrower than this.
    #[serde(default)]
    pub narrower_than_world: Option<f64>,
    /// False where the widths follow no light's similar triangles.
    #[serde(default)]
    pub law_holds: Option<bool>,
}

impl WidthPart {
    /// The light width to tell: a number where it could be measured and a light casts these
    /// widths (`LightWidthFit::measured_width_world`'s rule, on the report as read back).
    pub fn measured(&self) -> Option<f64> {
        self.implied_light_width_world
            .filter(|_| self.narrower_than_world.is_none() && self.law_holds != Some(false))
    }
}

#[derive(Clone, Debug, PartialEq, Deserialize)]
pub struct FindingPart {
    pub id: String,
    pub severity: Severity,
    /// By name; a figure that is not a number is null in the JSON.
    #[serde(default)]
    pub figures: BTreeMap<String, Option<f64>>,
    #[serde(default)]
    pub explanation: String,
    #[serde(default)]
    pub lesson: String,
    #[serde(default)]
    pub step: usize,
}

impl StudentReport {
    /// A report as a check printed or wrote it (one line on failure).
    pub fn parse(text: &str) -> Result<Self, String> {
        serde_json::from_str(text).map_err(|e| format!("not a homework report: {e}"))
    }

    fn mistakes(&self) -> usize {
        self.findings.iter().filter(|f| f.severity == Severity::Mistake).count()
    }
}

/// One student of the class.
#[derive(Clone, Debug, PartialEq)]
pub struct ClassRow {
    /// The submission's name (its folder's, or its zip's without `.zip`).
    pub name: String,
    /// The folder under the class report's its check wrote to.
    pub folder: String,
    /// The submission as the class folder holds it (its folder or .zip).
    pub path: String,
    pub status: Status,
    /// What the check said on failure, or its warning; one line.
    pub message: String,
    /// Its report (a check that ran, or a shader that did not compile).
    pub report: Option<StudentReport>,
    /// Which of `PICTURES` are in its folder.
    pub pictures: Vec<&'static str>,
}

/// One line for each finding of the registry: what the ranked list says of it, and what a page in
/// another language than the reports' shows in place of their explanation. Their Chinese is in
/// `i18n/class_zh.rs`.
const DESCRIPTIONS: &[(&str, &str)] = &[
    ("nan_blocker_depth", "findBlocker divides by zero blockers where nothing blocks the light (NaN depth)."),
    ("nan_visibility", "The visibility is NaN or infinite on some pixels."),
    (
        "visibility_out_of_range",
        "The visibility leaves [0, 1]: a sum of tests divided by the wrong count, or not at all.",
    ),
    ("visibility_scaled", "The visibility is scaled by a constant: lit points do not reach 1."),
    ("light_model_matrix", "CalcLightMVP places the objects differently from the framework's model matrix."),
    ("light_direction_off", "The light's map projects along another direction than the light looks."),
    ("light_frustum_clips", "The light's frustum leaves part of the scene outside the shadow map."),
    ("light_not_drawn", "The page never draws with this light's matrix: its shadows are another light's."),
    ("light_matrix_stale", "A light or an object moves, but the uLightMVP its draws get stays where it was."),
    ("shadows_missing", "Shadows are missing: the lookups never meet the blockers (wrong space or units)."),
    ("peter_panning", "A bias so large that shadows come loose from what casts them (peter panning)."),
    (
        "umbra_not_dark",
        "The umbra is not dark: the filter reaches far past the blocker (world units used as uv).",
    ),
    (
        "depth_round_trip_wrong",
        "Depth does not come back from the map as it went in: pack and unpack disagree.",
    ),
    (
        "search_radius_wrong",
        "findBlocker's search radius is wrong for the light's size and the receiver's depth.",
    ),
    (
        "filter_radius_not_finite",
        "PCSS filters over a radius that is not a number (a blocker depth of 0 divided by).",
    ),
    ("receiver_counts_as_blocker", "findBlocker counts the receiver as its own blocker."),
    ("blocker_depth_wrong", "findBlocker returns a depth no blocker has where the disk is blocked."),
    (
        "penumbra_estimate_wrong",
        "PCSS's filter radius collapses under blockers: the penumbra estimate misses the receiver's depth.",
    ),
    ("samples_not_around_receiver", "The filter's taps are not spread over a disk around the receiver."),
    (
        "penumbra_law_wrong",
        "PCSS's filter radius scales with the depths beyond similar triangles (near / z_r on an orthographic light).",
    ),
    (
        "filter_ignores_blocker",
        "PCSS's filter radius does not use the blocker's depth: PCF with a radius of its own.",
    ),
    (
        "search_and_filter_lights_differ",
        "The blocker search and the filter behave as lights of different sizes (one length, two units).",
    ),
    ("no_penumbra", "PCSS draws hard shadows: the filter is under a texel wide."),
    ("no_contact_hardening", "Penumbrae do not widen with the blocker's distance as similar triangles say."),
    ("self_shadowing", "Lit surfaces shadow themselves: shadow acne, a bias too small."),
    (
        "round_trip_acne",
        "The framework's far floor acnes: its RGBA8 round trip reads depths over 0.5 nearer than the bias.",
    ),
    ("depends_on_uncleared_map", "The picture depends on the texels the framework never clears."),
];

/// The one-line description of finding `id` in `lang` (None: an id this table lacks).
pub fn description(lang: Lang, id: &str) -> Option<&'static str> {
    DESCRIPTIONS.iter().find(|(known, _)| *known == id).map(|(_, en)| tr(lang, en))
}

/// The lesson step that teaches finding `id`: the registry's, else what a report said.
fn lesson_of<'a>(id: &str, finding: Option<&'a FindingPart>) -> Option<(&'a str, usize)> {
    match FINDINGS.iter().find(|k| k.id == id) {
        Some(kind) => Some((kind.lesson, kind.step)),
        None => finding.filter(|f| !f.lesson.is_empty()).map(|f| (f.lesson.as_str(), f.step)),
    }
}

/// A finding and the students who have it.
#[derive(Clone, Debug, PartialEq)]
pub struct Ranked {
    pub id: String,
    pub severity: Severity,
    /// Indices into the rows, in class order.
    pub students: Vec<usize>,
}

/// The findings across the class, most students first: mistakes, then latent ones; ties in the
/// registry's order.
pub fn ranked(rows: &[ClassRow]) -> Vec<Ranked> {
    let mut found: Vec<Ranked> = Vec::new();
    for (i, row) in rows.iter().enumerate() {
        for f in row.report.iter().flat_map(|r| &r.findings) {
            match found.iter_mut().find(|r| r.id == f.id && r.severity == f.severity) {
                Some(r) if r.students.last() != Some(&i) => r.students.push(i),
                Some(_) => {}
                None => found.push(Ranked { id: f.id.clone(), severity: f.severity, students: vec![i] }),
            }
        }
    }
    let order = |id: &str| FINDINGS.iter().position(|k| k.id == id).unwrap_or(FINDINGS.len());
    found.sort_by(|a, b| {
        let rank = |r: &Ranked| (r.severity == Severity::Latent, std::cmp::Reverse(r.students.len()));
        rank(a).cmp(&rank(b)).then_with(|| order(&a.id).cmp(&order(&b.id))).then_with(|| a.id.cmp(&b.id))
    });
    found
}

/// A number for people: whole numbers as such, others with a few decimals.
fn number(v: f64) -> String {
    if !v.is_finite() {
        return "n/a".into();
    }
    if v.fract() == 0.0 && v.abs() < 1e12 {
        return format!("{v:.0}");
    }
    let decimals = if v.abs() >= 100.0 { 1 } else { 3 };
    let text = format!("{v:.decimals$}");
    text.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// One CSV field (RFC 4180): quoted where it holds a comma, a quote or a line break, its quotes
/// doubled.
pub fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\r', '\n']) || s.starts_with(' ') || s.ends_with(' ') {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// A field of text the student controls: as `csv_field`, and one a spreadsheet would run as a
/// formula (`=`, `+`, `-`, `@` first) starts with `'` instead.
fn csv_text(s: &str) -> String {
    if s.starts_with(['=', '+', '-', '@', '\t', '\r']) { csv_field(&format!("'{s}")) } else { csv_field(s) }
}

/// `grades.csv`: one row per student, a column per finding of the registry (1: a mistake,
/// `latent`, 0: not found; empty where nothing was judged) and their count of mistakes. With a
/// byte order mark, so that a spreadsheet reads the names as UTF-8.
pub fn csv(rows: &[ClassRow]) -> String {
    let mut out = String::from("\u{feff}");
    let mut header: Vec<String> =
        ["name", "status", "message", "visibility function", "light from", "implied light width", "lights"]
            .iter()
            .map(|h| h.to_string())
            .collect();
    header.extend(FINDINGS.iter().map(|k| k.id.to_string()));
    header.push("mistakes".into());
    out.push_str(&header.join(","));
    out.push_str("\r\n");
    for row in rows {
        let report = row.report.as_ref().filter(|r| r.compiled);
        let light = report.and_then(|r| r.light.as_ref());
        let mut fields = vec![
            csv_text(&row.name),
            csv_field(row.status.label()),
            csv_text(&row.message),
            csv_field(report.and_then(|r| r.visibility_function.as_deref()).unwrap_or("")),
            csv_text(light.map_or("", |l| l.from.as_str())),
            report.and_then(|r| r.light_width.as_ref()).map_or(String::new(), |w| {
                match (w.measured(), w.narrower_than_world) {
                    (_, Some(bound)) => format!("<{}", number(bound)),
                    (Some(width), None) => number(width),
                    (None, None) => String::new(),
                }
            }),
            // The bonus: each light the page made, with its own check's findings.
            csv_text(&report.map_or(String::new(), |r| {
                r.lights
                    .iter()
                    .map(|l| {
                        let verdict = l.verdict("no findings", "not checked", |t| format!("at {t} s"));
                        format!("{} {}: {verdict}", l.kind, l.made_at)
                    })
                    .collect::<Vec<_>>()
                    .join(" | ")
            })),
        ];
        for kind in FINDINGS {
            let cell = report.map(|r| match r.findings.iter().find(|f| f.id == kind.id) {
                Some(f) if f.severity == Severity::Mistake => "1",
                Some(_) => "latent",
                None => "0",
            });
            fields.push(cell.unwrap_or("").to_string());
        }
        fields.push(report.map_or(String::new(), |r| r.mistakes().to_string()));
        out.push_str(&fields.join(","));
        out.push_str("\r\n");
    }
    out
}

/// Write the class report into `out` (which exists): `index.html`, `index_zh.html` and
/// `grades.csv`. `reports_in` is the language the students' reports were written in (their
/// explanations show on that language's page; the other shows each finding's description).
pub fn write(out: &Path, rows: &[ClassRow], reports_in: Lang) -> Result<(), super::ExportError> {
    let files = [
        (INDEX_EN, page::html(Lang::En, rows, reports_in)),
        (INDEX_ZH, page::html(Lang::Zh, rows, reports_in)),
        (GRADES, csv(rows)),
        (CLASS, saved::json(rows)),
    ];
    for (name, text) in &files {
        super::write_atomic(&out.join(name), text.as_bytes())?;
    }
    Ok(())
}

#[cfg(test)]
mod tests;

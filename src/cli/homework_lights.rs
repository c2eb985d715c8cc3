//! The homework's bonus, checked: each light of a student's page with a shadow map of its own
//! (every DirectionalLight, a PointLight whose class has a CalcLightMVP) on its own, as their
//! renderer draws it (a pass per light, each with its own map), and each light again at the times
//! of their animation where it had moved (an orbit, a light their code moves each frame). Findings
//! go into the report's `lights`, pictures beside (`student_light1.png`, its map
//! `student_light1_map.png`, `student_light0_t1.0s.png`).

use super::CliError;
use crate::homework::student_light::{PageLight, TimedCheck, student_light_of};
use crate::homework::{
    HomeworkRenderer, HomeworkReport, HomeworkRequest, HomeworkSource, ShaderSource, run_check,
};
use crate::i18n::Lang;
use crate::render::Renderer;
use crate::scene::Scene;
use std::task::Poll;

/// What every light's check shares.
pub(super) struct Check<'a> {
    pub homework: &'a HomeworkRenderer,
    pub shader: &'a ShaderSource,
    pub source: &'a HomeworkSource,
    pub scene: &'a Scene,
}

fn ids(report: &HomeworkReport) -> Vec<String> {
    report.findings.iter().map(|f| f.id.to_string()).collect()
}

/// One light's check: its outcome and where the light was (world units), or why its light could
/// not be used.
type LightCheck = Result<(crate::homework::CheckOutcome, [f32; 3]), String>;

/// Checks the page's light `page_light` on `check`'s scene: its report and picture, None where
/// the page has no matrices for it then; Err(message) where its light could not be used.
fn check_light(
    check: &Check<'_>,
    renderer: &mut Renderer,
    request: &HomeworkRequest,
    (light, time_s, lang): (usize, f32, Lang),
    page_light: PageLight,
) -> Result<Option<LightCheck>, CliError> {
    let Poll::Ready(Some(student)) =
        student_light_of(check.source, check.scene, light, time_s, Some(page_light))
    else {
        return Ok(None);
    };
    if let Some(error) = student.report.error {
        return Ok(Some(Err(error)));
    }
    let outcome =
        run_check(check.homework, renderer, check.shader, &student.scene, &student.light, request, lang)
            .map_err(|e| CliError { code: 1, message: format!("{}: {e}", check.shader.name) })?;
    Ok(Some(Ok((outcome, student.light.position.to_array()))))
}

/// Checks each other light of the page with a map of its own, and each light at the times it had moved;
/// fills `report.lights` (the first light's findings are the report's own) and returns the
/// pictures to write, by file name.
pub(super) fn check_each_light(
    check: &Check<'_>,
    renderer: &mut Renderer,
    request: &HomeworkRequest,
    settings: (usize, f32, Lang),
    report: &mut HomeworkReport,
) -> Result<Vec<(String, image::RgbaImage)>, CliError> {
    let mut pictures = Vec::new();
    // Where the page made no light the check could use, the framework's is listed first.
    let inserted = usize::from(report.lights.first().is_some_and(|l| l.made_at == "framework"));
    for listed in 0..report.lights.len() {
        let entry = &report.lights[listed];
        // A light the page computed no matrices for (a lamp without a map) has no set: skipped below.
        if entry.error.is_some() {
            continue;
        }
        let checked = entry.checked;
        // The framework's light listed first is the checked one too, and no light of the page.
        let index = listed.checked_sub(inserted);
        if checked {
            report.lights[listed].findings = Some(ids(report));
            report.lights[listed].light_width = report.light_width.clone();
        }
        let Some(index) = index else { continue };
        if !checked {
            match check_light(check, renderer, request, settings, PageLight { index, time_s: None })? {
                None => continue,
                Some(Err(error)) => {
                    report.lights[listed].error = Some(error);
                    continue;
                }
                Some(Ok((outcome, _))) => {
                    let entry = &mut report.lights[listed];
                    entry.findings = Some(ids(&outcome.report));
                    entry.light_width = outcome.report.light_width.clone();
                    pictures.push((format!("student_light{listed}.png"), outcome.student_picture()));
                    if let Some(map) = outcome.map_picture() {
                        pictures.push((format!("student_light{listed}_map.png"), map));
                    }
                }
            }
        }
        for time_s in report.lights[listed].moved_at_s.clone() {
            let at = PageLight { index, time_s: Some(time_s) };
            if let Some(Ok((outcome, position))) = check_light(check, renderer, request, settings, at)? {
                let findings = ids(&outcome.report);
                report.lights[listed].at_times.push(TimedCheck { time_s, position, findings });
                let name = format!("student_light{listed}_t{time_s:.1}s.png");
                pictures.push((name, outcome.student_picture()));
            }
        }
    }
    Ok(pictures)
}

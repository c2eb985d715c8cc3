//! What the app benchmarks share (`bench --app`, offscreen or in the window, and the soak):
//! the window's size and time limits, the classroom session's start and its two drag phases, the
//! check that a phase moved what it drives, and the report.

use crate::cli::CliError;
use crate::lessons::Panel;
use crate::scene::LightSize;
use crate::ui::ShadowlabApp;
use serde::Serialize;
use std::time::Duration;

/// The app's window, points.
pub const WINDOW: [f32; 2] = [1600.0, 900.0];
/// Longest wait for the app to settle (first frame, release to full quality).
pub const SETTLE_LIMIT: Duration = Duration::from_secs(300);
/// UI frames timed with nothing rendering.
pub const IDLE_FRAMES: u32 = 20;
/// Frames a widget (and the window) must keep their place before the pointer presses on it.
pub const STILL_FRAMES: u32 = 3;
/// The session's two phases.
pub const PHASES: [&str; 2] = ["drag the light-width slider", "drag the light on the shadow map"];

/// Put the app where the session starts: the PCSS lesson's first step that shows the shadow map,
/// with a probe pinned. Returns the lesson's id and the step (from 1).
pub fn start_session(app: &mut ShadowlabApp) -> Result<(String, usize), String> {
    let pcss = app.lessons.iter().position(|l| l.id == "pcss").ok_or("no pcss lesson")?;
    let step = app.lessons[pcss]
        .steps
        .iter()
        .position(|s| s.panels.contains(&Panel::ShadowMap))
        .ok_or("no pcss step shows the shadow map")?;
    app.go_to_step(pcss, step);
    if app.probe_at.is_none() {
        app.probe_at = Some(crate::ui::ProbeAt::View(0.5, 0.6));
    }
    Ok((app.lessons[pcss].id.clone(), step + 1))
}

/// What a phase's input moves: the selected light's width (the slider) or its position (the
/// drag on the shadow map), as the app holds it.
#[derive(Clone, Debug, PartialEq)]
pub struct Driven {
    pub name: String,
    pub value: Vec<f32>,
}

impl Driven {
    pub fn read(app: &ShadowlabApp, phase: usize) -> Self {
        let i = app.selected_light;
        let Some(light) = app.scene.lights.get(i) else {
            return Self { name: "no light".into(), value: Vec::new() };
        };
        match (phase, &light.size) {
            (0, LightSize::Width { width_world }) => {
                Self { name: format!("light {i} width"), value: vec![*width_world] }
            }
            (0, LightSize::AngularDiameter { angular_diameter_deg }) => {
                Self { name: format!("light {i} angular diameter"), value: vec![*angular_diameter_deg] }
            }
            _ => Self { name: format!("light {i} position"), value: light.position.to_array().to_vec() },
        }
    }
}

impl std::fmt::Display for Driven {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let values: Vec<String> = self.value.iter().map(|v| format!("{v:.3}")).collect();
        match values.as_slice() {
            [one] => write!(f, "{one}"),
            _ => write!(f, "({})", values.join(", ")),
        }
    }
}

/// A phase's figures mean something only if its input moved what it drives and the views
/// showed at least one new image while it did; otherwise this says which (one line), and the
/// bench fails instead of reporting.
pub fn check_phase(what: &str, before: &Driven, after: &Driven, refreshes: u64) -> Result<(), String> {
    if before == after {
        return Err(format!(
            "{what}: the input changed nothing ({} stayed {before}; the pointer missed it?), so there is \
             nothing to report",
            before.name
        ));
    }
    if refreshes == 0 {
        return Err(format!(
            "{what}: the views showed no new image while dragging ({} {before} -> {after}), so there is \
             nothing to report",
            before.name
        ));
    }
    Ok(())
}

/// Whether a drag goes on after `elapsed`: for its `seconds`, then, where its input has moved
/// what it drives and a render is under way but no new image has reached the views yet (a
/// renderer slower than the drag), until one has, so that the figures rest on at least one.
pub fn keep_dragging(elapsed: Duration, seconds: f32, moved: bool, refreshes: u64, pending: bool) -> bool {
    elapsed.as_secs_f32() < seconds || (moved && refreshes == 0 && pending && elapsed < SETTLE_LIMIT)
}

#[derive(Serialize)]
pub struct Phase {
    pub what: &'static str,
    /// What the input moved, from and to (e.g. `light 0 width 3.000 -> 7.215`).
    pub moved: String,
    pub seconds: f64,
    pub ui_frames: u32,
    pub ui_frames_per_s: f64,
    /// Slowest UI frame while dragging, milliseconds.
    pub slowest_ui_frame_ms: f64,
    /// Mean time per UI frame of the app's own code and egui's layout, and of painting the
    /// frame (tessellation, texture uploads, the GPU draw and its read-back), milliseconds
    /// (offscreen only: a window paints after the app's frame, out of its sight).
    pub ui_logic_ms: Option<f64>,
    pub ui_paint_ms: Option<f64>,
    pub view_refreshes: u64,
    pub view_refreshes_per_s: f64,
    /// From the release to the full-resolution image on screen, seconds.
    pub release_to_full_image_s: f64,
    /// From the release until everything is up to date (probe and overlays too), seconds.
    pub release_to_full_quality_s: f64,
}

#[derive(Serialize)]
pub struct AppReport {
    pub window: [f32; 2],
    /// What painted the UI: kittest's offscreen wgpu painter, or the window's own.
    pub painter: String,
    pub lesson: String,
    pub step: usize,
    pub startup_to_first_frame_s: f64,
    /// A UI frame with nothing rendering, milliseconds.
    pub idle_ui_frame_ms: f64,
    pub phases: Vec<Phase>,
}

impl AppReport {
    pub fn empty() -> Self {
        Self {
            window: WINDOW,
            painter: String::new(),
            lesson: String::new(),
            step: 0,
            startup_to_first_frame_s: 0.0,
            idle_ui_frame_ms: 0.0,
            phases: Vec::new(),
        }
    }
}

pub fn print_report(report: &AppReport, json: bool) -> Result<(), CliError> {
    if json {
        let json =
            serde_json::to_string_pretty(report).map_err(|e| CliError { code: 1, message: e.to_string() })?;
        println!("{json}");
        return Ok(());
    }
    println!(
        "app: {}x{} window painted by {}, lesson {} step {}, probe pinned; first frame after {:.1} s; idle UI frame {:.1} ms",
        report.window[0],
        report.window[1],
        report.painter,
        report.lesson,
        report.step,
        report.startup_to_first_frame_s,
        report.idle_ui_frame_ms
    );
    println!(
        "{:<34} {:>7} {:>9} {:>9} {:>11} {:>15} {:>13} {:>14}",
        "phase",
        "UI fps",
        "logic ms",
        "paint ms",
        "slowest ms",
        "view refresh/s",
        "release:image",
        "release:probe"
    );
    let opt = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.1}"));
    for p in &report.phases {
        println!(
            "{:<34} {:>7.1} {:>9} {:>9} {:>11.0} {:>15.1} {:>11.2} s {:>12.2} s",
            p.what,
            p.ui_frames_per_s,
            opt(p.ui_logic_ms),
            opt(p.ui_paint_ms),
            p.slowest_ui_frame_ms,
            p.view_refreshes_per_s,
            p.release_to_full_image_s,
            p.release_to_full_quality_s
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn width(w: f32) -> Driven {
        Driven { name: "light 0 width".into(), value: vec![w] }
    }

    #[test]
    fn a_phase_that_moved_nothing_or_showed_no_new_image_is_an_error() {
        let what = PHASES[0];
        assert_eq!(check_phase(what, &width(4.0), &width(31.0), 3), Ok(()));
        // The pointer missed the slider: the width stayed, whatever the views did.
        for refreshes in [0, 3] {
            let missed = check_phase(what, &width(4.0), &width(4.0), refreshes).expect_err("nothing moved");
            assert!(missed.starts_with(what) && missed.contains("changed nothing"), "{missed}");
            assert!(missed.contains("light 0 width stayed 4.000") && !missed.contains('\n'), "{missed}");
        }
        // The slider moved but no new image reached the views: 0 refreshes/s is no figure.
        let no_image = check_phase(what, &width(4.0), &width(31.0), 0).expect_err("no image");
        assert!(no_image.contains("no new image") && no_image.contains("4.000 -> 31.000"), "{no_image}");
        assert!(!no_image.contains('\n'), "{no_image}");
        // The map drag: the light's position.
        let at = |x: f32| Driven { name: "light 0 position".into(), value: vec![x, 36.0, 14.0] };
        assert_eq!(check_phase(PHASES[1], &at(-20.0), &at(-21.5), 1), Ok(()));
        let missed = check_phase(PHASES[1], &at(-20.0), &at(-20.0), 2).expect_err("nothing moved");
        assert!(missed.contains("(-20.000, 36.000, 14.000)"), "{missed}");
    }

    #[test]
    fn a_drag_lasts_its_seconds_and_then_until_a_moved_input_shows_a_new_image() {
        let s = Duration::from_secs_f32;
        // Within its seconds, whatever else.
        assert!(keep_dragging(s(0.2), 0.5, false, 0, false));
        // After them: on only while the input moved something, a render is under way and no
        // image has come yet.
        assert!(keep_dragging(s(0.7), 0.5, true, 0, true));
        assert!(!keep_dragging(s(0.7), 0.5, true, 1, true));
        assert!(!keep_dragging(s(0.7), 0.5, false, 0, true), "a missed input does not wait");
        assert!(!keep_dragging(s(0.7), 0.5, true, 0, false), "nothing is coming");
        assert!(!keep_dragging(SETTLE_LIMIT, 0.5, true, 0, true), "not for ever");
    }
}

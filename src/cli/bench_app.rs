//! `shadowlab bench --app`: the real app, driven offscreen (egui_kittest on the wgpu renderer)
//! through a scripted classroom session: the PCSS lesson with a probe pinned, then seconds of
//! dragging the light-width slider, then of dragging the light on the shadow map. It reports
//! what a student feels: UI frames per second (logic and painting of each frame), how often
//! the views show a new image, and how long after the release the full-quality frame arrives.

use super::{BenchArgs, CliError};
use crate::lessons::Panel;
use crate::scene::LightSize;
use crate::ui::{LANDMARK_SHADOW_MAP, Settings, ShadowlabApp, app_for_test, configure_wgpu, landmark};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use serde::Serialize;
use std::time::{Duration, Instant};

pub(super) const WINDOW: [f32; 2] = [1600.0, 900.0];
/// Longest wait for the app to settle (first frame, release to full quality).
pub(super) const SETTLE_LIMIT: Duration = Duration::from_secs(300);
/// UI frames timed with nothing rendering.
pub(super) const IDLE_FRAMES: u32 = 20;
/// Frames a widget (and the window) must keep their place before the pointer presses on it,
/// and the most waited for that offscreen.
pub(super) const STILL_FRAMES: u32 = 3;
const STILL_FRAMES_LIMIT: u32 = 600;
/// The session's two phases.
pub(super) const PHASES: [&str; 2] = ["drag the light-width slider", "drag the light on the shadow map"];

/// Put the app where the session starts: the PCSS lesson's first step that shows the shadow map,
/// with a probe pinned. Returns the lesson's id and the step (from 1).
pub(super) fn start_session(app: &mut ShadowlabApp) -> Result<(String, usize), String> {
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
pub(super) struct Driven {
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
pub(super) fn check_phase(what: &str, before: &Driven, after: &Driven, refreshes: u64) -> Result<(), String> {
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
pub(super) fn keep_dragging(
    elapsed: Duration,
    seconds: f32,
    moved: bool,
    refreshes: u64,
    pending: bool,
) -> bool {
    elapsed.as_secs_f32() < seconds || (moved && refreshes == 0 && pending && elapsed < SETTLE_LIMIT)
}

#[derive(Serialize)]
pub(super) struct Phase {
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
pub(super) struct AppReport {
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

fn fail(message: impl Into<String>) -> CliError {
    CliError { code: 1, message: message.into() }
}

/// Step frames until the app has nothing in flight; returns how long that took.
fn settle(h: &mut Harness<'_, ShadowlabApp>) -> Result<Duration, CliError> {
    let start = Instant::now();
    loop {
        step(h)?;
        if !h.state().render_pending() {
            return Ok(start.elapsed());
        }
        if start.elapsed() > SETTLE_LIMIT {
            return Err(fail(format!("the app did not settle in {} s", SETTLE_LIMIT.as_secs())));
        }
        std::thread::sleep(Duration::from_millis(2));
    }
}

/// Step frames until `rect` (a widget's, as the last frame drew it) has kept its place for
/// `STILL_FRAMES` frames; returns it. A press on a widget still moving (scrolling, a panel
/// resized by a new frame) misses it under load.
fn wait_still(
    h: &mut Harness<'_, ShadowlabApp>,
    rect: impl Fn(&Harness<'_, ShadowlabApp>) -> Result<egui::Rect, CliError>,
    what: &str,
) -> Result<egui::Rect, CliError> {
    let (mut last, mut still) = (rect(h)?, 0);
    for _ in 0..STILL_FRAMES_LIMIT {
        if still >= STILL_FRAMES {
            return Ok(last);
        }
        step(h)?;
        let now = rect(h)?;
        still = if now == last { still + 1 } else { 0 };
        last = now;
    }
    Err(fail(format!("{what} kept moving ({last:?})")))
}

/// One UI frame: the app's logic, then painting it (as a window would each frame). Returns the
/// time of each part.
fn step(h: &mut Harness<'_, ShadowlabApp>) -> Result<(Duration, Duration), CliError> {
    let start = Instant::now();
    h.step();
    let logic = start.elapsed();
    h.render().map_err(|e| fail(format!("painting the UI failed: {e}")))?;
    Ok((logic, start.elapsed() - logic))
}

/// Drag from `from` along `path(t)` (t in seconds) for `seconds` (longer if no new image has
/// reached the views yet), then release and wait for the full-quality frame. Fails where the
/// drag moved nothing or no new image was shown.
fn drag_phase(
    h: &mut Harness<'_, ShadowlabApp>,
    phase: usize,
    from: egui::Pos2,
    seconds: f32,
    path: impl Fn(f32) -> egui::Pos2,
) -> Result<Phase, CliError> {
    let what = PHASES[phase];
    let before = Driven::read(h.state(), phase);
    h.hover_at(from);
    step(h)?;
    h.drag_at(from);
    step(h)?;
    let shown_before = h.state().frames_shown();
    let start = Instant::now();
    let (mut frames, mut slowest) = (0u32, Duration::ZERO);
    let (mut logic, mut paint) = (Duration::ZERO, Duration::ZERO);
    loop {
        let app = h.state();
        let moved = Driven::read(app, phase) != before;
        let refreshes = app.frames_shown() - shown_before;
        if !keep_dragging(start.elapsed(), seconds, moved, refreshes, app.render_pending()) {
            break;
        }
        let frame_start = Instant::now();
        h.hover_at(path(start.elapsed().as_secs_f32()));
        let (l, p) = step(h)?;
        logic += l;
        paint += p;
        slowest = slowest.max(frame_start.elapsed());
        frames += 1;
    }
    let elapsed = start.elapsed().as_secs_f64();
    let refreshes = h.state().frames_shown() - shown_before;
    h.drop_at(path(elapsed as f32));
    let released = Instant::now();
    let shown_at_release = h.state().frames_shown();
    let mut full_image = None;
    loop {
        step(h)?;
        let app = h.state();
        if full_image.is_none() && app.frames_shown() > shown_at_release && !app.showing_preview() {
            full_image = Some(released.elapsed());
        }
        if !app.render_pending() {
            break;
        }
        if released.elapsed() > SETTLE_LIMIT {
            return Err(fail(format!("{what}: the app did not settle after the release")));
        }
        std::thread::sleep(Duration::from_millis(2));
    }
    let settled = released.elapsed();
    if h.state().showing_preview() {
        return Err(fail(format!("{what}: still showing a preview after the release")));
    }
    let after = Driven::read(h.state(), phase);
    check_phase(what, &before, &after, refreshes).map_err(fail)?;
    Ok(Phase {
        what,
        moved: format!("{} {before} -> {after}", before.name),
        seconds: elapsed,
        ui_frames: frames,
        ui_frames_per_s: f64::from(frames) / elapsed,
        slowest_ui_frame_ms: slowest.as_secs_f64() * 1e3,
        ui_logic_ms: Some(logic.as_secs_f64() * 1e3 / f64::from(frames.max(1))),
        ui_paint_ms: Some(paint.as_secs_f64() * 1e3 / f64::from(frames.max(1))),
        view_refreshes: refreshes,
        view_refreshes_per_s: refreshes as f64 / elapsed,
        release_to_full_image_s: full_image.unwrap_or(settled).as_secs_f64(),
        release_to_full_quality_s: settled.as_secs_f64(),
    })
}

pub fn run(args: &BenchArgs) -> Result<(), CliError> {
    if let Some(seconds) = args.soak {
        return super::bench_soak::run(args, seconds);
    }
    if !(0.5..=600.0).contains(&args.seconds) {
        return Err(CliError::input(format!("--seconds {} is out of range 0.5..=600", args.seconds)));
    }
    let report = if args.window { super::bench_window::run(args)? } else { offscreen(args)? };
    print_report(&report, args.json)
}

/// The session offscreen: egui_kittest steps the app and paints each frame with wgpu.
fn offscreen(args: &BenchArgs) -> Result<AppReport, CliError> {
    let mut setup = egui_kittest::wgpu::default_wgpu_setup();
    if let eframe::egui_wgpu::WgpuSetup::CreateNew(create) = setup {
        setup = eframe::egui_wgpu::WgpuSetup::CreateNew(configure_wgpu(create));
    }
    let started = Instant::now();
    let mut h = Harness::builder()
        .with_size(WINDOW)
        .wgpu_setup(setup)
        // Paint as the app's window does (kittest's default filters textures in the shader,
        // for snapshots that match across machines, which is far slower).
        .with_render_options(crate::ui::window_render_options())
        .build_eframe(|cc| app_for_test(cc, Settings::default()));
    let (lesson, step_number) = start_session(h.state_mut()).map_err(fail)?;
    settle(&mut h)?;
    if let Some(problem) = h.state().gpu_problem().filter(|_| h.state().camera_image().is_none()) {
        return Err(CliError { code: 2, message: format!("the app has no GPU view: {problem}") });
    }
    let startup = started.elapsed().as_secs_f64();
    // The UI alone, nothing rendering: what painting a frame costs here.
    let idle_start = Instant::now();
    for _ in 0..IDLE_FRAMES {
        step(&mut h)?;
    }
    let idle_ui_frame_ms = idle_start.elapsed().as_secs_f64() * 1e3 / f64::from(IDLE_FRAMES);

    let slider_label = "light width (world units)";
    let slider_role = egui::accesskit::Role::Slider;
    match h.query_all_by_role_and_label(slider_role, slider_label).next() {
        Some(node) => node.scroll_to_me(),
        None => return Err(fail(format!("the app shows no '{slider_label}' slider"))),
    }
    // Scrolling animates over a few frames: press only once the slider has kept its place for
    // a few of them (under load, a rectangle read mid-scroll is not where the slider ends up).
    settle(&mut h)?;
    let slider_rect = |h: &Harness<'_, ShadowlabApp>| {
        h.query_all_by_role_and_label(slider_role, slider_label)
            .next()
            .map(|node| node.rect())
            .ok_or_else(|| fail(format!("the app shows no '{slider_label}' slider")))
    };
    let slider = wait_still(&mut h, slider_rect, &format!("the '{slider_label}' slider"))?;
    let (left, width, y) = (slider.left() + 4.0, (slider.width() * 0.5).max(40.0), slider.center().y);
    let slider_phase = drag_phase(&mut h, 0, slider.left_center(), args.seconds, |t| {
        egui::pos2(left + width * (0.3 + 0.25 * (t * 2.0).sin()), y)
    })?;

    // The middle of the map's picture, once it has kept its place for a few frames (the full
    // frame after the slider's release can move the panels).
    let map_rect = |h: &Harness<'_, ShadowlabApp>| {
        landmark(&h.ctx, LANDMARK_SHADOW_MAP)
            .ok_or_else(|| fail(format!("the app shows no {LANDMARK_SHADOW_MAP}")))
    };
    settle(&mut h)?;
    let centre = wait_still(&mut h, map_rect, LANDMARK_SHADOW_MAP)?.center();
    let map_phase = drag_phase(&mut h, 1, centre, args.seconds, |t| {
        centre + egui::vec2(30.0 * (t * 1.5).sin(), 20.0 * (t * 1.1).cos() - 20.0)
    })?;

    Ok(AppReport {
        window: WINDOW,
        painter: "wgpu (offscreen, egui_kittest)".into(),
        lesson,
        step: step_number,
        startup_to_first_frame_s: startup,
        idle_ui_frame_ms,
        phases: vec![slider_phase, map_phase],
    })
}

fn print_report(report: &AppReport, json: bool) -> Result<(), CliError> {
    if json {
        let json = serde_json::to_string_pretty(report).map_err(|e| fail(e.to_string()))?;
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

//! `shadowlab bench --app`: the real app, driven offscreen (egui_kittest on the wgpu renderer)
//! through a scripted classroom session: the PCSS lesson with a probe pinned, then seconds of
//! dragging the light-width slider, then of dragging the light on the shadow map. It reports
//! what a student feels: UI frames per second (logic and painting of each frame), how often
//! the views show a new image, and how long after the release the full-quality frame arrives.

use super::session::{
    AppReport, Driven, IDLE_FRAMES, PHASES, Phase, SETTLE_LIMIT, STILL_FRAMES, WINDOW, check_phase,
    keep_dragging, start_session,
};
use crate::cli::{BenchArgs, CliError};
use crate::ui::{LANDMARK_SHADOW_MAP, Settings, ShadowlabApp, app_for_test, configure_wgpu, landmark};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use std::time::{Duration, Instant};

/// The most frames waited for a widget to keep its place offscreen.
const STILL_FRAMES_LIMIT: u32 = 600;

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

/// The session offscreen: egui_kittest steps the app and paints each frame with wgpu.
pub fn run(args: &BenchArgs) -> Result<AppReport, CliError> {
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

//! `shadowlab bench --app --window`: the same classroom session as `bench --app`, in the real
//! window with the painter the app would use here (OpenGL on a software rasteriser), the input
//! injected frame by frame. Needs a display (`xvfb-run -a` where there is none).

use super::session::{
    AppReport, Driven, IDLE_FRAMES, PHASES, Phase, SETTLE_LIMIT, STILL_FRAMES, WINDOW, check_phase,
    keep_dragging, start_session,
};
use crate::cli::{BenchArgs, CliError};
use crate::ui::{LANDMARK_LIGHT_WIDTH, LANDMARK_SHADOW_MAP, Settings, ShadowlabApp, app_for_test, landmark};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

type Outcome = Arc<Mutex<Option<Result<AppReport, String>>>>;

/// Frames allowed for a phase's widget to come into view and keep still there.
const SEEK_FRAMES: u32 = 240;
/// Frames after the press for egui to report the drag on the widget.
const PRESS_FRAMES: u32 = 4;
/// How far the pointer moves after the press to start the drag (beyond egui's threshold).
const NUDGE: egui::Vec2 = egui::vec2(12.0, 0.0);
/// Rows at the window's top and bottom (top bar, status bar) where no press is made.
const EDGE_MARGIN: f32 = 60.0;

enum Stage {
    /// Wait for the first full frame of the lesson step.
    Starting,
    /// Time UI frames with nothing rendering.
    Idle {
        frames: u32,
        since: Instant,
    },
    /// Bring the phase's widget into view (the slider: scroll the inspector, as a user would)
    /// and wait until it and the window keep still.
    Seeking {
        phase: usize,
        attempt: u32,
        frames: u32,
        still: u32,
        last: Option<(egui::Rect, egui::Rect)>,
    },
    /// Pressed on the widget and moved a little: wait for egui to report a drag of that widget.
    Pressing {
        phase: usize,
        attempt: u32,
        from: egui::Pos2,
        frames: u32,
        before: Driven,
    },
    /// Move along the phase's path.
    Dragging {
        phase: usize,
        from: egui::Pos2,
        since: Instant,
        frames: u32,
        slowest: Duration,
        shown_before: u64,
        before: Driven,
    },
    /// Released: wait for the full-resolution image, then for everything (probe, overlays).
    Released {
        phase: usize,
        at: Instant,
        shown_at_release: u64,
        full_image: Option<Duration>,
        before: Driven,
    },
    Done,
}

struct Session {
    app: ShadowlabApp,
    stage: Stage,
    seconds: f32,
    started: Instant,
    last_frame: Option<Instant>,
    /// Pointer events for the next frame.
    pending: Vec<egui::Event>,
    report: AppReport,
    outcome: Outcome,
    /// Half-finished phase figures: (ui frames, elapsed s, slowest, refreshes).
    measured: Option<(u32, f64, Duration, u64)>,
}

/// The landmark a phase drags, and the point of it pressed first.
fn target(phase: usize) -> (&'static str, fn(egui::Rect) -> egui::Pos2) {
    match phase {
        // The slider's rail starts at the landmark's left (its value and label follow).
        0 => (LANDMARK_LIGHT_WIDTH, |r| r.left_center() + egui::vec2(8.0, 0.0)),
        _ => (LANDMARK_SHADOW_MAP, |r| r.center()),
    }
}

/// The rectangle of the widget egui is dragging this frame, if any.
fn dragged_rect(ctx: &egui::Context) -> Option<egui::Rect> {
    ctx.dragged_id().and_then(|id| ctx.read_response(id)).map(|r| r.rect)
}

impl Session {
    fn pointer_path(&self, phase: usize, from: egui::Pos2, t: f32) -> egui::Pos2 {
        match phase {
            0 => egui::pos2(from.x + 40.0 + 30.0 * (t * 2.0).sin(), from.y),
            _ => from + egui::vec2(30.0 * (t * 1.5).sin(), 20.0 * (t * 1.1).cos() - 20.0),
        }
    }

    /// A wheel step over the inspector at the slider's height, clamped into the window (its
    /// panel scrolls, the pointer stays over that panel), for the next frame.
    fn scroll_towards(&mut self, window: egui::Rect, rect: egui::Rect) {
        let y = rect.center().y.clamp(window.top() + EDGE_MARGIN, window.bottom() - EDGE_MARGIN);
        let delta = if rect.center().y > window.center().y { -60.0 } else { 60.0 };
        self.pending.push(egui::Event::PointerMoved(egui::pos2(rect.center().x, y)));
        self.pending.push(egui::Event::MouseWheel {
            unit: egui::MouseWheelUnit::Point,
            delta: egui::vec2(0.0, delta),
            phase: egui::TouchPhase::Move,
            source: egui::MouseWheelSource::Unknown,
            modifiers: Default::default(),
        });
    }

    fn press(&mut self, at: egui::Pos2, pressed: bool) {
        if pressed {
            self.pending.push(egui::Event::PointerMoved(at));
        }
        self.pending.push(egui::Event::PointerButton {
            pos: at,
            button: egui::PointerButton::Primary,
            pressed,
            modifiers: Default::default(),
        });
    }

    /// One frame of looking for the phase's widget: press on it once it and the window have
    /// kept still for a few frames well inside the window.
    fn seek(&mut self, ctx: &egui::Context) -> Result<(), String> {
        let Stage::Seeking { phase, attempt, frames, still, last } = &mut self.stage else { return Ok(()) };
        let (phase, attempt) = (*phase, *attempt);
        *frames += 1;
        let (name, offset) = target(phase);
        let window = ctx.content_rect();
        let rect = landmark(ctx, name);
        let inside = rect.is_some_and(|r| window.shrink2(egui::vec2(0.0, EDGE_MARGIN)).contains(offset(r)));
        let now = rect.map(|r| (window, r));
        *still = if inside && now == *last { *still + 1 } else { 0 };
        *last = now;
        let (still, frames) = (*still, *frames);
        if still >= STILL_FRAMES
            && let Some(rect) = rect
        {
            let from = offset(rect);
            self.press(from, true);
            let before = Driven::read(&self.app, phase);
            self.stage = Stage::Pressing { phase, attempt, from, frames: 0, before };
            return Ok(());
        }
        if frames > SEEK_FRAMES {
            let what = PHASES[phase];
            return Err(match rect {
                None => format!("{what}: the app shows no {name}"),
                Some(r) if !inside => {
                    format!("{what}: the {name} stays outside the window (at {r:?} in {window:?})")
                }
                Some(r) => format!("{what}: the {name} did not keep still in the window (last at {r:?})"),
            });
        }
        if let Some(rect) = rect
            && !inside
            && phase == 0
            && frames % 4 == 1
        {
            // A step every few frames: each scroll animates, and the landmark moves with it.
            self.scroll_towards(window, rect);
        }
        Ok(())
    }

    /// Advance the script after a frame that took `dt`.
    fn advance(&mut self, ctx: &egui::Context, dt: Duration) -> Result<(), String> {
        match &mut self.stage {
            Stage::Starting => {
                if self.app.camera_image().is_some() && !self.app.render_pending() {
                    self.report.startup_to_first_frame_s = self.started.elapsed().as_secs_f64();
                    self.stage = Stage::Idle { frames: 0, since: Instant::now() };
                } else if self.started.elapsed() > SETTLE_LIMIT {
                    return Err(self.app.gpu_problem().unwrap_or_else(|| "no first frame".into()));
                }
            }
            Stage::Idle { frames, since } => {
                *frames += 1;
                if *frames == IDLE_FRAMES {
                    self.report.idle_ui_frame_ms =
                        since.elapsed().as_secs_f64() * 1e3 / f64::from(IDLE_FRAMES);
                    self.stage = Stage::Seeking { phase: 0, attempt: 0, frames: 0, still: 0, last: None };
                }
            }
            Stage::Seeking { .. } => self.seek(ctx)?,
            Stage::Pressing { phase, attempt, from, frames, before } => {
                *frames += 1;
                let (phase, attempt, from) = (*phase, *attempt, *from);
                let (name, _) = target(phase);
                if *frames == 1 {
                    // The press is in; move past egui's drag threshold.
                    self.pending.push(egui::Event::PointerMoved(from + NUDGE));
                    return Ok(());
                }
                let widget = landmark(ctx, name);
                let dragged = dragged_rect(ctx);
                let landed = dragged
                    .zip(widget)
                    .is_some_and(|(d, w)| w.expand(1.0).contains_rect(d) && d.contains(from));
                if landed {
                    let before = before.clone();
                    self.stage = Stage::Dragging {
                        phase,
                        from,
                        since: Instant::now(),
                        frames: 0,
                        slowest: Duration::ZERO,
                        shown_before: self.app.frames_shown(),
                        before,
                    };
                } else if *frames >= PRESS_FRAMES {
                    // Let go (moved past the threshold: no click) and look for the widget again, once.
                    self.press(from + NUDGE, false);
                    if attempt > 0 {
                        let got = dragged.map_or("nothing".to_string(), |d| format!("a widget at {d:?}"));
                        let at = widget.map_or("gone".to_string(), |w| format!("at {w:?}"));
                        return Err(format!(
                            "{}: the pointer did not land on the {name}, twice (pressed at {from:?}, the \
                             {name} {at}, egui dragged {got})",
                            PHASES[phase]
                        ));
                    }
                    self.stage =
                        Stage::Seeking { phase, attempt: attempt + 1, frames: 0, still: 0, last: None };
                }
            }
            Stage::Dragging { phase, from, since, frames, slowest, shown_before, before } => {
                *frames += 1;
                *slowest = (*slowest).max(dt);
                let t = since.elapsed().as_secs_f32();
                let (phase, from) = (*phase, *from);
                let refreshes = self.app.frames_shown() - *shown_before;
                let moved = Driven::read(&self.app, phase) != *before;
                if keep_dragging(since.elapsed(), self.seconds, moved, refreshes, self.app.render_pending()) {
                    let pos = self.pointer_path(phase, from, t);
                    self.pending.push(egui::Event::PointerMoved(pos));
                } else {
                    self.measured = Some((*frames, since.elapsed().as_secs_f64(), *slowest, refreshes));
                    let before = before.clone();
                    self.press(self.pointer_path(phase, from, t), false);
                    self.stage = Stage::Released {
                        phase,
                        at: Instant::now(),
                        shown_at_release: self.app.frames_shown(),
                        full_image: None,
                        before,
                    };
                }
            }
            Stage::Released { phase, at, shown_at_release, full_image, before } => {
                let phase = *phase;
                if full_image.is_none()
                    && self.app.frames_shown() > *shown_at_release
                    && !self.app.showing_preview()
                {
                    *full_image = Some(at.elapsed());
                }
                if at.elapsed() > Duration::from_millis(50) && !self.app.render_pending() {
                    let settled = at.elapsed();
                    if self.app.showing_preview() {
                        return Err(format!("{}: still showing a preview after the release", PHASES[phase]));
                    }
                    let (frames, elapsed, slowest, refreshes) = self.measured.take().unwrap_or_default();
                    let after = Driven::read(&self.app, phase);
                    check_phase(PHASES[phase], before, &after, refreshes)?;
                    self.report.phases.push(Phase {
                        what: PHASES[phase],
                        moved: format!("{} {before} -> {after}", before.name),
                        seconds: elapsed,
                        ui_frames: frames,
                        ui_frames_per_s: f64::from(frames) / elapsed.max(1e-9),
                        slowest_ui_frame_ms: slowest.as_secs_f64() * 1e3,
                        ui_logic_ms: None,
                        ui_paint_ms: None,
                        view_refreshes: refreshes,
                        view_refreshes_per_s: refreshes as f64 / elapsed.max(1e-9),
                        release_to_full_image_s: full_image.unwrap_or(settled).as_secs_f64(),
                        release_to_full_quality_s: settled.as_secs_f64(),
                    });
                    self.stage = if phase + 1 < PHASES.len() {
                        Stage::Seeking { phase: phase + 1, attempt: 0, frames: 0, still: 0, last: None }
                    } else {
                        Stage::Done
                    };
                } else if at.elapsed() > SETTLE_LIMIT {
                    return Err("the app did not settle after the release".into());
                }
            }
            Stage::Done => {}
        }
        Ok(())
    }

    fn finish(&mut self, ctx: &egui::Context, result: Result<AppReport, String>) {
        if let Ok(mut slot) = self.outcome.lock() {
            slot.get_or_insert(result);
        }
        self.stage = Stage::Done;
        ctx.send_viewport_cmd(egui::ViewportCommand::Close);
    }
}

impl eframe::App for Session {
    fn clear_color(&self, visuals: &egui::Visuals) -> [f32; 4] {
        self.app.clear_color(visuals)
    }

    fn raw_input_hook(&mut self, _ctx: &egui::Context, raw_input: &mut egui::RawInput) {
        raw_input.events.append(&mut self.pending);
    }

    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        let ctx = ui.ctx().clone();
        let now = Instant::now();
        let dt = self.last_frame.map_or(Duration::ZERO, |t| now.duration_since(t));
        self.last_frame = Some(now);
        self.app.ui(ui, frame);
        if matches!(self.stage, Stage::Done) {
            return;
        }
        match self.advance(&ctx, dt) {
            Ok(()) if matches!(self.stage, Stage::Done) => {
                let report = std::mem::replace(&mut self.report, AppReport::empty());
                self.finish(&ctx, Ok(report));
            }
            Ok(()) => ctx.request_repaint(),
            Err(e) => self.finish(&ctx, Err(e)),
        }
    }
}

pub fn run(args: &BenchArgs) -> Result<AppReport, CliError> {
    let fail = |message: String| CliError { code: 1, message };
    if !crate::ui::display_available() {
        return Err(CliError::input(
            "bench --app --window: no display found (DISPLAY and WAYLAND_DISPLAY are unset); run it under \
             `xvfb-run -a`, or drop --window to drive the app offscreen",
        ));
    }
    let painter = crate::ui::ui_painter();
    let outcome: Outcome = Arc::new(Mutex::new(None));
    let sink = outcome.clone();
    let seconds = args.seconds;
    let mut options = crate::ui::window_options(painter);
    options.viewport = options.viewport.with_inner_size(WINDOW);
    options.persist_window = false;
    let result = eframe::run_native(
        "shadowlab-bench",
        options,
        Box::new(move |cc| {
            let mut app = app_for_test(cc, Settings::default());
            crate::ui::clear_paints_panels(&cc.egui_ctx);
            let (lesson, step) = start_session(&mut app)?;
            let mut report = AppReport::empty();
            report.lesson = lesson;
            report.step = step;
            report.painter = format!("{painter} (window)");
            Ok(Box::new(Session {
                app,
                stage: Stage::Starting,
                seconds,
                started: Instant::now(),
                last_frame: None,
                pending: Vec::new(),
                report,
                outcome: sink,
                measured: None,
            }))
        }),
    );
    if let Err(e) = result {
        return Err(CliError { code: 2, message: format!("could not open the window: {e}") });
    }
    let taken = outcome.lock().ok().and_then(|mut slot| slot.take());
    match taken {
        Some(Ok(report)) => Ok(report),
        Some(Err(e)) => Err(fail(e)),
        None => Err(fail("the window closed before the session ended".into())),
    }
}

//! `shadowlab bench --app --window --soak SECONDS`: a class hour in the real window. The PCSS and
//! multi-light lessons are first toured (each shown once in every view), then play in turn with a
//! probe pinned and overlays on; every few seconds the
//! playback pauses until the full-detail frame is in (probe, overlays, read-backs), the view
//! changes, and playback goes on. It reports how much was rendered, how far scene time went and
//! the process's memory every 30 s from a baseline taken once no pipeline has been built for a
//! minute, and fails where the scene stopped moving or memory trends up over the second half.

use super::session::{SETTLE_LIMIT, WINDOW};
use super::soak_memory::{MemoryFloor, rss_mb, second_half_trend};
use crate::cli::{BenchArgs, CliError};
use crate::ui::{PLAYBACK_RANGE_S, Settings, ShadowlabApp, app_for_test};
use crate::views::View;
use crate::views::overlays::Overlay;
use serde::Serialize;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// The lessons played in turn unless `--soak-lesson` names others: (id, step from 0). PCSS step 2
/// (blocker search, a probe) and multi-light step 4 (orbiting lights, spinning objects).
const LESSONS: [(&str, usize); 2] = [("pcss", 1), ("multi-light", 3)];
/// Overlays kept on throughout (camera-space ones, over the views that take them).
const OVERLAYS: [Overlay; 3] = [Overlay::Penumbra, Overlay::OutsideFrustum, Overlay::LightFrustum];
/// The views gone through, one per cycle.
const VIEWS: [View; 5] =
    [View::Final, View::Visibility, View::Penumbra, View::ShadowMap, View::BlockerRadius];
/// Playback between two pauses, seconds of wall-clock time, on the tour as after it: a tour stop
/// must play long enough to reach its lesson's steady state (the frames and read-backs in flight
/// while it plays), or the soak proper would count reaching it as growth.
const PLAY: Duration = Duration::from_secs(4);
/// Cycles (play, pause for the full detail, switch the view) per lesson before the next one.
const CYCLES_PER_LESSON: u32 = 5;
/// Memory is first read this far in at the earliest (after the tour): what the session's caches
/// hold by then, they hold for the rest of the hour.
const EARLY: Duration = Duration::from_secs(60);
/// ...and once no pipeline has been built for this long: a pipeline's memory (the driver's
/// compiled shader) arrives over the minute after it is created, so a reading taken sooner counts
/// start-up as growth on a slow machine.
const QUIET: f64 = 60.0;
/// Memory is judged on soaks at least this long (shorter ones are all start-up).
const JUDGE_MEMORY_FROM: Duration = Duration::from_secs(120);
/// A judged soak's readings after its baseline: three 30-second readings for the trend.
const JUDGED_SPAN: Duration = Duration::from_secs(90);
/// How long past its length a judged soak waits for that before it fails.
const JUDGE_WAIT_LIMIT: Duration = Duration::from_secs(600);
/// Over the soak's second half, memory may grow this much (the least-squares trend of the
/// 30-second readings, as a share of the early reading): one late reading is noise, a trend is
/// a leak.
const MEMORY_GROWTH_ALLOWED: f64 = 0.10;

#[derive(Serialize, Default)]
pub struct SoakReport {
    pub seconds: f64,
    pub painter: String,
    /// New images on screen, and those of them with the full detail (probe, overlays).
    pub frames_rendered: u64,
    pub full_detail_frames: u32,
    /// Scene time played, seconds (it loops over the time range).
    pub scene_time_advanced_s: f64,
    pub view_switches: u32,
    pub lesson_switches: u32,
    /// When the tour through every lesson in every view ended, seconds in (playing starts then).
    pub tour_s: f64,
    /// Resident memory a minute in, MB, and the growth from there to the end: what is left of
    /// start-up by then, reported beside the judged figures.
    pub rss_at_60_s_mb: Option<f64>,
    pub rss_growth_from_60_s: Option<f64>,
    /// Resident memory of the process, MB: `rss_early_at_s` in (a minute, or the end of the tour
    /// where that is later), and at the end.
    pub rss_early_at_s: f64,
    pub rss_early_mb: Option<f64>,
    pub rss_end_mb: Option<f64>,
    /// (end - early) / early.
    pub rss_growth: Option<f64>,
    /// The least-squares trend of the readings over the second half of the soak (those after
    /// the early reading), as growth over that span / early: what is judged.
    pub rss_trend_second_half: Option<f64>,
    /// Resident memory every 30 s of the soak, MB: each the least of the samples taken every 2 s
    /// over the 30 s before it (as are the early, 60-second and end readings).
    pub rss_every_30_s_mb: Vec<f64>,
    /// Specialised pipelines built by then (each cached for good: memory grows with them).
    pub pipelines_every_30_s: Vec<u64>,
    /// When the last new pipeline was built, seconds in, and memory then and at the end:
    /// what is left of the growth once every pipeline the session uses exists.
    pub last_new_pipeline_at_s: f64,
    pub rss_at_last_new_pipeline_mb: Option<f64>,
    /// GPU memory, where the adapter reports it (lavapipe does not).
    pub gpu_memory_mb: Option<f64>,
    /// Freed memory handed back to the system (`malloc_trim`, every 2 s of drawing and before
    /// each memory reading): how often, and the time it took on the UI thread, ms, in all and at
    /// most once.
    pub pages_returned: u64,
    pub pages_returned_total_ms: f64,
    pub pages_returned_max_ms: f64,
    /// Every play period advanced scene time and put new images on screen.
    pub moving_throughout: bool,
    /// Judged on soaks of `JUDGE_MEMORY_FROM` or longer: the second half's trend within 10% of
    /// the early reading.
    pub memory_held: Option<bool>,
}

enum Stage {
    Starting,
    /// Before the soak proper: every lesson once in every view (`index` counts them), played a
    /// moment and paused, so what the session's caches (pipelines, the drivers' compiled shaders,
    /// the allocator's pools) will hold is built in the first minute, as a teacher's walk
    /// through the lessons would build it.
    Touring {
        index: usize,
        since: Instant,
        frames_before: u64,
    },
    Playing {
        since: Instant,
        time_before: f32,
        frames_before: u64,
    },
    /// Paused: waiting for the full-detail frame.
    Pausing {
        since: Instant,
    },
    Done,
}

struct Soak {
    app: ShadowlabApp,
    /// The lessons played in turn: (id, step from 0).
    lessons: Vec<(String, usize)>,
    stage: Stage,
    length: Duration,
    started: Instant,
    lesson: usize,
    cycle: u32,
    report: SoakReport,
    last_time: f32,
    pipelines_seen: u64,
    memory: MemoryFloor,
    outcome: Arc<Mutex<Option<Result<SoakReport, String>>>>,
}

impl Soak {
    /// A soak long enough to be judged on memory goes on past its length until `JUDGED_SPAN`
    /// of readings follow the baseline (taken once the tour is over and no pipeline has been
    /// built for a minute, however long a slow machine takes to get there).
    fn judged_long_enough(&self, elapsed: Duration) -> bool {
        self.length < JUDGE_MEMORY_FROM
            || (self.report.rss_early_mb.is_some()
                && elapsed.as_secs_f64() >= self.report.rss_early_at_s + JUDGED_SPAN.as_secs_f64())
    }

    /// Open the `which`th of the lessons played in turn (the tour's stops are every lesson in
    /// every view; `soak_lessons` checked each step exists).
    fn open_lesson(&mut self, which: usize) -> Result<(), String> {
        let (id, step) = &self.lessons[which % self.lessons.len()];
        let lesson = self.app.lessons.iter().position(|l| l.id == *id).ok_or(format!("no lesson {id}"))?;
        let step = *step;
        self.app.go_to_step(lesson, step);
        self.app.overlays = OVERLAYS.to_vec();
        if self.app.probe_at.is_none() {
            self.app.probe_at = Some(crate::ui::ProbeAt::View(0.5, 0.6));
        }
        self.app.mark_dirty();
        Ok(())
    }

    /// Start the tour's `index`th stop: a lesson in a view, playing.
    fn tour(&mut self, index: usize) -> Result<(), String> {
        self.open_lesson(index / VIEWS.len())?;
        self.app.view = VIEWS[index % VIEWS.len()];
        self.app.playing = true;
        let frames_before = self.app.frames_shown();
        self.stage = Stage::Touring { index, since: Instant::now(), frames_before };
        Ok(())
    }

    fn play(&mut self) {
        self.app.playing = true;
        self.last_time = self.app.time_s;
        self.stage = Stage::Playing {
            since: Instant::now(),
            time_before: self.app.time_s,
            frames_before: self.app.frames_shown(),
        };
    }

    /// Scene time played since the last frame (it wraps at the end of the range).
    fn track_time(&mut self) {
        let t = self.app.time_s;
        let d = (t - self.last_time).rem_euclid(PLAYBACK_RANGE_S);
        self.report.scene_time_advanced_s += f64::from(d);
        self.last_time = t;
    }

    fn advance(&mut self) -> Result<(), String> {
        let elapsed = self.started.elapsed();
        self.memory.sample(elapsed.as_secs_f64());
        // The first reading comes a minute in, once the tour has shown every lesson in every
        // view and no pipeline has been built for a minute (later on a slower machine: the soak
        // goes on until it has been judged, `judged_long_enough`); on a soak too short to judge
        // memory by, at half of it.
        let quiet = elapsed.as_secs_f64() - self.report.last_new_pipeline_at_s >= QUIET;
        let warm = self.report.tour_s > 0.0 && elapsed >= EARLY && quiet;
        if self.report.rss_at_60_s_mb.is_none() && elapsed >= EARLY {
            self.report.rss_at_60_s_mb = self.memory.floor_mb();
        }
        let early_due = if self.length >= JUDGE_MEMORY_FROM { warm } else { elapsed >= self.length / 2 };
        if elapsed.as_secs_f64() >= 30.0 * (self.report.rss_every_30_s_mb.len() + 1) as f64 {
            self.report.rss_every_30_s_mb.extend(self.memory.floor_mb());
            self.report.pipelines_every_30_s.push(crate::render::pipelines_built());
        }
        let pipelines = crate::render::pipelines_built();
        if pipelines != self.pipelines_seen {
            self.pipelines_seen = pipelines;
            self.report.last_new_pipeline_at_s = elapsed.as_secs_f64();
            self.report.rss_at_last_new_pipeline_mb = rss_mb();
        }
        if self.report.rss_early_mb.is_none() && early_due {
            self.report.rss_early_mb = self.memory.floor_mb();
            self.report.rss_early_at_s = elapsed.as_secs_f64();
        }
        match self.stage {
            Stage::Starting => {
                if self.app.camera_image().is_some() && !self.app.render_pending() {
                    self.tour(0)?;
                } else if elapsed > SETTLE_LIMIT {
                    return Err(self.app.gpu_problem().unwrap_or_else(|| "no first frame".into()));
                }
            }
            Stage::Touring { index, since, frames_before } => {
                // Each stop is a short cycle: play, pause until the full-detail frame is in.
                if self.app.playing {
                    if since.elapsed() >= PLAY && self.app.frames_shown() > frames_before {
                        self.app.playing = false;
                        self.app.mark_dirty();
                        self.stage = Stage::Touring { index, since: Instant::now(), frames_before };
                    }
                } else if since.elapsed() > Duration::from_millis(50) && !self.app.render_pending() {
                    if index + 1 < self.lessons.len() * VIEWS.len() {
                        self.tour(index + 1)?;
                    } else {
                        self.report.tour_s = elapsed.as_secs_f64();
                        self.open_lesson(0)?;
                        self.app.view = VIEWS[0];
                        self.play();
                    }
                }
                if since.elapsed() > SETTLE_LIMIT {
                    return Err("the app did not settle on the tour through the lessons".into());
                }
            }
            Stage::Playing { since, time_before, frames_before } => {
                self.track_time();
                if since.elapsed() >= PLAY {
                    let moved = self.app.time_s != time_before;
                    let refreshed = self.app.frames_shown() > frames_before;
                    if !(moved && refreshed) {
                        return Err(format!(
                            "the scene stopped moving {:.0} s in (time {:.2} s, {} new images in {:.0} s of play)",
                            elapsed.as_secs_f64(),
                            self.app.time_s,
                            self.app.frames_shown() - frames_before,
                            PLAY.as_secs_f64()
                        ));
                    }
                    self.app.playing = false;
                    self.app.mark_dirty();
                    self.stage = Stage::Pausing { since: Instant::now() };
                }
            }
            Stage::Pausing { since } => {
                if since.elapsed() > Duration::from_millis(50) && !self.app.render_pending() {
                    if self.app.probe_report().is_none() {
                        return Err(format!("no probe after a pause {:.0} s in", elapsed.as_secs_f64()));
                    }
                    self.report.full_detail_frames += 1;
                    // However slow the machine, a soak goes through one view switch at least.
                    if elapsed >= self.length + JUDGE_WAIT_LIMIT && !self.judged_long_enough(elapsed) {
                        return Err(format!(
                            "memory could not be judged: {:.0} s in, a pipeline was last built {:.0} s in and \
                             the baseline waits a minute after the last (the machine is too slow for this \
                             soak, or pipelines keep being made)",
                            elapsed.as_secs_f64(),
                            self.report.last_new_pipeline_at_s
                        ));
                    }
                    if elapsed >= self.length && self.cycle >= 1 && self.judged_long_enough(elapsed) {
                        self.stage = Stage::Done;
                        return Ok(());
                    }
                    self.cycle += 1;
                    if self.cycle.is_multiple_of(CYCLES_PER_LESSON) {
                        self.lesson += 1;
                        self.report.lesson_switches += 1;
                        self.open_lesson(self.lesson)?;
                    }
                    self.app.view = VIEWS[self.cycle as usize % VIEWS.len()];
                    self.report.view_switches += 1;
                    self.app.mark_dirty();
                    self.play();
                } else if since.elapsed() > SETTLE_LIMIT {
                    return Err("the app did not settle after a pause".into());
                }
            }
            Stage::Done => {}
        }
        Ok(())
    }

    fn finish(&mut self, ctx: &egui::Context, result: Result<(), String>) {
        let result = result.map(|()| {
            let mut report = std::mem::take(&mut self.report);
            report.seconds = self.started.elapsed().as_secs_f64();
            report.frames_rendered = self.app.frames_shown();
            report.rss_end_mb = self.memory.floor_mb();
            let trims = crate::ui::trim_stats();
            report.pages_returned = trims.calls;
            report.pages_returned_total_ms = trims.total_ms;
            report.pages_returned_max_ms = trims.max_ms;
            report.rss_growth = report.rss_early_mb.zip(report.rss_end_mb).map(|(a, b)| (b - a) / a);
            report.rss_growth_from_60_s =
                report.rss_at_60_s_mb.zip(report.rss_end_mb).map(|(a, b)| (b - a) / a);
            report.moving_throughout = true;
            report.rss_trend_second_half = second_half_trend(
                &report.rss_every_30_s_mb,
                report.rss_early_at_s.max(report.seconds / 2.0),
                report.rss_early_mb,
            );
            report.memory_held = (self.length >= JUDGE_MEMORY_FROM).then(|| {
                // Too few readings for a trend (a short soak): the end against the early one.
                let growth = report.rss_trend_second_half.or(report.rss_growth);
                growth.is_some_and(|g| g <= MEMORY_GROWTH_ALLOWED)
            });
            report
        });
        if let Ok(mut slot) = self.outcome.lock() {
            slot.get_or_insert(result);
        }
        self.stage = Stage::Done;
        ctx.send_viewport_cmd(egui::ViewportCommand::Close);
    }
}

impl eframe::App for Soak {
    fn clear_color(&self, visuals: &egui::Visuals) -> [f32; 4] {
        self.app.clear_color(visuals)
    }

    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        let ctx = ui.ctx().clone();
        self.app.ui(ui, frame);
        if matches!(self.stage, Stage::Done) {
            return;
        }
        match self.advance() {
            Ok(()) if matches!(self.stage, Stage::Done) => self.finish(&ctx, Ok(())),
            Ok(()) => ctx.request_repaint(),
            Err(e) => self.finish(&ctx, Err(e)),
        }
    }
}

/// `--soak-lesson ID:STEP` (a lesson by id or number, a step from 1), or the default lessons.
fn soak_lessons(asked: &[String]) -> Result<Vec<(String, usize)>, CliError> {
    if asked.is_empty() {
        return Ok(LESSONS.iter().map(|(id, step)| (id.to_string(), *step)).collect());
    }
    let lessons = crate::lessons::load_all(&crate::lessons::default_dir())
        .map_err(|e| CliError::input(format!("--soak-lesson: {e}")))?;
    asked
        .iter()
        .map(|text| {
            let bad =
                || CliError::input(format!("--soak-lesson {text}: expected LESSON:STEP, e.g. more-maps:5"));
            let (id, step) = text.split_once(':').ok_or_else(bad)?;
            let step: usize = step.parse().ok().filter(|s| *s >= 1).ok_or_else(bad)?;
            let lesson = crate::lessons::find(&lessons, id)
                .map_err(|e| CliError::input(format!("--soak-lesson {text}: {e}")))?;
            if step > lesson.steps.len() {
                return Err(CliError::input(format!(
                    "--soak-lesson {text}: lesson {} has {} steps",
                    lesson.id,
                    lesson.steps.len()
                )));
            }
            Ok((lesson.id.clone(), step - 1))
        })
        .collect()
}

pub fn run(args: &BenchArgs, seconds: f32) -> Result<(), CliError> {
    if !(5.0..=86_400.0).contains(&seconds) {
        return Err(CliError::input(format!("--soak {seconds} is out of range 5..=86400 seconds")));
    }
    if !args.window {
        return Err(CliError::input("--soak plays in the real window: add --window"));
    }
    let lessons = soak_lessons(&args.soak_lesson)?;
    if !crate::ui::display_available() {
        return Err(CliError::input(
            "bench --app --window --soak: no display found (DISPLAY and WAYLAND_DISPLAY are unset); run \
             it under `xvfb-run -a`",
        ));
    }
    let painter = crate::ui::ui_painter();
    let outcome = Arc::new(Mutex::new(None));
    let sink = outcome.clone();
    let mut options = crate::ui::window_options(painter);
    options.viewport = options.viewport.with_inner_size(WINDOW);
    options.persist_window = false;
    let result = eframe::run_native(
        "shadowlab-soak",
        options,
        Box::new(move |cc| {
            let app = app_for_test(cc, Settings::default());
            crate::ui::clear_paints_panels(&cc.egui_ctx);
            let mut soak = Soak {
                app,
                lessons,
                stage: Stage::Starting,
                length: Duration::from_secs_f32(seconds),
                started: Instant::now(),
                lesson: 0,
                cycle: 0,
                report: SoakReport { painter: format!("{painter} (window)"), ..Default::default() },
                last_time: 0.0,
                pipelines_seen: 0,
                memory: MemoryFloor::default(),
                outcome: sink,
            };
            soak.open_lesson(0)?;
            Ok(Box::new(soak))
        }),
    );
    if let Err(e) = result {
        return Err(CliError { code: 2, message: format!("could not open the window: {e}") });
    }
    let taken = outcome.lock().ok().and_then(|mut slot| slot.take());
    let report = match taken {
        Some(Ok(report)) => report,
        Some(Err(e)) => return Err(CliError { code: 1, message: format!("soak: {e}") }),
        None => return Err(CliError { code: 1, message: "soak: the window closed before the end".into() }),
    };
    if args.json {
        let text = serde_json::to_string_pretty(&report)
            .map_err(|e| CliError { code: 1, message: e.to_string() })?;
        println!("{text}");
    } else {
        let mb = |v: Option<f64>| v.map_or("n/a".to_string(), |v| format!("{v:.1} MB"));
        println!("soak {:.0} s ({})", report.seconds, report.painter);
        println!("  images on screen        {}", report.frames_rendered);
        println!("  full-detail frames      {}", report.full_detail_frames);
        println!("  scene time played       {:.1} s", report.scene_time_advanced_s);
        println!("  view / lesson switches  {} / {}", report.view_switches, report.lesson_switches);
        println!("  memory at 60 s          {}", mb(report.rss_at_60_s_mb));
        println!("  memory at {:.0} s        {}", report.rss_early_at_s, mb(report.rss_early_mb));
        println!("  memory at the end       {}", mb(report.rss_end_mb));
        let trend = report.rss_trend_second_half.map_or("n/a".into(), |g| format!("{:+.1}%", g * 100.0));
        println!("  trend, second half      {trend}");
        println!(
            "  pipelines built         {} (the last {:.0} s in, memory then {})",
            report.pipelines_every_30_s.last().copied().unwrap_or(crate::render::pipelines_built()),
            report.last_new_pipeline_at_s,
            mb(report.rss_at_last_new_pipeline_mb)
        );
        println!("  GPU memory              {}", mb(report.gpu_memory_mb));
    }
    if report.memory_held == Some(false) {
        return Err(CliError {
            code: 1,
            message: format!(
                "soak: memory grew {:.0}% over the second half (allowed {:.0}%)",
                report.rss_trend_second_half.or(report.rss_growth).unwrap_or(0.0) * 100.0,
                MEMORY_GROWTH_ALLOWED * 100.0
            ),
        });
    }
    Ok(())
}

//! The two render schedulers give the app the same thing: the frame-driven one (what a page
//! without threads runs, a step per UI frame, never waiting for the GPU) against the render
//! thread, on the same lesson step with a probe whose ground truth the text quotes, and on a job
//! with every read-back and ground truth there is.

mod common;

use egui_kittest::Harness;
use shadowlab::app::scheduler::{
    FrameDriven, ProbeSpot, RenderEvent, RenderJob, RenderScheduler, WorkerThread,
};
use shadowlab::i18n::Lang;
use shadowlab::render::FrameRequest;
use shadowlab::render::readback::blocking_waits_on_this_thread;
use shadowlab::scene::Technique;
use shadowlab::ui::{SchedulerKind, Settings, ShadowlabApp, app_with_scheduler};

fn harness(kind: SchedulerKind) -> Harness<'static, ShadowlabApp> {
    let mut setup = egui_kittest::wgpu::default_wgpu_setup();
    if let eframe::egui_wgpu::WgpuSetup::CreateNew(create) = setup {
        setup = eframe::egui_wgpu::WgpuSetup::CreateNew(shadowlab::ui::configure_wgpu(create));
    }
    let settings = Settings { show_timings: false, ..Settings::default() };
    Harness::builder()
        .with_size([1400.0, 820.0])
        .wgpu_setup(setup)
        .build_eframe(move |cc| app_with_scheduler(cc, settings.clone(), kind))
}

/// Step UI frames until nothing is pending; returns how many it took.
fn settle(h: &mut Harness<'_, ShadowlabApp>) -> u32 {
    let start = std::time::Instant::now();
    let mut frames = 0;
    loop {
        h.step();
        frames += 1;
        if !h.state().render_pending() && h.state().camera_image().is_some() {
            h.step();
            return frames;
        }
        assert!(
            start.elapsed() < std::time::Duration::from_secs(300),
            "the scheduler did not finish ({:?})",
            h.state().gpu_problem()
        );
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
}

/// The PCSS lesson's step that quotes the ground truth at its probe.
fn open_quoting_step(h: &mut Harness<'_, ShadowlabApp>) {
    let lessons = &h.state().lessons;
    let (lesson, step) = lessons
        .iter()
        .enumerate()
        .find_map(|(i, l)| {
            let step = l.steps.iter().position(|s| !s.quoted_lights("visibility_reference").is_empty())?;
            (l.id == "pcss").then_some((i, step))
        })
        .expect("the PCSS lesson quotes a ground truth at its probe");
    h.state_mut().go_to_step(lesson, step);
    h.state_mut().playing = false;
}

#[test]
fn the_frame_driven_scheduler_shows_what_the_render_thread_shows() {
    let mut threaded = harness(SchedulerKind::Thread);
    settle(&mut threaded);
    open_quoting_step(&mut threaded);
    settle(&mut threaded);

    let mut driven = harness(SchedulerKind::FrameDriven);
    settle(&mut driven);
    open_quoting_step(&mut driven);
    let frames = settle(&mut driven);
    // A stage per frame: image and maps, details (probe, analysis), ground truths.
    assert!(frames >= 3, "the work was spread over {frames} frames");

    let (a, b) = (threaded.state(), driven.state());
    assert!(
        a.gpu_problem().is_none() && b.gpu_problem().is_none(),
        "{:?} {:?}",
        a.gpu_problem(),
        b.gpu_problem()
    );
    let (image_a, image_b) =
        (a.camera_image().expect("thread image"), b.camera_image().expect("driven image"));
    assert_eq!(image_a.dimensions(), image_b.dimensions());
    let differing = image_a.pixels().zip(image_b.pixels()).filter(|(p, q)| p != q).count();
    assert!(
        differing * 1000 <= (image_a.width() * image_a.height()) as usize,
        "{differing} pixels differ between the schedulers' pictures"
    );
    let (probe_a, probe_b) =
        (a.probe_report().expect("thread probe"), b.probe_report().expect("driven probe"));
    assert_eq!(probe_a.pixel, probe_b.pixel);
    let (la, lb) = (&probe_a.lights[0], &probe_b.lights[0]);
    assert_eq!(la.visibility_twin, lb.visibility_twin, "the twin's visibility at the probe");
    assert_eq!(la.visibility_gpu, lb.visibility_gpu, "the GPU's visibility at the probe");
    let truth = |h: &ShadowlabApp| {
        let light = h.current_step().map_or(0, |(_, s, _)| s.light);
        (h.probe_reference_progress(light), h.probe_report().and_then(|p| p.lights[0].visibility_reference))
    };
    let (truth_a, truth_b) = (truth(a), truth(b));
    assert!(
        truth_b.0.is_some_and(|(done, all)| done == all && all > 0),
        "the ground truth completed: {truth_b:?}"
    );
    assert_eq!(truth_a, truth_b, "the same ground truth at the probe");
}

/// The same job through a scheduler, without the window: every read-back and ground truth the
/// app can ask for (VSM for the moments and the bleeding, an A/B side, thumbnails of two lights,
/// a probe and both ground truths).
fn full_job() -> RenderJob {
    let scene = common::scene("multi_light", &[("technique", "vsm"), ("reference_samples", "40")]);
    let size = (240, 136);
    RenderJob {
        scene,
        request: FrameRequest { size, selected_light: 0, ..Default::default() },
        probe: Some(ProbeSpot { pixel: (120, 80), frame: size }),
        analysis: true,
        reference: true,
        probe_reference: vec![0, 1],
        bleeding: true,
        moments: true,
        technique_b: Some(Technique::Pcss),
        thumbnails: true,
        preview: false,
        map_texels: 256,
        homework: None,
    }
}

/// Polls at most, for a job of a few dozen steps (each poll after the GPU is idle makes one).
const MAX_POLLS: usize = 1000;

/// Poll `driven` until its job is done, holding it to never waiting for the GPU within a poll:
/// the events of each poll. The test waits for the GPU itself after every second poll, so that
/// each pair makes progress (the count of polls does not depend on the machine's speed), while
/// the poll after one that submitted work finds it under way, its read-backs not yet mapped.
fn poll_through(driven: &mut FrameDriven) -> Vec<Vec<RenderEvent>> {
    let mut polls = Vec::new();
    while driven.needs_polling() {
        let waits = blocking_waits_on_this_thread();
        polls.push(driven.poll());
        assert_eq!(blocking_waits_on_this_thread(), waits, "poll {} waited for the GPU", polls.len());
        if polls.len() % 2 == 0 {
            driven.wait_for_gpu().expect("the GPU finishes");
        }
        assert!(polls.len() < MAX_POLLS, "the job did not finish in {MAX_POLLS} polls");
    }
    polls
}

/// Events of the render thread until its job's last ground truth is finished.
fn worker_events(job: RenderJob) -> Vec<RenderEvent> {
    let (woken, wake) = std::sync::mpsc::channel();
    let adapter = shadowlab::render::headless_adapter().expect("an adapter");
    let mut worker = WorkerThread::spawn(adapter, move || {
        let _ = woken.send(());
    });
    worker.submit(job);
    let mut events = Vec::new();
    loop {
        events.extend(worker.poll());
        match events.last() {
            Some(RenderEvent::Reference { done, total, .. }) if done == total => return events,
            Some(RenderEvent::Failed { message, .. }) => panic!("the render thread failed: {message}"),
            _ => wake.recv().expect("the render thread is running"),
        }
    }
}

/// What a job's events tell the views, to compare between the schedulers: the colours, the
/// maps, the probe and analysis, and every ground-truth report in order.
#[derive(Debug, PartialEq)]
struct Told {
    color: Option<image::RgbaImage>,
    color_b: Option<image::RgbaImage>,
    map: Option<Vec<f32>>,
    thumbnails: Vec<image::RgbaImage>,
    probe: Option<shadowlab::probe::ProbeReport>,
    analysis_shadow: Option<Vec<[f32; 4]>>,
    bleeding: Option<Vec<f32>>,
    moments: Option<Vec<[f32; 2]>>,
    probe_truths: Vec<(usize, u32, u32, f32)>,
    view_truths: Vec<(u32, u32, Vec<f32>)>,
}

fn told<'a>(events: impl IntoIterator<Item = &'a RenderEvent>) -> Told {
    let mut told = Told {
        color: None,
        color_b: None,
        map: None,
        thumbnails: Vec::new(),
        probe: None,
        analysis_shadow: None,
        bleeding: None,
        moments: None,
        probe_truths: Vec::new(),
        view_truths: Vec::new(),
    };
    for event in events {
        match event {
            RenderEvent::Frame(out) => {
                (told.color, told.color_b) = (Some(out.color.clone()), out.color_b.clone())
            }
            RenderEvent::Maps(maps) => {
                told.map = maps.map.as_ref().map(|m| m.depth.depth_ndc.clone());
                told.thumbnails = maps.thumbnails.clone();
            }
            RenderEvent::Details(details) => {
                told.probe = details.probe.clone().map(|p| p.expect("the probe"));
                let analysis = details.analysis.as_ref().expect("the analysis");
                told.analysis_shadow = Some(analysis.shadow.clone());
                told.bleeding = analysis.bleeding.clone();
                told.moments = analysis.moments.as_ref().map(|m| m.texels.clone());
            }
            RenderEvent::ProbeReference { light, done, total, value, .. } => {
                told.probe_truths.push((*light, *done, *total, *value))
            }
            RenderEvent::Reference { done, total, values, .. } => {
                told.view_truths.push((*done, *total, values.clone()))
            }
            RenderEvent::Failed { message, .. } => panic!("the job failed: {message}"),
            RenderEvent::Ready(_) | RenderEvent::Homework { .. } => {}
        }
    }
    told
}

#[test]
fn the_frame_driven_scheduler_returns_between_read_backs_and_batches_and_tells_what_the_thread_tells() {
    let mut driven = FrameDriven::new(shadowlab::render::headless_adapter().expect("an adapter"));
    driven.submit(full_job());
    let polls = poll_through(&mut driven);
    let first = |wanted: fn(&RenderEvent) -> bool| polls.iter().position(|p| p.iter().any(wanted));
    // The first poll opens the device and submits the image; its bytes come on a later poll.
    let frame = first(|e| matches!(e, RenderEvent::Frame(_))).expect("a frame");
    assert!(frame >= 1, "the image came in the poll that submitted it");
    assert!(first(|e| matches!(e, RenderEvent::Ready(Ok(_)))) == Some(0));
    // The maps, a picture per poll, and the details after them.
    let maps = first(|e| matches!(e, RenderEvent::Maps(_))).expect("the maps");
    let details = first(|e| matches!(e, RenderEvent::Details(_))).expect("the details");
    assert!(frame < maps && maps < details, "frame {frame}, maps {maps}, details {details}");
    // Every ground truth a batch per poll: 4, 8, 16 and the 12 left of 40 samples.
    for polled in &polls {
        let view = polled.iter().filter(|e| matches!(e, RenderEvent::Reference { .. })).count();
        let probe = polled.iter().filter(|e| matches!(e, RenderEvent::ProbeReference { .. })).count();
        assert!(view <= 1 && probe <= 1, "{view} view and {probe} probe reports in one poll");
    }
    let all = told(polls.iter().flatten());
    let batches: Vec<u32> = all.view_truths.iter().map(|t| t.0).collect();
    assert_eq!(batches, [4, 12, 28, 40]);
    let probe_batches: Vec<(usize, u32)> = all.probe_truths.iter().map(|t| (t.0, t.1)).collect();
    assert_eq!(probe_batches, [(0, 4), (0, 12), (0, 28), (0, 40), (1, 4), (1, 12), (1, 28), (1, 40)]);

    // What the render thread tells, waiting for the GPU in each stage, is the same.
    let threaded = told(&worker_events(full_job()));
    assert!(all.probe.as_ref().is_some_and(|p| p.hit && p.lights.len() == 2), "{:?}", all.probe);
    assert!(all.moments.is_some() && all.bleeding.is_some() && all.thumbnails.len() == 2);
    let differing = |a: &Option<image::RgbaImage>, b: &Option<image::RgbaImage>| {
        let (a, b) = (a.as_ref().expect("a colour"), b.as_ref().expect("a colour"));
        assert_eq!(a.dimensions(), b.dimensions());
        a.pixels().zip(b.pixels()).filter(|(p, q)| p != q).count() * 1000 > (a.width() * a.height()) as usize
    };
    assert!(!differing(&all.color, &threaded.color), "the schedulers' pictures differ");
    assert!(!differing(&all.color_b, &threaded.color_b), "the schedulers' B sides differ");
    let without_colours = |t: Told| Told { color: None, color_b: None, ..t };
    assert!(
        without_colours(all) == without_colours(threaded),
        "the schedulers' maps, probes, analyses or ground truths differ"
    );
}

#[test]
fn a_newer_job_drops_the_frame_driven_ground_truth_under_way() {
    let mut driven = FrameDriven::new(shadowlab::render::headless_adapter().expect("an adapter"));
    let first = driven.submit(full_job());
    let mut polls = 0;
    // Until the first partial average at the probe.
    while !driven.poll().iter().any(|e| matches!(e, RenderEvent::ProbeReference { done: 4, .. })) {
        driven.wait_for_gpu().expect("the GPU finishes");
        polls += 1;
        assert!(polls < MAX_POLLS, "no ground truth began");
    }
    let mut newer = full_job();
    newer.request.time_s = 1.0;
    let second = driven.submit(newer);
    let events: Vec<RenderEvent> = poll_through(&mut driven).into_iter().flatten().collect();
    let job = |e: &RenderEvent| match e {
        RenderEvent::Frame(out) => Some(out.job),
        RenderEvent::Maps(maps) => Some(maps.job),
        RenderEvent::Details(details) => Some(details.job),
        RenderEvent::Reference { job, .. }
        | RenderEvent::ProbeReference { job, .. }
        | RenderEvent::Homework { job, .. }
        | RenderEvent::Failed { job, .. } => Some(*job),
        RenderEvent::Ready(_) => None,
    };
    assert!(events.iter().filter_map(job).all(|j| j == second), "job {first} went on after job {second}");
    let done: Vec<u32> = told(&events).view_truths.iter().map(|t| t.0).collect();
    assert_eq!(done, [4, 12, 28, 40], "the newer job's ground truth, from its first batch");
}

/// A homework check as a page runs it: the student's two pictures, shadowlab's frame and the
/// ground truth a piece per poll, never waiting for the GPU within one, with the findings and
/// figures of the check that waits (the command line's).
#[test]
fn the_frame_driven_scheduler_checks_a_homework_without_waiting() {
    use shadowlab::app::scheduler::HomeworkJob;
    use shadowlab::homework::{HomeworkFiles, HomeworkProgram, HomeworkRenderer, HomeworkRequest};
    let shader = common::repo_path("assets/homework/phongFragment_tiny_light.glsl");
    let files = HomeworkFiles::read(&shader, None, None).expect("the example reads");
    let program = std::sync::Arc::new(HomeworkProgram::translate(files).expect("the example compiles"));
    let scene = common::scene("homework_check", &[]);
    // The view's size; the check is at `CHECK_SIZE` whatever it is.
    let size = (480, 270);
    let job = RenderJob {
        scene: scene.clone(),
        request: FrameRequest { size, selected_light: 0, ..Default::default() },
        probe: None,
        analysis: false,
        reference: false,
        probe_reference: Vec::new(),
        bleeding: false,
        moments: false,
        technique_b: None,
        thumbnails: false,
        preview: false,
        map_texels: 256,
        homework: Some(HomeworkJob {
            program: program.clone(),
            source: None,
            generation: 1,
            lang: Lang::En,
            page_light: None,
        }),
    };
    let mut driven = FrameDriven::new(shadowlab::render::headless_adapter().expect("an adapter"));
    driven.submit(job);
    let polls = poll_through(&mut driven);
    let checked: Vec<usize> = polls
        .iter()
        .enumerate()
        .filter(|(_, p)| p.iter().any(|e| matches!(e, RenderEvent::Homework { .. })))
        .map(|(i, _)| i)
        .collect();
    let outcome = match polls.iter().flatten().find(|e| matches!(e, RenderEvent::Homework { .. })) {
        Some(RenderEvent::Homework { outcome, generation: 1, .. }) => {
            outcome.as_ref().expect("the check ran").clone()
        }
        other => panic!("no homework event: {}", other.is_some()),
    };
    assert_eq!(checked.len(), 1, "one outcome");
    // Student pictures, shadowlab's frame, the ground truth: at least a poll each after the image.
    let frame = polls.iter().position(|p| p.iter().any(|e| matches!(e, RenderEvent::Frame(_))));
    assert!(checked[0] >= frame.expect("a frame") + 3, "the check came in poll {}", checked[0]);

    let (_gpu, mut renderer) = common::gpu();
    let homework =
        HomeworkRenderer::new(renderer.device(), renderer.queue(), &program).expect("the pipelines");
    // The app checks at the command line's size whatever its view's (the view's job asked 480x270).
    let request = HomeworkRequest {
        time_s: 0.0,
        size: shadowlab::homework::CHECK_SIZE,
        light: 0,
        map: shadowlab::homework::MapKind::Framework,
    };
    let light = shadowlab::homework::HomeworkLight::of_scene(
        &scene,
        0,
        0.0,
        shadowlab::homework::FRAMEWORK_LIGHT_INTENSITY,
    )
    .expect("a light");
    let waited = shadowlab::homework::run_check(
        &homework,
        &mut renderer,
        &program.files.phong_fragment,
        &scene,
        &light,
        &request,
        Lang::En,
    )
    .expect("the check runs");
    let ids = |r: &shadowlab::homework::HomeworkReport| r.findings.iter().map(|f| f.id).collect::<Vec<_>>();
    assert_eq!(ids(&outcome.report), ["no_penumbra"], "the tiny light's finding");
    assert_eq!(outcome.report, waited.report, "the polled check and the waited one differ");
    assert_eq!(outcome.ground_truth, waited.ground_truth);
}

//! The two render schedulers give the app the same thing: the frame-driven one (what a page
//! without threads runs, a stage per UI frame) against the render thread, on the same lesson
//! step with a probe whose ground truth the text quotes.

use egui_kittest::Harness;
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

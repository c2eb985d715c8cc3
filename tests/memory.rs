//! Memory held while the renderer draws again and again with values that change every frame or
//! every dispatch (lights orbiting, sliders dragged, the ground truth's light samples): whatever
//! such values key, in our caches or in the driver's, must stay bounded.
//!
//! On lavapipe (Mesa's software Vulkan driver, what classrooms without a GPU run) a uniform
//! value that decides a branch, directly or through a local copy used five times or more, is
//! inlined into a new compiled variant of the shader for each value it takes, and every variant
//! is kept until the pipeline is destroyed. A per-dispatch value in a uniform therefore grows the
//! process by a compiled shader per dispatch: the ground truth's light sample did, about 7 MB a
//! second while lessons played. These tests read the process's resident memory after a warm-up
//! and after many more frames or ground truths, each with new values.

mod common;

use shadowlab::render::{FrameRequest, Renderer};
use shadowlab::scene::{LightSize, Scene};

/// Growth allowed from the reading after the warm-up to the end, MB. One compiled shader
/// variant of the ground truth is hundreds of kilobytes on lavapipe: the loops below would add
/// hundreds of MB if each new value made one.
const GROWTH_ALLOWED_MB: f64 = 24.0;

/// Resident memory of this process, MB, once freed memory is handed back to the system.
fn rss_mb() -> f64 {
    shadowlab::ui::return_free_pages();
    let status = std::fs::read_to_string("/proc/self/status").expect("read /proc/self/status");
    let line = status.lines().find(|l| l.starts_with("VmRSS:")).expect("VmRSS in /proc/self/status");
    let kb: f64 = line.split_whitespace().nth(1).and_then(|v| v.parse().ok()).expect("VmRSS in kB");
    kb / 1024.0
}

/// Runs `step(k)` for k in 0..warm_up, reads memory, runs it for warm_up..warm_up + measured
/// and reads again: (early, end) MB.
fn memory_over(warm_up: u32, measured: u32, mut step: impl FnMut(u32)) -> (f64, f64) {
    (0..warm_up).for_each(&mut step);
    let early = rss_mb();
    (warm_up..warm_up + measured).for_each(&mut step);
    (early, rss_mb())
}

fn assert_held(what: &str, (early, end): (f64, f64)) {
    eprintln!("{what}: {early:.1} MB after the warm-up, {end:.1} MB at the end");
    assert!(
        end - early <= GROWTH_ALLOWED_MB,
        "{what}: memory grew {:.1} MB ({early:.1} -> {end:.1} MB; allowed {GROWTH_ALLOWED_MB} MB): \
         something keeps what each new value makes",
        end - early
    );
}

/// The scene at frame k of a drag: its time moves (lights orbit, objects spin) and the values a
/// student drags change with every frame.
fn dragged(base: &Scene, k: u32) -> Scene {
    let mut scene = base.clone();
    let f = k as f32;
    scene.shadow.bias = 0.0005 + 1e-5 * f;
    scene.shadow.normal_offset_texels = 0.5 + 0.01 * f;
    scene.shadow.radius_texels = 4.0 + 0.05 * f;
    scene.shadow.min_filter_radius_texels = 0.5 + 0.003 * f;
    scene.shadow.search_radius_scale = 1.0 + 0.002 * f;
    scene.shadow.adaptive_c = 1.0 + 0.001 * f;
    for light in &mut scene.lights {
        if let LightSize::Width { width_world } = &mut light.size {
            *width_world *= 1.0 + 0.001 * f;
        }
    }
    scene.camera.position.x += 0.01 * f;
    scene
}

fn frame(renderer: &mut Renderer, scene: &Scene, k: u32) {
    let request =
        FrameRequest { time_s: 0.37 * k as f32, final_color: true, ..common::analysis_request((160, 90), 0) };
    renderer.render(scene, &request).expect("render");
    renderer.read_color().expect("read the picture back");
}

#[test]
fn ground_truths_of_orbiting_lights_hold_memory() {
    let (_ctx, mut renderer) = common::gpu();
    let mut scene = common::scene("multi_light", &[]);
    scene.shadow.reference_samples = 64;
    for light in &mut scene.lights {
        light.shadow_map_size = 256;
    }
    // Each ground truth: 64 samples of each orbiting light, every one a dispatch with its own
    // light position and view.
    let growth = memory_over(4, 30, |k| {
        let request = FrameRequest { time_s: 0.37 * k as f32, ..common::analysis_request((96, 54), 0) };
        renderer.render(&scene, &request).expect("render");
        for light in 0..scene.lights.len() {
            renderer.render_reference(&scene, light).expect("ground truth");
        }
    });
    assert_held("ground truths of the multi-light scene at 34 times", growth);
}

#[test]
fn frames_with_lights_moving_and_values_dragged_hold_memory() {
    let (_ctx, mut renderer) = common::gpu();
    // The multi-light lesson (orbiting lights, spinning objects), a lamp's six cube faces and a
    // sun's four cascades down the avenue, under PCSS and PCF, each dragged.
    let scenes: Vec<Scene> =
        [("multi_light", "pcss"), ("multi_light", "pcf"), ("point_lamp", "pcss"), ("sun_avenue", "pcss")]
            .iter()
            .map(|(name, technique)| {
                let mut scene = common::scene(name, &[("technique", technique)]);
                for light in &mut scene.lights {
                    light.shadow_map_size = light.shadow_map_size.min(512);
                }
                scene
            })
            .collect();
    let growth = memory_over(3, 40, |k| {
        for base in &scenes {
            frame(&mut renderer, &dragged(base, k), k);
        }
    });
    assert_held("frames of four scenes with every value changing", growth);
}

//! Helpers shared by the GPU tests. They need a real adapter (lavapipe on CI) and fail loudly
//! without one: a skipped rendering test would hide a broken renderer.
#![allow(dead_code)]

use shadowlab::render::{FrameRequest, GpuContext, Renderer};
use shadowlab::scene::{Scene, load_scene};
use std::path::{Path, PathBuf};

pub fn repo_path(relative: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(relative)
}

pub fn gpu() -> (GpuContext, Renderer) {
    let ctx = GpuContext::new_headless().unwrap_or_else(|e| {
        panic!("these tests need a GPU adapter; on a machine without a GPU install Mesa's software one (apt-get install mesa-vulkan-drivers): {e}")
    });
    let renderer = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    (ctx, renderer)
}

pub fn scene(name: &str, overrides: &[(&str, &str)]) -> Scene {
    let overrides: Vec<(String, String)> =
        overrides.iter().map(|(k, v)| (k.to_string(), v.to_string())).collect();
    load_scene(&repo_path(&format!("assets/scenes/{name}.toml")), &overrides)
        .unwrap_or_else(|e| panic!("scene {name}: {e}"))
}

pub fn analysis_request(size: (u32, u32), light: usize) -> FrameRequest {
    FrameRequest { size, selected_light: light, final_color: false, analysis: true, ..Default::default() }
}

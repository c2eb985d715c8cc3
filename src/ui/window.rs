//! The window: which painter draws it, the wgpu device eframe makes, and opening it.

#[cfg(not(target_arch = "wasm32"))]
use super::ShadowlabApp;
use std::sync::Arc;

/// The device shadowlab needs: Vulkan unless `WGPU_BACKEND` says otherwise, the adapter's own
/// limits (the analysis pass writes 48 bytes per pixel, over WebGPU's default 32), timestamps
/// where available.
pub fn configure_wgpu(
    mut setup: eframe::egui_wgpu::WgpuSetupCreateNew,
) -> eframe::egui_wgpu::WgpuSetupCreateNew {
    setup.instance_descriptor.backends = wgpu::Backends::from_env().unwrap_or(wgpu::Backends::VULKAN);
    setup.device_descriptor = Arc::new(|adapter: &wgpu::Adapter| wgpu::DeviceDescriptor {
        label: Some("shadowlab"),
        required_features: adapter.features() & crate::render::optional_features(),
        required_limits: adapter.limits(),
        ..Default::default()
    });
    setup
}

/// How the window paints: egui's defaults (hardware texture filtering) with one sample per pixel.
pub fn window_render_options() -> eframe::egui_wgpu::RendererOptions {
    eframe::egui_wgpu::RendererOptions { msaa_samples: 1, ..Default::default() }
}

#[cfg(not(target_arch = "wasm32"))]
/// What paints the window: `SHADOWLAB_UI_PAINTER=glow|wgpu`, or by default OpenGL where the
/// GPU is a software rasteriser and wgpu elsewhere. On Mesa's llvmpipe egui's OpenGL shader costs
/// about a sixth of its wgpu shader per pixel (a 1600x900 window: ~25 ms a frame against ~140 ms),
/// and the window's frames compete with the renders for the same cores. Rendering itself is
/// wgpu either way, on the render worker's own device.
pub fn ui_painter() -> eframe::Renderer {
    match std::env::var("SHADOWLAB_UI_PAINTER").as_deref() {
        Ok("glow") => eframe::Renderer::Glow,
        Ok("wgpu") => eframe::Renderer::Wgpu,
        _ => {
            let software = crate::render::headless_adapter()
                .is_ok_and(|adapter| adapter.get_info().device_type == wgpu::DeviceType::Cpu);
            if software { eframe::Renderer::Glow } else { eframe::Renderer::Wgpu }
        }
    }
}

#[cfg(not(target_arch = "wasm32"))]
/// Whether a window can be opened here (on Linux: an X11 or Wayland display is named).
pub fn display_available() -> bool {
    !cfg!(target_os = "linux")
        || ["DISPLAY", "WAYLAND_DISPLAY"].iter().any(|v| std::env::var_os(v).is_some_and(|s| !s.is_empty()))
}

#[cfg(not(target_arch = "wasm32"))]
/// Open the app on what `launch` asks for. Returns a one-line reason where no window can be
/// opened.
pub fn run(launch: super::launch::Launch) -> Result<(), String> {
    if !display_available() {
        return Err("no display found (DISPLAY and WAYLAND_DISPLAY are unset): run it on a desktop, under \
                    `xvfb-run -a`, or use `shadowlab render`/`shadowlab export`, which need no display"
            .into());
    }
    let first = ui_painter();
    let second = match first {
        eframe::Renderer::Glow => eframe::Renderer::Wgpu,
        eframe::Renderer::Wgpu => eframe::Renderer::Glow,
    };
    // Where the chosen painter cannot open a window (no OpenGL, no Vulkan surface), the other may.
    let first_error = match open_window(first, launch.clone()) {
        Ok(()) => return Ok(()),
        Err(e) => e,
    };
    open_window(second, launch).map_err(|second_error| {
        format!(
            "could not open the window ({first}: {first_error}; {second}: {second_error}); install a \
             Vulkan driver (apt-get install mesa-vulkan-drivers) or use `shadowlab render`"
        )
    })
}

#[cfg(not(target_arch = "wasm32"))]
fn open_window(painter: eframe::Renderer, launch: super::launch::Launch) -> Result<(), String> {
    eframe::run_native(
        "shadowlab",
        window_options(painter),
        Box::new(|cc| {
            let mut app = ShadowlabApp::new(cc);
            app.state.apply_launch(launch);
            clear_paints_panels(&cc.egui_ctx);
            Ok(Box::new(app))
        }),
    )
    .map_err(|e| e.to_string())
}

/// The colour the window is cleared to each frame: the panels' own (the app is always dark).
pub fn window_clear_color() -> [f32; 4] {
    egui::Visuals::dark().panel_fill.to_normalized_gamma_f32()
}

/// In a window the clear (`window_clear_color`) paints the panels' background, so the panels
/// draw no fill of their own: the same picture, one full-window layer less per frame. On a
/// software rasteriser that layer is about a third of an idle frame (1560x880 on llvmpipe:
/// ~30 ms -> ~20 ms). Offscreen harnesses clear to transparent and keep the panel fills.
pub fn clear_paints_panels(ctx: &egui::Context) {
    ctx.all_styles_mut(|style| style.visuals.panel_fill = egui::Color32::TRANSPARENT);
}

#[cfg(not(target_arch = "wasm32"))]
/// The window the app opens, painted by `painter`.
pub fn window_options(painter: eframe::Renderer) -> eframe::NativeOptions {
    eframe::NativeOptions {
        renderer: painter,
        viewport: egui::ViewportBuilder::default()
            .with_title("shadowlab")
            .with_inner_size([1560.0, 880.0])
            .with_drag_and_drop(true),
        wgpu_options: eframe::egui_wgpu::WgpuConfiguration {
            wgpu_setup: eframe::egui_wgpu::WgpuSetup::CreateNew(configure_wgpu(
                eframe::egui_wgpu::WgpuSetupCreateNew::without_display_handle(),
            )),
            ..Default::default()
        },
        ..Default::default()
    }
}

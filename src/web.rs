//! The page: eframe's web runner on index.html's canvas `shadowlab_canvas`, the app rendering
//! with the frame-driven scheduler on the page's own device (WebGPU where the browser has it,
//! else WebGL2; `?backend=webgl2` asks for WebGL2). What cannot start is said on the page.

use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::wasm_bindgen;

/// Runs when the module loads (`wasm-bindgen`'s start).
#[wasm_bindgen(start)]
pub fn start() {
    let _ = eframe::WebLogger::init(log::LevelFilter::Warn);
    wasm_bindgen_futures::spawn_local(async {
        let Some(document) = web_sys::window().and_then(|w| w.document()) else { return };
        let Some(canvas) = document
            .get_element_by_id("shadowlab_canvas")
            .and_then(|e| e.dyn_into::<web_sys::HtmlCanvasElement>().ok())
        else {
            return say(&document, "this page has no canvas named shadowlab_canvas");
        };
        let runner = eframe::WebRunner::new();
        let started = runner
            .start(
                canvas,
                web_options(),
                Box::new(|cc| {
                    let app = crate::ui::ShadowlabApp::new(cc);
                    crate::ui::clear_paints_panels(&cc.egui_ctx);
                    Ok(Box::new(app))
                }),
            )
            .await;
        match started {
            Ok(()) => {
                if let Some(loading) = document.get_element_by_id("loading") {
                    loading.remove();
                }
            }
            Err(e) => say(&document, &format!("shadowlab could not start: {e:?}")),
        }
        // The runner lives as long as the page.
        std::mem::forget(runner);
    });
}

/// The device the app renders on: the adapter's limits (the analysis pass writes 48 bytes per
/// pixel, over WebGPU's default 32) and timestamps where the browser has them.
fn web_options() -> eframe::WebOptions {
    let mut setup = eframe::egui_wgpu::WgpuSetupCreateNew::without_display_handle();
    if backend_asked().as_deref() == Some("webgl2") {
        setup.instance_descriptor.backends = wgpu::Backends::GL;
    }
    setup.device_descriptor = std::sync::Arc::new(|adapter: &wgpu::Adapter| wgpu::DeviceDescriptor {
        label: Some("shadowlab"),
        required_features: adapter.features() & crate::render::optional_features(),
        required_limits: adapter.limits(),
        ..Default::default()
    });
    eframe::WebOptions {
        wgpu_options: eframe::egui_wgpu::WgpuConfiguration {
            wgpu_setup: eframe::egui_wgpu::WgpuSetup::CreateNew(setup),
            ..Default::default()
        },
        ..Default::default()
    }
}

/// The page address's `backend=` value, if any.
fn backend_asked() -> Option<String> {
    let search = web_sys::window()?.location().search().ok()?;
    search
        .trim_start_matches('?')
        .split('&')
        .find_map(|pair| pair.strip_prefix("backend=").map(str::to_owned))
}

/// Put `message` where the loading text was.
fn say(document: &web_sys::Document, message: &str) {
    log::error!("{message}");
    if let Some(loading) = document.get_element_by_id("loading") {
        loading.set_text_content(Some(message));
    }
}

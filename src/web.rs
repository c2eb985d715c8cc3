//! The page: eframe's web runner on index.html's canvas `shadowlab_canvas`, the app rendering
//! with the frame-driven scheduler on the page's own device (WebGPU where the browser has it).
//! On WebGL2 (no WebGPU, or `?backend=webgl2`) the app runs without its views and says why, in
//! its own window and on `<body data-views>`; what cannot start at all is said on the page.

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
        // The CJK font is served beside the wasm; index.html started fetching it with the wasm.
        let font = served_cjk_font().await;
        mark_body("data-cjk-font", if font.is_some() { "served" } else { "missing" });
        if let Some(bytes) = font {
            crate::diagrams::set_served_cjk_font(bytes);
        }
        let runner = eframe::WebRunner::new();
        let started = runner
            .start(
                canvas,
                web_options(),
                Box::new(|cc| {
                    let mut app = crate::ui::ShadowlabApp::new(cc);
                    crate::ui::clear_paints_panels(&cc.egui_ctx);
                    let backend = cc.wgpu_render_state.as_ref().map(|rs| rs.adapter.get_info().backend);
                    let views = match backend {
                        Some(wgpu::Backend::Gl) => {
                            let why = no_webgpu_reason();
                            app.without_webgpu(why);
                            why.code()
                        }
                        Some(_) => "webgpu",
                        None => "none",
                    };
                    mark_body("data-views", views);
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
            Err(e) => {
                mark_body("data-views", "failed");
                say(&document, &format!("{CANNOT_START}\n\n({e:?})"));
            }
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

/// The bytes of the CJK font index.html fetches (`window.shadowlabCjkFont`, a promise of an
/// ArrayBuffer or null); None where it did not arrive.
async fn served_cjk_font() -> Option<Vec<u8>> {
    let window = web_sys::window()?;
    let promise = js_sys::Reflect::get(&window, &"shadowlabCjkFont".into()).ok()?;
    let promise = promise.dyn_into::<js_sys::Promise>().ok()?;
    let buffer = wasm_bindgen_futures::JsFuture::from(promise).await.ok()?;
    if buffer.is_null() || buffer.is_undefined() {
        log::warn!("the CJK font did not arrive: Chinese text is drawn without its glyphs");
        return None;
    }
    Some(js_sys::Uint8Array::new(&buffer).to_vec())
}

/// The page address's `backend=` value, if any.
fn backend_asked() -> Option<String> {
    let search = web_sys::window()?.location().search().ok()?;
    search
        .trim_start_matches('?')
        .split('&')
        .find_map(|pair| pair.strip_prefix("backend=").map(str::to_owned))
}

/// Where neither WebGPU nor WebGL2 gave the page a device, in both languages (the app, which
/// would follow the reader's choice, is not there to ask).
const CANNOT_START: &str = "shadowlab could not start: this browser gave the page neither WebGPU nor WebGL2. \
    Open it in a browser with WebGPU: Chrome or Edge 113 or later, Safari 26 or later, Firefox 141 or later on Windows.\n\n\
    shadowlab 无法启动：这个浏览器既不给网页 WebGPU，也不给 WebGL2。\
    请用支持 WebGPU 的浏览器打开本页：Chrome 或 Edge 113 及以上、Safari 26 及以上、Windows 上的 Firefox 141 及以上。";

/// Why the device eframe opened is WebGL2's.
fn no_webgpu_reason() -> crate::browser::NoWebGpu {
    let window = web_sys::window();
    let secure = window.as_ref().is_some_and(|w| w.is_secure_context());
    let has_webgpu_api = window.is_some_and(|w| {
        js_sys::Reflect::get(&w.navigator(), &"gpu".into())
            .is_ok_and(|gpu| !gpu.is_undefined() && !gpu.is_null())
    });
    crate::browser::NoWebGpu::diagnose(backend_asked().as_deref() == Some("webgl2"), secure, has_webgpu_api)
}

/// Set an attribute on `<body>` for scripts and tests to read.
fn mark_body(name: &str, value: &str) {
    if let Some(body) = web_sys::window().and_then(|w| w.document()).and_then(|d| d.body()) {
        let _ = body.set_attribute(name, value);
    }
}

/// Put `message` where the loading text was.
fn say(document: &web_sys::Document, message: &str) {
    log::error!("{message}");
    if let Some(loading) = document.get_element_by_id("loading") {
        loading.set_text_content(Some(message));
    }
}

//! Files a page is given: dropped on it, or picked in the browser's file dialog. A browser hands
//! over their bytes (never a path) and only asynchronously: each batch is read whole, kept under
//! `handed-over/` (`files::hand_over`, where everything that opens a path finds it) and its
//! paths queued for the next frame to open.

use std::cell::RefCell;
use std::path::PathBuf;
use wasm_bindgen::JsCast;
use wasm_bindgen::closure::Closure;

/// Files picked in the dialog, and dropped, accepted by the dialog (what the app opens, and what
/// a model brings along).
const ACCEPT: &str = ".glsl,.frag,.fs,.zip,.toml,.obj,.mtl,.png,.jpg,.jpeg";

thread_local! {
    /// Batches read and handed over, not yet opened.
    static ARRIVED: RefCell<Vec<Vec<PathBuf>>> = const { RefCell::new(Vec::new()) };
}

/// The batches handed over since the last call.
pub(super) fn take_arrived() -> Vec<Vec<PathBuf>> {
    ARRIVED.take()
}

fn arrive(batch: Vec<PathBuf>, ctx: &egui::Context) {
    if !batch.is_empty() {
        ARRIVED.with_borrow_mut(|arrived| arrived.push(batch));
        ctx.request_repaint();
    }
}

/// Read the files dropped on the page this frame.
pub(super) fn read(dropped: Vec<egui::DroppedFileHandle>, ctx: egui::Context) {
    if dropped.is_empty() {
        return;
    }
    wasm_bindgen_futures::spawn_local(async move {
        let mut batch = Vec::new();
        for file in &dropped {
            let name = file.path().to_string_lossy().into_owned();
            match file.bytes_async().await {
                Ok(bytes) => batch.push(crate::files::hand_over(&name, &bytes)),
                Err(e) => log::error!("{name}: could not be read: {e}"),
            }
        }
        arrive(batch, &ctx);
    });
}

/// Show the browser's file dialog; what is picked arrives as a batch (nothing, where it is
/// cancelled).
pub(super) fn pick(ctx: &egui::Context) {
    let Some(document) = web_sys::window().and_then(|w| w.document()) else { return };
    let Some(input) =
        document.create_element("input").ok().and_then(|e| e.dyn_into::<web_sys::HtmlInputElement>().ok())
    else {
        return;
    };
    input.set_type("file");
    input.set_multiple(true);
    input.set_accept(ACCEPT);
    let ctx = ctx.clone();
    let picked = input.clone();
    let on_change = Closure::once_into_js(move || {
        let Some(list) = picked.files() else { return };
        let files: Vec<web_sys::File> = (0..list.length()).filter_map(|i| list.get(i)).collect();
        wasm_bindgen_futures::spawn_local(async move {
            let mut batch = Vec::new();
            for file in files {
                let name = file.name();
                match wasm_bindgen_futures::JsFuture::from(file.array_buffer()).await {
                    Ok(buffer) => {
                        let bytes = js_sys::Uint8Array::new(&buffer).to_vec();
                        batch.push(crate::files::hand_over(&name, &bytes));
                    }
                    Err(e) => log::error!("{name}: could not be read: {e:?}"),
                }
            }
            arrive(batch, &ctx);
        });
    });
    input.set_onchange(Some(on_change.unchecked_ref()));
    input.click();
}

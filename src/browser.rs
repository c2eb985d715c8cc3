//! What the page needs from its browser beyond the canvas: why it got no WebGPU (the views need
//! it; WebGL2 has no storage buffers or compute shaders), and files handed to the user as
//! downloads (a page has no folder to write to).

/// Why a page runs on WebGL2 instead of WebGPU.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NoWebGpu {
    /// The address asked for it (`?backend=webgl2`).
    Asked,
    /// Plain http away from localhost: browsers give WebGPU to secure pages only.
    Insecure,
    /// No `navigator.gpu`: the browser has no WebGPU, or has it turned off.
    Missing,
    /// `navigator.gpu` is there but gave no adapter (a blocklisted GPU, acceleration off).
    NoAdapter,
}

impl NoWebGpu {
    pub const ALL: [NoWebGpu; 4] =
        [NoWebGpu::Asked, NoWebGpu::Insecure, NoWebGpu::Missing, NoWebGpu::NoAdapter];

    /// The reason from what the page sees: whether its address asked for WebGL2, whether it is
    /// a secure context and whether it has `navigator.gpu`.
    pub fn diagnose(asked_for_webgl2: bool, secure: bool, has_webgpu_api: bool) -> NoWebGpu {
        match (asked_for_webgl2, secure, has_webgpu_api) {
            (true, _, _) => NoWebGpu::Asked,
            (false, false, _) => NoWebGpu::Insecure,
            (false, true, false) => NoWebGpu::Missing,
            (false, true, true) => NoWebGpu::NoAdapter,
        }
    }

    /// The reason, in English (the key of its translation).
    pub fn reason(self) -> &'static str {
        match self {
            NoWebGpu::Asked => "The page asked for WebGL2 (?backend=webgl2).",
            NoWebGpu::Insecure => "WebGPU needs a secure page: https, or http on localhost.",
            NoWebGpu::Missing => "This browser has no WebGPU, or has it turned off.",
            NoWebGpu::NoAdapter => {
                "This browser's WebGPU found no GPU it may use (a GPU on its blocklist, or hardware acceleration off)."
            }
        }
    }

    /// The reason whose English is `text`, if it is one.
    pub fn from_reason(text: &str) -> Option<NoWebGpu> {
        NoWebGpu::ALL.into_iter().find(|why| why.reason() == text)
    }

    /// Its name on the page's `<body data-views>`, for scripts and tests.
    pub fn code(self) -> &'static str {
        match self {
            NoWebGpu::Asked => "webgl2-asked",
            NoWebGpu::Insecure => "webgl2-insecure",
            NoWebGpu::Missing => "webgl2-no-webgpu",
            NoWebGpu::NoAdapter => "webgl2-no-adapter",
        }
    }
}

/// Hand `bytes` to the user as a download named `name` (the browser saves it where it saves
/// downloads, or asks).
#[cfg(target_arch = "wasm32")]
pub fn download(name: &str, mime: &str, bytes: &[u8]) -> Result<(), String> {
    use wasm_bindgen::JsCast;
    let describe = |e: wasm_bindgen::JsValue| format!("{name}: the browser refused the download ({e:?})");
    let document = web_sys::window().and_then(|w| w.document()).ok_or("this page has no document")?;
    let parts = js_sys::Array::of1(&js_sys::Uint8Array::from(bytes));
    let options = web_sys::BlobPropertyBag::new();
    options.set_type(mime);
    let blob = web_sys::Blob::new_with_u8_array_sequence_and_options(&parts, &options).map_err(describe)?;
    let url = web_sys::Url::create_object_url_with_blob(&blob).map_err(describe)?;
    let link = document
        .create_element("a")
        .map_err(describe)?
        .dyn_into::<web_sys::HtmlAnchorElement>()
        .map_err(|_| format!("{name}: no link element to download with"))?;
    link.set_href(&url);
    link.set_download(name);
    link.click();
    // The bytes' address is let go once the download has surely read them (revoked at once,
    // some browsers cancel it).
    let revoke = wasm_bindgen::closure::Closure::once_into_js(move || {
        let _ = web_sys::Url::revoke_object_url(&url);
    });
    let window = web_sys::window().ok_or("this page has no window")?;
    window
        .set_timeout_with_callback_and_timeout_and_arguments_0(revoke.unchecked_ref(), 60_000)
        .map(drop)
        .map_err(describe)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_reason_follows_what_the_page_sees() {
        assert_eq!(NoWebGpu::diagnose(true, true, true), NoWebGpu::Asked);
        assert_eq!(NoWebGpu::diagnose(false, false, true), NoWebGpu::Insecure);
        assert_eq!(NoWebGpu::diagnose(false, true, false), NoWebGpu::Missing);
        assert_eq!(NoWebGpu::diagnose(false, true, true), NoWebGpu::NoAdapter);
        for why in NoWebGpu::ALL {
            assert_eq!(NoWebGpu::from_reason(why.reason()), Some(why));
            assert_ne!(crate::i18n::tr(crate::i18n::Lang::Zh, why.reason()), why.reason(), "{why:?}");
        }
        assert_eq!(NoWebGpu::from_reason("device lost"), None);
    }
}

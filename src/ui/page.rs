//! What the page tells its tests on `<body>`: `data-frames`, the renders that reached the views.

use std::cell::Cell;

thread_local! {
    static PUBLISHED: Cell<Option<u64>> = const { Cell::new(None) };
}

/// Set `data-frames` to `frames` where it changed.
pub(super) fn publish(frames: u64) {
    if PUBLISHED.get() == Some(frames) {
        return;
    }
    let body = web_sys::window().and_then(|w| w.document()).and_then(|d| d.body());
    if let Some(body) = body
        && body.set_attribute("data-frames", &frames.to_string()).is_ok()
    {
        PUBLISHED.set(Some(frames));
    }
}

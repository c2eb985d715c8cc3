//! What the page tells its tests on `<body>`: `data-frames` (the renders that reached the
//! views), and where the student is: `data-lesson`, `data-step` (from 1), `data-lang`,
//! `data-technique` (empty outside a lesson).

use crate::app::AppState;
use std::cell::RefCell;

thread_local! {
    static PUBLISHED: RefCell<Vec<(&'static str, String)>> = const { RefCell::new(Vec::new()) };
}

/// Set each attribute that changed since the last call.
pub(super) fn publish(frames: u64, state: &AppState) {
    let (lesson, step) = match state.current_step() {
        Some((lesson, _, index)) => (lesson.id.clone(), (index + 1).to_string()),
        None => (String::new(), String::new()),
    };
    let now = vec![
        ("data-frames", frames.to_string()),
        ("data-lesson", lesson),
        ("data-step", step),
        ("data-lang", state.lang.code().to_string()),
        ("data-technique", state.scene.shadow.technique.name().to_string()),
    ];
    if PUBLISHED.with_borrow(|published| *published == now) {
        return;
    }
    let Some(body) = web_sys::window().and_then(|w| w.document()).and_then(|d| d.body()) else { return };
    if now.iter().all(|(name, value)| body.set_attribute(name, value).is_ok()) {
        PUBLISHED.set(now);
    }
}

//! The page around the app: the address's link opened at start and kept following where the
//! student goes (`?lesson=pcss&step=3&lang=zh`), and what the page tells its tests on `<body>`:
//! `data-frames` (the renders that reached the views), where the student is (`data-lesson`,
//! `data-step` from 1, `data-lang`, `data-technique`), `data-probe` (the probed pixel, `x,y`,
//! once its values are in), `data-homework` (`checking`, `checked`, `error` or empty) with
//! `data-findings` (the check's finding ids) and `data-homework-light` (the light the check used
//! and every light the student's page made, as the report's JSON has them), and `data-links`
//! (links are followed).

use crate::app::AppState;
use crate::app::link;
use std::cell::RefCell;

thread_local! {
    static PUBLISHED: RefCell<Vec<(&'static str, String)>> = const { RefCell::new(Vec::new()) };
    static ADDRESS: RefCell<String> = const { RefCell::new(String::new()) };
    /// The parts of the address every place keeps (`&backend=...`), as the page was opened.
    static KEPT: String = link::kept_parts(&query());
}

/// The address's query, as the page was opened.
fn query() -> String {
    web_sys::window().and_then(|w| w.location().search().ok()).unwrap_or_default()
}

/// Go where the page's address says (after the saved settings are restored).
pub(super) fn open_link(state: &mut AppState) {
    let query = query();
    if query.trim_start_matches('?').is_empty() {
        return;
    }
    let (wanted, problems) = link::parse(&query);
    state.follow_link(&wanted, problems);
}

/// Keep the address on where the student is (replacing it: the back button leaves the page, as
/// it would a slide's link).
pub(super) fn follow(state: &AppState) {
    let Some(window) = web_sys::window() else { return };
    let now = format!("?{}{}", state.link(), KEPT.with(|kept| kept.clone()));
    if ADDRESS.with_borrow(|address| *address == now) {
        return;
    }
    if let Ok(history) = window.history()
        && history.replace_state_with_url(&wasm_bindgen::JsValue::NULL, "", Some(&now)).is_ok()
    {
        ADDRESS.set(now);
    }
}

/// Set each attribute that changed since the last call.
pub(super) fn publish(frames: u64, state: &AppState) {
    let (lesson, step) = match state.current_step() {
        Some((lesson, _, index)) => (lesson.id.clone(), (index + 1).to_string()),
        None => (String::new(), String::new()),
    };
    let probe = state.probe.as_ref().map_or(String::new(), |p| format!("{},{}", p.pixel[0], p.pixel[1]));
    let (homework, findings, light) = match &state.homework {
        None => (String::new(), String::new(), String::new()),
        Some(hw) if hw.error.is_some() || hw.gpu_error.is_some() => {
            ("error".into(), String::new(), String::new())
        }
        Some(hw) if hw.checked() => {
            let ids: Vec<&str> =
                hw.outcome.iter().flat_map(|o| o.report.findings.iter().map(|f| f.id)).collect();
            let light = hw.outcome.as_ref().map_or(String::new(), |o| {
                serde_json::json!({ "light": o.report.light, "lights": o.report.lights }).to_string()
            });
            ("checked".into(), ids.join(","), light)
        }
        Some(_) => ("checking".into(), String::new(), String::new()),
    };
    let now = vec![
        ("data-frames", frames.to_string()),
        ("data-lesson", lesson),
        ("data-step", step),
        ("data-lang", state.lang.code().to_string()),
        ("data-technique", state.scene.shadow.technique.name().to_string()),
        ("data-probe", probe),
        ("data-homework", homework),
        ("data-findings", findings),
        ("data-homework-light", light),
        ("data-links", "1".into()),
    ];
    if PUBLISHED.with_borrow(|published| *published == now) {
        return;
    }
    let Some(body) = web_sys::window().and_then(|w| w.document()).and_then(|d| d.body()) else { return };
    if now.iter().all(|(name, value)| body.set_attribute(name, value).is_ok()) {
        PUBLISHED.set(now);
    }
}

//! The browser's own engine for a student's page: a dedicated Worker
//! (assets/homework/page/worker.js) runs the same prelude and driver.js as the desktop's engine
//! and posts the record back. The page's scheduler polls: a run is Pending until its Worker
//! answers, and its answer is kept (for the same input, Ready at once).
//!
//! Bounds: the Worker is terminated once the time bound passes, and the message names the file
//! it was running. Memory and stack are the browser's own bounds for a Worker (an endless
//! recursion is a catchable RangeError there as on the desktop).

use std::cell::RefCell;
use std::rc::Rc;
use std::task::Poll;
use std::time::Duration;

use serde::Deserialize;
use wasm_bindgen::JsCast;
use wasm_bindgen::closure::Closure;

use super::ScriptError;
use super::input::Text;

const WORKER_JS: &str = include_str!("../../../assets/homework/page/worker.js");

/// Runs kept: the newest few (a check asks again for the same page each time the view changes).
const KEPT_RUNS: usize = 4;

enum State {
    /// The file the Worker said it runs, and what in it (for the message of a run stopped by
    /// the time bound).
    Running {
        file: String,
        what: String,
    },
    Done(Result<String, ScriptError>),
}

struct Run {
    input_hash: u64,
    state: Rc<RefCell<State>>,
    worker: web_sys::Worker,
    // Kept alive as long as the Worker can call them.
    _on_message: Closure<dyn FnMut(web_sys::MessageEvent)>,
    _on_error: Closure<dyn FnMut(web_sys::ErrorEvent)>,
}

impl Drop for Run {
    fn drop(&mut self) {
        self.worker.terminate();
    }
}

thread_local! {
    static RUNS: RefCell<Vec<Run>> = const { RefCell::new(Vec::new()) };
}

/// What the Worker posts.
#[derive(Deserialize)]
struct Message {
    nonce: String,
    #[serde(default)]
    running: Option<String>,
    #[serde(default)]
    what: Option<String>,
    #[serde(default)]
    output: Option<String>,
    #[serde(default)]
    failed: Option<ScriptErrorJson>,
}

#[derive(Deserialize)]
struct ScriptErrorJson {
    file: String,
    line: usize,
    message: String,
}

/// driver.js's answer for `input`, run with `prelude` in a Worker: Pending until it comes (the
/// Worker is started on the first call). `blame` names the file of a failure that names none.
pub(super) fn poll(
    prelude: &[(&str, Text)],
    input: &str,
    blame: &str,
    time: Duration,
) -> Poll<Result<String, ScriptError>> {
    let input_hash = hash(input);
    RUNS.with(|runs| {
        let mut runs = runs.borrow_mut();
        if let Some(run) = runs.iter().find(|r| r.input_hash == input_hash) {
            return match &*run.state.borrow() {
                State::Running { .. } => Poll::Pending,
                State::Done(answer) => Poll::Ready(answer.clone()),
            };
        }
        match start(prelude, input, input_hash, blame, time) {
            Ok(run) => {
                runs.push(run);
                if runs.len() > KEPT_RUNS {
                    runs.remove(0);
                }
                Poll::Pending
            }
            Err(e) => Poll::Ready(Err(e)),
        }
    })
}

fn hash(text: &str) -> u64 {
    use std::hash::{Hash, Hasher};
    let mut h = std::collections::hash_map::DefaultHasher::new();
    text.hash(&mut h);
    h.finish()
}

fn shadowlab(message: String) -> ScriptError {
    ScriptError { file: "shadowlab".into(), line: 0, message }
}

fn start(
    prelude: &[(&str, Text)],
    input: &str,
    input_hash: u64,
    blame: &str,
    time: Duration,
) -> Result<Run, ScriptError> {
    let refused = |e: wasm_bindgen::JsValue| {
        shadowlab(format!("the browser could not start the page's worker ({})", describe(&e)))
    };
    let options = web_sys::BlobPropertyBag::new();
    options.set_type("text/javascript");
    let parts = js_sys::Array::of1(&wasm_bindgen::JsValue::from_str(WORKER_JS));
    let blob = web_sys::Blob::new_with_str_sequence_and_options(&parts, &options).map_err(refused)?;
    let url = web_sys::Url::create_object_url_with_blob(&blob).map_err(refused)?;
    let worker = web_sys::Worker::new(&url);
    let _ = web_sys::Url::revoke_object_url(&url);
    let worker = worker.map_err(refused)?;

    let nonce = format!("{:016x}{:016x}", random_u64(), input_hash);
    let state = Rc::new(RefCell::new(State::Running { file: blame.to_string(), what: String::new() }));

    let on_message = {
        let (state, nonce, worker) = (state.clone(), nonce.clone(), worker.clone());
        Closure::<dyn FnMut(web_sys::MessageEvent)>::new(move |event: web_sys::MessageEvent| {
            let Some(text) = event.data().as_string() else { return };
            // Only shadowlab's own answers count: a page cannot post one in its place.
            let Ok(message) = serde_json::from_str::<Message>(&text) else { return };
            if message.nonce != nonce || !matches!(*state.borrow(), State::Running { .. }) {
                return;
            }
            let done = if let Some(output) = message.output {
                Ok(output)
            } else if let Some(f) = message.failed {
                Err(ScriptError { file: f.file, line: f.line, message: f.message })
            } else {
                if let Some(file) = message.running {
                    *state.borrow_mut() = State::Running { file, what: message.what.unwrap_or_default() };
                }
                return;
            };
            *state.borrow_mut() = State::Done(done);
            worker.terminate();
        })
    };
    let on_error = {
        let state = state.clone();
        Closure::<dyn FnMut(web_sys::ErrorEvent)>::new(move |event: web_sys::ErrorEvent| {
            let file = match &*state.borrow() {
                State::Running { file, .. } => file.clone(),
                State::Done(_) => return,
            };
            *state.borrow_mut() = State::Done(Err(ScriptError {
                file,
                line: 0,
                message: format!("the page's worker stopped ({})", event.message()),
            }));
        })
    };
    let on_time = {
        let (state, worker) = (state.clone(), worker.clone());
        // Given to the browser's timer for good: it may fire after the run was let go.
        Closure::once_into_js(move || {
            let (file, what) = match &*state.borrow() {
                State::Running { file, what } => (file.clone(), what.clone()),
                State::Done(_) => return,
            };
            worker.terminate();
            let within = if what.is_empty() { String::new() } else { format!(" in {what}") };
            *state.borrow_mut() = State::Done(Err(ScriptError {
                file: if file.is_empty() { "the page".into() } else { file },
                line: 0,
                message: format!(
                    "the script ran past its time bound of {} s{within} (an endless loop?)",
                    time.as_secs_f32()
                ),
            }));
        })
    };
    worker.set_onmessage(Some(on_message.as_ref().unchecked_ref()));
    worker.set_onerror(Some(on_error.as_ref().unchecked_ref()));
    let window = web_sys::window().ok_or_else(|| shadowlab("this page has no window".into()))?;
    window
        .set_timeout_with_callback_and_timeout_and_arguments_0(
            on_time.unchecked_ref(),
            time.as_millis().min(i32::MAX as u128) as i32,
        )
        .map_err(refused)?;

    // Each script as [name, text], or [name, null, url] for a library the page serves (the
    // Worker, started from a Blob, is given the whole address).
    let page = window.location().href().map_err(refused)?;
    let mut scripts = Vec::new();
    for (name, text) in prelude {
        scripts.push(match text {
            Text::Included(text) => serde_json::json!([name, text]),
            Text::Served(path) => {
                let url = web_sys::Url::new_with_base(path, &page).map_err(refused)?.href();
                serde_json::json!([name, null, url])
            }
        });
    }
    let message = serde_json::json!({ "nonce": nonce, "prelude": scripts, "input": input });
    worker.post_message(&wasm_bindgen::JsValue::from_str(&message.to_string())).map_err(refused)?;
    Ok(Run { input_hash, state, worker, _on_message: on_message, _on_error: on_error })
}

fn random_u64() -> u64 {
    let high = (js_sys::Math::random() * 4_294_967_296.0) as u64;
    let low = (js_sys::Math::random() * 4_294_967_296.0) as u64;
    (high << 32) | low
}

fn describe(value: &wasm_bindgen::JsValue) -> String {
    value
        .dyn_ref::<js_sys::Error>()
        .map(|e| String::from(e.message()))
        .or_else(|| value.as_string())
        .unwrap_or_else(|| format!("{value:?}"))
}

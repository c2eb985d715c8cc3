//! The JavaScript engine a student's page runs in on the desktop: QuickJS (through rquickjs), a
//! complete ES2023 engine in one C library. Chosen over boa_engine because it bounds what a hostile
//! script can take (a memory limit the allocator enforces, a wall-clock interrupt, a stack
//! limit), each ending the script with a catchable error rather than the process; it builds in
//! about 25 s here, and loads three.js in about 35 ms.
//!
//! Every failure is one line naming the student's file and line (`engine.js:12: ...`).

use std::sync::{Arc, Mutex};
use std::time::Instant;

use rquickjs::context::EvalOptions;
use rquickjs::{CatchResultExt, CaughtError, Context, Ctx, Runtime};

use super::{Limits, ScriptError};

/// A fresh engine with the page's bounds. Not shared between pages.
pub struct Engine {
    // Declared before `runtime`: a context is dropped before its runtime.
    context: Context,
    _runtime: Runtime,
    deadline: Arc<Mutex<Option<Instant>>>,
    limits: Limits,
}

impl Engine {
    pub fn new(limits: Limits) -> Result<Engine, String> {
        let runtime = Runtime::new().map_err(|e| format!("the JavaScript engine could not start ({e})"))?;
        runtime.set_memory_limit(limits.memory_bytes);
        runtime.set_max_stack_size(limits.stack_bytes);
        let deadline: Arc<Mutex<Option<Instant>>> = Arc::new(Mutex::new(None));
        let shared = Arc::clone(&deadline);
        runtime.set_interrupt_handler(Some(Box::new(move || {
            shared.lock().ok().and_then(|d| *d).is_some_and(|d| Instant::now() > d)
        })));
        let context =
            Context::full(&runtime).map_err(|e| format!("the JavaScript engine could not start ({e})"))?;
        Ok(Engine { context, _runtime: runtime, deadline, limits })
    }

    /// Runs `f` with the time bound armed (and the promise jobs it queued, within the same bound).
    fn bounded<T>(&self, f: impl FnOnce(&Ctx<'_>) -> Result<T, Failure>) -> Result<T, Failure> {
        if let Ok(mut d) = self.deadline.lock() {
            *d = Some(Instant::now() + self.limits.time);
        }
        let out = self.context.with(|ctx| {
            let out = f(&ctx)?;
            while ctx.execute_pending_job() {}
            Ok(out)
        });
        if let Ok(mut d) = self.deadline.lock() {
            *d = None;
        }
        out
    }

    /// Runs a classic script as a page's `<script>` does: its top-level declarations are global.
    pub fn run_script(&self, file: &str, source: &str) -> Result<(), ScriptError> {
        self.bounded(|ctx| {
            let mut options = EvalOptions::default();
            options.global = true;
            options.strict = false;
            options.filename = Some(file.to_string());
            ctx.eval_with_options::<(), _>(source.as_bytes().to_vec(), options)
                .catch(ctx)
                .map_err(Failure::from)
        })
        .map_err(|f| f.into_error(file, &self.limits))
    }

    /// Runs the page: driver.js's `runPage` with this engine as its host (`evalScript` runs a
    /// classic script as global code under its file name), then the promise jobs it queues until
    /// it settles, all within the time bound. Returns what the driver returns.
    pub fn run_page(&self, blame: &str, input: &str) -> Result<String, ScriptError> {
        if let Ok(mut d) = self.deadline.lock() {
            *d = Some(Instant::now() + self.limits.time);
        }
        let out = self.drive_page(input);
        if let Ok(mut d) = self.deadline.lock() {
            *d = None;
        }
        out.map_err(|f| f.into_error(blame, &self.limits))
    }

    fn drive_page(&self, input: &str) -> Result<String, Failure> {
        let started = self.context.with(|ctx| {
            let start = || -> rquickjs::Result<rquickjs::Promise<'_>> {
                let host = rquickjs::Object::new(ctx.clone())?;
                let eval_script = rquickjs::Function::new(
                    ctx.clone(),
                    |ctx: Ctx<'_>, name: String, text: String| -> rquickjs::Result<()> {
                        let mut options = EvalOptions::default();
                        options.global = true;
                        options.strict = false;
                        options.filename = Some(name);
                        ctx.eval_with_options::<(), _>(text.into_bytes(), options)
                    },
                )?;
                host.set("evalScript", eval_script)?;
                host.set("engine", "quickjs")?;
                let started = Instant::now();
                let elapsed_ms =
                    rquickjs::Function::new(ctx.clone(), move || started.elapsed().as_secs_f64() * 1000.0)?;
                host.set("elapsedMs", elapsed_ms)?;
                let record: rquickjs::Object = ctx.globals().get("__shadowlab")?;
                let run_page: rquickjs::Function = record.get("runPage")?;
                run_page.call((host, input.to_string()))
            };
            start().catch(&ctx).map(|p| rquickjs::Persistent::save(&ctx, p)).map_err(Failure::from)
        })?;
        loop {
            let settled = self.context.with(|ctx| {
                let promise =
                    started.clone().restore(&ctx).map_err(|e| Failure::from(CaughtError::Error(e)))?;
                promise.result::<String>().map(|r| r.catch(&ctx).map_err(Failure::from)).transpose()
            })?;
            if let Some(output) = settled {
                return Ok(output);
            }
            match self._runtime.execute_pending_job() {
                Ok(true) => {}
                // A job thrown out of (a bound it hit): the page cannot settle.
                Err(job) => {
                    return Err(job.0.with(|ctx| {
                        Failure::from(CaughtError::from_error(&ctx, rquickjs::Error::Exception))
                    }));
                }
                Ok(false) => {
                    return Err(Failure {
                        message: "the page waits for something that never comes (its scripts never finished)"
                            .into(),
                        stack: String::new(),
                    });
                }
            }
        }
    }
}

/// What a script threw, as text: its message and stack (or the value, for a throw of a non-error).
struct Failure {
    message: String,
    stack: String,
}

impl From<CaughtError<'_>> for Failure {
    fn from(e: CaughtError<'_>) -> Self {
        match e {
            CaughtError::Exception(ex) => {
                Failure { message: ex.message().unwrap_or_default(), stack: ex.stack().unwrap_or_default() }
            }
            CaughtError::Value(v) => {
                let shown = v
                    .as_string()
                    .and_then(|s| s.to_string().ok())
                    .or_else(|| v.as_number().map(|n| n.to_string()))
                    .unwrap_or_else(|| format!("a {}", v.type_name()));
                Failure { message: format!("uncaught {shown}"), stack: String::new() }
            }
            CaughtError::Error(e) => Failure { message: e.to_string(), stack: String::new() },
        }
    }
}

/// Each stack frame's file, line and function (`    at f (engine.js:12:5)`, or
/// `    at engine.js:12:5` with no function).
pub fn frames(stack: &str) -> Vec<Frame> {
    stack
        .lines()
        .filter_map(|frame| {
            let frame = frame.trim().strip_prefix("at ")?.trim_end_matches(')');
            let (function, place) = match frame.rsplit_once(" (") {
                Some((f, p)) => (f.to_string(), p),
                None => (String::new(), frame),
            };
            let mut parts = place.rsplitn(3, ':');
            let (last, middle) = (parts.next()?, parts.next()?);
            // file:line:col, or file:line
            let (file, line) = match parts.next() {
                Some(file) => (file.to_string(), middle.parse().ok()?),
                None => (middle.to_string(), last.parse().ok()?),
            };
            Some(Frame { file, line, function })
        })
        .collect()
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Frame {
    pub file: String,
    pub line: usize,
    /// Empty for a script's top level.
    pub function: String,
}

/// shadowlab's own scripts and the framework's libraries: a frame there is never the student's.
pub fn is_ours(file: &str) -> bool {
    file.starts_with("shadowlab/") || file.starts_with("lib/")
}

impl Failure {
    fn into_error(self, file: &str, limits: &Limits) -> ScriptError {
        let frames = frames(&self.stack);
        let theirs = frames.iter().find(|f| !is_ours(&f.file)).or(frames.first());
        let (file, line) = theirs.map_or((file.to_string(), 0), |f| (f.file.clone(), f.line));
        // QuickJS places an interrupted loop on its function's first line: name the function too.
        let within = theirs
            .filter(|f| !f.function.is_empty() && f.function != "<eval>")
            .map_or(String::new(), |f| format!(" in {}", f.function));
        let message = match self.message.as_str() {
            "interrupted" => format!(
                "the script ran past its time bound of {} s{within} (an endless loop?)",
                limits.time.as_secs_f32()
            ),
            "out of memory" => {
                format!("the script used more than its memory bound of {} MiB", limits.memory_bytes >> 20)
            }
            "Maximum call stack size exceeded" | "stack overflow" => {
                format!("the script recursed deeper than its stack bound{within} (endless recursion?)")
            }
            m => m.split(['\n', '\r']).next().unwrap_or_default().to_string(),
        };
        ScriptError { file, line, message }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_read_both_forms() {
        let stack = "    at f (lights/DirectionalLight.js:12:5)\n    at engine.js:40:3\n    at <eval> (shadowlab/call.js:1:1)\n";
        let read: Vec<(String, usize, String)> =
            frames(stack).into_iter().map(|f| (f.file, f.line, f.function)).collect();
        assert_eq!(
            read,
            vec![
                ("lights/DirectionalLight.js".to_string(), 12, "f".to_string()),
                ("engine.js".to_string(), 40, String::new()),
                ("shadowlab/call.js".to_string(), 1, "<eval>".to_string())
            ]
        );
    }
}

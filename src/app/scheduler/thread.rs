//! The native scheduler: a thread that owns the app's renderers, on a GPU device of its own, so
//! that a slow render never holds up the window (on a software rasteriser each device has its own
//! queue; egui's frames do not wait behind a 300 ms PCSS frame).

use super::renderers::open;
use super::{JobBook, RenderEvent, RenderJob, RenderScheduler, Stage};
use crate::render::GpuWait;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc;
use std::time::Duration;
use web_time::Instant;

pub struct WorkerThread {
    jobs: mpsc::Sender<(u64, RenderJob)>,
    events: mpsc::Receiver<RenderEvent>,
    /// The newest job submitted: the thread cancels anything older.
    latest: Arc<AtomicU64>,
    book: JobBook,
    /// The render thread, joined on drop: the device must be torn down by its thread before the
    /// process exits (a software Vulkan driver torn down under a live thread can crash at exit).
    thread: Option<std::thread::JoinHandle<()>>,
}

impl Drop for WorkerThread {
    fn drop(&mut self) {
        // Everything submitted is stale now (a ground truth stops at its next batch), and a
        // closed queue ends the thread's loop.
        self.latest.store(u64::MAX, Ordering::Release);
        self.jobs = mpsc::channel().0;
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}

impl WorkerThread {
    /// Start the thread on a new device of `adapter`. `wake` is called after every event (the
    /// app asks egui for a repaint there).
    pub fn spawn(adapter: wgpu::Adapter, wake: impl Fn() + Send + 'static) -> Self {
        let (job_tx, job_rx) = mpsc::channel::<(u64, RenderJob)>();
        let (event_tx, event_rx) = mpsc::channel();
        let latest = Arc::new(AtomicU64::new(0));
        let latest_in_thread = latest.clone();
        let spawned = std::thread::Builder::new().name("shadowlab render".into()).spawn(move || {
            lower_priority();
            let mut send = |event| {
                let _ = event_tx.send(event);
                wake();
            };
            let mut renderers = match open(&adapter) {
                Ok(r) => {
                    send(RenderEvent::Ready(Ok(crate::render::describe_adapter(&adapter.get_info()))));
                    r
                }
                Err(e) => {
                    send(RenderEvent::Ready(Err(e.to_string())));
                    return;
                }
            };
            while let Ok(mut next) = job_rx.recv() {
                // Newest request wins.
                while let Ok(newer) = job_rx.try_recv() {
                    next = newer;
                }
                let (id, job) = next;
                let cancelled = || latest_in_thread.load(Ordering::Acquire) > id;
                let (started, mut stage) = (Instant::now(), Stage::Image);
                // A thread may wait: the call after a submission waits for its read-backs.
                while !stage.is_done() {
                    stage =
                        renderers.run_stage(id, &job, stage, started, &mut send, &cancelled, GpuWait::Block);
                }
            }
        });
        let (thread, events) = match spawned {
            Ok(thread) => (Some(thread), event_rx),
            Err(e) => {
                // No thread: report it the way a device failure is reported.
                let (tx, rx) = mpsc::channel();
                let _ = tx.send(RenderEvent::Ready(Err(format!("could not start the render thread: {e}"))));
                (None, rx)
            }
        };
        Self { jobs: job_tx, events, latest, book: JobBook::default(), thread }
    }
}

impl RenderScheduler for WorkerThread {
    fn submit(&mut self, job: RenderJob) -> u64 {
        let id = self.latest.load(Ordering::Acquire) + 1;
        self.latest.store(id, Ordering::Release);
        let _ = self.jobs.send((id, job));
        self.book.submitted(id);
        id
    }

    fn poll(&mut self) -> Vec<RenderEvent> {
        let events: Vec<RenderEvent> = self.events.try_iter().collect();
        self.book.heard(&events);
        events
    }

    fn busy(&self) -> bool {
        self.book.busy()
    }

    fn waiting_for(&self) -> Option<Duration> {
        self.book.waiting_for()
    }
}

/// Renders yield the CPU to the window: on a software rasteriser both compete for the same
/// cores, and a UI frame matters more than a render finishing a few milliseconds sooner. Linux
/// keeps a nice value per thread, and the rasteriser's threads, made when the device is opened
/// from this thread, inherit it.
fn lower_priority() {
    #[cfg(target_os = "linux")]
    // SAFETY: setpriority only changes this thread's scheduling priority (who 0 = the caller).
    unsafe {
        libc::setpriority(libc::PRIO_PROCESS, 0, RENDER_NICE);
    }
}

/// The render threads' nice value (0 is normal, 19 the lowest priority).
#[cfg(target_os = "linux")]
const RENDER_NICE: libc::c_int = 4;

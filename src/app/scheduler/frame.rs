//! The scheduler for a page without threads: the renderers live on the caller's thread and each
//! `poll` (once per UI frame) runs the next stage of the newest job: the image and maps in one
//! frame, the probe and the overlays' analysis in the next, then the ground truths. A newer job
//! replaces the one in progress between stages. Read-backs still wait for the GPU within a stage,
//! and a ground truth is worked out whole in its stage (the web build will need both to resume
//! across frames instead).

use super::renderers::{Renderers, Stage, open};
use super::{JobBook, RenderEvent, RenderJob, RenderScheduler};
use std::time::{Duration, Instant};

pub struct FrameDriven {
    /// None until the device opens (on the first poll), and where it failed.
    renderers: Option<Renderers>,
    adapter: Option<wgpu::Adapter>,
    /// The job in progress: (id, job, the stage to run next, when it started).
    current: Option<(u64, RenderJob, Stage, Instant)>,
    /// Events to hand out on the next poll (the device's readiness).
    pending: Vec<RenderEvent>,
    book: JobBook,
}

impl FrameDriven {
    /// A scheduler that opens a device of `adapter` on its first poll.
    pub fn new(adapter: wgpu::Adapter) -> Self {
        Self {
            renderers: None,
            adapter: Some(adapter),
            current: None,
            pending: Vec::new(),
            book: JobBook::default(),
        }
    }
}

impl RenderScheduler for FrameDriven {
    fn submit(&mut self, job: RenderJob) -> u64 {
        let id = self.book.latest + 1;
        self.book.submitted(id);
        // Newest request wins: whatever stage the last one was at.
        self.current = Some((id, job, Stage::Image, Instant::now()));
        id
    }

    fn poll(&mut self) -> Vec<RenderEvent> {
        let mut events = std::mem::take(&mut self.pending);
        if let Some(adapter) = self.adapter.take() {
            match open(&adapter) {
                Ok(r) => {
                    self.renderers = Some(r);
                    events.push(RenderEvent::Ready(Ok(crate::render::describe_adapter(&adapter.get_info()))));
                }
                Err(e) => events.push(RenderEvent::Ready(Err(e.to_string()))),
            }
        }
        let (Some(renderers), Some((id, job, stage, started))) =
            (self.renderers.as_mut(), self.current.as_mut())
        else {
            self.book.heard(&events);
            return events;
        };
        // Nothing newer can arrive during a stage here: only between polls.
        let next = renderers.run_stage(*id, job, *stage, *started, &mut |e| events.push(e), &|| false);
        *stage = next;
        if next == Stage::Done {
            self.current = None;
        }
        self.book.heard(&events);
        events
    }

    fn busy(&self) -> bool {
        self.book.busy()
    }

    fn waiting_for(&self) -> Option<Duration> {
        self.book.waiting_for()
    }

    fn needs_polling(&self) -> bool {
        self.current.is_some() || self.adapter.is_some() || !self.pending.is_empty()
    }
}

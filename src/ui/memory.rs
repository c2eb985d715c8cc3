//! Handing freed memory back to the system over a long session.
//!
//! A session churns through large buffers: the camera and analysis read-backs and the depth
//! maps (4-48 MB each), made and dropped on every frame and view switch. glibc keeps what is
//! freed inside its arenas for reuse and returns pages only from an arena's top, so a long
//! session would hold memory nothing uses, and a reading of the process's memory could not tell
//! it from a leak. `malloc_trim` returns every arena's free pages. Every 2 s is often enough to
//! keep up with the churn and rare enough that its cost stays out of the UI's frames. (Device
//! memory, the process's own on a software adapter, is kept in check by
//! `render::device_descriptor`.)

use std::cell::Cell;
use std::time::Duration;
use web_time::Instant;

/// How often free pages are handed back at most, while the window is drawing.
const EVERY: Duration = Duration::from_secs(2);

/// How often pages were handed back and what it cost, for the soak's report.
#[derive(Clone, Copy, Debug, Default)]
pub struct TrimStats {
    pub calls: u64,
    pub total_ms: f64,
    pub max_ms: f64,
}

thread_local! {
    static LAST: Cell<Option<Instant>> = const { Cell::new(None) };
    static STATS: Cell<TrimStats> = const { Cell::new(TrimStats { calls: 0, total_ms: 0.0, max_ms: 0.0 }) };
}

/// Hand freed memory back to the system if `EVERY` has passed since the last time (called each
/// UI frame). Nothing to do where the allocator is not glibc's.
pub fn return_free_pages_now_and_then() {
    let now = Instant::now();
    if LAST.get().is_some_and(|last| now.duration_since(last) < EVERY) {
        return;
    }
    LAST.set(Some(now));
    return_free_pages();
}

/// Hand freed memory back to the system now (a memory reading first does, so that it reads what
/// the process holds, not what the allocator kept of what it freed).
pub fn return_free_pages() {
    let now = Instant::now();
    if release() {
        let ms = now.elapsed().as_secs_f64() * 1e3;
        let mut stats = STATS.get();
        stats.calls += 1;
        stats.total_ms += ms;
        stats.max_ms = stats.max_ms.max(ms);
        STATS.set(stats);
    }
}

/// What handing pages back has cost on this (the UI's) thread so far.
pub fn trim_stats() -> TrimStats {
    STATS.get()
}

#[cfg(all(target_os = "linux", target_env = "gnu"))]
fn release() -> bool {
    // SAFETY: malloc_trim only walks glibc's own arenas; 0 keeps no padding at the top.
    unsafe { libc::malloc_trim(0) };
    true
}

#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
fn release() -> bool {
    false
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pages_are_handed_back_at_most_once_in_two_seconds() {
        // A thread of its own: the throttle and the counts are per thread.
        let stats = std::thread::spawn(|| {
            let churn: Vec<Vec<u8>> = (0..8).map(|i| vec![i; 4 << 20]).collect();
            drop(churn);
            return_free_pages_now_and_then();
            return_free_pages_now_and_then();
            trim_stats()
        })
        .join()
        .expect("the test thread ends");
        let expected = u64::from(cfg!(all(target_os = "linux", target_env = "gnu")));
        assert_eq!(stats.calls, expected);
        assert!(stats.max_ms >= 0.0 && stats.total_ms >= stats.max_ms);
    }
}

//! A class run's progress: a bar with the rate (submissions a minute) and the time left on a
//! terminal; elsewhere (logs, CI) one `[n/N] name: status` line per submission, with its time and
//! the rate so far.

use crate::export::class_report::{ClassRow, Status};
use std::io::{IsTerminal, Write};
use std::time::{Duration, Instant};

/// Progress: a bar with the rate on a terminal, one line per submission otherwise.
pub(super) enum Progress {
    Bar(indicatif::ProgressBar),
    Lines { started: Instant },
}

/// A bar's rate, submissions per minute.
fn per_minute(state: &indicatif::ProgressState, w: &mut dyn std::fmt::Write) {
    let _ = write!(w, "{:.1}/min", state.per_sec() * 60.0);
}

impl Progress {
    pub(super) fn new(total: usize) -> Self {
        if !std::io::stderr().is_terminal() {
            return Progress::Lines { started: Instant::now() };
        }
        let bar = indicatif::ProgressBar::new(total as u64);
        let template = "{bar:30.cyan/blue} {pos}/{len} submissions · {rate} · {eta} left · {msg}";
        if let Ok(style) = indicatif::ProgressStyle::with_template(template) {
            bar.set_style(style.progress_chars("█▌ ").with_key("rate", per_minute));
        }
        bar.enable_steady_tick(Duration::from_millis(500));
        Progress::Bar(bar)
    }

    pub(super) fn running(&self, names: &[&str]) {
        if let Progress::Bar(bar) = self {
            bar.set_message(names.join(", "));
        }
    }

    pub(super) fn done(&self, n: usize, total: usize, row: &ClassRow, took: Duration) {
        let mut line = format!("[{n}/{total}] {}: {}", row.name, row.status.label());
        if !row.message.is_empty() {
            line.push_str(&format!(" ({})", row.message));
        }
        match self {
            Progress::Bar(bar) => {
                bar.inc(1);
                if row.status != Status::Checked {
                    bar.println(line);
                }
            }
            Progress::Lines { started } => {
                let rate = 60.0 * n as f64 / started.elapsed().as_secs_f64().max(1e-3);
                let mut err = std::io::stderr().lock();
                let _ = writeln!(err, "{line} in {:.1} s; {rate:.1} per minute", took.as_secs_f64());
                let _ = err.flush();
            }
        }
    }

    pub(super) fn finish(&self) {
        if let Progress::Bar(bar) = self {
            bar.finish_and_clear();
        }
    }
}

//! The soak's memory readings: resident memory sampled every few seconds, each reading the floor
//! of the samples before it, and the trend over a soak's second half that is judged.

use std::collections::VecDeque;
use std::time::{Duration, Instant};

/// Memory is sampled this often, and each reading the soak reports and judges is the least of
/// the samples over the `FLOOR_WINDOW` before it: read-backs and depth maps in flight (4-48 MB
/// each) come and go between samples, what the process holds stays in the floor, and a leak
/// raises it. A single sample swung the 30-second readings by up to 40 MB (10%).
const SAMPLE_EVERY: Duration = Duration::from_secs(2);
const FLOOR_WINDOW: f64 = 30.0;

/// Resident memory of this process, MB (Linux), once freed memory is handed back: what the
/// process holds, whenever within the app's 2 s between two hand-backs it is read.
pub fn rss_mb() -> Option<f64> {
    crate::ui::return_free_pages();
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmRSS:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb / 1024.0)
}

/// The least-squares trend of the 30-second readings (`every_30_s[i]` taken 30 (i + 1) s in)
/// from `from_s` on, as the growth it gives over their span, a share of `early_mb`; None with
/// fewer than three readings.
pub fn second_half_trend(every_30_s: &[f64], from_s: f64, early_mb: Option<f64>) -> Option<f64> {
    let points: Vec<(f64, f64)> = every_30_s
        .iter()
        .enumerate()
        .map(|(i, &mb)| (30.0 * (i + 1) as f64, mb))
        .filter(|&(t, _)| t >= from_s)
        .collect();
    let early = early_mb.filter(|e| *e > 0.0)?;
    if points.len() < 3 {
        return None;
    }
    let n = points.len() as f64;
    let (mt, mm) = points.iter().fold((0.0, 0.0), |(a, b), (t, m)| (a + t / n, b + m / n));
    let (cov, var) =
        points.iter().fold((0.0, 0.0), |(c, v), (t, m)| (c + (t - mt) * (m - mm), v + (t - mt) * (t - mt)));
    let span = points[points.len() - 1].0 - points[0].0;
    Some(cov / var * span / early)
}

/// Memory sampled every `SAMPLE_EVERY` over the last `FLOOR_WINDOW`.
#[derive(Default)]
pub struct MemoryFloor {
    /// (seconds in, MB).
    samples: VecDeque<(f64, f64)>,
    last_sample: Option<Instant>,
}

impl MemoryFloor {
    /// Take a sample where one is due, keeping those of the last `FLOOR_WINDOW`.
    pub fn sample(&mut self, elapsed_s: f64) {
        if self.last_sample.is_some_and(|t| t.elapsed() < SAMPLE_EVERY) {
            return;
        }
        self.last_sample = Some(Instant::now());
        if let Some(mb) = rss_mb() {
            self.samples.push_back((elapsed_s, mb));
        }
        while self.samples.front().is_some_and(|&(t, _)| t < elapsed_s - FLOOR_WINDOW) {
            self.samples.pop_front();
        }
    }

    /// The least memory sampled over the last `FLOOR_WINDOW`, MB.
    pub fn floor_mb(&self) -> Option<f64> {
        self.samples.iter().map(|&(_, mb)| mb).reduce(f64::min)
    }
}

#[cfg(test)]
mod tests {
    use super::second_half_trend;

    #[test]
    fn a_flat_second_half_holds_whatever_its_noise_and_a_steady_rise_is_measured() {
        // Start-up growth before the second half does not count; noise around a flat line does
        // not add up to a trend.
        let flat = [300.0, 330.0, 355.0, 349.0, 367.0, 352.0, 360.0, 351.0, 366.0, 355.0];
        let g = second_half_trend(&flat, 150.0, Some(349.0)).expect("a trend");
        assert!(g.abs() < 0.05, "{g}");
        // 10 MB a minute over 3 minutes of 300 MB: +10%.
        let rising: Vec<f64> = (0..10).map(|i| 300.0 + 5.0 * i as f64).collect();
        let g = second_half_trend(&rising, 120.0, Some(300.0)).expect("a trend");
        assert!((g - 0.1).abs() < 1e-9, "{g}");
        assert_eq!(second_half_trend(&rising[..4], 90.0, Some(300.0)), None);
    }
}

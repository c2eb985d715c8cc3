//! The command line's values: KEY=VALUE, WIDTHxHEIGHT, X,Y, seconds, timeouts and view names,
//! each refused with a message that says what was expected.

use crate::views::View;
use std::time::Duration;

pub(super) fn parse_key_value(s: &str) -> Result<(String, String), String> {
    let (k, v) = s.split_once('=').ok_or_else(|| format!("`{s}` is not KEY=VALUE"))?;
    if k.trim().is_empty() {
        return Err(format!("`{s}` has an empty key"));
    }
    Ok((k.trim().to_string(), v.trim().to_string()))
}

pub(super) fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(|| format!("`{s}` is not WIDTHxHEIGHT"))?;
    let parse = |v: &str| v.trim().parse::<u32>().ok().filter(|&n| (1..=16384).contains(&n));
    match (parse(w), parse(h)) {
        (Some(w), Some(h)) => Ok((w, h)),
        _ => Err(format!("`{s}` is not WIDTHxHEIGHT with sides 1..=16384")),
    }
}

pub(super) fn parse_pixel(s: &str) -> Result<(u32, u32), String> {
    let (x, y) = s.split_once(',').ok_or_else(|| format!("`{s}` is not X,Y"))?;
    match (x.trim().parse(), y.trim().parse()) {
        (Ok(x), Ok(y)) => Ok((x, y)),
        _ => Err(format!("`{s}` is not X,Y with whole non-negative numbers")),
    }
}

/// Longest scene time accepted, seconds (a day: beyond it f32 time loses sub-frame precision).
pub const MAX_TIME_S: f32 = 86_400.0;

pub(super) fn parse_time(s: &str) -> Result<f32, String> {
    match s.parse::<f32>() {
        Ok(t) if t.is_finite() && t.abs() <= MAX_TIME_S => Ok(t),
        _ => Err(format!("`{s}` is not a number of seconds in -{MAX_TIME_S}..={MAX_TIME_S}")),
    }
}

pub(super) fn parse_view(s: &str) -> Result<View, String> {
    View::from_name(s).ok_or_else(|| {
        let names: Vec<_> = View::ALL.iter().map(|v| v.name()).collect();
        format!("unknown view `{s}` (expected one of {})", names.join(", "))
    })
}

/// The longest --timeout (a day).
const MAX_TIMEOUT_S: f64 = 86_400.0;

pub(super) fn parse_timeout(s: &str) -> Result<Duration, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v > 0.0 && v <= MAX_TIMEOUT_S => Ok(Duration::from_secs_f64(v)),
        _ => Err(format!("`{s}` is not a number of seconds above 0 and at most {MAX_TIMEOUT_S}")),
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_homework_checks_default_size_is_the_one_the_app_checks_at() {
        assert_eq!(super::parse_size(crate::homework::CHECK_SIZE_ARG), Ok(crate::homework::CHECK_SIZE));
    }
}

//! Draws of the page's animation whose `uLightMVP` did not follow what moved (driver.js finds
//! them: a draw that matched its light's matrix times its own model matrix on the first frames,
//! and later matches only the light or the object as it was), with where the page computes its
//! light matrices.

use serde::Deserialize;

use super::record::PageDraws;
use crate::homework::light::StaleMatrix;

/// A draw whose uLightMVP did not follow what moved, as the driver found it.
#[derive(Deserialize)]
pub(super) struct StaleJson {
    seconds: f64,
    kind: String,
    light: usize,
    request: Option<usize>,
}

/// A place where the page itself calls CalcLightMVP, and the first and last frame it did (-1:
/// while it loaded).
#[derive(Deserialize)]
pub(super) struct CalcCallJson {
    file: String,
    line: usize,
    /// In shadowlab's copy of a framework file the submission does not bring.
    #[serde(default)]
    framework: bool,
    first: i64,
    last: i64,
}

/// What the driver found, as the report says it.
pub(super) fn stale_matrices(
    stale: &[StaleJson],
    calls: &[CalcCallJson],
    draws: Option<&PageDraws>,
) -> Vec<StaleMatrix> {
    let computed_at: Vec<String> = calls
        .iter()
        .map(|c| {
            let whose = if c.framework { " (the framework's)" } else { "" };
            format!("{}:{}{whose}", c.file, c.line)
        })
        .collect();
    let computed_only_while_loading = !calls.is_empty() && calls.iter().all(|c| c.first < 0 && c.last < 0);
    stale
        .iter()
        .map(|s| StaleMatrix {
            time_s: s.seconds,
            moved: match s.kind.as_str() {
                "light" => "light",
                "object" => "object",
                _ => "none",
            },
            light: s.light,
            object: s.request.and_then(|r| draws?.request_url(r)),
            computed_at: computed_at.clone(),
            computed_only_while_loading,
        })
        .collect()
}

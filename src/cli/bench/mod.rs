//! `shadowlab bench`: the renderer's frame time per technique (`techniques`), the diagrams'
//! drawing time (`diagrams`), and the real app driven through a classroom session (`--app`:
//! `offscreen`, `window`, `soak`, on what `session` holds for the three; built with the
//! `bench-app` feature only).
//!
//! The dependencies run one way: this file picks a bench; each bench uses only `session` (and
//! `diagrams` the median of `techniques`), never another bench.

mod diagrams;
#[cfg(feature = "bench-app")]
mod offscreen;
#[cfg(feature = "bench-app")]
mod session;
#[cfg(feature = "bench-app")]
mod soak;
#[cfg(feature = "bench-app")]
mod soak_memory;
mod techniques;
#[cfg(feature = "bench-app")]
mod window;

use crate::cli::{BenchArgs, CliError};

pub fn run(args: BenchArgs) -> Result<(), CliError> {
    if args.app {
        return app(&args);
    }
    if args.diagrams {
        return diagrams::run(&args);
    }
    techniques::run(args)
}

/// `bench --app`: the soak, or the session offscreen or in the window.
#[cfg(feature = "bench-app")]
fn app(args: &BenchArgs) -> Result<(), CliError> {
    if let Some(seconds) = args.soak {
        return soak::run(args, seconds);
    }
    if !(0.5..=600.0).contains(&args.seconds) {
        return Err(CliError::input(format!("--seconds {} is out of range 0.5..=600", args.seconds)));
    }
    let report = if args.window { window::run(args)? } else { offscreen::run(args)? };
    session::print_report(&report, args.json)
}

/// The shipped binary leaves the app benchmark out (it drives the app through egui_kittest and
/// the test hooks): say how to build one that has it.
#[cfg(not(feature = "bench-app"))]
fn app(_args: &BenchArgs) -> Result<(), CliError> {
    Err(CliError::input(APP_BENCH_MISSING))
}

#[cfg(not(feature = "bench-app"))]
const APP_BENCH_MISSING: &str = "bench --app: this shadowlab was built without the app benchmark; \
    run it from the checkout with `cargo run --release --features bench-app -- bench --app`";

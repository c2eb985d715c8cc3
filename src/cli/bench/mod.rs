//! `shadowlab bench`: the renderer's frame time per technique (`techniques`), the diagrams'
//! drawing time (`diagrams`), and the real app driven through a classroom session (`--app`:
//! `offscreen`, `window`, `soak`, on what `session` holds for the three).
//!
//! The dependencies run one way: this file picks a bench; each bench uses only `session` (and
//! `diagrams` the median of `techniques`), never another bench.

mod diagrams;
mod offscreen;
mod session;
mod soak;
mod techniques;
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

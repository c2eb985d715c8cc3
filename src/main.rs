use clap::Parser;
use shadowlab::cli::{Cli, run};

fn main() {
    let cli = Cli::parse();
    let Some(command) = cli.command else {
        eprintln!(
            "shadowlab: the interactive app is not part of this build yet; use `shadowlab render`, `probe` or `bench` (see --help)"
        );
        std::process::exit(2);
    };
    if let Err(e) = run(command) {
        eprintln!("shadowlab: {}", e.message);
        std::process::exit(e.code);
    }
}

use clap::Parser;
use shadowlab::cli::{Cli, run};

fn main() {
    let cli = Cli::parse();
    let Some(command) = cli.command else {
        // No command: the interactive app.
        if let Err(message) = shadowlab::ui::run() {
            eprintln!("shadowlab: {message}");
            std::process::exit(2);
        }
        return;
    };
    if let Err(e) = run(command) {
        eprintln!("shadowlab: {}", e.message);
        std::process::exit(e.code);
    }
}

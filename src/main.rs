use clap::Parser;
use shadowlab::cli::{Cli, run};

fn main() {
    let cli = Cli::parse();
    let Some(command) = cli.command else {
        // No command: the interactive app, on what the arguments name (checked before a window).
        let open = &cli.open;
        let launched = shadowlab::ui::launch::resolve(
            open.file.as_deref(),
            open.lesson.as_deref(),
            open.step,
            open.lang,
        )
        .and_then(shadowlab::ui::run);
        if let Err(message) = launched {
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

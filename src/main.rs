//! The desktop app and the command line. (The page starts from the library: `src/web.rs`.)

#[cfg(not(target_arch = "wasm32"))]
fn main() {
    use clap::Parser;
    use shadowlab::cli::{Cli, run};

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

#[cfg(target_arch = "wasm32")]
fn main() {}

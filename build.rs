//! Lists the shipped folders (src/built_in/list.rs) and writes the table of their files, each
//! with `include_bytes!`, to `$OUT_DIR/shipped_files.rs` for src/built_in.rs: a lesson, scene,
//! mesh or homework example dropped into its folder is built in without a line of Rust.

use std::fmt::Write as _;
use std::path::Path;

#[path = "src/built_in/list.rs"]
mod list;

fn main() {
    println!("cargo::rerun-if-changed=build.rs");
    println!("cargo::rerun-if-changed=src/built_in/list.rs");
    let root = std::env::var("CARGO_MANIFEST_DIR").unwrap_or_else(|_| ".".into());
    let root = Path::new(&root);
    let mut files: Vec<String> = list::SHIPPED_FILES.iter().map(|f| f.to_string()).collect();
    for f in list::SHIPPED_FILES {
        println!("cargo::rerun-if-changed={f}");
    }
    for dir in list::SHIPPED_DIRS {
        // A folder is scanned for any change, so a file added to it reruns this script.
        println!("cargo::rerun-if-changed={dir}");
        let entries = std::fs::read_dir(root.join(dir)).unwrap_or_else(|e| fail(&format!("{dir}: {e}")));
        for entry in entries {
            let entry = entry.unwrap_or_else(|e| fail(&format!("{dir}: {e}")));
            if !entry.path().is_file() {
                continue; // a shipped folder below is listed on its own
            }
            let Some(name) = entry.file_name().to_str().map(str::to_owned) else {
                let name = entry.file_name().to_string_lossy().into_owned();
                println!("cargo::warning={dir}/{name}: not built in (the name is not UTF-8)");
                continue;
            };
            if list::ships(&name) {
                files.push(format!("{dir}/{name}"));
            }
        }
    }
    // Sorted, so the table (and the hash naming the unpacked copy) is the same on every machine.
    files.sort();
    let mut out = String::from(
        "/// Every shipped file, by its path relative to the checkout, with its bytes (sorted by path).\n\
         pub const FILES: &[(&str, &[u8])] = &[\n",
    );
    for f in &files {
        let _ = writeln!(
            out,
            "    ({f:?}, include_bytes!(concat!(env!(\"CARGO_MANIFEST_DIR\"), \"/\", {f:?}))),"
        );
    }
    out.push_str("];\n");
    let out_dir = std::env::var("OUT_DIR").unwrap_or_else(|_| fail("OUT_DIR is not set"));
    let path = Path::new(&out_dir).join("shipped_files.rs");
    std::fs::write(&path, out).unwrap_or_else(|e| fail(&format!("{}: {e}", path.display())));
}

fn fail(message: &str) -> ! {
    eprintln!("build.rs: {message}");
    std::process::exit(1);
}

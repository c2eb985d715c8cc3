//! Helpers shared by the GPU tests. They need a real adapter (lavapipe on CI) and fail loudly
//! without one: a skipped rendering test would hide a broken renderer.
#![allow(dead_code)]

use shadowlab::render::{FrameRequest, GpuContext, Renderer};
use shadowlab::scene::{Scene, load_scene};
use std::path::{Path, PathBuf};

pub fn repo_path(relative: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(relative)
}

pub fn gpu() -> (GpuContext, Renderer) {
    let ctx = GpuContext::new_headless().unwrap_or_else(|e| {
        panic!("these tests need a GPU adapter; on a machine without a GPU install Mesa's software one (apt-get install mesa-vulkan-drivers): {e}")
    });
    let renderer = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    (ctx, renderer)
}

pub fn scene(name: &str, overrides: &[(&str, &str)]) -> Scene {
    let overrides: Vec<(String, String)> =
        overrides.iter().map(|(k, v)| (k.to_string(), v.to_string())).collect();
    load_scene(&repo_path(&format!("assets/scenes/{name}.toml")), &overrides)
        .unwrap_or_else(|e| panic!("scene {name}: {e}"))
}

pub fn analysis_request(size: (u32, u32), light: usize) -> FrameRequest {
    FrameRequest { size, selected_light: light, final_color: false, analysis: true, ..Default::default() }
}

/// What a `shadowlab` process did.
pub struct Run {
    pub code: Option<i32>,
    pub stdout: String,
    pub stderr: String,
}

impl std::fmt::Display for Run {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "exit code {:?}\n--- stdout\n{}--- stderr\n{}", self.code, self.stdout, self.stderr)
    }
}

/// A private runtime folder for child processes. Without `XDG_RUNTIME_DIR` the Vulkan driver's
/// Wayland client library prints a complaint on stderr while the adapter is set up: the
/// environment's noise, not shadowlab's, and the one-line error checks need a quiet stderr.
pub fn runtime_dir() -> &'static Path {
    static DIR: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
    DIR.get_or_init(|| {
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("shadowlab-runtime-dir");
        std::fs::create_dir_all(&dir).expect("create runtime folder");
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            std::fs::set_permissions(&dir, std::fs::Permissions::from_mode(0o700))
                .expect("chmod runtime folder");
        }
        dir
    })
}

/// The `shadowlab` binary, run from the repository with a quiet runtime folder.
pub fn shadowlab_command() -> std::process::Command {
    let mut command = std::process::Command::new(env!("CARGO_BIN_EXE_shadowlab"));
    command.current_dir(env!("CARGO_MANIFEST_DIR")).env("XDG_RUNTIME_DIR", runtime_dir());
    command
}

/// Run a prepared command to completion.
pub fn run(command: &mut std::process::Command) -> Run {
    let output = command.output().expect("the shadowlab binary runs");
    Run {
        code: output.status.code(),
        stdout: String::from_utf8_lossy(&output.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&output.stderr).into_owned(),
    }
}

/// A virtual X server of this test's own, killed on drop. Xvfb picks a free display itself and
/// says which once it accepts connections (`-displayfd`), so tests never guess a display number
/// or wait on `xvfb-run`'s start-up handshake. One at a time in a test binary, so that two
/// windows never share a server's CPU.
#[allow(dead_code)]
pub struct Xvfb {
    child: std::process::Child,
    /// `:N`, for DISPLAY.
    pub display: String,
    _one_at_a_time: std::sync::MutexGuard<'static, ()>,
}

static X_SERVER: std::sync::Mutex<()> = std::sync::Mutex::new(());

#[allow(dead_code)]
impl Xvfb {
    pub fn start(screen: &str) -> Xvfb {
        use std::io::BufRead;
        // A test that failed while holding it leaves nothing behind to protect.
        let guard = X_SERVER.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
        let mut child = std::process::Command::new("Xvfb")
            .args(["-displayfd", "1", "-nolisten", "tcp", "-screen", "0", screen])
            .stdout(std::process::Stdio::piped())
            .stderr(
                std::fs::File::create(std::env::temp_dir().join(format!("xvfb-{}.log", std::process::id())))
                    .expect("log"),
            )
            .spawn()
            .expect("Xvfb runs (apt-get install xvfb)");
        let mut line = String::new();
        let stdout = child.stdout.take().expect("Xvfb's stdout");
        let mut stdout = std::io::BufReader::new(stdout);
        stdout.read_line(&mut line).expect("Xvfb names its display");
        // Keep reading what else it says (the keymap compiler's warnings, when the first client
        // connects): with the pipe closed, that write would kill the server with SIGPIPE.
        std::thread::spawn(move || std::io::copy(&mut stdout, &mut std::io::sink()));
        let number = line.trim();
        assert!(!number.is_empty() && number.bytes().all(|b| b.is_ascii_digit()), "Xvfb said {line:?}");
        Xvfb { child, display: format!(":{number}"), _one_at_a_time: guard }
    }
}

#[allow(dead_code)]
impl Xvfb {
    /// What became of the server, for a failing test's message.
    pub fn state(&mut self) -> String {
        let log =
            std::fs::read_to_string(std::env::temp_dir().join(format!("xvfb-{}.log", std::process::id())))
                .unwrap_or_default();
        let socket = std::path::Path::new("/tmp/.X11-unix").join(format!("X{}", &self.display[1..]));
        format!(
            "Xvfb {}: {:?}, socket {} exists: {}, log:\n{log}",
            self.display,
            self.child.try_wait(),
            socket.display(),
            socket.exists()
        )
    }
}

impl Drop for Xvfb {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// Run `shadowlab ARGS` in a window on an Xvfb of its own. Now and then (about one run in ten
/// on a loaded machine, not explained yet) a window cannot connect to a server that is up and
/// whose socket is there; that one failure, and only it, is tried again on a fresh server, up to
/// three times, each attempt said on stderr.
#[allow(dead_code)]
pub fn run_in_window(args: &[&str]) -> Run {
    const REFUSED: &str = "Failed to open connection to X server";
    let mut attempt = 1;
    loop {
        let mut xvfb = Xvfb::start("1600x900x24");
        let result =
            run(shadowlab_command().args(args).env("DISPLAY", &xvfb.display).env_remove("WAYLAND_DISPLAY"));
        if !result.stderr.contains(REFUSED) || attempt == 3 {
            return result;
        }
        eprintln!("attempt {attempt}: the window could not connect; {}", xvfb.state());
        attempt += 1;
    }
}

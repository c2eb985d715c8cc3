//! The native Open dialog: the desktop's file chooser through xdg-desktop-portal (rfd), asked
//! for on a thread of its own so the window keeps drawing. Where no portal answers (a bare X
//! server, a container, CI) the app says so and hands the path box the keyboard instead. (A page
//! uses the browser's own dialog: `page_files`.)

use std::path::PathBuf;
use std::sync::mpsc::{Receiver, channel};

/// What came back from the dialog.
pub enum DialogOutcome {
    Picked(PathBuf),
    Cancelled,
    /// No file-chooser service on this desktop.
    Unavailable,
}

/// A dialog on its way; poll it each frame.
pub struct OpenDialog {
    answer: Receiver<DialogOutcome>,
}

const PORTAL: &str = "org.freedesktop.portal.Desktop";

/// Whether a file chooser answers on the session bus: the portal is running, or D-Bus can start
/// it on demand.
pub fn portal_available() -> bool {
    let Ok(connection) = zbus::blocking::Connection::session() else { return false };
    let Ok(bus) = zbus::blocking::fdo::DBusProxy::new(&connection) else { return false };
    let Ok(name) = zbus::names::BusName::try_from(PORTAL) else { return false };
    let running = bus.name_has_owner(name).unwrap_or(false);
    running || bus.list_activatable_names().is_ok_and(|names| names.iter().any(|n| n.as_str() == PORTAL))
}

impl OpenDialog {
    /// Ask for a scene or lesson (.toml), a model (.obj), a homework shader (.glsl) or a zipped
    /// homework (.zip), starting in
    /// `folder`; `wake` is
    /// called when the answer is in.
    pub fn open(folder: PathBuf, wake: impl Fn() + Send + 'static) -> Self {
        let (send, answer) = channel();
        std::thread::spawn(move || {
            let outcome = if !portal_available() {
                DialogOutcome::Unavailable
            } else {
                match rfd::FileDialog::new()
                    .set_title("shadowlab: open a scene, lesson, model or homework shader")
                    .add_filter(
                        "scene or lesson (.toml), model (.obj), homework (.glsl, .zip)",
                        &["toml", "obj", "glsl", "frag", "fs", "zip"],
                    )
                    .set_directory(folder)
                    .pick_file()
                {
                    Some(path) => DialogOutcome::Picked(path),
                    None => DialogOutcome::Cancelled,
                }
            };
            let _ = send.send(outcome);
            wake();
        });
        Self { answer }
    }

    /// The answer, once there is one (a dialog thread that died counts as cancelled).
    pub fn poll(&self) -> Option<DialogOutcome> {
        match self.answer.try_recv() {
            Ok(outcome) => Some(outcome),
            Err(std::sync::mpsc::TryRecvError::Empty) => None,
            Err(std::sync::mpsc::TryRecvError::Disconnected) => Some(DialogOutcome::Cancelled),
        }
    }
}

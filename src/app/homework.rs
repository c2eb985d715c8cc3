//! A student's homework open in the app: what they hand in (a shader, their homework folder or
//! a .zip of it), its files watched (an edit in their editor reloads it), the last program that
//! compiled with the light scripts read beside it (its picture stays while a newer edit does not
//! compile), the current error on the student's own line, and the last check's outcome.

use super::{AppError, AppState, Source};
use crate::homework::{CheckOutcome, HomeworkError, HomeworkProgram, HomeworkSource, ShaderSource};
use crate::scene::load_scene;
use crate::shipped_path;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::SystemTime;

/// The scene a homework is checked on in the app (as on the command line).
pub const HOMEWORK_SCENE: &str = "assets/scenes/homework_check.toml";

/// What the camera view shows while a homework is open.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum HomeworkPicture {
    /// The student's picture, as their shader drew it.
    #[default]
    Student,
    /// The same over a map cleared to white instead of the framework's 0s.
    WhiteMap,
    /// shadowlab's own technique at the same settings.
    Shadowlab,
    /// The student's visibility alone (white = lit).
    Visibility,
    /// The ground truth's visibility.
    GroundTruth,
    /// Student minus ground truth: red where the student's is darker, blue where lighter.
    Difference,
}

impl HomeworkPicture {
    pub const ALL: [HomeworkPicture; 6] = [
        HomeworkPicture::Student,
        HomeworkPicture::WhiteMap,
        HomeworkPicture::Shadowlab,
        HomeworkPicture::Visibility,
        HomeworkPicture::GroundTruth,
        HomeworkPicture::Difference,
    ];

    /// The label (English; the i18n table has the Chinese).
    pub fn label(self) -> &'static str {
        match self {
            HomeworkPicture::Student => "your shader",
            HomeworkPicture::WhiteMap => "your shader, map cleared to white",
            HomeworkPicture::Shadowlab => "shadowlab's",
            HomeworkPicture::Visibility => "your visibility",
            HomeworkPicture::GroundTruth => "ground truth",
            HomeworkPicture::Difference => "difference",
        }
    }
}

/// A homework open in the app.
pub struct HomeworkState {
    /// What was opened: the student's phongFragment.glsl, their homework folder or a .zip of it;
    /// and a shadowFragment / phongVertex given beside it, in place of what was found.
    pub path: PathBuf,
    pub shadow_fragment: Option<PathBuf>,
    pub vertex: Option<PathBuf>,
    /// The submission as last read with `program`: its name, where each file came from, and its
    /// light scripts (DirectionalLight.js, engine.js), which build the light the check draws with.
    pub source: Option<Arc<HomeworkSource>>,
    /// Each file's modification time when last read (None: could not be read).
    modified: Vec<Option<SystemTime>>,
    /// The last program that compiled; a newer edit that does not keeps it on screen.
    pub program: Option<Arc<HomeworkProgram>>,
    /// Bumped each time `program` changes (the renderer rebuilds its pipelines for a new one).
    pub generation: u64,
    /// Why the files as they are now do not compile (the student's file and line).
    pub error: Option<HomeworkError>,
    /// Why the check of the program that compiled failed on the GPU (a pipeline wgpu refused).
    pub gpu_error: Option<String>,
    /// The last check of `program`: pictures, figures and findings.
    pub outcome: Option<Arc<CheckOutcome>>,
    /// The generation `outcome` was worked out for.
    pub outcome_generation: u64,
    /// Which of the page's lights the check is of (None: the first), and which `outcome` is of.
    pub page_light: Option<crate::homework::student_light::PageLight>,
    pub outcome_light: Option<crate::homework::student_light::PageLight>,
    pub picture: HomeworkPicture,
    /// Times the files were read again after a change on disk.
    pub reloads: u64,
}

fn modified(path: &Path) -> Option<SystemTime> {
    std::fs::metadata(path).and_then(|m| m.modified()).ok()
}

impl HomeworkState {
    /// Read and translate the student's files. A shader that does not compile still opens (with
    /// its error shown), so the student can fix it and see it reload.
    pub fn open(path: &Path, shadow_fragment: Option<&Path>, vertex: Option<&Path>) -> Self {
        let mut state = Self {
            path: path.to_path_buf(),
            shadow_fragment: shadow_fragment.map(Path::to_path_buf),
            vertex: vertex.map(Path::to_path_buf),
            source: None,
            modified: Vec::new(),
            program: None,
            generation: 0,
            error: None,
            gpu_error: None,
            outcome: None,
            outcome_generation: 0,
            page_light: None,
            outcome_light: None,
            picture: HomeworkPicture::default(),
            reloads: 0,
        };
        state.read();
        state
    }

    /// What is watched: what was opened (a zip as a whole), every file found in a folder, and
    /// the files given beside it.
    fn paths(&self) -> Vec<PathBuf> {
        let mut paths = vec![self.path.clone()];
        let found = self.source.iter().flat_map(|s| s.paths()).map(Path::to_path_buf);
        for path in found.chain(self.shadow_fragment.clone()).chain(self.vertex.clone()) {
            if !paths.contains(&path) {
                paths.push(path);
            }
        }
        paths
    }

    fn read(&mut self) {
        let read = HomeworkSource::read(&self.path).and_then(|mut source| {
            if let Some(path) = &self.shadow_fragment {
                source.files.shadow_fragment = ShaderSource::read(path)?;
            }
            if let Some(path) = &self.vertex {
                source.files.phong_vertex = ShaderSource::read(path)?;
            }
            let program = HomeworkProgram::translate(source.files.clone())?;
            Ok((source, program))
        });
        match read {
            Ok((source, program)) => {
                self.source = Some(Arc::new(source));
                self.program = Some(Arc::new(program));
                self.generation += 1;
                self.error = None;
            }
            Err(e) => self.error = Some(e),
        }
        self.modified = self.paths().iter().map(|p| modified(p)).collect();
    }

    /// Read the files again where one changed on disk since the last read; true where it did.
    pub fn reload_if_changed(&mut self) -> bool {
        let now: Vec<Option<SystemTime>> = self.paths().iter().map(|p| modified(p)).collect();
        if now == self.modified {
            return false;
        }
        self.reloads += 1;
        self.read();
        true
    }

    /// The name errors and the panel show: the submission's (its folder's or zip's, or the
    /// shader's file name).
    pub fn name(&self) -> String {
        match &self.source {
            Some(source) => source.name.clone(),
            None => self
                .path
                .file_name()
                .map_or_else(|| self.path.display().to_string(), |n| n.to_string_lossy().into()),
        }
    }

    /// A check of the current program is on screen.
    pub fn checked(&self) -> bool {
        self.outcome.is_some()
            && self.outcome_generation == self.generation
            && self.outcome_light == self.page_light
    }
}

/// What the student's functions returned at one pixel, beside shadowlab's side.
#[derive(Clone, Debug, PartialEq)]
pub struct HomeworkProbe {
    pub pixel: (u32, u32),
    /// The student's shader ran here (a surface is under the pixel).
    pub covered: bool,
    /// What each of `RECORDED_FUNCTIONS` returned last here; None where it did not run.
    pub returned: [Option<f32>; 4],
    /// The visibility `main` used, and which function gave it.
    pub visibility: Option<(f32, &'static str)>,
    pub shadowlab: f32,
    pub ground_truth: f32,
    /// The penumbra's width here, world units: the student's and the ground truth's (where
    /// the ground truth has an edge at the probe).
    pub penumbra_widths: Option<(f32, f32)>,
}

impl HomeworkState {
    /// The check's values at the probe (`at`, as the views place it), once a check is in.
    pub fn probe(&self, at: super::ProbeAt) -> Option<HomeworkProbe> {
        let outcome = self.outcome.as_ref()?;
        let images = &outcome.student;
        let (fx, fy) = match at {
            super::ProbeAt::View(fx, fy) => (fx, fy),
            super::ProbeAt::LessonFrame(x, y) => {
                let (w, h) = crate::lessons::PROBE_FRAME;
                ((x as f32 + 0.5) / w as f32, (y as f32 + 0.5) / h as f32)
            }
        };
        let x = ((fx * images.width as f32) as u32).min(images.width.checked_sub(1)?);
        let y = ((fy * images.height as f32) as u32).min(images.height.checked_sub(1)?);
        let i = (y * images.width + x) as usize;
        let ran = images.calls[i][0];
        let returned = std::array::from_fn(|k| (ran & (1 << k) != 0).then_some(images.returned[i][k]));
        let function = images.calls[i][1] as usize;
        let visibility =
            images.visibility(i).map(|v| (v, crate::homework::RECORDED_FUNCTIONS[function.clamp(1, 3) - 1]));
        Some(HomeworkProbe {
            pixel: (x, y),
            covered: images.covered(i),
            returned,
            visibility,
            shadowlab: outcome.shadowlab_visibility[i],
            ground_truth: outcome.ground_truth[i],
            penumbra_widths: outcome.penumbra_widths((x, y)),
        })
    }
}

/// A path that names a homework as a student hands it in: a folder or a `.zip`.
pub fn is_submission(path: &Path) -> bool {
    crate::homework::is_zip(path) || (crate::files::exists(path) && !crate::files::is_file(path))
}

/// A path that names a homework shader (`.glsl`, `.frag`, `.fs`).
pub fn is_shader_file(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| ["glsl", "frag", "fs"].contains(&e.to_ascii_lowercase().as_str()))
}

impl AppState {
    /// Open a student's homework on the homework scene: their `phongFragment.glsl`, their
    /// homework folder or a .zip of it (checked with the light their DirectionalLight.js builds).
    /// The camera view shows their picture, the homework panel what the check found. A shader
    /// that does not compile opens too, with its error, and shows once it does.
    pub fn open_homework(&mut self, path: &Path) {
        self.open_homework_with(path, None);
    }

    /// `open_homework` with the student's light-pass shader (`shadowFragment.glsl`) too.
    pub fn open_homework_with(&mut self, path: &Path, shadow_fragment: Option<&Path>) {
        if !crate::files::exists(path) {
            let detail = format!("{}: no such file or folder", path.display());
            self.error = Some(AppError::new("could not open the homework", detail));
            return;
        }
        // A folder or zip with no homework in it is refused here, the last state kept; a folder of
        // several students' homeworks is a class.
        if is_submission(path)
            && let Err(e) = HomeworkSource::read(path)
        {
            if shadow_fragment.is_none() && super::class::is_class(path) {
                return self.open_class(path);
            }
            self.error = Some(AppError::new("could not open the homework", e.to_string()));
            return;
        }
        let scene_path = shipped_path(HOMEWORK_SCENE);
        if self.source != Source::Scene(scene_path.clone()) || self.homework.is_none() {
            match load_scene(&scene_path, &[]) {
                Ok(scene) => {
                    self.set_fresh_scene(scene, Source::Scene(scene_path));
                    self.ab = None;
                }
                Err(e) => {
                    self.error = Some(AppError::new("could not open the scene", e));
                    return;
                }
            }
        }
        // Whatever was offered at the start, the student chose their shader.
        self.show_lesson_list = false;
        let state = HomeworkState::open(path, shadow_fragment, None);
        self.status = format!("{} {}", crate::i18n::tr(self.lang, "opened"), path.display());
        self.settings.remember_file(path);
        self.homework = Some(state);
        self.error = None;
        self.mark_dirty();
    }

    /// Read the homework's files again where one changed on disk (the student saved in their
    /// editor); camera, probe and view stay. True where they were read again.
    pub fn reload_homework_if_changed(&mut self) -> bool {
        let changed = self.homework.as_mut().is_some_and(HomeworkState::reload_if_changed);
        if changed {
            self.mark_dirty();
        }
        changed
    }
}

//! What `shadowlab [FILE] [--lesson ID [--step N]] [--lang zh]` opens in the app. It is worked
//! out and checked before any window opens, so a bad argument is one line and exit 2, as in the
//! rest of the command line.

use crate::i18n::Lang;
use crate::lessons::{self, Lesson};
use std::path::{Path, PathBuf};

/// What the app shows first.
#[derive(Clone, Debug)]
pub enum Opening {
    /// A scene file (TOML).
    Scene(PathBuf),
    /// A model (OBJ), set on a floor under a light.
    Model(PathBuf),
    /// A lesson (shipped, or a lesson file of one's own) at a step, from 0.
    Lesson { lesson: Box<Lesson>, step: usize },
    /// A student's homework shader (`phongFragment.glsl`), checked on the homework scene.
    Homework(PathBuf),
}

/// The command line's wishes for the app; `None`s keep what was saved from the last session.
#[derive(Clone, Debug, Default)]
pub struct Launch {
    pub opening: Option<Opening>,
    pub lang: Option<Lang>,
}

/// Work out what to open: `file` (a scene or lesson `.toml`, an `.obj`, or a shipped lesson's
/// id or number), or `lesson` (id or number) at `step` (from 1). Each file is loaded here once,
/// so its errors (named, with the line) come before the window.
pub fn resolve(
    file: Option<&str>,
    lesson: Option<&str>,
    step: Option<u32>,
    lang: Option<Lang>,
) -> Result<Launch, String> {
    let opening = match (file, lesson) {
        (Some(_), Some(_)) => return Err("give a file or `--lesson`, not both".into()),
        (None, Some(id)) => Some(shipped_lesson(id, step)?),
        (Some(file), None) => Some(open_file(file, step)?),
        (None, None) if step.is_some() => return Err("`--step` needs a lesson (`--lesson ID`)".into()),
        (None, None) => None,
    };
    Ok(Launch { opening, lang })
}

fn shipped_lesson(id: &str, step: Option<u32>) -> Result<Opening, String> {
    let all = lessons::load_all(&lessons::default_dir()).map_err(|e| e.to_string())?;
    let lesson = lessons::find(&all, id).map_err(|e| e.to_string())?;
    at_step(lesson.clone(), step)
}

fn at_step(lesson: Lesson, step: Option<u32>) -> Result<Opening, String> {
    let n = lesson.steps.len();
    let step = step.unwrap_or(1) as usize;
    if !(1..=n).contains(&step) {
        return Err(format!("lesson `{}` has steps 1 to {n}, not {step}", lesson.id));
    }
    Ok(Opening::Lesson { lesson: Box::new(lesson), step: step - 1 })
}

fn open_file(file: &str, step: Option<u32>) -> Result<Opening, String> {
    let path = Path::new(file);
    if !crate::files::exists(path) {
        // Not a file: a shipped lesson's id or number, or a typo worth naming.
        let all = lessons::load_all(&lessons::default_dir()).map_err(|e| e.to_string())?;
        return match lessons::find(&all, file) {
            Ok(lesson) => at_step(lesson.clone(), step),
            Err(_) => {
                let ids: Vec<&str> = all.iter().map(|l| l.id.as_str()).collect();
                Err(format!("{file}: no such file, and no lesson has that id (lessons: {})", ids.join(", ")))
            }
        };
    }
    let extension = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    let not_lesson = |step: Option<u32>| match step {
        Some(_) => Err(format!("{file}: `--step` needs a lesson, and this is not one")),
        None => Ok(()),
    };
    match extension.as_deref() {
        _ if super::homework::is_shader_file(path) => {
            not_lesson(step)?;
            crate::files::check_regular_file(path).map_err(|e| format!("{file}: {e}"))?;
            Ok(Opening::Homework(path.to_path_buf()))
        }
        // A homework folder or a .zip of one, as the student hands it in; or a class of them.
        _ if super::homework::is_submission(path) => {
            not_lesson(step)?;
            if let Err(e) = crate::homework::HomeworkSource::read(path)
                && !super::class::is_class(path)
            {
                return Err(e.to_string());
            }
            Ok(Opening::Homework(path.to_path_buf()))
        }
        Some("obj") => {
            not_lesson(step)?;
            super::scene_for_obj(path)?;
            Ok(Opening::Model(path.to_path_buf()))
        }
        Some("toml") if is_lesson_file(path) => {
            let lesson = lessons::load_lesson(path).map_err(|e| e.to_string())?;
            at_step(lesson, step)
        }
        Some("toml") => {
            not_lesson(step)?;
            crate::scene::load_scene(path, &[]).map_err(|e| e.to_string())?;
            Ok(Opening::Scene(path.to_path_buf()))
        }
        _ => Err(format!(
            "{file}: not a scene or lesson (.toml), a model (.obj), a homework shader (.glsl), folder or .zip"
        )),
    }
}

/// A lesson file has `[[step]]` tables; a scene file has none (unreadable files are left to the
/// scene loader, which names the problem).
pub fn is_lesson_file(path: &Path) -> bool {
    crate::files::read_input_text(path, crate::files::MAX_TEXT_FILE_BYTES)
        .ok()
        .and_then(|text| text.parse::<toml::Table>().ok())
        .is_some_and(|table| table.contains_key("step"))
}

impl super::AppState {
    /// Open files dropped or picked together: the one `main_file` picks; where that is a
    /// homework shader, with a light pass's shader given beside it.
    pub fn open_files(&mut self, paths: &[PathBuf]) {
        let Some(main) = main_file(paths) else { return };
        let light_pass = paths.iter().find(|p| **p != main && is_light_pass_shader(p));
        if crate::files::exists(&main)
            && super::homework::is_shader_file(&main)
            && !is_light_pass_shader(&main)
        {
            self.open_homework_with(&main, light_pass.map(PathBuf::as_path));
        } else {
            self.open_any(&main);
        }
    }

    /// Open what the path box, a drop or the dialog names: a scene or lesson (.toml), a model
    /// (.obj), or a shipped lesson's id. A bad path keeps what is shown and says why.
    pub fn open_any(&mut self, path: &Path) {
        // Scenes and models through `open` (loaded once, the old scene kept if this one fails);
        // lesson files and lesson ids as the command line takes them.
        if crate::files::exists(path)
            && (super::homework::is_shader_file(path) || super::homework::is_submission(path))
        {
            return self.open_homework(path);
        }
        if crate::files::exists(path) && !is_lesson_file(path) {
            return self.open(path);
        }
        match resolve(Some(&path.to_string_lossy()), None, None, None) {
            Ok(launch) => self.apply_launch(launch),
            Err(e) => self.error = Some(super::AppError::new("could not open the scene", e)),
        }
    }

    /// Show what the command line asked for (after the saved settings are restored).
    pub fn apply_launch(&mut self, launch: Launch) {
        if let Some(lang) = launch.lang {
            self.lang = lang;
            self.settings.lang = lang;
        }
        match launch.opening {
            None => {}
            Some(Opening::Scene(path) | Opening::Model(path)) => {
                self.open(&path);
                self.show_lesson_list = false;
            }
            Some(Opening::Homework(path)) => {
                self.open_homework(&path);
                self.show_lesson_list = false;
            }
            Some(Opening::Lesson { lesson, step }) => {
                // A lesson file of one's own joins the list (in place of a shipped one of its id).
                let index = match self.lessons.iter().position(|l| l.id == lesson.id) {
                    Some(i) if self.lessons[i].path == lesson.path => i,
                    Some(i) => {
                        self.lessons[i] = *lesson;
                        i
                    }
                    None => {
                        self.lessons.push(*lesson);
                        self.lessons.len() - 1
                    }
                };
                self.go_to_step(index, step);
                self.show_lesson_list = false;
            }
        }
    }
}

/// A light pass's shader by its name (`shadowFragment.glsl`), as the framework names it.
fn is_light_pass_shader(path: &Path) -> bool {
    let name = path.file_name().map(|n| n.to_string_lossy().to_ascii_lowercase()).unwrap_or_default();
    super::homework::is_shader_file(path) && name.starts_with("shadow")
}

/// Of several files dropped or picked at once, the one to open: a homework folder or zip, a
/// homework shader (the camera pass's, `phongFragment`, before a light pass's), a scene or
/// lesson, a model; else the last.
/// The others (a model's material and textures) are found by the one opened.
pub fn main_file(paths: &[PathBuf]) -> Option<PathBuf> {
    let extension = |p: &PathBuf| p.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    let rank = |p: &PathBuf| match extension(p).as_deref() {
        _ if super::homework::is_submission(p) => 0,
        _ if super::homework::is_shader_file(p) => usize::from(is_light_pass_shader(p)),
        Some("toml") => 2,
        Some("obj") => 3,
        _ => 4,
    };
    paths.iter().enumerate().min_by_key(|(i, p)| (rank(p), usize::MAX - i)).map(|(_, p)| p.clone())
}

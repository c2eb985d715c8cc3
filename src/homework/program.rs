//! A student's homework as the framework runs it: two programs (the light pass writing packed
//! depth, the camera pass shading with the student's `phongFragment.glsl`), each stage rewritten
//! and translated. What the student does not hand over is the framework's own shader.

use super::{HomeworkError, Interface, Stage, Translated, translate};
use std::path::{Path, PathBuf};

/// The framework's shaders, for the stages a student does not hand over: the template's vertex
/// shaders and the light pass's `pack` into four 8-bit channels.
pub const FRAMEWORK_PHONG_VERTEX: &str = include_str!("../../assets/homework/framework/phongVertex.glsl");
pub const FRAMEWORK_SHADOW_VERTEX: &str = include_str!("../../assets/homework/framework/shadowVertex.glsl");
pub const FRAMEWORK_SHADOW_FRAGMENT: &str =
    include_str!("../../assets/homework/framework/shadowFragment.glsl");

/// One shader's text and where it came from (a file, or the framework's own).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ShaderSource {
    /// The name errors use: the file's name, or `framework/NAME` for the framework's own.
    pub name: String,
    pub path: Option<PathBuf>,
    pub text: String,
}

impl ShaderSource {
    pub fn framework(name: &str, text: &str) -> Self {
        Self { name: format!("framework/{name}"), path: None, text: text.to_string() }
    }

    /// A shader file, read whole; a file that cannot be read is an error naming it.
    pub fn read(path: &Path) -> Result<Self, HomeworkError> {
        let name =
            path.file_name().map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into());
        let bytes = crate::files::read(path).map_err(|e| HomeworkError::Shader {
            file: path.display().to_string(),
            line: None,
            message: format!("cannot read it: {e}"),
        })?;
        let text = String::from_utf8(bytes).map_err(|e| HomeworkError::Shader {
            file: name.clone(),
            line: None,
            message: format!("not UTF-8 text (byte {})", e.utf8_error().valid_up_to()),
        })?;
        Ok(Self { name, path: Some(path.to_path_buf()), text })
    }
}

/// The files a student hands over: the camera pass's fragment shader always, the others where
/// they changed the framework's.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct HomeworkFiles {
    pub phong_fragment: ShaderSource,
    pub phong_vertex: ShaderSource,
    pub shadow_vertex: ShaderSource,
    pub shadow_fragment: ShaderSource,
}

impl HomeworkFiles {
    /// The student's `phongFragment.glsl` with the framework's other three shaders.
    pub fn with_framework(phong_fragment: ShaderSource) -> Self {
        Self {
            phong_fragment,
            phong_vertex: ShaderSource::framework("phongVertex.glsl", FRAMEWORK_PHONG_VERTEX),
            shadow_vertex: ShaderSource::framework("shadowVertex.glsl", FRAMEWORK_SHADOW_VERTEX),
            shadow_fragment: ShaderSource::framework("shadowFragment.glsl", FRAMEWORK_SHADOW_FRAGMENT),
        }
    }

    /// Read the files: `fragment` and, where given, the student's own vertex and light-pass
    /// fragment shaders.
    pub fn read(
        fragment: &Path,
        vertex: Option<&Path>,
        shadow_fragment: Option<&Path>,
    ) -> Result<Self, HomeworkError> {
        let mut files = Self::with_framework(ShaderSource::read(fragment)?);
        if let Some(path) = vertex {
            files.phong_vertex = ShaderSource::read(path)?;
        }
        if let Some(path) = shadow_fragment {
            files.shadow_fragment = ShaderSource::read(path)?;
        }
        Ok(files)
    }
}

/// A vertex and a fragment stage translated against one interface.
#[derive(Clone, Debug)]
pub struct TranslatedProgram {
    pub vertex: Translated,
    pub fragment: Translated,
    pub interface: Interface,
}

impl TranslatedProgram {
    fn new(vertex: &ShaderSource, fragment: &ShaderSource) -> Result<Self, HomeworkError> {
        // Each alone first, so that an error names the file it is in; then both, where a
        // declaration the two disagree on is the fragment stage's to fix.
        Interface::gather(&[&vertex.text]).map_err(|e| e.in_file(&vertex.name))?;
        Interface::gather(&[&fragment.text]).map_err(|e| e.in_file(&fragment.name))?;
        let interface =
            Interface::gather(&[&vertex.text, &fragment.text]).map_err(|e| e.in_file(&fragment.name))?;
        let vertex_stage = translate(&vertex.name, &vertex.text, Stage::Vertex, &interface)?;
        let fragment_stage = translate(&fragment.name, &fragment.text, Stage::Fragment, &interface)?;
        Ok(Self { vertex: vertex_stage, fragment: fragment_stage, interface })
    }
}

/// Both of a homework's programs, ready for the GPU.
#[derive(Clone, Debug)]
pub struct HomeworkProgram {
    pub files: HomeworkFiles,
    /// The light pass: shadowVertex + shadowFragment (packed depth).
    pub light: TranslatedProgram,
    /// The camera pass: phongVertex + the student's phongFragment.
    pub camera: TranslatedProgram,
}

impl HomeworkProgram {
    /// Rewrite and translate all four stages; the first error is the one reported.
    pub fn translate(files: HomeworkFiles) -> Result<Self, HomeworkError> {
        let camera = TranslatedProgram::new(&files.phong_vertex, &files.phong_fragment)?;
        let light = TranslatedProgram::new(&files.shadow_vertex, &files.shadow_fragment)?;
        Ok(Self { files, light, camera })
    }

    /// Which of the student's functions the fragment stage records.
    pub fn recorded(&self) -> &[&'static str] {
        &self.camera.fragment.rewritten.recorded
    }
}

/// A homework as a student hands it over: its shaders (the framework's where it has none), the
/// scripts its light comes from, and notes on how its files were found.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct HomeworkSource {
    /// The submission's name (its folder's or zip's, or the shader's file name).
    pub name: String,
    pub files: HomeworkFiles,
    /// `lights/DirectionalLight.js` and `engine.js`, where the submission has them.
    pub light_script: Option<ShaderSource>,
    pub engine: Option<ShaderSource>,
    /// The rest of the student's page (scripts, shaders, index.html), named by their path in the
    /// submission; empty for a lone shader.
    pub page: Vec<ShaderSource>,
    pub notes: Vec<String>,
}

impl HomeworkSource {
    /// A `phongFragment.glsl` alone (the rest the framework's), a student's homework folder, or a
    /// `.zip` of one; an error on one line naming the file and the problem.
    pub fn read(path: &Path) -> Result<Self, HomeworkError> {
        let limits = super::submission::Limits::default();
        let refused = |e: super::submission::SubmissionError| HomeworkError::Shader {
            file: e.path,
            line: None,
            message: e.message,
        };
        if is_zip(path) && crate::files::is_handed_over(path) {
            // A page's drop: the zip's bytes, not a path on a disk.
            let bytes = crate::files::read(path).map_err(|e| HomeworkError::Shader {
                file: path.display().to_string(),
                line: None,
                message: format!("cannot read it: {e}"),
            })?;
            let name = path.file_name().map_or_else(String::new, |n| n.to_string_lossy().into_owned());
            let submission = super::submission::read_zip_bytes(&name, &bytes, limits).map_err(refused)?;
            return Ok(Self::from_submission(submission, None, path));
        }
        if crate::files::is_file(path) && !is_zip(path) {
            // A shader alone, whatever its extension (as the app and the command line took it).
            let files = HomeworkFiles::with_framework(ShaderSource::read(path)?);
            let name = files.phong_fragment.name.clone();
            return Ok(Self {
                name,
                files,
                light_script: None,
                engine: None,
                page: Vec::new(),
                notes: Vec::new(),
            });
        }
        let submission = super::submission::read_path(path, limits).map_err(refused)?;
        let folder = (!crate::files::is_file(path)).then_some(path);
        Ok(Self::from_submission(submission, folder, path))
    }

    /// The files a submission was found to have; `folder` is where a folder submission's files lie
    /// on the disk (for watching them), `path` what was handed over.
    pub fn from_submission(
        submission: super::submission::Submission,
        folder: Option<&Path>,
        path: &Path,
    ) -> Self {
        let lone_file = folder.is_none() && !is_zip(path);
        let source = |found: super::submission::FoundFile| {
            let file_path = match folder {
                Some(dir) => Some(dir.join(&found.path)),
                None if lone_file => Some(path.to_path_buf()),
                None => None,
            };
            // A lone shader is named by its file name, as before; a submission's files by their
            // path in it (a class has many `phongFragment.glsl`).
            let name = if lone_file {
                path.file_name().map_or_else(|| found.path.clone(), |n| n.to_string_lossy().into_owned())
            } else {
                found.path.clone()
            };
            ShaderSource { name, path: file_path, text: found.text }
        };
        let found = submission.files;
        let mut files = HomeworkFiles::with_framework(source(found.phong_fragment));
        if let Some(f) = found.phong_vertex {
            files.phong_vertex = source(f);
        }
        if let Some(f) = found.shadow_vertex {
            files.shadow_vertex = source(f);
        }
        if let Some(f) = found.shadow_fragment {
            files.shadow_fragment = source(f);
        }
        Self {
            name: submission.name,
            files,
            light_script: found.light_script.map(source),
            engine: found.engine.map(source),
            page: found.page.into_iter().map(source).collect(),
            notes: submission.notes,
        }
    }

    /// Where the source's files lie on the disk (what the app watches).
    pub fn paths(&self) -> Vec<&Path> {
        let f = &self.files;
        [&f.phong_fragment, &f.phong_vertex, &f.shadow_vertex, &f.shadow_fragment]
            .into_iter()
            .chain(self.light_script.as_ref())
            .chain(self.engine.as_ref())
            .filter_map(|s| s.path.as_deref())
            .collect()
    }
}

/// A path that names a zip archive.
pub fn is_zip(path: &Path) -> bool {
    path.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("zip"))
}

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

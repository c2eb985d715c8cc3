//! Writing output files atomically (see [`crate::files`]), and the lesson slides `shadowlab export` writes:
//! the pictures of a step (`step`), the slide itself (`slide`, drawn on the diagrams' canvas),
//! the index page (`html`) and the loop over the lessons that writes them all (`lessons`); and
//! the class report of a class's homework checks (`class_report`).

pub mod class_report;
pub mod html;
pub mod lessons;
pub mod slide;
pub mod step;

use std::path::Path;

#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    #[error("{path}: {reason}")]
    Write { path: String, reason: String },
    #[error("{path}: {reason}")]
    Encode { path: String, reason: String },
    #[error("{path}: cannot create the folder: {reason}")]
    Folder { path: String, reason: String },
    #[error("{0}")]
    Draw(String),
    #[error(transparent)]
    Render(#[from] crate::render::RenderError),
}

/// Write `bytes` to `path` atomically.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), ExportError> {
    crate::files::write_atomic(path, bytes)
        .map_err(|reason| ExportError::Write { path: path.display().to_string(), reason })
}

/// Encode an RGBA8 image as PNG in memory.
pub fn encode_png(image: &image::RgbaImage, path_for_errors: &Path) -> Result<Vec<u8>, ExportError> {
    let mut bytes = Vec::new();
    image::DynamicImage::ImageRgba8(image.clone())
        .write_to(&mut std::io::Cursor::new(&mut bytes), image::ImageFormat::Png)
        .map_err(|e| ExportError::Encode {
            path: path_for_errors.display().to_string(),
            reason: e.to_string(),
        })?;
    Ok(bytes)
}

/// Encode and write a PNG atomically.
pub fn write_png(path: &Path, image: &image::RgbaImage) -> Result<(), ExportError> {
    write_atomic(path, &encode_png(image, path)?)
}

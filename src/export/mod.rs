//! Writing files: atomically (temporary file in the same folder, then rename), so a failure
//! never leaves a half-written output behind. And the lesson slides `shadowlab export` writes:
//! the pictures of a step (`step`), the slide itself (`slide`, drawn on the diagrams' canvas)
//! and the index page (`html`).

pub mod html;
pub mod slide;
pub mod step;

use std::path::Path;

#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    #[error("{path}: {reason}")]
    Write { path: String, reason: String },
    #[error("{path}: {reason}")]
    Encode { path: String, reason: String },
}

/// Write `bytes` to `path` atomically.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), ExportError> {
    let err = |reason: String| ExportError::Write { path: path.display().to_string(), reason };
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    if !dir.is_dir() {
        return Err(err(format!("folder {} does not exist", dir.display())));
    }
    let name = path.file_name().ok_or_else(|| err("not a file name".into()))?;
    let tmp = dir.join(format!(".{}.tmp-{}", name.to_string_lossy(), std::process::id()));
    let result = std::fs::write(&tmp, bytes).and_then(|_| std::fs::rename(&tmp, path));
    if let Err(e) = result {
        let _ = std::fs::remove_file(&tmp);
        return Err(err(e.to_string()));
    }
    Ok(())
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

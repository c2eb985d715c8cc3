//! Triangle meshes: the vertex layout shared with the shaders and Wavefront OBJ/MTL loading
//! (the built-in primitives are src/scene/primitives.rs).
//!
//! Conventions: right-handed, +Y up, counter-clockwise front faces seen from
//! outside, and texture coordinates with the origin at the top-left of the
//! image (the wgpu / `image` row order).

use std::cell::RefCell;
use std::collections::HashMap;
use std::io::Cursor;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::Vec3;

use crate::files::{OneLine, path_line};

/// One vertex as uploaded to the GPU: 32 bytes, position at offset 0, normal
/// at 12, uv at 24.
///
/// Keep in sync with the vertex inputs in `shaders/camera.wgsl` (locations 0,
/// 1 and 2, in this order) and with the vertex buffer layout built from it.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct Vertex {
    pub position: [f32; 3],
    pub normal: [f32; 3],
    pub uv: [f32; 2],
}

const _: () = assert!(std::mem::size_of::<Vertex>() == 32);

/// A decoded texture: `width * height * 4` bytes, rows top to bottom,
/// sRGB-encoded RGBA8 exactly as stored in the file (upload it as an sRGB
/// format so sampling returns linear values).
#[derive(Clone, Debug)]
pub struct TextureImage {
    pub path: PathBuf,
    pub width: u32,
    pub height: u32,
    pub rgba8: Vec<u8>,
}

/// A surface material.
#[derive(Clone, Debug)]
pub struct Material {
    pub name: String,
    /// Linear RGB, each channel in 0..=1.
    pub diffuse: Vec3,
    /// Multiplied with `diffuse` when present.
    pub diffuse_texture: Option<Arc<TextureImage>>,
}

/// A range of `Mesh::indices` drawn with one material.
#[derive(Clone, Debug)]
pub struct MeshPart {
    pub name: String,
    pub index_start: u32,
    pub index_count: u32,
    /// Index into `Mesh::materials`.
    pub material: Option<usize>,
}

/// An indexed triangle list in object space.
#[derive(Clone, Debug)]
pub struct Mesh {
    pub name: String,
    pub vertices: Vec<Vertex>,
    pub indices: Vec<u32>,
    pub parts: Vec<MeshPart>,
    pub materials: Vec<Material>,
}

/// Why a mesh file could not be loaded. Each message is one line that starts
/// with the file concerned.
#[derive(Debug, thiserror::Error)]
pub enum MeshError {
    /// The OBJ file or one of its material libraries could not be read.
    #[error("{}: cannot read file: {}", path_line(path), OneLine(reason))]
    Read { path: PathBuf, reason: String },
    /// A malformed line, an index out of range or a non-finite position.
    #[error("{}: {}", path_line(path), OneLine(reason))]
    Invalid { path: PathBuf, reason: String },
    /// `path` is the MTL file naming the texture.
    #[error(
        "{}: texture `{}` not found (looked for {})",
        path_line(path),
        OneLine(name),
        path_line(resolved)
    )]
    TextureNotFound { path: PathBuf, name: String, resolved: PathBuf },
    /// `path` is the MTL file naming the texture.
    #[error(
        "{}: cannot load texture `{}` ({}): {}",
        path_line(path),
        OneLine(name),
        path_line(resolved),
        OneLine(reason)
    )]
    Texture { path: PathBuf, name: String, resolved: PathBuf, reason: String },
    #[error("{}: contains no triangles", path_line(path))]
    NoTriangles { path: PathBuf },
}

impl Mesh {
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// Object-space (min, max) over all vertices; zero for an empty mesh.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        let mut points = self.vertices.iter().map(|v| Vec3::from(v.position));
        let Some(first) = points.next() else {
            return (Vec3::ZERO, Vec3::ZERO);
        };
        points.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p)))
    }
}

/// Loads a Wavefront OBJ file and its MTL material libraries.
///
/// - Polygons are triangulated (fan); points and lines are ignored. The
///   file's winding is kept (OBJ front faces are counter-clockwise).
/// - All objects and groups are concatenated into one mesh with one part per
///   object (or per material within an object), named after it.
/// - `mtllib` paths are relative to the OBJ file's folder; a missing or
///   unreadable material library is an error, not silently ignored.
/// - Diffuse colour is `Kd` (0.8 grey if absent). `map_Kd` is resolved
///   relative to the MTL file's folder and decoded to RGBA8; a missing or
///   undecodable texture, or one wider or taller than [`MAX_TEXTURE_SIDE`], is an error
///   naming the MTL file and the texture path.
/// - Objects without normals get smooth, area-weighted normals; vertices
///   without texture coordinates get uv = (0, 0). OBJ texture coordinates
///   have v pointing up, so v is flipped to the top-left origin used here.
pub fn load_obj(path: &Path) -> Result<Mesh, MeshError> {
    let text = read_text(path)?;
    let dir = path.parent().unwrap_or_else(|| Path::new(""));
    // Each loaded library and its material count, in load order (tobj appends).
    let libraries: RefCell<Vec<(PathBuf, usize)>> = RefCell::default();
    let mtl_error: RefCell<Option<MeshError>> = RefCell::default();
    let load_mtl = |name: &Path| -> tobj::MTLLoadResult {
        let mtl_path = dir.join(name);
        // After an error nothing more is read; a library named again adds nothing new (its
        // materials are known by name already). Read again, thousands of `mtllib` lines naming
        // a large file took minutes.
        if mtl_error.borrow().is_some() {
            return Err(tobj::LoadError::OpenFileFailed);
        }
        if libraries.borrow().iter().any(|(loaded, _)| *loaded == mtl_path) {
            return Ok((Vec::new(), Default::default()));
        }
        let loaded = read_text(&mtl_path).and_then(|text| {
            check_mtl_colours(&text).map_err(|reason| invalid(&mtl_path, reason))?;
            guarded(|| tobj::load_mtl_buf(&mut Cursor::new(text.as_bytes())))
                .map_err(|reason| invalid(&mtl_path, reason))
        });
        match loaded {
            Ok((materials, names)) => {
                libraries.borrow_mut().push((mtl_path, materials.len()));
                Ok((materials, names))
            }
            Err(error) => {
                mtl_error.borrow_mut().get_or_insert(error);
                Err(tobj::LoadError::OpenFileFailed)
            }
        }
    };
    // Triangulated, one index per vertex, points and lines ignored.
    let mut reader = Cursor::new(text.as_bytes());
    let (models, tobj_materials) =
        guarded(|| tobj::load_obj_buf(&mut reader, &tobj::GPU_LOAD_OPTIONS, load_mtl))
            .map_err(|reason| invalid(path, reason))?;
    if let Some(error) = mtl_error.into_inner() {
        return Err(error);
    }

    let mut textures = HashMap::new();
    let owners =
        (libraries.into_inner().into_iter()).flat_map(|(lib, count)| std::iter::repeat_n(lib, count));
    let materials = (tobj_materials.unwrap_or_default().into_iter().zip(owners))
        .map(|(m, lib)| convert_material(m, &lib, &mut textures))
        .collect::<Result<Vec<_>, _>>()?;
    let name = path.file_stem().unwrap_or_default().to_string_lossy().into_owned();
    let mut mesh = Mesh { name, vertices: Vec::new(), indices: Vec::new(), parts: Vec::new(), materials };
    for model in models.into_iter().filter(|m| !m.mesh.indices.is_empty()) {
        append_model(&mut mesh, model).map_err(|reason| invalid(path, reason))?;
    }
    if mesh.indices.is_empty() {
        return Err(MeshError::NoTriangles { path: path.to_owned() });
    }
    Ok(mesh)
}

fn invalid(path: &Path, reason: String) -> MeshError {
    let path = path.to_owned();
    MeshError::Invalid { path, reason }
}

/// Appends one tobj model as a new part, validating it.
fn append_model(mesh: &mut Mesh, model: tobj::Model) -> Result<(), String> {
    let (m, name) = (&model.mesh, model.name);
    let count = m.positions.len() / 3;
    let first = mesh.vertices.len();
    let (Ok(base), Ok(_), Ok(index_start), Ok(index_count)) = (
        u32::try_from(first),
        u32::try_from(first + count),
        u32::try_from(mesh.indices.len()),
        u32::try_from(m.indices.len()),
    ) else {
        return Err("too many vertices for 32-bit indices".to_owned());
    };
    if m.indices.len() % 3 != 0 || m.indices.iter().any(|&i| i as usize >= count) {
        return Err(format!("object `{name}` has an index out of range"));
    }
    // Attributes present on only some vertices are ignored as a whole.
    let normals = (m.normals.len() == count * 3).then_some(&m.normals);
    let uvs = (m.texcoords.len() == count * 2).then_some(&m.texcoords);
    let mut needs_normals = normals.is_none();
    for (i, p) in m.positions.chunks_exact(3).enumerate() {
        let position = Vec3::from_slice(p);
        if !position.is_finite() {
            return Err(format!("object `{name}` has a non-finite vertex position"));
        }
        let normal =
            normals.map_or(Vec3::ZERO, |n| Vec3::from_slice(&n[i * 3..i * 3 + 3]).normalize_or_zero());
        needs_normals |= normal == Vec3::ZERO;
        let uv = uvs
            .map(|t| [t[i * 2], 1.0 - t[i * 2 + 1]])
            .filter(|uv| uv.iter().all(|x| x.is_finite()))
            .unwrap_or_default();
        let (position, normal) = (position.into(), normal.into());
        mesh.vertices.push(Vertex { position, normal, uv });
    }
    if needs_normals {
        smooth_normals(&mut mesh.vertices[first..], &m.indices);
    }
    mesh.indices.extend(m.indices.iter().map(|&i| base + i));
    let material = m.material_id.filter(|&i| i < mesh.materials.len());
    mesh.parts.push(MeshPart { name, index_start, index_count, material });
    Ok(())
}

/// Reads a text file; bytes that are not UTF-8 are replaced, not rejected.
fn read_text(path: &Path) -> Result<String, MeshError> {
    let bytes = crate::files::read_input(path, crate::files::MAX_MESH_FILE_BYTES)
        .map_err(|reason| MeshError::Read { path: path.to_owned(), reason })?;
    Ok(String::from_utf8(bytes).unwrap_or_else(|e| String::from_utf8_lossy(e.as_bytes()).into_owned()))
}

/// tobj panics on a colour of fewer than three numbers (`Kd 1`): name the line instead.
fn check_mtl_colours(text: &str) -> Result<(), String> {
    for (i, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        if let Some(key @ ("Ka" | "Kd" | "Ks" | "Ke")) = words.next()
            && words.count() < 3
        {
            return Err(format!("line {}: `{key}` needs three numbers (red, green, blue)", i + 1));
        }
    }
    Ok(())
}

/// Runs a tobj parser, turning its error or a panic on malformed input into a
/// message.
fn guarded<T>(parse: impl FnOnce() -> Result<T, tobj::LoadError>) -> Result<T, String> {
    match catch_unwind(AssertUnwindSafe(parse)) {
        Ok(result) => result.map_err(|e| e.to_string()),
        Err(_) => Err("malformed line rejected by the parser".to_owned()),
    }
}

/// Sets smooth normals: the sum of the (area-weighted) normals of the
/// triangles around each position, so split vertices still match.
fn smooth_normals(vertices: &mut [Vertex], indices: &[u32]) {
    let key = |v: &Vertex| v.position.map(|x| (x + 0.0).to_bits());
    let mut sums: HashMap<[u32; 3], Vec3> = HashMap::new();
    for tri in indices.chunks_exact(3) {
        let [a, b, c] = [tri[0], tri[1], tri[2]].map(|i| vertices[i as usize]);
        let [pa, pb, pc] = [a, b, c].map(|v| Vec3::from(v.position));
        let n = (pb - pa).cross(pc - pa);
        for v in [a, b, c] {
            *sums.entry(key(&v)).or_default() += n;
        }
    }
    for v in vertices {
        let sum = sums.get(&key(v)).copied().unwrap_or_default();
        v.normal = sum.normalize_or(Vec3::Y).into();
    }
}

fn convert_material(
    m: tobj::Material,
    mtl_path: &Path,
    textures: &mut HashMap<PathBuf, Arc<TextureImage>>,
) -> Result<Material, MeshError> {
    let diffuse = m
        .diffuse
        .map(Vec3::from)
        .filter(|c| c.is_finite())
        .map_or(Vec3::splat(0.8), |c| c.clamp(Vec3::ZERO, Vec3::ONE));
    let diffuse_texture = match m.diffuse_texture.as_deref() {
        Some(spec) => Some(load_texture(mtl_path, spec, textures)?),
        None => None,
    };
    Ok(Material { name: m.name, diffuse, diffuse_texture })
}

/// The widest texture accepted: WebGPU's guaranteed 2D texture size, so a texture that loads
/// uploads on every adapter.
pub const MAX_TEXTURE_SIDE: u32 = 8192;

fn load_texture(
    mtl_path: &Path,
    spec: &str,
    cache: &mut HashMap<PathBuf, Arc<TextureImage>>,
) -> Result<Arc<TextureImage>, MeshError> {
    let name = texture_file_name(spec);
    let dir = mtl_path.parent().unwrap_or_else(|| Path::new(""));
    let joined = dir.join(name.replace('\\', "/"));
    let resolved = std::path::absolute(&joined).unwrap_or(joined);
    if let Some(texture) = cache.get(&resolved) {
        return Ok(texture.clone());
    }
    let (path, name) = (mtl_path.to_owned(), name.to_owned());
    if !crate::files::exists(&resolved) {
        return Err(MeshError::TextureNotFound { path, name, resolved });
    }
    // A folder, a device or a FIFO (whose open would block) is refused before it is opened.
    if let Err(reason) = crate::files::check_regular_file(&resolved) {
        return Err(MeshError::Texture { path, name, resolved, reason });
    }
    let reader = || {
        crate::files::open_input(&resolved)
            .and_then(|input| {
                // The format the name says, unless the bytes say otherwise.
                let mut reader = image::ImageReader::new(input);
                if let Ok(format) = image::ImageFormat::from_path(&resolved) {
                    reader.set_format(format);
                }
                reader.with_guessed_format()
            })
            .map_err(|e| e.to_string())
    };
    // The size first, from the header: a texture no GPU can hold is refused before it is decoded.
    let decoded = reader()
        .and_then(|reader| reader.into_dimensions().map_err(|e| e.to_string()))
        .and_then(|(width, height)| {
            if width.max(height) > MAX_TEXTURE_SIDE {
                Err(format!("{width}x{height} texels; at most {MAX_TEXTURE_SIDE} on a side"))
            } else {
                reader()
            }
        })
        .and_then(|reader| reader.decode().map_err(|e| e.to_string()));
    let image = match decoded {
        Ok(image) => image.into_rgba8(),
        Err(reason) => {
            let reason = reason.replace('\n', " ");
            return Err(MeshError::Texture { path, name, resolved, reason });
        }
    };
    let texture = Arc::new(TextureImage {
        path: resolved.clone(),
        width: image.width(),
        height: image.height(),
        rgba8: image.into_raw(),
    });
    cache.insert(resolved, texture.clone());
    Ok(texture)
}

/// The file name in a `map_Kd` value, after any options such as `-s 1 1 1`.
fn texture_file_name(spec: &str) -> &str {
    fn split(s: &str) -> (&str, &str) {
        s.split_once(char::is_whitespace).map_or((s, ""), |(word, rest)| (word, rest.trim_start()))
    }
    let mut rest = spec.trim();
    while rest.starts_with('-') {
        let (option, tail) = split(rest);
        rest = tail;
        let numeric_args = match option {
            "-o" | "-s" | "-t" => 3,
            "-mm" => 2,
            "-bm" | "-boost" | "-texres" => 1,
            _ => {
                // -blendu on, -clamp off, -imfchan r, -type sphere, ...
                rest = split(rest).1;
                continue;
            }
        };
        for _ in 0..numeric_args {
            let (word, tail) = split(rest);
            if word.parse::<f32>().is_err() {
                break;
            }
            rest = tail;
        }
    }
    rest
}

#[cfg(test)]
#[path = "mesh_tests.rs"]
mod tests;

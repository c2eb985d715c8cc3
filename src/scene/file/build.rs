//! From a parsed scene file to a `Scene`: every value checked against its range (with the key
//! and, where it can be found, the line named), the meshes resolved and loaded once.

use super::*;
use crate::scene::parameters::{self, MAX_COORDINATE, Parameter};
use crate::scene::primitives::{PRIMITIVES, primitive};

/// A problem found while building, before we know whether the file or an override caused it.
pub(super) enum BuildError {
    Invalid(String),
    Mesh(MeshError),
}

impl BuildError {
    /// The error of a file: at the line of the key it names where `text` (the file) is given.
    pub(super) fn with_path(self, label: &str, text: Option<&str>) -> SceneError {
        match self {
            BuildError::Invalid(message) => match text.and_then(|text| key_line(text, &message)) {
                Some(line) => SceneError::Parse { path: label.into(), line, message },
                None => SceneError::Invalid { path: label.into(), message },
            },
            BuildError::Mesh(e) => SceneError::Mesh(e),
        }
    }
    pub(super) fn with_override(self, key: &str) -> SceneError {
        match self {
            BuildError::Invalid(message) => SceneError::Override { key: key.into(), message },
            BuildError::Mesh(e) => SceneError::Mesh(e),
        }
    }
}

/// The line of the key a build error names first (in backticks: `camera.far`, `light.0.near`,
/// `object.2.scale`, or a bare `[shadow]` key): the key's own line, or where the file leaves it
/// out, the line of its `[[light]]` or `[[object]]`.
fn key_line(text: &str, message: &str) -> Option<usize> {
    use toml::de::{DeTable, DeValue};
    let key = message.split('`').nth(1)?;
    let parts: Vec<&str> = key.split('.').collect();
    let path: Vec<&str> = match parts[0] {
        "camera" | "light" | "object" | "ambient" => parts,
        _ => std::iter::once("shadow").chain(parts).collect(),
    };
    let doc = DeTable::parse(text).ok()?;
    let mut table = doc.get_ref();
    let mut line = None;
    let mut rest = &path[..];
    while let Some((name, tail)) = rest.split_first() {
        let Some((k, v)) = table.iter().find(|(k, _)| k.get_ref() == name) else { break };
        line = Some(line_of(text, k.span().start));
        rest = tail;
        match (v.get_ref(), rest.split_first()) {
            (DeValue::Table(inner), Some(_)) => table = inner,
            (DeValue::Array(items), Some((index, tail))) => {
                let Some(item) = index.parse::<usize>().ok().and_then(|i| items.get(i)) else { break };
                line = Some(line_of(text, item.span().start));
                let DeValue::Table(inner) = item.get_ref() else { break };
                table = inner;
                rest = tail;
            }
            _ => break,
        }
    }
    line
}

/// Largest and smallest scale factor on an axis: a unit mesh scaled past 1e6 outgrows
/// `MAX_COORDINATE`; one scaled below 1e-6 is far smaller than a shadow-map texel of any scene.
const SCALE_RANGE: (f32, f32) = (1e-6, 1e6);

/// Farthest any point of an object may reach from the origin, world units: the longest `far`,
/// so an object always fits in a frustum.
const MAX_REACH: f32 = 1e7;

/// Brightest colour component of a light or of the ambient light (linear). With `intensity` up
/// to 1e4, their product stays far from f32's overflow in the shaders' sums.
const MAX_COLOR: f32 = 1e4;

fn vec3(name: &str, v: [f32; 3]) -> Result<Vec3, BuildError> {
    if v.iter().all(|c| c.is_finite()) {
        Ok(Vec3::from(v))
    } else {
        Err(BuildError::Invalid(format!("`{name}` must be finite numbers, got {v:?}")))
    }
}

/// A position: finite and within `MAX_COORDINATE` of the origin on each axis.
fn coordinates(name: &str, v: [f32; 3]) -> Result<Vec3, BuildError> {
    let p = vec3(name, v)?;
    if p.abs().max_element() > MAX_COORDINATE {
        return Err(BuildError::Invalid(format!(
            "`{name}` = {v:?} is more than {MAX_COORDINATE:e} world units from the origin"
        )));
    }
    Ok(p)
}

/// A colour: finite, each component in 0..=`MAX_COLOR`.
fn rgb(name: &str, v: [f32; 3]) -> Result<Vec3, BuildError> {
    let c = vec3(name, v)?;
    if c.min_element() < 0.0 {
        return Err(BuildError::Invalid(format!("`{name}` must not be negative, got {v:?}")));
    }
    if c.max_element() > MAX_COLOR {
        return Err(BuildError::Invalid(format!("`{name}` = {v:?} is brighter than {MAX_COLOR:e}")));
    }
    Ok(c)
}

/// A frustum's far plane: beyond its near plane (by `factor`) and at most `hi`.
fn far_plane(
    name: &str,
    far: f32,
    near_name: &str,
    near: f32,
    factor: f32,
    hi: f32,
) -> Result<f32, BuildError> {
    parameters::far_plane(name, far, near_name, near, factor, hi).map_err(BuildError::Invalid)
}

fn ranged(name: &str, v: f32, lo: f32, hi: f32) -> Result<f32, BuildError> {
    parameters::in_range(name, v, lo, hi).map_err(BuildError::Invalid)
}

/// `v`, the value of `key`, if `row` of the parameters' table accepts it.
fn real(row: &Parameter, key: &str, v: f32) -> Result<f32, BuildError> {
    row.check_real(key, v).map_err(BuildError::Invalid)
}

pub(super) fn build_scene(
    file: SceneFile,
    base_dir: &Path,
    cache: &mut HashMap<PathBuf, Arc<Mesh>>,
) -> Result<Scene, BuildError> {
    let c = &file.camera;
    let projection = match c.projection {
        ProjectionName::Perspective => Projection::Perspective {
            fov_deg: real(&parameters::CAMERA_FOV, "camera.fov_deg", c.fov_deg.unwrap_or(45.0))?,
        },
        ProjectionName::Orthographic => Projection::Orthographic {
            height_world: ranged("camera.height", c.height.unwrap_or(10.0), 1e-4, 1e6)?,
        },
    };
    let near = ranged("camera.near", c.near, 1e-5, 1e6)?;
    let camera = Camera {
        projection,
        position: coordinates("camera.position", c.position)?,
        target: coordinates("camera.target", c.target)?,
        up: vec3("camera.up", c.up)?,
        near,
        far: far_plane("camera.far", c.far, "camera.near", near, 1.0001, 1e7)?,
    };
    if camera.up.length() < 1e-6 {
        return Err(BuildError::Invalid("`camera.up` must not be zero".into()));
    }
    if (camera.target - camera.position).length() < 1e-6 {
        return Err(BuildError::Invalid("`camera.target` coincides with `camera.position`".into()));
    }

    let mut objects = Vec::with_capacity(file.objects.len());
    for (i, o) in file.objects.into_iter().enumerate() {
        let key = format!("object.{i}");
        let mesh = resolve_mesh(&format!("{key}.mesh"), &o.mesh, base_dir, cache)?;
        let scale = match o.scale {
            None => Vec3::ONE,
            Some(ScaleFile::Uniform(s)) => Vec3::splat(s),
            Some(ScaleFile::PerAxis(s)) => Vec3::from(s),
        };
        let (min_scale, max_scale) = SCALE_RANGE;
        if !scale.is_finite()
            || scale.abs().min_element() < min_scale
            || scale.abs().max_element() > max_scale
        {
            return Err(BuildError::Invalid(format!(
                "`{key}.scale` must be finite, non-zero and at most {max_scale:e} in size on each axis, got {:?}",
                scale.to_array()
            )));
        }
        let translate = coordinates(&format!("{key}.translate"), o.translate)?;
        // However it turns, the object stays within this distance of the origin.
        let (lo, hi) = mesh.bounds();
        let reach = translate.length() + (lo.abs().max(hi.abs()) * scale.abs()).length();
        if !reach.is_finite() || reach > MAX_REACH {
            return Err(BuildError::Invalid(format!(
                "`{key}.scale`: mesh `{}` scaled to {scale} reaches {reach:e} world units from the origin, \
                 more than {MAX_REACH:e}",
                mesh.name
            )));
        }
        let color = vec3(&format!("{key}.color"), o.color)?;
        objects.push(Object {
            name: o.name.unwrap_or_else(|| mesh.name.clone()),
            name_zh: o.name_zh,
            mesh,
            color: color.clamp(Vec3::ZERO, Vec3::ONE),
            translate: vec3(&format!("{key}.translate"), o.translate)?,
            rotate_deg: vec3(&format!("{key}.rotate_deg"), o.rotate_deg)?,
            scale,
            spin_deg_per_s: vec3(&format!("{key}.spin_deg_per_s"), o.spin_deg_per_s)?,
        });
    }

    if file.lights.len() > MAX_LIGHTS {
        return Err(BuildError::Invalid(format!(
            "{} lights; shadowlab supports at most {MAX_LIGHTS} (`light.{MAX_LIGHTS}` is one too many)",
            file.lights.len()
        )));
    }
    let mut lights = Vec::with_capacity(file.lights.len());
    for (i, l) in file.lights.into_iter().enumerate() {
        lights.push(build_light(i, l)?);
    }
    file.shadow.validate().map_err(BuildError::Invalid)?;
    Ok(Scene {
        path: None,
        camera,
        objects,
        lights,
        shadow: file.shadow,
        ambient: rgb("ambient", file.ambient)?,
    })
}

fn build_light(i: usize, l: LightFile) -> Result<Light, BuildError> {
    let key = |k: &str| format!("light.{i}.{k}");
    let kind = match l.kind {
        LightKindName::Directional => {
            if l.fov_deg.is_some() {
                return Err(BuildError::Invalid(format!(
                    "`{}` is for spot lights; directional lights use `extent`",
                    key("fov_deg")
                )));
            }
            let extent = l.extent.ok_or_else(|| {
                BuildError::Invalid(format!("`{}` is required for a directional light", key("extent")))
            })?;
            LightKind::Directional { extent_world: real(&parameters::LIGHT_EXTENT, &key("extent"), extent)? }
        }
        LightKindName::Spot => {
            if l.extent.is_some() {
                return Err(BuildError::Invalid(format!(
                    "`{}` is for directional lights; spot lights use `fov_deg`",
                    key("extent")
                )));
            }
            let fov = l.fov_deg.ok_or_else(|| {
                BuildError::Invalid(format!("`{}` is required for a spot light", key("fov_deg")))
            })?;
            LightKind::Spot { fov_deg: real(&parameters::LIGHT_FOV, &key("fov_deg"), fov)? }
        }
        LightKindName::Point => {
            for (given, name) in [(l.extent.is_some(), "extent"), (l.fov_deg.is_some(), "fov_deg")] {
                if given {
                    return Err(BuildError::Invalid(format!(
                        "`{}` is not for point lights: they shadow in every direction (six 90° faces)",
                        key(name)
                    )));
                }
            }
            LightKind::Point
        }
    };
    let size = match (l.width, l.angular_diameter_deg) {
        (Some(_), Some(_)) => {
            return Err(BuildError::Invalid(format!(
                "`{}` and `{}` are both given; give one",
                key("width"),
                key("angular_diameter_deg")
            )));
        }
        (None, Some(a)) => {
            if l.kind != LightKindName::Directional {
                return Err(BuildError::Invalid(format!(
                    "`{}` is for directional lights only; spot and point lights use `width`",
                    key("angular_diameter_deg")
                )));
            }
            LightSize::AngularDiameter {
                angular_diameter_deg: real(
                    &parameters::LIGHT_ANGULAR_DIAMETER,
                    &key("angular_diameter_deg"),
                    a,
                )?,
            }
        }
        (w, None) => {
            LightSize::Width { width_world: real(&parameters::LIGHT_WIDTH, &key("width"), w.unwrap_or(0.0))? }
        }
    };
    let default_near = match l.kind {
        LightKindName::Spot => 1.0,
        LightKindName::Point => 0.1,
        LightKindName::Directional => 0.01,
    };
    let near = real(&parameters::LIGHT_NEAR, &key("near"), l.near.unwrap_or(default_near))?;
    let far = parameters::LIGHT_FAR
        .check_far(&key("far"), l.far, &key("near"), near)
        .map_err(BuildError::Invalid)?;
    parameters::LIGHT_SHADOW_MAP_SIZE
        .check_whole(&key("shadow_map_size"), i64::from(l.shadow_map_size))
        .map_err(BuildError::Invalid)?;
    let position = coordinates(&key("position"), l.position)?;
    let target = coordinates(&key("target"), l.target)?;
    // A point light has no axis to aim (its target is only the centre it may orbit).
    if l.kind != LightKindName::Point && (target - position).length() < 1e-6 {
        return Err(BuildError::Invalid(format!("`{}` coincides with `{}`", key("target"), key("position"))));
    }
    let color = rgb(&key("color"), l.color)?;
    let cascades = build_cascades(&l, &key)?;
    Ok(Light {
        kind,
        position,
        target,
        up: vec3(&key("up"), l.up)?,
        color,
        intensity: real(&parameters::LIGHT_INTENSITY, &key("intensity"), l.intensity)?,
        shadow_map_size: l.shadow_map_size,
        near,
        far,
        size,
        orbit_deg_per_s: real(&parameters::LIGHT_ORBIT, &key("orbit_deg_per_s"), l.orbit_deg_per_s)?,
        cascades,
    })
}

/// A directional light's cascades; the other kinds refuse the keys.
fn build_cascades(l: &LightFile, key: &dyn Fn(&str) -> String) -> Result<Cascades, BuildError> {
    let given = [
        (l.cascades.is_some(), "cascades"),
        (l.cascade_lambda.is_some(), "cascade_lambda"),
        (l.cascade_distance.is_some(), "cascade_distance"),
        (l.cascade_selection.is_some(), "cascade_selection"),
    ];
    if l.kind != LightKindName::Directional {
        if let Some((_, name)) = given.iter().find(|(g, _)| *g) {
            return Err(BuildError::Invalid(format!(
                "`{}` is for directional lights: cascades split a sun's map along the camera's view",
                key(name)
            )));
        }
        return Ok(Cascades::default());
    }
    let defaults = Cascades::default();
    let count = match l.cascades {
        Some(n) => parameters::LIGHT_CASCADES
            .check_whole(&key("cascades"), i64::from(n))
            .map_err(BuildError::Invalid)? as u32,
        None => defaults.count,
    };
    let lambda = match l.cascade_lambda {
        Some(v) => real(&parameters::LIGHT_CASCADE_LAMBDA, &key("cascade_lambda"), v)?,
        None => defaults.lambda,
    };
    let distance_world = match l.cascade_distance {
        Some(v) => real(&parameters::LIGHT_CASCADE_DISTANCE, &key("cascade_distance"), v)?,
        None => defaults.distance_world,
    };
    let selection = match &l.cascade_selection {
        Some(name) => CascadeSelection::from_name(name).ok_or_else(|| {
            let names: Vec<&str> = CascadeSelection::ALL.iter().map(|s| s.name()).collect();
            BuildError::Invalid(format!(
                "`{}` = \"{name}\" is not one of {}",
                key("cascade_selection"),
                names.join(", ")
            ))
        })?,
        None => defaults.selection,
    };
    Ok(Cascades { count, lambda, distance_world, selection })
}

fn resolve_mesh(
    key: &str,
    name: &str,
    base_dir: &Path,
    cache: &mut HashMap<PathBuf, Arc<Mesh>>,
) -> Result<Arc<Mesh>, BuildError> {
    if let Some(mesh) = primitive(name) {
        let key = PathBuf::from(format!("<primitive {name}>"));
        return Ok(cache.entry(key).or_insert_with(|| Arc::new(mesh)).clone());
    }
    if !name.to_ascii_lowercase().ends_with(".obj") {
        return Err(BuildError::Invalid(format!(
            "`{key}`: unknown mesh `{name}` (expected one of {} or a path to an .obj file)",
            PRIMITIVES.join(", ")
        )));
    }
    let path = base_dir.join(name);
    if let Some(mesh) = cache.get(&path) {
        return Ok(mesh.clone());
    }
    let mesh = Arc::new(mesh::load_obj(&path).map_err(BuildError::Mesh)?);
    cache.insert(path, mesh.clone());
    Ok(mesh)
}

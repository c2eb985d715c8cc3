//! A scene around a model a user opens on its own (an `.obj`): the model on a floor under a
//! directional light, scaled to fit.

use crate::scene::{Scene, parse_scene_str};
use std::path::Path;

/// A scene around one OBJ file: the model on a floor under a directional light, scaled to fit.
pub fn scene_for_obj(path: &Path) -> Result<Scene, String> {
    let name = path.file_name().map(|n| n.to_string_lossy().to_string()).unwrap_or_default();
    let dir = path.parent().unwrap_or(Path::new("."));
    let mesh = crate::scene::mesh::load_obj(path).map_err(|e| e.to_string())?;
    let (lo, hi) = mesh.bounds();
    let extent = (hi - lo).max_element().max(1e-6);
    let scale = 10.0 / extent;
    let lift = -lo.y * scale;
    // The light's frustum fitted to the model and its shadow: the model's footprint (half its
    // XZ diagonal from the origin) plus how far its top's shadow reaches along the light, with a
    // 15% margin. The light shines from (10, 40, 20) towards the origin.
    let size = (hi - lo) * scale;
    let centre_xz = ((lo + hi) * 0.5 * scale).truncate();
    let footprint = centre_xz.length() + 0.5 * (size.x * size.x + size.z * size.z).sqrt();
    let light_dir = glam::Vec3::new(10.0, 40.0, 20.0).normalize();
    let reach = size.y * (light_dir.x * light_dir.x + light_dir.z * light_dir.z).sqrt() / light_dir.y;
    let light_extent = 1.15 * (footprint + reach);
    let text = format!(
        r#"[camera]
position = [18.0, 14.0, 18.0]
target = [0.0, 4.0, 0.0]
fov_deg = 50.0
[[object]]
name = "floor"
name_zh = "地面"
mesh = "plane"
scale = [60.0, 1.0, 60.0]
[[object]]
name = {name:?}
mesh = {name:?}
scale = {scale}
translate = [0.0, {lift}, 0.0]
[[light]]
kind = "directional"
position = [10.0, 40.0, 20.0]
extent = {light_extent}
far = 120.0
width = 2.0
"#
    );
    parse_scene_str(&text, dir, &path.display().to_string(), &[]).map_err(|e| e.to_string())
}

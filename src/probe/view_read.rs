//! Which of a light's shadow views a probe read, and why that one: a point light's cube face, a
//! sun's cascade with the sharper ones that did not hold the point.

use crate::shadow::{LightGpu, ShadowViewGpu};
use glam::Vec3;
use serde::{Deserialize, Serialize};

/// The cube faces by number (`scene::CUBE_FACES`), as the probe and the map panel name them.
pub const CUBE_FACE_NAMES: [&str; 6] = ["+X", "-X", "+Y", "-Y", "+Z", "-Z"];

/// The cascade a lookup read. By map, the sharpest whose map holds the point
/// `CASCADE_BORDER_TEXELS` inside its edge (`cascade_holds`): each sharper one lands it outside
/// that square. By interval, the one whose slice holds the point's depth along the camera's view
/// axis (`in_cascade_slice`).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct CascadeProbe {
    /// 0 is the sharpest, nearest the camera.
    pub index: usize,
    pub count: usize,
    /// The side of its map, world units, and of one texel of it.
    pub width_world: f32,
    pub texel_world: f32,
    /// By map: where the point lands on each sharper cascade's map (uv), none of them holding it
    /// (empty by interval, where a sharper map may hold it).
    pub uv_in_sharper: Vec<[f32; 2]>,
    /// By interval: the point's depth along the camera's view axis, and the slice of the cascade
    /// read, which holds it, world units.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub view_depth_world: Option<f32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub slice_world: Option<[f32; 2]>,
}

/// Which of a cascaded sun's maps `view_index` is, and where the point fell on the sharper ones.
pub(super) fn cascade_probe(
    light: &LightGpu,
    views: &[ShadowViewGpu],
    view_index: usize,
    p: Vec3,
) -> Option<CascadeProbe> {
    let first = light.first_view as usize;
    let view = views.get(view_index)?;
    if light.directional == 0 || light.view_count < 2 {
        return None;
    }
    let by_interval = light.cascade_selection == crate::shadow::CASCADE_BY_INTERVAL;
    let uv_in_sharper = match by_interval {
        true => Vec::new(),
        false => views[first..view_index]
            .iter()
            .map(|v| crate::shadow::project_to_light(v, p).truncate().to_array())
            .collect(),
    };
    Some(CascadeProbe {
        index: view_index - first,
        count: light.view_count as usize,
        width_world: view.frustum_width_world,
        texel_world: view.frustum_width_world / view.map_size_texels,
        uv_in_sharper,
        view_depth_world: by_interval.then(|| crate::shadow::view_axis_depth(view, p)),
        slice_world: by_interval.then_some([view.split_near_world, view.split_far_world]),
    })
}

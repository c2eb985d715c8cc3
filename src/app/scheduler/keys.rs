//! What a kept result depends on: a ground truth (kept per probe and for the view) and the
//! selected light's map picture (not read again while it stays the same).

use crate::render::FrameRequest;
use crate::scene::{Camera, Light, Mesh, Scene, ShadowSettings};
use crate::shadow::ShadowViewGpu;
use std::sync::Arc;

/// Everything a ground truth depends on: the surface under each pixel (camera, frame, pixel,
/// objects, time), the light it averages over and the settings its hard shadows read
/// (`reference::settings_read`): the technique, filter and bias shown are not among them.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct ReferenceKey {
    camera: Camera,
    size: (u32, u32),
    /// The one pixel shaded (a probe); None: the whole view.
    pixel: Option<(u32, u32)>,
    time_bits: u32,
    objects: Vec<ObjectKey>,
    light_index: usize,
    light: Option<Light>,
    settings: ShadowSettings,
}

/// An object as the camera and the shadow passes see it: its mesh (kept alive here, so the
/// comparison by address cannot be fooled by a new mesh at a freed one's address) and placement.
#[derive(Clone)]
struct ObjectKey(Arc<Mesh>, [f32; 12]);

impl std::fmt::Debug for ObjectKey {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "ObjectKey({} at {:p}, {:?})", self.0.name, Arc::as_ptr(&self.0), self.1)
    }
}

impl PartialEq for ObjectKey {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0) && self.1 == other.1
    }
}

impl ReferenceKey {
    pub(super) fn new(
        scene: &Scene,
        request: &FrameRequest,
        pixel: Option<(u32, u32)>,
        light_index: usize,
    ) -> Self {
        Self {
            camera: scene.camera,
            size: request.size,
            pixel,
            time_bits: request.time_s.to_bits(),
            objects: scene.objects.iter().map(|o| ObjectKey(o.mesh.clone(), placement(o))).collect(),
            light_index,
            light: scene.lights.get(light_index).copied(),
            settings: crate::reference::settings_read(&scene.shadow),
        }
    }
}

/// An object's translation, rotation, scale and spin, in a row.
fn placement(o: &crate::scene::Object) -> [f32; 12] {
    let mut placement = [0.0; 12];
    for (chunk, v) in placement.chunks_mut(3).zip([o.translate, o.rotate_deg, o.scale, o.spin_deg_per_s]) {
        chunk.copy_from_slice(&v.to_array());
    }
    placement
}

/// Everything the selected light's shadow map and its picture depend on. Dragging a value that
/// leaves the map alone (the light's width, a filter setting) then skips its read-back.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct MapKey {
    /// Every shadow view's matrix (a sun's far cascade moves while its first stays put) and the
    /// first's depth range (not the light's colour or size, which the maps do not see).
    view_clip_from_world: Vec<[[f32; 4]; 4]>,
    view_depth: (f32, f32, u32, f32),
    time_bits: u32,
    depth_bias: (i32, u32, bool),
    /// Per object: the mesh and its placement and spin.
    objects: Vec<(usize, [f32; 12])>,
    picture_texels: u32,
}

impl MapKey {
    /// The key of the picture of a light's `views` (its first, then the rest).
    pub(super) fn new(scene: &Scene, views: &[ShadowViewGpu], time_s: f32, picture_texels: u32) -> Self {
        let view = views.first().copied().unwrap_or_else(bytemuck::Zeroable::zeroed);
        let objects =
            scene.objects.iter().map(|o| (std::sync::Arc::as_ptr(&o.mesh) as usize, placement(o))).collect();
        let s = &scene.shadow;
        Self {
            view_clip_from_world: views.iter().map(|v| v.clip_from_world).collect(),
            view_depth: (view.near, view.far, view.orthographic, view.map_size_texels),
            time_bits: time_s.to_bits(),
            depth_bias: (s.depth_bias_constant, s.depth_bias_slope.to_bits(), s.cull_front_faces),
            objects,
            picture_texels,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Technique;

    #[test]
    fn the_map_key_follows_what_the_map_depends_on() {
        let path = crate::shipped_path("assets/scenes/games202.toml");
        let scene = crate::scene::load_scene(&path, &[]).expect("scene");
        let key = |scene: &Scene, time_s: f32| {
            let (_, views) = crate::shadow::frame_lights(scene, 1.5, time_s, scene.lights[0].shadow_map_size);
            MapKey::new(scene, &views[..1], time_s, 1024)
        };
        let base = key(&scene, 0.0);
        // The light's width and the filter do not change the map: no new read-back.
        let mut wider = scene.clone();
        wider.lights[0].size = crate::scene::LightSize::Width { width_world: 20.0 };
        wider.shadow.samples = 7;
        assert_eq!(key(&wider, 0.0), base);
        // Moving the light, an object, the time or the hardware bias does.
        let mut moved = scene.clone();
        moved.lights[0].position.x += 1.0;
        assert_ne!(key(&moved, 0.0), base);
        let mut shifted = scene.clone();
        shifted.objects[1].translate.y += 0.5;
        assert_ne!(key(&shifted, 0.0), base);
        assert_ne!(key(&scene, 1.0), base);
        let mut biased = scene.clone();
        biased.shadow.depth_bias_constant = 4;
        assert_ne!(key(&biased, 0.0), base);
        // A sun's cascades: a view after the first that moves changes the key too.
        let (_, views) = crate::shadow::frame_lights(&scene, 1.5, 0.0, 1024);
        let mut cascades = vec![views[0], views[0]];
        let before = MapKey::new(&scene, &cascades, 0.0, 1024);
        cascades[1].clip_from_world[3][0] += 0.01;
        assert_ne!(MapKey::new(&scene, &cascades, 0.0, 1024), before);
    }

    #[test]
    fn the_ground_truths_key_follows_what_the_ground_truth_depends_on() {
        let path = crate::shipped_path("assets/scenes/contact.toml");
        let scene = crate::scene::load_scene(&path, &[]).expect("scene");
        let request = FrameRequest { size: (960, 540), ..Default::default() };
        let key = |scene: &Scene| ReferenceKey::new(scene, &request, Some((650, 200)), 0);
        let base = key(&scene);
        assert_eq!(key(&scene.clone()), base);
        // The technique's own settings do not change the ground truth: it is kept.
        let mut filtered = scene.clone();
        filtered.shadow.technique = Technique::Pcf;
        filtered.shadow.samples = 7;
        filtered.shadow.bias_mode = crate::scene::BiasMode::ReceiverPlane;
        filtered.shadow.blocker_samples = 8;
        assert_eq!(key(&filtered), base);
        // The light, the camera, an object, its mesh, the time, the pixel, the frame and the
        // samples averaged do.
        let mut wider = scene.clone();
        wider.lights[0].size = crate::scene::LightSize::Width { width_world: 8.0 };
        assert_ne!(key(&wider), base);
        let mut turned = scene.clone();
        turned.camera.position.x += 1.0;
        assert_ne!(key(&turned), base);
        let mut moved = scene.clone();
        moved.objects[1].translate.y += 0.5;
        assert_ne!(key(&moved), base);
        let mut remeshed = scene.clone();
        remeshed.objects[1].mesh = std::sync::Arc::new((*scene.objects[1].mesh).clone());
        assert_ne!(key(&remeshed), base);
        let mut more = scene.clone();
        more.shadow.reference_samples *= 2;
        assert_ne!(key(&more), base);
        let later = FrameRequest { time_s: 1.0, ..request };
        assert_ne!(ReferenceKey::new(&scene, &later, Some((650, 200)), 0), base);
        assert_ne!(ReferenceKey::new(&scene, &request, Some((651, 200)), 0), base);
        assert_ne!(ReferenceKey::new(&scene, &request, None, 0), base);
        let smaller = FrameRequest { size: (480, 270), ..request };
        assert_ne!(ReferenceKey::new(&scene, &smaller, Some((650, 200)), 0), base);
    }
}

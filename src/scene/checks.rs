//! Scenes that load but leave the picture empty or dark: warnings, not errors. Each value is
//! legal on its own (and a lesson may set one on purpose); it is the scene as a whole that shows
//! nothing, which a reader would otherwise take for a broken renderer. The CLI prints them on
//! stderr; the app shows them in its status bar.

use super::{Object, Scene};
use glam::{Mat4, Vec3, Vec4};

impl Scene {
    /// What in the scene at time `t`, seen at `aspect` (width / height), leaves the picture
    /// empty or dark: each warning one line, none for a scene that shows something.
    pub fn warnings(&self, t_s: f32, aspect: f32) -> Vec<String> {
        let mut out = Vec::new();
        if self.objects.is_empty() {
            out.push("the scene has no objects: the picture shows only the background".to_string());
            return out;
        }
        let camera = self.camera.clip_from_world(aspect);
        if self.objects.iter().all(|o| outside(camera, o.world_bounds(t_s))) {
            out.push(format!(
                "no object is in the camera's view (from {} towards {}, depths {}..{}): the picture \
                 shows only the background",
                self.camera.position, self.camera.target, self.camera.near, self.camera.far
            ));
        }
        if let Some(o) = self.objects.iter().find(|o| inside(o, t_s, self.camera.position)) {
            out.push(format!(
                "the camera is inside object `{}` (within its bounds): the view may show only its inside",
                o.name
            ));
        }
        for (i, light) in self.lights.iter().enumerate() {
            let position = light.position_at(t_s);
            if let Some(o) = self.objects.iter().find(|o| inside(o, t_s, position)) {
                out.push(format!(
                    "light {i} is inside object `{}` (within its bounds): its shadow map sees that \
                     object from inside, so everything beyond it is in shadow",
                    o.name
                ));
            } else if self.objects.iter().all(|o| outside(light.clip_from_world(t_s), o.world_bounds(t_s))) {
                out.push(format!(
                    "light {i}'s frustum (depths {}..{}) holds no object: it casts no shadow",
                    light.near, light.far
                ));
            }
        }
        let lit = self.lights.iter().any(|l| l.intensity > 0.0 && l.color.max_element() > 0.0);
        if !lit && self.ambient.max_element() <= 0.0 {
            out.push("nothing lights the scene (no light has colour and intensity, the ambient is black): the picture is black".to_string());
        }
        out
    }
}

/// The box lies wholly outside one of the frustum's planes (conservative: a box near an edge
/// may count as in view).
fn outside(clip_from_world: Mat4, (lo, hi): (Vec3, Vec3)) -> bool {
    let corners = (0..8).map(|i| {
        let pick = |bit: i32, a: f32, b: f32| if i & bit == 0 { a } else { b };
        clip_from_world * Vec4::new(pick(1, lo.x, hi.x), pick(2, lo.y, hi.y), pick(4, lo.z, hi.z), 1.0)
    });
    let corners: Vec<Vec4> = corners.collect();
    // wgpu's clip volume: -w <= x, y <= w and 0 <= z <= w, one linear inequality a plane.
    let planes: [fn(Vec4) -> f32; 6] =
        [|c| c.w + c.x, |c| c.w - c.x, |c| c.w + c.y, |c| c.w - c.y, |c| c.z, |c| c.w - c.z];
    planes.iter().any(|plane| corners.iter().all(|&c| plane(c) < 0.0))
}

/// `p` lies strictly within the object's own bounding box (a flat mesh such as the plane has no
/// inside).
fn inside(object: &Object, t_s: f32, p: Vec3) -> bool {
    let local = object.world_from_object(t_s).inverse().transform_point3(p);
    let (lo, hi) = object.mesh.bounds();
    local.cmpgt(lo).all() && local.cmplt(hi).all()
}

//! What to sample (the twin of shaders/shadow_lookup.wgsl): where a surface
//! point lands in a light's shadow view, at which depth, with which bias; and the light-space formulas
//! every other part of shadowlab (probe, views, overlays, diagrams) calls rather than copies.

use super::{
    BIAS_ADAPTIVE, BIAS_CONSTANT, BIAS_RECEIVER_PLANE, BIAS_SLOPE, CASCADE_BORDER_TEXELS,
    CASCADE_BY_INTERVAL, LightGpu, SIZE_MODEL_ANGULAR, ShadowCoord, ShadowParamsGpu, ShadowViewGpu,
};
use crate::scene::{CUBE_FACES, cube_face_of};
use glam::{Vec2, Vec3, Vec4};

fn orthographic(view: &ShadowViewGpu) -> bool {
    view.orthographic == 1
}

fn is_cube(view: &ShadowViewGpu) -> bool {
    view.cube == 1
}

/// A cube face stores (distance - near) / (far - near): linear, like an orthographic map.
fn stores_linear_depth(view: &ShadowViewGpu) -> bool {
    orthographic(view) || is_cube(view)
}

pub fn depth_linear_from_ndc(view: &ShadowViewGpu, z: f32) -> f32 {
    if stores_linear_depth(view) {
        return view.near + z * (view.far - view.near);
    }
    view.near * view.far / (view.far - z * (view.far - view.near))
}

/// The inverse of [`depth_linear_from_ndc`]: the NDC depth (0..1, wgpu's range) the map stores
/// for a surface `depth_linear` world units from the light along its axis.
pub fn depth_ndc_from_linear(view: &ShadowViewGpu, depth_linear: f32) -> f32 {
    let (n, f) = (view.near, view.far);
    if stores_linear_depth(view) {
        (depth_linear - n) / (f - n)
    } else {
        f * (depth_linear - n) / (depth_linear * (f - n))
    }
}

/// dz/dd at distance d: turns a world-unit bias into NDC depth units.
pub fn ndc_per_world(view: &ShadowViewGpu, depth_linear: f32) -> f32 {
    if stores_linear_depth(view) {
        return 1.0 / (view.far - view.near);
    }
    view.far * view.near / (depth_linear * depth_linear * (view.far - view.near))
}

/// sec(theta) of the direction from the light that lands at `uv` of a cube face, theta its angle
/// from the face's axis; 1 for any other view (the shader's `off_axis_sec`, where the derivation
/// is). A width w (world units) across the ray at straight distance d spans
/// 0.5 sec²(theta) w / (d tan_half_fov) uv radially and 0.5 sec(theta) w / (d tan_half_fov)
/// tangentially: the blocker search takes sec² (the disk around that ellipse), a filter and a
/// texel's footprint sec^1.5 (the disk of its area). A spot light's map needs neither (its disk
/// light faces along its axis, and its depths are along the axis).
pub fn off_axis_sec(view: &ShadowViewGpu, uv: Vec2) -> f32 {
    if !is_cube(view) {
        return 1.0;
    }
    let tan_theta = (2.0 * uv - Vec2::ONE) * view.tan_half_fov;
    (1.0 + tan_theta.dot(tan_theta)).sqrt()
}

/// One texel's footprint at `uv`, world units, on a surface at `depth_linear`: orthographic, the
/// map's texel; a spot light, on a plane parallel to the map (2 d tan_half_fov / N); a cube face,
/// across the ray at straight distance d, the disk of the texel's area: 2 d tan_half_fov / N
/// divided by sec^1.5(theta) ([`off_axis_sec`]).
pub fn texel_world_at(view: &ShadowViewGpu, depth_linear: f32, uv: Vec2) -> f32 {
    if orthographic(view) {
        return view.frustum_width_world / view.map_size_texels;
    }
    let sec = off_axis_sec(view, uv);
    2.0 * depth_linear * view.tan_half_fov / (view.map_size_texels * sec * sec.sqrt())
}

/// The largest footprint a texel has at `depth_linear`, world units: at the map's centre
/// ([`texel_world_at`] shrinks off a cube face's axis). The normal offset and the adaptive bias
/// take it (the shader's `texel_world_bound` says why).
pub fn texel_world_bound(view: &ShadowViewGpu, depth_linear: f32) -> f32 {
    texel_world_at(view, depth_linear, Vec2::splat(0.5))
}

pub fn light_dir_to(light: &LightGpu, world_pos: Vec3) -> Vec3 {
    if light.directional == 1 {
        return -Vec4::from(light.direction).truncate();
    }
    (Vec4::from(light.position).truncate() - world_pos).normalize()
}

/// Face `face`'s axes (forward, up, right = forward x up), from `CUBE_FACES`.
pub fn cube_face_axes(face: u32) -> [Vec3; 3] {
    let (forward, up) = CUBE_FACES[face as usize];
    [forward, up, forward.cross(up)]
}

/// The same light's view on face `face` (the shader's `cube_face_view`).
pub fn cube_face_view(view: &ShadowViewGpu, face: u32) -> ShadowViewGpu {
    view.on_face(face)
}

/// The view of a light's maps that covers a point: a cube's face towards it, else the view
/// itself (the shader's `face_covering`).
pub fn face_covering(view: &ShadowViewGpu, world_pos: Vec3) -> ShadowViewGpu {
    if is_cube(view) {
        let origin = Vec4::from(view.origin).truncate();
        return cube_face_view(view, cube_face_of(world_pos - origin) as u32);
    }
    *view
}

/// Index into `views` of the view of `light` that a lookup at `world_pos` reads (the camera
/// pass's `shadow_view_at`): a cube's face towards the point; a sun's cascade, else its last;
/// else the light's one view. The cascade by the light's selection [Microsoft-CSM]: the sharpest
/// whose map holds the point (`cascade_holds`), or the first whose slice holds its depth along
/// the camera's view axis (`in_cascade_slice`).
pub fn view_covering(light: &LightGpu, views: &[ShadowViewGpu], world_pos: Vec3) -> usize {
    let first = light.first_view as usize;
    let Some(view) = views.get(first) else { return first };
    if is_cube(view) {
        // A cube's faces lie in consecutive views from its first.
        return first + (face_covering(view, world_pos).face - view.face) as usize;
    }
    let last = first + (light.view_count.max(1) as usize - 1);
    let picks = |v: &ShadowViewGpu| match light.cascade_selection {
        CASCADE_BY_INTERVAL => in_cascade_slice(v, world_pos),
        _ => cascade_holds(v, world_pos),
    };
    (first..last).find(|&i| views.get(i).is_some_and(picks)).unwrap_or(last)
}

/// A point's depth along the camera's view axis that a cascade was cut along, world units
/// (`ShadowViewGpu::view_axis_world`).
pub fn view_axis_depth(view: &ShadowViewGpu, world_pos: Vec3) -> f32 {
    Vec4::from(view.view_axis_world).dot(world_pos.extend(1.0))
}

/// A cascade's slice holds a point nearer than its far split along the camera's view axis (the
/// nearer slices were tried first; the shader's `in_cascade_slice`).
pub fn in_cascade_slice(view: &ShadowViewGpu, world_pos: Vec3) -> bool {
    view_axis_depth(view, world_pos) < view.split_far_world
}

/// A cascade holds a point when it lands on its map at least `CASCADE_BORDER_TEXELS` inside the
/// edge, so that a filter's nearest taps stay on the map (the shader's `cascade_holds`).
pub fn cascade_holds(view: &ShadowViewGpu, world_pos: Vec3) -> bool {
    let uv = project_to_light(view, world_pos).truncate();
    let border = CASCADE_BORDER_TEXELS as f32 / view.map_size_texels;
    uv.cmpge(Vec2::splat(border)).all() && uv.cmple(Vec2::splat(1.0 - border)).all()
}

/// Where direction `d` from the light lands on face `face`'s map (uv; behind the face: outside).
pub fn cube_face_uv(face: u32, d: Vec3) -> Vec2 {
    let [forward, up, right] = cube_face_axes(face);
    let ahead = d.dot(forward);
    // Also for NaN, as in the shader.
    if ahead.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return Vec2::splat(-1.0);
    }
    Vec2::new(0.5 + 0.5 * d.dot(right) / ahead, 0.5 - 0.5 * d.dot(up) / ahead)
}

/// A tap at `uv` of `view`'s map as read: on a cube face, a tap past the edge is a direction from
/// the light, read on the face it falls in (the shader's `map_tap`).
pub fn map_tap(view: &ShadowViewGpu, uv: Vec2) -> (ShadowViewGpu, Vec2) {
    if !is_cube(view) || !outside_map(uv) {
        return (*view, uv);
    }
    let [forward, up, right] = cube_face_axes(view.face);
    let d = forward + right * (2.0 * uv.x - 1.0) + up * (1.0 - 2.0 * uv.y);
    let face = cube_face_of(d) as u32;
    (cube_face_view(view, face), cube_face_uv(face, d).clamp(Vec2::ZERO, Vec2::ONE))
}

/// The centre of the texel a point-sampled tap at `uv` of `view` reads, in uv of `view` (the
/// shader's `read_texel_centre_uv`): on the map, its texel's (the last texel holds uv = 1); past a
/// cube face's edge, the centre of the texel read on the neighbouring face, seen from the light
/// on this face's plane gone on past its edge; elsewhere past the edge, the grid's texel there.
pub fn read_texel_centre_uv(view: &ShadowViewGpu, params: &ShadowParamsGpu, uv: Vec2) -> Vec2 {
    let size = view.map_size_texels;
    if !outside_map(uv) {
        return ((uv * size).floor().min(Vec2::splat(size - 1.0)) + 0.5) / size;
    }
    if !is_cube(view) {
        return ((uv * size).floor() + 0.5) / size;
    }
    let (tap_view, tap_uv) = map_tap(view, uv);
    let lookup = if params.clamp_outside == 0 { tap_uv - tap_uv.floor() } else { tap_uv };
    let centre = ((lookup * size).floor().clamp(Vec2::ZERO, Vec2::splat(size - 1.0)) + 0.5) / size;
    let [forward, up, right] = cube_face_axes(tap_view.face);
    let d = forward + right * (2.0 * centre.x - 1.0) + up * (1.0 - 2.0 * centre.y);
    let [forward, up, right] = cube_face_axes(view.face);
    let ahead = d.dot(forward);
    Vec2::new(0.5 + 0.5 * d.dot(right) / ahead, 0.5 - 0.5 * d.dot(up) / ahead)
}

/// The receiver has no map data (the shader's `no_map_data`): a cube face's neighbours hold what
/// lies past its edge, so there only the depth range counts.
pub fn no_map_data(view: &ShadowViewGpu, coord: &ShadowCoord) -> bool {
    if is_cube(view) { outside_depth(coord.depth_ndc) } else { outside_frustum(coord) }
}

pub fn project_to_light(view: &ShadowViewGpu, world_pos: Vec3) -> Vec3 {
    if is_cube(view) {
        let d = world_pos - Vec4::from(view.origin).truncate();
        let uv = cube_face_uv(view.face, d);
        return uv.extend((d.length() - view.near) / (view.far - view.near));
    }
    let clip = glam::Mat4::from_cols_array_2d(&view.clip_from_world) * world_pos.extend(1.0);
    let ndc = clip.truncate() / clip.w;
    Vec3::new(ndc.x * 0.5 + 0.5, ndc.y * -0.5 + 0.5, ndc.z)
}

/// The uv lies off the shadow map. Written as "not inside", like the shader, so NaN counts as
/// outside.
pub fn outside_map(uv: Vec2) -> bool {
    !(uv.x >= 0.0 && uv.y >= 0.0 && uv.x <= 1.0 && uv.y <= 1.0)
}

/// The NDC depth lies outside the map's range, 0..1.
pub fn outside_depth(z: f32) -> bool {
    !(0.0..=1.0).contains(&z)
}

/// The receiver has no shadow-map data: outside the map or past its depth range.
pub fn outside_frustum(coord: &ShadowCoord) -> bool {
    outside_map(coord.uv) || outside_depth(coord.depth_ndc)
}

/// Two unit vectors that span the plane with unit normal n [Duff-2017].
fn tangents_of(n: Vec3) -> [Vec3; 2] {
    let sign = if n.z >= 0.0 { 1.0 } else { -1.0 };
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    [Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x), Vec3::new(b, sign + n.y * n.y * a, -n.y)]
}

/// The receiver's plane (through p, normal n, projected at s) as NDC depth per uv of the map,
/// from two points of the plane a texel from p; 0 edge-on to the light [Isidoro-2006].
pub fn receiver_plane_gradient(view: &ShadowViewGpu, p: Vec3, n: Vec3, s: Vec3) -> Vec2 {
    let step = texel_world_at(view, depth_linear_from_ndc(view, s.z), s.truncate());
    let t = tangents_of(n);
    let a = project_to_light(view, p + t[0] * step) - s;
    let b = project_to_light(view, p + t[1] * step) - s;
    let det = a.x * b.y - a.y * b.x;
    let (a_uv, b_uv) = (Vec2::new(a.x, a.y), Vec2::new(b.x, b.y));
    // Also false for NaN, as in the shader.
    let spans_the_map = det.abs() > 1e-3 * a_uv.length() * b_uv.length();
    if !spans_the_map {
        return Vec2::ZERO;
    }
    Vec2::new(a.z * b.y - a.y * b.z, a.x * b.z - a.z * b.x) / det
}

/// The GAMES202 framework's RGBA8 depth round trip (`pack`, 8-bit storage, `unpack`); see the
/// shader's `rgba8_round_trip`.
pub fn rgba8_round_trip(depth_ndc: f32) -> f32 {
    let unpack_shift = Vec4::new(1.0, 1.0 / 256.0, 1.0 / 65_536.0, 1.0 / 16_777_216.0);
    if depth_ndc >= 1.0 {
        return ((unpack_shift.x + unpack_shift.y) + unpack_shift.z) + unpack_shift.w;
    }
    let scaled = depth_ndc * Vec4::new(1.0, 256.0, 65_536.0, 16_777_216.0);
    let mut rgba = scaled - scaled.floor();
    rgba -= Vec4::new(rgba.y, rgba.z, rgba.w, rgba.w) * Vec4::new(1.0 / 256.0, 1.0 / 256.0, 1.0 / 256.0, 0.0);
    let quantised = (rgba.clamp(Vec4::ZERO, Vec4::ONE) * 255.0).to_array().map(f32::round_ties_even);
    let parts = Vec4::from_array(quantised) * (1.0 / 255.0) * unpack_shift;
    ((parts.x + parts.y) + parts.z) + parts.w
}

/// The light-space lookup of a surface point in one of the light's views (the shader's
/// `light_space_lookup`): it needs the light, the view and the parameters, not the map.
pub fn light_space_lookup(
    light: &LightGpu,
    view: &ShadowViewGpu,
    params: &ShadowParamsGpu,
    world_pos: Vec3,
    normal: Vec3,
) -> ShadowCoord {
    let mut out = ShadowCoord { n_dot_l: normal.dot(light_dir_to(light, world_pos)), ..Default::default() };
    let mut p = world_pos;
    if params.normal_offset_texels > 0.0 {
        let d = depth_linear_from_ndc(view, project_to_light(view, world_pos).z);
        p = world_pos + normal * (params.normal_offset_texels * texel_world_bound(view, d));
    }
    let s = project_to_light(view, p);
    out.uv = Vec2::new(s.x, s.y);
    out.depth_ndc = s.z;
    out.depth_linear = depth_linear_from_ndc(view, s.z);
    if params.bias_mode == BIAS_RECEIVER_PLANE {
        out.depth_gradient = receiver_plane_gradient(view, p, normal, s);
    }
    out
}

/// Depth bias in NDC units (the shader's `receiver_bias_ndc`; the modes' sources are under Bias in
/// docs/REFERENCES.md): `filter_radius_texels` grows the adaptive bias with the filter it has to
/// cover [DrFlower-HW1].
pub fn receiver_bias_ndc(
    view: &ShadowViewGpu,
    params: &ShadowParamsGpu,
    coord: &ShadowCoord,
    filter_radius_texels: f32,
) -> f32 {
    let p = params;
    match p.bias_mode {
        BIAS_CONSTANT => p.bias,
        BIAS_SLOPE => (p.slope_bias * (1.0 - coord.n_dot_l)).max(p.bias),
        BIAS_RECEIVER_PLANE => p.bias,
        BIAS_ADAPTIVE => {
            let a = (1.0 + filter_radius_texels.ceil()) * 0.5 * texel_world_bound(view, coord.depth_linear);
            let b = 1.0 - coord.n_dot_l;
            let bias_world = p.adaptive_c * a.max(a * b);
            bias_world * ndc_per_world(view, coord.depth_linear)
        }
        _ => 0.0,
    }
}

/// PCSS step 1's region (the shader's `blocker_search_radius_uv`): the part of the map between
/// the light's area and a receiver at `depth_linear` that lands at `receiver_uv`, in uv of the
/// map (on a cube face off its axis, times sec²(theta): [`off_axis_sec`]).
pub fn blocker_search_radius_uv(
    light: &LightGpu,
    view: &ShadowViewGpu,
    params: &ShadowParamsGpu,
    depth_linear: f32,
    receiver_uv: Vec2,
) -> f32 {
    let d_r = depth_linear;
    let radius_world = if light.size_model == SIZE_MODEL_ANGULAR {
        (d_r - view.near) * light.tan_half_angle
    } else {
        0.5 * light.light_width_world * (d_r - view.near) / d_r
    };
    let sec = off_axis_sec(view, receiver_uv);
    radius_world.max(0.0) * params.search_radius_scale * sec * sec / view.frustum_width_world
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The homework's pack / RGBA8 / unpack round trip: channels in 1/256 steps kept in 1/255
    /// steps give +z/255 below the middle of the depth range and -(1 - z)/255 above it; the
    /// clear colour, white, reads back just past 1.
    #[test]
    fn the_rgba8_round_trip_is_off_by_about_a_255th_with_a_sign_change_at_half_depth() {
        for z in [0.05f32, 0.2, 0.3, 0.45, 0.5] {
            let error = rgba8_round_trip(z) - z;
            assert!((error - z / 255.0).abs() < 2e-5, "z {z}: error {error}");
        }
        for z in [0.51f32, 0.6, 0.8, 0.99] {
            let error = rgba8_round_trip(z) - z;
            assert!((error + (1.0 - z) / 255.0).abs() < 2e-5, "z {z}: error {error}");
        }
        let white = 1.0 + 1.0 / 256.0 + 1.0 / 65_536.0 + 1.0 / 16_777_216.0;
        assert_eq!(rgba8_round_trip(1.0), white);
        // Monotone within each half: a nearer depth never reads back farther.
        let samples: Vec<f32> = (0..2000).map(|i| i as f32 / 4000.0).collect();
        for w in samples.windows(2) {
            assert!(rgba8_round_trip(w[0]) <= rgba8_round_trip(w[1]), "{w:?}");
        }
    }

    /// A cube face's lookup (its axes, `cube_face_uv`, the distance) is what its shadow pass
    /// draws (`Light::cube_face_clip_from_world`), and a tap past a face's edge is read where its
    /// direction really is: on the neighbouring face, at the same place the point projects to.
    #[test]
    fn cube_faces_look_up_where_their_matrices_draw_and_taps_cross_seams_to_the_right_texel() {
        let scene = crate::scene::load_scene(&crate::shipped_path("assets/scenes/point_lamp.toml"), &[])
            .expect("scene");
        let light = &scene.lights[0];
        let (lights, views) = crate::shadow::frame_lights(&scene, 1.5, 0.0, 1024);
        let lamp = light.position_at(0.0);
        let mut h = 1u32;
        let mut next = || {
            h = h.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
            (h >> 8) as f32 / 16_777_216.0 * 2.0 - 1.0
        };
        for _ in 0..500 {
            let p = lamp + Vec3::new(next(), next(), next()) * 8.0;
            let view = face_covering(&views[0], p);
            assert_eq!(view.face as usize, cube_face_of(p - lamp));
            let s = project_to_light(&view, p);
            let drawn = light.cube_face_clip_from_world(view.face as usize, 0.0) * p.extend(1.0);
            let ndc = drawn.truncate() / drawn.w;
            let uv = Vec2::new(ndc.x * 0.5 + 0.5, ndc.y * -0.5 + 0.5);
            assert!((Vec2::new(s.x, s.y) - uv).length() < 1e-4, "face {}: {s} vs {uv}", view.face);
            assert!(!outside_map(uv));
            let distance = (p - lamp).length();
            assert!((depth_linear_from_ndc(&view, s.z) - distance).abs() < 1e-3);
            // The same point seen from a neighbouring face lies past that face's edge: the tap
            // comes back to the point's own face and uv.
            for other in 0..6u32 {
                let on_other = cube_face_view(&view, other);
                let past = project_to_light(&on_other, p);
                let past_uv = Vec2::new(past.x, past.y);
                if other == view.face || !past_uv.is_finite() || past_uv == Vec2::splat(-1.0) {
                    continue;
                }
                let (tap_view, tap_uv) = map_tap(&on_other, past_uv);
                assert_eq!(tap_view.face, view.face, "from face {other}");
                assert_eq!(tap_view.layer, lights[0].first_view + view.face);
                assert!((tap_uv - uv).length() < 1e-4, "from face {other}: {tap_uv} vs {uv}");
            }
        }
    }

    /// Where a world point lands on face `face` through the matrix the shadow pass draws it with
    /// (not the lookup's own `cube_face_uv`), uv.
    fn drawn_uv(light: &crate::scene::Light, face: u32, p: Vec3) -> Vec2 {
        let clip = light.cube_face_clip_from_world(face as usize, 0.0) * p.extend(1.0);
        let ndc = clip.truncate() / clip.w;
        Vec2::new(ndc.x * 0.5 + 0.5, ndc.y * -0.5 + 0.5)
    }

    /// On a cube face at 0°, 30°, the middle of an edge (44.4°) and a corner (54.2°), the twin's
    /// search radius, filter radius and texel footprint against the face's own projection of the
    /// widths they stand for, across the ray radially (away from the face's centre) and
    /// tangentially. The search covers the radial width (the larger), the filter and the texel
    /// are the geometric mean of the two (the disk of the ellipse's area), each within 10%. The
    /// face centre's scale, used everywhere before, is short by up to 3x at the corner.
    #[test]
    fn cube_face_radii_follow_the_faces_projection_off_its_axis() {
        let scene = crate::scene::load_scene(&crate::shipped_path("assets/scenes/point_lamp.toml"), &[])
            .expect("scene");
        let (lights, views) = crate::shadow::frame_lights(&scene, 0.0, 0.0, 1024);
        let mut light = lights[0];
        // A small lamp, so that its cones are thin and the projection is near linear over them.
        light.light_width_world = 0.02;
        let params = ShadowParamsGpu { search_radius_scale: 1.0, ..bytemuck::Zeroable::zeroed() };
        let lamp = scene.lights[0].position_at(0.0);
        let face = 3u32; // -Y: the floor's face
        let view = cube_face_view(&views[0], face);
        let [forward, up, right] = cube_face_axes(face);
        let (half_w, d, d_b) = (0.5 * light.light_width_world, 8.0f32, 6.0f32);
        let n = view.near;
        let size = view.map_size_texels;
        for (name, lateral) in [
            ("0°", Vec3::ZERO),
            ("30°", right * 30f32.to_radians().tan()),
            ("edge", right * 0.98),
            ("corner", (right + up) * 0.98),
        ] {
            let ray = (forward + lateral).normalize();
            let p = lamp + ray * d;
            let uv = drawn_uv(&scene.lights[0], face, p);
            let radial =
                if lateral == Vec3::ZERO { right } else { (lateral - ray * lateral.dot(ray)).normalize() };
            let tangential = ray.cross(radial);
            let projected =
                |offset: Vec3, at: Vec3| (drawn_uv(&scene.lights[0], face, at + offset) - uv).length();
            // Search: the cone from the receiver to the lamp's edge, cut at distance `near` from
            // the lamp, lands `half_w (d - n) / d` from the ray there.
            let cut = |e: Vec3| {
                let towards = lamp + e * half_w;
                towards + (p - towards) * (n / d)
            };
            let search = [radial, tangential].map(|e| projected(cut(e) - lamp - ray * n, lamp + ray * n));
            let ours = blocker_search_radius_uv(&light, &view, &params, d, uv);
            let before = blocker_search_radius_uv(&light, &view, &params, d, Vec2::splat(0.5));
            // Filter: half the penumbra's width across the ray at the receiver.
            let penumbra = crate::shadow::estimate_penumbra(&light, &view, &params, d, uv, d_b);
            let half_p = 0.5 * penumbra.width_world;
            let filter = [radial, tangential].map(|e| projected(e * half_p, p) * size);
            let filter_mean = (filter[0] * filter[1]).sqrt();
            let filter_before =
                crate::shadow::estimate_penumbra(&light, &view, &params, d, Vec2::splat(0.5), d_b);
            // A texel's footprint: its world width projected back spans a texel (geometric mean).
            let texel = texel_world_at(&view, d, uv);
            let spans = [radial, tangential].map(|e| projected(e * texel, p) * size);
            let texel_mean = (spans[0] * spans[1]).sqrt();
            eprintln!(
                "{name}: search {ours:.5} uv (centre's {before:.5}) vs radial {:.5}, tangential {:.5}; \
                 filter {:.3} texels (centre's {:.3}) vs radial {:.3}, tangential {:.3}; \
                 a texel_world_at spans {texel_mean:.3} texels",
                search[0],
                search[1],
                penumbra.filter_radius_texels,
                filter_before.filter_radius_texels,
                filter[0],
                filter[1]
            );
            let within = |what: &str, got: f32, want: f32| {
                assert!((got / want - 1.0).abs() < 0.1, "{name}: {what} {got} vs {want}");
            };
            within("search radius against the radial width", ours, search[0]);
            assert!(ours >= 0.97 * search[1], "{name}: the search must cover the tangential width too");
            within("filter radius against the mean width", penumbra.filter_radius_texels, filter_mean);
            within("texel footprint", texel_mean, 1.0);
        }
    }

    /// A spot light's map needs no correction off its axis: a width in a plane parallel to the
    /// map, at depth d along the axis, spans 0.5 w / (d tan_half_fov) uv anywhere on the map,
    /// which is what the twin's filter radius uses.
    #[test]
    fn a_spot_lights_widths_parallel_to_its_map_span_the_same_uv_off_its_axis() {
        let scene =
            crate::scene::load_scene(&crate::shipped_path("assets/scenes/contact.toml"), &[]).expect("scene");
        let spot = &scene.lights[0];
        assert!(matches!(spot.kind, crate::scene::LightKind::Spot { .. }));
        let gpu = crate::shadow::LightViewGpu::single(spot, 0.0, spot.shadow_map_size);
        let (view, light) = (gpu.view, gpu.light);
        let params = ShadowParamsGpu { search_radius_scale: 1.0, ..bytemuck::Zeroable::zeroed() };
        let eye = spot.position_at(0.0);
        let axis = spot.direction_at(0.0);
        let x = axis.any_orthonormal_vector();
        let (d, d_b) = (0.5 * (spot.near + spot.far), 0.4 * (spot.near + spot.far));
        for tan in [0.0f32, 0.3, 0.6] {
            let p = eye + (axis + x * tan * view.tan_half_fov) * d;
            let uv = project_to_light(&view, p).truncate();
            let penumbra = crate::shadow::estimate_penumbra(&light, &view, &params, d, uv, d_b);
            let half = 0.5 * penumbra.width_world;
            let spanned =
                (project_to_light(&view, p + x * half).truncate() - uv).length() * view.map_size_texels;
            assert!((penumbra.filter_radius_texels / spanned - 1.0).abs() < 0.02, "tan {tan}");
        }
    }

    /// The lamp of the lamp scene over an endless flat floor and nothing else, at 256² faces,
    /// under the receiver-plane bias: every tap of a floor point is lit, also the taps that
    /// cross a seam onto the neighbouring face and read a texel there. Floor points along the
    /// four seams of the bottom face, taps up to 3 texels away.
    #[test]
    fn taps_that_cross_a_cube_seam_under_the_receiver_plane_bias_see_no_false_shadow() {
        use crate::shadow::{DepthImage, Twin};
        let overrides: Vec<(String, String)> =
            [("technique", "pcf"), ("bias_mode", "receiver_plane"), ("bias", "0.0001")]
                .map(|(k, v)| (k.to_string(), v.to_string()))
                .to_vec();
        let path = crate::shipped_path("assets/scenes/point_lamp.toml");
        let mut scene = crate::scene::load_scene(&path, &overrides).expect("scene");
        scene.lights[0].shadow_map_size = 256;
        let (lights, views) = crate::shadow::frame_lights(&scene, 1.5, 0.0, 256);
        let params = ShadowParamsGpu::new(&scene.shadow);
        let lamp = scene.lights[0].position_at(0.0);
        let size = 256usize;
        // What the shadow pass stores for the floor (y = 0): the distance at each texel's centre.
        let maps: Vec<DepthImage> = (0..6u32)
            .map(|face| {
                let view = &views[face as usize];
                let [forward, up, right] = cube_face_axes(face);
                let depth_ndc = (0..size * size)
                    .map(|i| {
                        let c = (Vec2::new((i % size) as f32, (i / size) as f32) + 0.5) / size as f32;
                        let d = forward + right * (2.0 * c.x - 1.0) + up * (1.0 - 2.0 * c.y);
                        if d.y >= 0.0 {
                            return 1.0;
                        }
                        let distance = lamp.y / -d.y * d.length();
                        depth_ndc_from_linear(view, distance)
                    })
                    .collect();
                DepthImage { size: size as u32, depth_ndc }
            })
            .collect();
        let (mut seam_taps, mut seam_shadowed, mut inner_taps, mut inner_shadowed) = (0, 0, 0, 0);
        let h = lamp.y;
        for k in 0..400 {
            // Along the seams: at horizontal distance about h from the lamp's foot.
            let along = (k as f32 / 400.0 * 2.0 - 1.0) * 0.9 * h;
            let across = h * (1.0 + 0.04 * ((k * 7) % 11) as f32 / 10.0 - 0.02);
            let side = [
                Vec2::new(across, along),
                Vec2::new(-across, along),
                Vec2::new(along, across),
                Vec2::new(along, -across),
            ][k % 4];
            let p = Vec3::new(lamp.x + side.x, 0.0, lamp.z + side.y);
            let view = face_covering(&views[0], p);
            let twin = Twin::cube(&lights[0], &view, &params, &maps);
            let coord = twin.light_space_lookup(p, Vec3::Y);
            let bias = twin.receiver_bias_ndc(&coord, 0.0);
            for dy in -6..=6 {
                for dx in -6..=6 {
                    let uv = coord.uv + Vec2::new(dx as f32, dy as f32) * 0.5 / size as f32;
                    let lit = twin.depth_test(&coord, uv, bias);
                    if outside_map(uv) {
                        seam_taps += 1;
                        seam_shadowed += usize::from(lit < 1.0);
                    } else {
                        inner_taps += 1;
                        inner_shadowed += usize::from(lit < 1.0);
                    }
                }
            }
        }
        eprintln!(
            "seam-crossing taps falsely shadowed: {seam_shadowed} of {seam_taps}; inside a face: \
             {inner_shadowed} of {inner_taps}"
        );
        assert!(seam_taps > 10_000, "too few taps cross a seam: {seam_taps}");
        assert_eq!(inner_shadowed, 0, "of {inner_taps} taps inside a face");
        assert_eq!(seam_shadowed, 0, "of {seam_taps} taps across a seam");
    }

    #[test]
    fn nan_counts_as_outside_the_map_as_in_the_shader() {
        assert!(outside_map(Vec2::new(f32::NAN, 0.5)));
        assert!(outside_depth(f32::NAN));
        assert!(!outside_map(Vec2::new(0.0, 1.0)));
        assert!(outside_map(Vec2::new(-1e-6, 0.5)));
    }
}

// Pass 1: depth from the light [Williams-1978]. A spot or directional light's view writes the
// projection's depth alone (no fragment stage); a cube face writes the distance to the light,
// (|p - origin| - near) / (far - near), from `fs_shadow_distance` [LearnOpenGL-PointShadows]:
// one measure for all six faces, so a filter's taps can cross from one face to the next.

@group(0) @binding(0) var<uniform> shadow_view: ShadowViewGpu;
@group(1) @binding(0) var<uniform> object: ObjectGpu;

@vertex
fn vs_shadow(@location(0) position: vec3<f32>) -> @builtin(position) vec4<f32> {
    return shadow_view.clip_from_world * object.world_from_object * vec4<f32>(position, 1.0);
}

struct DistanceOut {
    @builtin(position) clip_position: vec4<f32>,
    @location(0) world_position: vec3<f32>,
}

@vertex
fn vs_shadow_distance(@location(0) position: vec3<f32>) -> DistanceOut {
    let world = object.world_from_object * vec4<f32>(position, 1.0);
    return DistanceOut(shadow_view.clip_from_world * world, world.xyz);
}

@fragment
fn fs_shadow_distance(in: DistanceOut) -> @builtin(frag_depth) f32 {
    let distance = length(in.world_position - shadow_view.origin.xyz);
    return (distance - shadow_view.near) / (shadow_view.far - shadow_view.near);
}

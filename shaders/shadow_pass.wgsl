// Pass 1: depth from the light [Williams-1978]. Only the depth attachment is written (no
// fragment stage).

@group(0) @binding(0) var<uniform> shadow_view: ShadowViewGpu;
@group(1) @binding(0) var<uniform> object: ObjectGpu;

@vertex
fn vs_shadow(@location(0) position: vec3<f32>) -> @builtin(position) vec4<f32> {
    return shadow_view.clip_from_world * object.world_from_object * vec4<f32>(position, 1.0);
}

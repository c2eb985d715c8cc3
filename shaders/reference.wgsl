// Ground truth: one hard shadow per light sample, averaged into a per-pixel sum
// [Guennebaud-2006].
// Dispatched once per sample, after the sample's shadow map is rendered into layer 0.

struct ReferenceInfo {
    width: u32,
    height: u32,
    weight: f32,   // 1 / sample count
    _pad: u32,
}

@group(0) @binding(0) var positions: texture_2d<f32>;
@group(0) @binding(1) var normals: texture_2d<f32>;
@group(0) @binding(2) var<storage, read_write> accumulated: array<f32>;
@group(0) @binding(3) var<uniform> info: ReferenceInfo;
// One sample of the light's area: the light moved there, and its one view.
struct LightViewGpu {
    light: LightGpu,
    view: ShadowViewGpu,
}
// Storage, not uniform: a value that changes with every dispatch must not be a uniform that
// a driver may inline into a new shader variant per value (src/render/layouts.rs, LightBinding).
@group(1) @binding(0) var<storage, read> sample: LightViewGpu;

@compute @workgroup_size(8, 8)
fn cs_accumulate(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= info.width || id.y >= info.height {
        return;
    }
    let position = textureLoad(positions, vec2<i32>(id.xy), 0);
    if position.w < 0.5 {
        return;
    }
    let normal = textureLoad(normals, vec2<i32>(id.xy), 0).xyz;
    let view = face_covering(sample.view, position.xyz);
    let coord = light_space_lookup(sample.light, view, position.xyz, normal);
    let index = id.y * info.width + id.x;
    accumulated[index] += info.weight * visibility_hard(view, coord);
}

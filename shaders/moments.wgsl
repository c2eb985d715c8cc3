// VSM moments of the shadow maps: (depth, depth²) averaged over blocks of texels, as a mip chain.
// Level 0 holds one texel per `block` x `block` map texels (block = 1 for maps up to 2048 texels);
// each further level averages 2x2 texels of the one before (sizes halve rounding down, so an odd
// last row or column is left out). The camera pass reads one level bilinearly
// (`filtered_moments` in shadow_sampling.wgsl). Built after the shadow pass for frames that use
// VSM; the CPU twin builds the same chain (src/shadow/moments.rs).

struct MomentsInfo {
    block: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

@group(0) @binding(0) var depth_maps: texture_depth_2d_array;
@group(0) @binding(1) var finer: texture_2d_array<f32>;
@group(0) @binding(2) var moments_out: texture_storage_2d_array<rg32float, write>;
@group(0) @binding(3) var<uniform> info: MomentsInfo;

@compute @workgroup_size(8, 8)
fn cs_moments_from_depth(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(moments_out);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let last = vec2<i32>(textureDimensions(depth_maps)) - 1;
    let block = i32(info.block);
    var sum = vec2<f32>(0.0);
    for (var y = 0; y < block; y++) {
        for (var x = 0; x < block; x++) {
            let texel = min(vec2<i32>(id.xy) * block + vec2<i32>(x, y), last);
            let z = textureLoad(depth_maps, texel, i32(id.z), 0);
            sum += vec2<f32>(z, z * z);
        }
    }
    textureStore(moments_out, id.xy, id.z, vec4<f32>(sum / f32(block * block), 0.0, 0.0));
}

@compute @workgroup_size(8, 8)
fn cs_moments_reduce(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(moments_out);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let last = vec2<i32>(textureDimensions(finer)) - 1;
    let at = vec2<i32>(id.xy) * 2;
    let layer = i32(id.z);
    let a = textureLoad(finer, min(at, last), layer, 0).xy;
    let b = textureLoad(finer, min(at + vec2<i32>(1, 0), last), layer, 0).xy;
    let c = textureLoad(finer, min(at + vec2<i32>(0, 1), last), layer, 0).xy;
    let d = textureLoad(finer, min(at + vec2<i32>(1, 1), last), layer, 0).xy;
    textureStore(moments_out, id.xy, id.z, vec4<f32>((((a + b) + c) + d) * 0.25, 0.0, 0.0));
}

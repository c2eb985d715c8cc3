// VSM moments of the shadow maps: (depth, depth²) averaged over blocks of texels, as a mip chain.
// Level 0 holds one texel per `block` x `block` map texels (block = 1 for maps up to 2048 texels);
// each further level averages 2x2 texels of the one before (sizes halve rounding down, so an odd
// last row or column is left out). The camera pass reads one level bilinearly
// (`filtered_moments` in shadow_filter.wgsl). Built after the shadow pass for frames that use
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
@group(0) @binding(4) var moments_out_1: texture_storage_2d_array<rg32float, write>;

// Level-0 moments of one level-0 texel: the mean of (z, z²) over its block of map texels.
fn level_0_at(texel0: vec2<i32>, layer: i32) -> vec2<f32> {
    let last = vec2<i32>(textureDimensions(depth_maps)) - 1;
    let block = i32(info.block);
    var sum = vec2<f32>(0.0);
    for (var y = 0; y < block; y++) {
        for (var x = 0; x < block; x++) {
            let texel = min(texel0 * block + vec2<i32>(x, y), last);
            let z = textureLoad(depth_maps, texel, layer, 0);
            sum += vec2<f32>(z, z * z);
        }
    }
    return sum / f32(block * block);
}

// Level 0 alone (a chain of one level).
@compute @workgroup_size(8, 8)
fn cs_moments_from_depth(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(moments_out);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    textureStore(moments_out, id.xy, id.z, vec4<f32>(level_0_at(vec2<i32>(id.xy), i32(id.z)), 0.0, 0.0));
}

// Levels 0 and 1 in one pass: each invocation makes a 2x2 square of level 0 and, from the same
// values in the same order as `cs_moments_reduce`, the level-1 texel over it. Level 1 is then
// never read back to be made, which is most of a separate pass's cost on a CPU rasteriser.
@compute @workgroup_size(8, 8)
fn cs_moments_levels_0_1(@builtin(global_invocation_id) id: vec3<u32>) {
    let size0 = textureDimensions(moments_out);
    let at = vec2<i32>(id.xy) * 2;
    if u32(at.x) >= size0.x || u32(at.y) >= size0.y {
        return;
    }
    let layer = i32(id.z);
    let a = level_0_at(at, layer);
    let b = level_0_at(at + vec2<i32>(1, 0), layer);
    let c = level_0_at(at + vec2<i32>(0, 1), layer);
    let d = level_0_at(at + vec2<i32>(1, 1), layer);
    // An odd last row or column of level 0 has no level-1 texel over it.
    let inside = vec2<u32>(at + 1) < size0;
    textureStore(moments_out, at, layer, vec4<f32>(a, 0.0, 0.0));
    if inside.x {
        textureStore(moments_out, at + vec2<i32>(1, 0), layer, vec4<f32>(b, 0.0, 0.0));
    }
    if inside.y {
        textureStore(moments_out, at + vec2<i32>(0, 1), layer, vec4<f32>(c, 0.0, 0.0));
    }
    if inside.x && inside.y {
        textureStore(moments_out, at + vec2<i32>(1, 1), layer, vec4<f32>(d, 0.0, 0.0));
        textureStore(moments_out_1, id.xy, layer, vec4<f32>((((a + b) + c) + d) * 0.25, 0.0, 0.0));
    }
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

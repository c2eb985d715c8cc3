// The camera pass's fast paths on a software rasteriser (lavapipe, llvmpipe, SwiftShader): the
// same picture as the plain code would give, for less work per pixel. The lighting that calls
// them is shaders/camera.wgsl.

// The camera view's albedo cache: the diffuse texture's value at each pixel, written by
// `fs_albedo` for the still textured objects while the camera and those objects keep still.
@group(3) @binding(0) var albedo_cache: texture_2d<f32>;

// The pipeline that draws the still textured objects reads their albedo from the cache rather
// than sampling it again: the floor's anisotropic lookup is most of the base cost on a software
// rasteriser, and the cached value is the same sample (same triangle, same derivatives), so the
// picture is unchanged. A constant, not a per-object switch: llvmpipe pays for a sample behind
// any run-time branch.
override ALBEDO_FROM_CACHE: bool = false;

fn surface_albedo(in: VertexOut) -> vec3<f32> {
    var albedo = object.base_color.rgb;
    if object.base_color.w > 0.5 {
        if ALBEDO_FROM_CACHE {
            albedo = albedo * textureLoad(albedo_cache, vec2<i32>(in.clip_position.xy), 0).rgb;
        } else {
            albedo = albedo * textureSample(diffuse_texture, diffuse_sampler, in.uv).rgb;
        }
    }
    return albedo;
}

// The albedo cache pass: the texture's value, as `surface_albedo` samples it.
@fragment
fn fs_albedo(in: VertexOut) -> @location(0) vec4<f32> {
    return vec4<f32>(textureSample(diffuse_texture, diffuse_sampler, in.uv).rgb, 1.0);
}

// The scene's light count, fixed per pipeline so the light loop unrolls (SPECIALISED only).
override SPEC_LIGHT_COUNT: u32 = 4294967295u;

fn light_count() -> u32 {
    if SPECIALISED && SPEC_LIGHT_COUNT <= MAX_LIGHTS {
        return SPEC_LIGHT_COUNT;
    }
    return frame.light_count;
}

// x^48 by squaring (x^32 * x^16): five multiplies instead of pow's log2 and exp2 per pixel.
fn pow48(x: f32) -> f32 {
    let x2 = x * x;
    let x4 = x2 * x2;
    let x8 = x4 * x4;
    let x16 = x8 * x8;
    return x16 * x16 * x16;
}

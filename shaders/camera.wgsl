// Pass 2: the camera view. `fs_final` shades with Blinn-Phong and every light's shadow;
// `fs_analysis` writes floats for one light (visibility and PCSS intermediates) plus the
// surface position and normal, which the CPU twin, the probe and the ground truth read.
// What makes it fast on a software rasteriser (the albedo cache, the unrolled light loop,
// `pow48`) is shaders/camera_fast_paths.wgsl; this file is the lighting.

@group(0) @binding(0) var<uniform> frame: FrameGpu;
@group(1) @binding(0) var<uniform> lights: array<LightGpu, MAX_LIGHTS>;
@group(1) @binding(6) var<uniform> shadow_views: array<ShadowViewGpu, MAX_SHADOW_VIEWS>;
@group(2) @binding(0) var<uniform> object: ObjectGpu;
@group(2) @binding(1) var diffuse_texture: texture_2d<f32>;
@group(2) @binding(2) var diffuse_sampler: sampler;

struct VertexOut {
    @builtin(position) clip_position: vec4<f32>,
    @location(0) world_position: vec3<f32>,
    @location(1) world_normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
}

@vertex
fn vs_camera(
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
) -> VertexOut {
    var out: VertexOut;
    let world = object.world_from_object * vec4<f32>(position, 1.0);
    out.world_position = world.xyz;
    out.world_normal = (object.normal_from_object * vec4<f32>(normal, 0.0)).xyz;
    out.uv = uv;
    out.clip_position = frame.clip_from_world * world;
    return out;
}

// The normal used for shading and bias: unit length, towards the viewer on back faces
// (planes are single-sided meshes seen from both sides).
fn shading_normal(in: VertexOut, front_facing: bool) -> vec3<f32> {
    let n = normalize(in.world_normal);
    return select(-n, n, front_facing);
}

fn noise_seed_at(frag: vec4<f32>) -> u32 {
    return pixel_seed(vec2<u32>(frag.xy), params.noise_seed, params.rotate_per_pixel == 1u);
}

// The shadow view of `light` that covers a point: a point light's cube face towards it, a sun's
// cascade (else its last), or the light's one view. The cascade, by the light's selection
// [Microsoft-CSM]: by map, the sharpest whose map holds the point; by interval, the first whose
// slice ends beyond the point's depth along the camera's view axis (world units).
fn shadow_view_at(light: LightGpu, world_pos: vec3<f32>) -> ShadowViewGpu {
    let first = shadow_views[light.first_view];
    if is_cube(first) {
        return face_covering(first, world_pos);
    }
    let last = light.first_view + max(light.view_count, 1u) - 1u;
    for (var i = light.first_view; i < last; i++) {
        let view = shadow_views[i];
        if select(cascade_holds(view, world_pos), in_cascade_slice(view, world_pos),
                  light.cascade_selection == CASCADE_BY_INTERVAL) {
            return view;
        }
    }
    return shadow_views[last];
}

// Spot lights light only inside their square frustum (soft 5% edge); a point light everywhere.
fn spot_falloff(view: ShadowViewGpu, world_pos: vec3<f32>) -> f32 {
    if is_orthographic(view) || is_cube(view) {
        return 1.0;
    }
    let s = project_to_light(view, world_pos);
    let edge = min(min(s.x, 1.0 - s.x), min(s.y, 1.0 - s.y));
    return smoothstep(0.0, 0.05, edge) * select(0.0, 1.0, s.z > 0.0 && s.z < 1.0);
}

// Blinn-Phong with every light's shadow; the selected light's shadow terms on the side.
struct Shaded {
    color: vec4<f32>,
    selected: ShadowVisibility,
    selected_coord: ShadowCoord,
}

fn shade(in: VertexOut, front_facing: bool) -> Shaded {
    var out: Shaded;
    let n = shading_normal(in, front_facing);
    let albedo = surface_albedo(in);
    let v = normalize(frame.camera_position.xyz - in.world_position);
    let seed = noise_seed_at(in.clip_position);
    var color = frame.ambient.rgb * albedo;
    out.selected.visibility = 1.0;
    for (var i = 0u; i < light_count(); i++) {
        let light = lights[i];
        let view = shadow_view_at(light, in.world_position);
        let l = light_dir_to(light, in.world_position);
        let n_dot_l = max(dot(n, l), 0.0);
        let h = normalize(l + v);
        let specular = 0.25 * pow48(max(dot(n, h), 0.0)) * select(0.0, 1.0, n_dot_l > 0.0);
        let coord = light_space_lookup(light, view, in.world_position, n);
        let result = shadow_visibility(light, view, coord, seed);
        if i == frame.selected_light {
            out.selected = result;
            out.selected_coord = coord;
        }
        let radiance = light.color.rgb * spot_falloff(view, in.world_position);
        color += result.visibility * radiance * (albedo * n_dot_l + vec3<f32>(specular));
    }
    // Linear: the target's sRGB view encodes on store.
    out.color = vec4<f32>(clamp(color, vec3<f32>(0.0), vec3<f32>(1.0)), 1.0);
    return out;
}

@fragment
fn fs_final(in: VertexOut, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    return shade(in, front_facing).color;
}

struct AnalysisOut {
    // visibility, blocker-search radius (texels), penumbra width (texels on the receiver), blockers found
    @location(0) shadow: vec4<f32>,
    // world position; w = 1 where a surface was hit (cleared to 0)
    @location(1) position: vec4<f32>,
    // shading normal; w = object index
    @location(2) normal: vec4<f32>,
}

fn analysis_of(in: VertexOut, front_facing: bool, result: ShadowVisibility, coord: ShadowCoord) -> AnalysisOut {
    var out: AnalysisOut;
    out.position = vec4<f32>(in.world_position, 1.0);
    out.normal = vec4<f32>(shading_normal(in, front_facing), f32(object.object_index));
    if light_count() == 0u {
        out.shadow = vec4<f32>(1.0, 0.0, 0.0, 0.0);
        return out;
    }
    let view = shadow_view_at(lights[frame.selected_light], in.world_position);
    let penumbra_texels = result.penumbra.width_world / texel_world_at(view, coord.depth_linear, coord.uv);
    out.shadow = vec4<f32>(result.visibility, result.search.radius_texels, penumbra_texels, f32(result.search.found));
    return out;
}

@fragment
fn fs_analysis(in: VertexOut, @builtin(front_facing) front_facing: bool) -> AnalysisOut {
    if light_count() == 0u {
        var none: ShadowVisibility;
        var nowhere: ShadowCoord;
        return analysis_of(in, front_facing, none, nowhere);
    }
    let light = lights[frame.selected_light];
    let view = shadow_view_at(light, in.world_position);
    let n = shading_normal(in, front_facing);
    let coord = light_space_lookup(light, view, in.world_position, n);
    let result = shadow_visibility(light, view, coord, noise_seed_at(in.clip_position));
    return analysis_of(in, front_facing, result, coord);
}

// Both at once: the selected light's shadow terms are the ones the colour used, so a frame that
// wants the picture and its analysis filters once, not twice.
struct FinalAndAnalysisOut {
    @location(0) color: vec4<f32>,
    @location(1) shadow: vec4<f32>,
    @location(2) position: vec4<f32>,
    @location(3) normal: vec4<f32>,
}

@fragment
fn fs_final_and_analysis(in: VertexOut, @builtin(front_facing) front_facing: bool) -> FinalAndAnalysisOut {
    let shaded = shade(in, front_facing);
    let analysis = analysis_of(in, front_facing, shaded.selected, shaded.selected_coord);
    return FinalAndAnalysisOut(shaded.color, analysis.shadow, analysis.position, analysis.normal);
}

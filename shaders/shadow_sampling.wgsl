// Shadow sampling: what to sample (light-space lookup, bias) and how to filter it
// (hard, PCF with five kernels, PCSS in three steps).
// The CPU twin in src/shadow/ has the same functions with the same names; fix a formula in both.
//
// Units: `depth_ndc` is what the map stores (0..1); `depth_linear` is world units from the light
// along its axis; `_uv` is shadow-map uv (0..1 over the light's map); `_texels` is map texels.

@group(1) @binding(1) var<uniform> params: ShadowParamsGpu;
@group(1) @binding(2) var shadow_maps: texture_depth_2d_array;
@group(1) @binding(3) var shadow_compare_sampler: sampler_comparison;
// Unit-disk sample patterns, unrotated: tap i of the filter in .xy, of the blocker search in
// .zw (filled from params by the renderer; see `kernel_offset`).
@group(1) @binding(4) var<uniform> kernel_table: array<vec4<f32>, MAX_TAPS>;
const FILTER_TABLE: u32 = 0u;
const SEARCH_TABLE: u32 = 1u;
// VSM: (depth, depth²) averaged per block of map texels, a mip chain (shaders/moments.wgsl).
@group(1) @binding(5) var moments: texture_2d_array<f32>;

// ---------------------------------------------------------------- pipeline specialisation
// The camera pipelines are built once per technique, kernel, bias mode and clamping, with these
// override constants set (SPECIALISED = true): the shader compiler then drops every branch the
// pipeline never takes. Without it a SIMD rasteriser (lavapipe) runs masked copies of every
// technique's loops for every pixel. SPECIALISED = false (the ground-truth pass) reads `params`.
override SPECIALISED: bool = false;
override SPEC_TECHNIQUE: u32 = 0u;
override SPEC_KERNEL: u32 = 0u;
override SPEC_BIAS_MODE: u32 = 0u;
override SPEC_CLAMP_OUTSIDE: u32 = 1u;
override SPEC_DEPTH_STORAGE: u32 = 0u;
// What every light of the scene shares: SPEC_ALL_* (or SPEC_MIXED: read it from the light).
override SPEC_PROJECTION: u32 = 0u;
override SPEC_SIZE_MODEL: u32 = 0u;
const SPEC_MIXED: u32 = 0u;
const SPEC_ALL_ORTHOGRAPHIC: u32 = 1u;
const SPEC_ALL_PERSPECTIVE: u32 = 2u;
const SPEC_ALL_WIDTH: u32 = 1u;
const SPEC_ALL_ANGULAR: u32 = 2u;

fn technique() -> u32 {
    if SPECIALISED {
        return SPEC_TECHNIQUE;
    }
    return params.technique;
}

fn kernel() -> u32 {
    if SPECIALISED {
        return SPEC_KERNEL;
    }
    return params.kernel;
}

fn bias_mode() -> u32 {
    if SPECIALISED {
        return SPEC_BIAS_MODE;
    }
    return params.bias_mode;
}

fn clamp_outside() -> u32 {
    if SPECIALISED {
        return SPEC_CLAMP_OUTSIDE;
    }
    return params.clamp_outside;
}

fn depth_storage() -> u32 {
    if SPECIALISED {
        return SPEC_DEPTH_STORAGE;
    }
    return params.depth_storage;
}

fn is_orthographic(light: LightGpu) -> bool {
    if SPECIALISED && SPEC_PROJECTION != SPEC_MIXED {
        return SPEC_PROJECTION == SPEC_ALL_ORTHOGRAPHIC;
    }
    return light.orthographic == 1u;
}

fn is_angular(light: LightGpu) -> bool {
    if SPECIALISED && SPEC_SIZE_MODEL != SPEC_MIXED {
        return SPEC_SIZE_MODEL == SPEC_ALL_ANGULAR;
    }
    return light.size_model == SIZE_MODEL_ANGULAR;
}

// ---------------------------------------------------------------- what to sample

struct ShadowCoord {
    uv: vec2<f32>,          // wgpu: uv = ndc.xy * (0.5, -0.5) + 0.5
    depth_ndc: f32,         // receiver depth as the map would store it
    depth_linear: f32,      // receiver distance from the light, world units
    n_dot_l: f32,
    // Receiver-plane bias only (else 0): the receiver's plane in the map, as NDC depth per uv,
    // so that the plane's depth at uv + delta is depth_ndc + dot(depth_gradient, delta).
    depth_gradient: vec2<f32>,
}

fn depth_linear_from_ndc(light: LightGpu, z: f32) -> f32 {
    if is_orthographic(light) {
        return light.near + z * (light.far - light.near);
    }
    return light.near * light.far / (light.far - z * (light.far - light.near));
}

// dz/dd at distance d: turns a world-unit bias into NDC depth units.
fn ndc_per_world(light: LightGpu, depth_linear: f32) -> f32 {
    if is_orthographic(light) {
        return 1.0 / (light.far - light.near);
    }
    return light.far * light.near / (depth_linear * depth_linear * (light.far - light.near));
}

// One texel's footprint on a surface facing the light at distance d, world units.
fn texel_world_at(light: LightGpu, depth_linear: f32) -> f32 {
    if is_orthographic(light) {
        return light.frustum_width_world / light.map_size_texels;
    }
    return 2.0 * depth_linear * light.tan_half_fov / light.map_size_texels;
}

fn light_dir_to(light: LightGpu, world_pos: vec3<f32>) -> vec3<f32> {
    if is_orthographic(light) {
        return -light.direction.xyz;
    }
    return normalize(light.position.xyz - world_pos);
}

fn project_to_light(light: LightGpu, world_pos: vec3<f32>) -> vec3<f32> {
    let clip = light.clip_from_world * vec4<f32>(world_pos, 1.0);
    let ndc = clip.xyz / clip.w;
    return vec3<f32>(ndc.xy * vec2<f32>(0.5, -0.5) + vec2<f32>(0.5), ndc.z);
}

// Light-space lookup of a surface point, with the normal offset applied
// (three.js normalBias; Bevy uses 1.8 texels): move along the normal by k texels in world units.
fn light_space_lookup(light: LightGpu, world_pos: vec3<f32>, normal: vec3<f32>) -> ShadowCoord {
    var out: ShadowCoord;
    out.n_dot_l = dot(normal, light_dir_to(light, world_pos));
    var p = world_pos;
    if params.normal_offset_texels > 0.0 {
        let d = depth_linear_from_ndc(light, project_to_light(light, world_pos).z);
        p = world_pos + normal * (params.normal_offset_texels * texel_world_at(light, d));
    }
    let s = project_to_light(light, p);
    out.uv = s.xy;
    out.depth_ndc = s.z;
    out.depth_linear = depth_linear_from_ndc(light, s.z);
    if bias_mode() == BIAS_RECEIVER_PLANE {
        out.depth_gradient = receiver_plane_gradient(light, p, normal, s);
    }
    return out;
}

// Two unit vectors that span the plane with unit normal n (Duff et al. 2017, branchless).
fn tangents_of(n: vec3<f32>) -> array<vec3<f32>, 2> {
    let sign = select(-1.0, 1.0, n.z >= 0.0);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    return array<vec3<f32>, 2>(
        vec3<f32>(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        vec3<f32>(b, sign + n.y * n.y * a, -n.y),
    );
}

// The receiver's plane (through p, normal n) as NDC depth per uv of the map: two points of the
// plane a texel from p, projected like p (at s), fix it. A light's projection maps planes to
// planes, so this is exact for spot lights too. Edge-on to the light (the two projected steps
// parallel) there is no such plane: 0, the constant bias alone.
fn receiver_plane_gradient(light: LightGpu, p: vec3<f32>, n: vec3<f32>, s: vec3<f32>) -> vec2<f32> {
    let step = texel_world_at(light, depth_linear_from_ndc(light, s.z));
    let t = tangents_of(n);
    let a = project_to_light(light, p + t[0] * step) - s;
    let b = project_to_light(light, p + t[1] * step) - s;
    let det = a.x * b.y - a.y * b.x;
    if !(abs(det) > 1e-3 * length(a.xy) * length(b.xy)) {
        return vec2<f32>(0.0);
    }
    return vec2<f32>(a.z * b.y - a.y * b.z, a.x * b.z - a.z * b.x) / det;
}

// Depth bias in NDC units (REFERENCES "Bias"). `filter_radius_texels` grows the adaptive bias.
fn receiver_bias_ndc(light: LightGpu, coord: ShadowCoord, filter_radius_texels: f32) -> f32 {
    switch bias_mode() {
        case BIAS_CONSTANT: {
            return params.bias;
        }
        case BIAS_SLOPE: {
            // LearnOpenGL: max(0.05 * (1 - N.L), 0.005)
            return max(params.slope_bias * (1.0 - coord.n_dot_l), params.bias);
        }
        case BIAS_RECEIVER_PLANE: {
            // The plane does the rest, per tap (`tap_reference_ndc`); this is the margin for
            // depth precision.
            return params.bias;
        }
        case BIAS_ADAPTIVE: {
            // Seed 000: A = (1 + ceil(R)) * W / (2 * map_size) is half a texel in world units,
            // grown with the filter; B = 1 - N.L; bias = c * max(A, A * B). As published,
            // max(A, A*B) is A wherever the light reaches (N.L >= 0, so B <= 1): texel-aware,
            // not slope-aware.
            let a = (1.0 + ceil(filter_radius_texels)) * 0.5 * texel_world_at(light, coord.depth_linear);
            let b = 1.0 - coord.n_dot_l;
            let bias_world = params.adaptive_c * max(a, a * b);
            return bias_world * ndc_per_world(light, coord.depth_linear);
        }
        default: {
            return 0.0;
        }
    }
}

// Written as "not inside" so that NaN (a point in a spot light's own plane) counts as outside.
fn outside_map(uv: vec2<f32>) -> bool {
    return !(all(uv >= vec2<f32>(0.0)) && all(uv <= vec2<f32>(1.0)));
}

fn outside_depth(z: f32) -> bool {
    return !(z >= 0.0 && z <= 1.0);
}

// The receiver has no shadow-map data: outside the map or past its depth range.
fn outside_frustum(coord: ShadowCoord) -> bool {
    return outside_map(coord.uv) || outside_depth(coord.depth_ndc);
}

// The GAMES202 framework's RGBA8 depth: `pack` splits the depth over the four 8-bit channels of
// a colour target, which keeps each as round(255 v) / 255 like any RGBA8 target, and `unpack`
// sums them back. Without three.js's 256/255 correction the round trip is off by up to about
// 1/255: too far below half the depth range, too near above it. Texels nothing was drawn to hold
// the clear colour, white: unpack(1, 1, 1, 1).
fn rgba8_round_trip(depth_ndc: f32) -> f32 {
    if depth_ndc >= 1.0 {
        return ((1.0 + 1.0 / 256.0) + 1.0 / 65536.0) + 1.0 / 16777216.0;
    }
    // pack: fract(depth * (1, 256, 256², 256³)), each channel less the next one's share.
    let scaled = fract(depth_ndc * vec4<f32>(1.0, 256.0, 65536.0, 16777216.0));
    let next = vec4<f32>(scaled.y, scaled.z, scaled.w, 0.0);
    let rgba = scaled - next * (1.0 / 256.0);
    // The RGBA8 target keeps round(255 v) of each channel.
    let stored = round(saturate(rgba) * 255.0) * (1.0 / 255.0);
    // unpack: dot with (1, 1/256, 1/256², 1/256³), summed in order.
    let parts = stored * vec4<f32>(1.0, 1.0 / 256.0, 1.0 / 65536.0, 1.0 / 16777216.0);
    return ((parts.x + parts.y) + parts.z) + parts.w;
}

// Stored depth at a uv, point-sampled. Without clamping the lookup wraps, the classic bug.
fn stored_depth_ndc(light: LightGpu, uv: vec2<f32>) -> f32 {
    var lookup = uv;
    if clamp_outside() == 0u {
        lookup = fract(uv);
    }
    let size = i32(light.map_size_texels);
    let texel = clamp(vec2<i32>(floor(lookup * light.map_size_texels)), vec2<i32>(0), vec2<i32>(size - 1));
    let depth = textureLoad(shadow_maps, texel, i32(light.layer), 0);
    if depth_storage() == DEPTH_RGBA8 {
        return rgba8_round_trip(depth);
    }
    return depth;
}

// The depth a tap at `uv` compares the map's with: the receiver's, less the bias. With the
// receiver-plane bias it is the receiver's plane at the centre of the texel the tap reads (where
// that texel's depth was rendered), so a flat receiver never shadows itself however far the tap
// lands from the pixel; a bilinear tap of the sampler (not `point_sampled`) uses the plane at the
// tap itself.
fn tap_reference_ndc(
    light: LightGpu,
    coord: ShadowCoord,
    uv: vec2<f32>,
    bias_ndc: f32,
    point_sampled: bool,
) -> f32 {
    if bias_mode() == BIAS_RECEIVER_PLANE {
        var at = uv;
        if point_sampled {
            at = (floor(uv * light.map_size_texels) + 0.5) / light.map_size_texels;
        }
        return coord.depth_ndc + dot(coord.depth_gradient, at - coord.uv) - bias_ndc;
    }
    return coord.depth_ndc - bias_ndc;
}

// 1 = lit, 0 = shadowed, for one tap. Outside the light frustum counts as lit when clamped.
fn depth_test(light: LightGpu, coord: ShadowCoord, uv: vec2<f32>, bias_ndc: f32) -> f32 {
    if clamp_outside() == 1u && (outside_map(uv) || outside_depth(coord.depth_ndc)) {
        return 1.0;
    }
    let bilinear = kernel() == KERNEL_HARDWARE && technique() != TECHNIQUE_HARD;
    let reference = tap_reference_ndc(light, coord, uv, bias_ndc, !bilinear);
    if bilinear {
        var lookup = uv;
        if clamp_outside() == 0u {
            lookup = fract(uv);
        }
        // Bilinear 2x2 comparison in the sampler (LessEqual: lit where reference <= stored).
        return textureSampleCompareLevel(shadow_maps, shadow_compare_sampler, lookup * light.atlas_scale,
                                         i32(light.layer), reference);
    }
    return select(0.0, 1.0, reference <= stored_depth_ndc(light, uv));
}

// ---------------------------------------------------------------- sample patterns

// floor(sqrt(n)) made exact: WGSL's sqrt need not be correctly rounded (9 -> 2.9999998).
fn grid_side(n: u32) -> u32 {
    var side = u32(sqrt(f32(n)) + 0.5);
    if side * side > n {
        side -= 1u;
    }
    return max(1u, side);
}

// An angle brought into [-pi, pi], where WGSL's sin and cos have their stated accuracy.
fn wrap_angle(a: f32) -> f32 {
    return a - TAU * floor(a / TAU + 0.5);
}

// The pixel's rotation of the pattern, as (cos, sin) of TAU * unit_float(seed): one sin and
// one cos per pixel, not per tap.
fn pixel_rotation(seed: u32) -> vec2<f32> {
    let angle = wrap_angle(TAU * unit_float(seed));
    return vec2<f32>(cos(angle), sin(angle));
}

fn rotate_by(p: vec2<f32>, rotation: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(rotation.x * p.x - rotation.y * p.y, rotation.y * p.x + rotation.x * p.y);
}

// Tap i of n in the unit disk. The patterns are computed once on the CPU into `kernel_table`
// (src/shadow/kernels.rs, `kernel_base`, which the CPU twin uses too) and turned by the pixel's
// rotation here:
//   poisson (GAMES202 poissonDiskSamples): angle i * TAU * 10 / n (NUM_RINGS = 10), radius ((i+1)/n)^0.75;
//   vogel: angle i * GOLDEN_ANGLE, radius sqrt((i + 0.5) / n);
//   grid: side x side points over [-1, 1]^2, not turned (LearnOpenGL's 3x3 is side = 3 with a radius of
//   one texel: offsets -1, 0, 1).
// `table_start` is FILTER_TABLE or SEARCH_TABLE.
fn kernel_offset(kernel: u32, table_start: u32, i: u32, seed: u32, rotation: vec2<f32>) -> vec2<f32> {
    if kernel == KERNEL_UNIFORM {
        // GAMES202 uniformDiskSamples: (cos 2 pi x, sin 2 pi x) * sqrt(y), new random points per
        // pixel, so there is no table to turn.
        let h = pcg_hash(seed ^ pcg_hash(i + 1u));
        let x = unit_float(h);
        let y = unit_float(pcg_hash(h));
        return vec2<f32>(cos(TAU * x), sin(TAU * x)) * sqrt(y);
    }
    let taps = kernel_table[i];
    let tap = select(taps.xy, taps.zw, table_start == SEARCH_TABLE);
    if kernel == KERNEL_GRID {
        // LearnOpenGL's regular grid: axis-aligned texel offsets, never turned.
        return tap;
    }
    return rotate_by(tap, rotation);
}

fn filter_taps(kernel: u32, samples: u32) -> u32 {
    if kernel == KERNEL_GRID {
        let side = grid_side(samples);
        return side * side;
    }
    return samples;
}

// ---------------------------------------------------------------- how to filter

// Hard shadow: one depth comparison.
fn visibility_hard(light: LightGpu, coord: ShadowCoord) -> f32 {
    let bias = receiver_bias_ndc(light, coord, 0.0);
    if clamp_outside() == 1u && outside_frustum(coord) {
        return 1.0;
    }
    let reference = tap_reference_ndc(light, coord, coord.uv, bias, true);
    return select(0.0, 1.0, reference <= stored_depth_ndc(light, coord.uv));
}

// PCF: V = (1/N) sum_i [d_receiver - bias <= map(uv + r * s_i)], r in uv = radius_texels / map_size.
fn visibility_pcf(light: LightGpu, coord: ShadowCoord, radius_texels: f32, seed: u32) -> f32 {
    let n = filter_taps(kernel(), params.samples);
    let radius_uv = radius_texels / light.map_size_texels;
    let bias = receiver_bias_ndc(light, coord, radius_texels);
    let rotation = pixel_rotation(seed);
    var lit = 0.0;
    for (var i = 0u; i < n; i++) {
        let uv = coord.uv + kernel_offset(kernel(), FILTER_TABLE, i, seed, rotation) * radius_uv;
        lit += depth_test(light, coord, uv, bias);
    }
    return lit / f32(n);
}

struct BlockerSearch {
    radius_texels: f32,       // search radius on the map
    found: u32,               // taps closer to the light than the receiver
    avg_depth_linear: f32,    // d_blocker, world units (0 when none found)
}

// The blocker search's radius in uv: the cone from the receiver to the light's area, cut at
// the near plane, times `search_radius_scale`.
fn blocker_search_radius_uv(light: LightGpu, coord: ShadowCoord) -> f32 {
    let d_r = coord.depth_linear;
    var radius_world = 0.0;
    if is_angular(light) {
        radius_world = (d_r - light.near) * light.tan_half_angle;
    } else {
        radius_world = 0.5 * light.light_width_world * (d_r - light.near) / d_r;
    }
    return max(radius_world, 0.0) * params.search_radius_scale / light.frustum_width_world;
}

fn blocker_search_radius_texels(light: LightGpu, coord: ShadowCoord) -> f32 {
    return blocker_search_radius_uv(light, coord) * light.map_size_texels;
}

// PCSS step 1: blocker search. The region is the cone from the receiver to the light's area,
// cut at the near plane (NVIDIA: w_search = w_light * (d_r - near) / d_r, in uv / W_near).
fn search_blockers(light: LightGpu, coord: ShadowCoord, seed: u32) -> BlockerSearch {
    var out: BlockerSearch;
    // No map data for this receiver: nothing to search (and nothing to report).
    if clamp_outside() == 1u && outside_frustum(coord) {
        return out;
    }
    let radius_uv = blocker_search_radius_uv(light, coord);
    out.radius_texels = radius_uv * light.map_size_texels;
    let search_kernel = select(kernel(), KERNEL_VOGEL, kernel() == KERNEL_HARDWARE);
    let n = filter_taps(search_kernel, params.blocker_samples);
    let bias = receiver_bias_ndc(light, coord, 0.0);
    let rotation = pixel_rotation(seed);
    var sum = 0.0;
    for (var i = 0u; i < n; i++) {
        let uv = coord.uv + kernel_offset(search_kernel, SEARCH_TABLE, i, seed, rotation) * radius_uv;
        if clamp_outside() == 1u && outside_map(uv) {
            continue;
        }
        let z = stored_depth_ndc(light, uv);
        if z < tap_reference_ndc(light, coord, uv, bias, true) {
            out.found += 1u;
            sum += depth_linear_from_ndc(light, z);
        }
    }
    if out.found > 0u {
        out.avg_depth_linear = sum / f32(out.found);
    }
    return out;
}

struct Penumbra {
    width_world: f32,            // on the receiver
    filter_radius_texels: f32,   // half the width, mapped to the shadow map
}

// PCSS step 2: penumbra by similar triangles (Fernando 2005).
// Width model: w_p = w_light * (d_r - d_b) / d_b. Angular model: w_p = (d_r - d_b) * 2 tan(theta/2).
// The filter radius is half the penumbra width, mapped to the map: orthographic / W,
// perspective projected to the near plane first (* near / d_r) and then / W_near.
fn estimate_penumbra(light: LightGpu, coord: ShadowCoord, d_blocker: f32) -> Penumbra {
    var out: Penumbra;
    let d_r = coord.depth_linear;
    let gap = max(d_r - d_blocker, 0.0);
    if is_angular(light) {
        out.width_world = gap * 2.0 * light.tan_half_angle;
    } else {
        out.width_world = light.light_width_world * gap / max(d_blocker, 1e-6);
    }
    var radius_uv = 0.5 * out.width_world / light.frustum_width_world;
    if !is_orthographic(light) || params.ortho_near_factor == 1u {
        radius_uv = radius_uv * light.near / d_r;
    }
    out.filter_radius_texels = max(radius_uv * light.map_size_texels, params.min_filter_radius_texels);
    return out;
}

struct PcssResult {
    visibility: f32,
    search: BlockerSearch,
    penumbra: Penumbra,
}

// PCSS step 3: filter with the estimated radius. No blockers: fully lit (saves the filter).
fn visibility_pcss(light: LightGpu, coord: ShadowCoord, seed: u32) -> PcssResult {
    var out: PcssResult;
    out.search = search_blockers(light, coord, seed);
    if out.search.found == 0u {
        out.visibility = 1.0;
        return out;
    }
    out.penumbra = estimate_penumbra(light, coord, out.search.avg_depth_linear);
    out.visibility = visibility_pcf(light, coord, out.penumbra.filter_radius_texels, seed);
    return out;
}

// ---------------------------------------------------------------- variance shadow maps

// Mean depth and mean squared depth around uv for a filter of radius r map texels: the moments
// at the (fractional) level whose texels span r map texels (level 0 spans `moments_block` map
// texels, each level twice the one before), bilinear within the two nearest levels and linear
// between them; a tent about as wide as the disk PCF uses, without seams where the level changes.
fn filtered_moments(light: LightGpu, uv: vec2<f32>, radius_texels: f32) -> vec2<f32> {
    let widest = f32(textureNumLevels(moments) - 1u);
    let level = clamp(log2(max(radius_texels / f32(light.moments_block), 1.0)), 0.0, widest);
    let finer = floor(level);
    let coarser = min(finer + 1.0, widest);
    return mix(moments_at_level(light, uv, finer), moments_at_level(light, uv, coarser), level - finer);
}

// The moments at one level, bilinear between its four texels nearest to uv.
fn moments_at_level(light: LightGpu, uv: vec2<f32>, level_f: f32) -> vec2<f32> {
    let level = i32(level_f);
    let texel_span = f32(light.moments_block) * exp2(level_f);
    let p = uv * light.map_size_texels / texel_span - 0.5;
    let i0 = vec2<i32>(floor(p));
    let f = p - floor(p);
    let last = vec2<i32>(textureDimensions(moments, level)) - 1;
    let layer = i32(light.layer);
    let m00 = textureLoad(moments, clamp(i0, vec2<i32>(0), last), layer, level).xy;
    let m10 = textureLoad(moments, clamp(i0 + vec2<i32>(1, 0), vec2<i32>(0), last), layer, level).xy;
    let m01 = textureLoad(moments, clamp(i0 + vec2<i32>(0, 1), vec2<i32>(0), last), layer, level).xy;
    let m11 = textureLoad(moments, clamp(i0 + vec2<i32>(1, 1), vec2<i32>(0), last), layer, level).xy;
    let top = m00 * (1.0 - f.x) + m10 * f.x;
    let bottom = m01 * (1.0 - f.x) + m11 * f.x;
    return top * (1.0 - f.y) + bottom * f.y;
}

// VSM (Donnelly & Lauritzen 2006): with mean mu and variance sigma² of the depths around the
// lookup, Chebyshev's one-sided bound P(depth >= t) <= sigma² / (sigma² + (t - mu)²) for t > mu
// is taken as the lit fraction; t <= mu is lit.
fn visibility_vsm(light: LightGpu, coord: ShadowCoord, radius_texels: f32) -> f32 {
    if clamp_outside() == 1u && outside_frustum(coord) {
        return 1.0;
    }
    let m = filtered_moments(light, coord.uv, radius_texels);
    let t = coord.depth_ndc - receiver_bias_ndc(light, coord, radius_texels);
    return reduce_light_bleeding(chebyshev_upper_bound(m, t));
}

// Light-bleeding reduction (Lauritzen, GPU Gems 3 ch. 8): bounds up to a are taken as shadow
// and the rest stretched back over 0..1. Removes the bleeding where the bound stays below a,
// and darkens real penumbrae a little too.
fn reduce_light_bleeding(p: f32) -> f32 {
    let a = params.vsm_bleed_reduction;
    return clamp((p - a) / (1.0 - a), 0.0, 1.0);
}

// P(depth >= t) <= sigma² / (sigma² + (t - mu)²) for t > mu; 1 for t <= mu.
fn chebyshev_upper_bound(m: vec2<f32>, t: f32) -> f32 {
    if t <= m.x {
        return 1.0;
    }
    let variance = max(m.y - m.x * m.x, params.vsm_min_variance);
    let d = t - m.x;
    return variance / (variance + d * d);
}

// VSSM (Yang et al. 2010): over PCSS's search region, the moments give the mean depth z_avg
// and Chebyshev's bound P of the unoccluded share; with the unoccluded depths taken as the
// receiver's, z_avg = P t + (1 - P) z_occ gives z_occ = (z_avg - P t) / (1 - P), the average
// blocker depth (NDC, then linear). Then PCSS's similar triangles, and a VSM filter of half the
// penumbra. `found` is 1 where blockers were estimated (the count has no meaning here).
fn visibility_vssm(light: LightGpu, coord: ShadowCoord) -> PcssResult {
    var out: PcssResult;
    out.visibility = 1.0;
    if clamp_outside() == 1u && outside_frustum(coord) {
        return out;
    }
    out.search.radius_texels = blocker_search_radius_texels(light, coord);
    let m = filtered_moments(light, coord.uv, out.search.radius_texels);
    let t = coord.depth_ndc - receiver_bias_ndc(light, coord, 0.0);
    let unoccluded = chebyshev_upper_bound(m, t);
    if unoccluded >= 1.0 {
        return out;
    }
    let z_occ = (m.x - unoccluded * t) / (1.0 - unoccluded);
    out.search.found = 1u;
    out.search.avg_depth_linear = depth_linear_from_ndc(light, clamp(z_occ, 0.0, 1.0));
    out.penumbra = estimate_penumbra(light, coord, out.search.avg_depth_linear);
    out.visibility = visibility_vsm(light, coord, out.penumbra.filter_radius_texels);
    return out;
}

// The selected technique, with PCSS's intermediate values for the debug views.
fn shadow_visibility(light: LightGpu, coord: ShadowCoord, seed: u32) -> PcssResult {
    var out: PcssResult;
    switch technique() {
        case TECHNIQUE_PCF: {
            out.visibility = visibility_pcf(light, coord, params.radius_texels, seed);
        }
        case TECHNIQUE_PCSS: {
            out = visibility_pcss(light, coord, seed);
        }
        case TECHNIQUE_NONE: {
            out.visibility = 1.0;
        }
        case TECHNIQUE_VSM: {
            out.visibility = visibility_vsm(light, coord, params.radius_texels);
        }
        case TECHNIQUE_VSSM: {
            out = visibility_vssm(light, coord);
        }
        default: {
            out.visibility = visibility_hard(light, coord);
        }
    }
    return out;
}

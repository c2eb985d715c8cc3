// How to filter: the sample patterns, then hard shadows, PCF with five kernels, PCSS in three
// steps, VSM and VSSM, on the taps shaders/shadow_lookup.wgsl defines. The CPU twin in
// src/shadow/ (mod.rs, kernels.rs, vsm.rs) has the same functions with the same names; fix a
// formula in both.
//
// Units: `depth_ndc` is what the map stores (0..1); `depth_linear` is world units from the light
// along its axis (a cube face: the straight distance to the light); `_uv` is shadow-map uv (0..1
// over the shadow view's map); `_texels` is map texels.

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
//   poisson (poissonDiskSamples [GAMES202-HW1]): angle i * TAU * 10 / n (NUM_RINGS = 10),
//     radius ((i+1)/n)^0.75;
//   vogel [Vogel-1979]: angle i * GOLDEN_ANGLE, radius sqrt((i + 0.5) / n);
//   grid: side x side points over [-1, 1]^2, not turned (the 3x3 of [LearnOpenGL-ShadowMapping] is
//     side = 3 with a radius of one texel: offsets -1, 0, 1).
// `table_start` is FILTER_TABLE or SEARCH_TABLE.
fn kernel_offset(kernel: u32, table_start: u32, i: u32, seed: u32, rotation: vec2<f32>) -> vec2<f32> {
    if kernel == KERNEL_UNIFORM {
        // uniformDiskSamples [GAMES202-HW1]: (cos 2 pi x, sin 2 pi x) * sqrt(y), new random
        // points per pixel, so there is no table to turn.
        let h = pcg_hash(seed ^ pcg_hash(i + 1u));
        let x = unit_float(h);
        let y = unit_float(pcg_hash(h));
        return vec2<f32>(cos(TAU * x), sin(TAU * x)) * sqrt(y);
    }
    let taps = kernel_table[i];
    let tap = select(taps.xy, taps.zw, table_start == SEARCH_TABLE);
    if kernel == KERNEL_GRID {
        // The regular grid [LearnOpenGL-ShadowMapping]: axis-aligned texel offsets, never turned.
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

// Hard shadow: one depth comparison [Williams-1978].
fn visibility_hard(view: ShadowViewGpu, coord: ShadowCoord) -> f32 {
    let bias = receiver_bias_ndc(view, coord, 0.0);
    let tap = map_tap(view, coord.uv);
    if clamp_outside() == 1u && (no_map_data(view, coord) || outside_map(tap.uv)) {
        return 1.0;
    }
    let reference = tap_reference_ndc(view, coord, coord.uv, bias, true);
    return select(0.0, 1.0, reference <= stored_depth_ndc(tap.view, tap.uv));
}

// PCF [Reeves-1987]: V = (1/N) sum_i [d_receiver - bias <= map(uv + r * s_i)],
// r in uv = radius_texels / map_size.
fn visibility_pcf(view: ShadowViewGpu, coord: ShadowCoord, radius_texels: f32, seed: u32) -> f32 {
    let n = filter_taps(kernel(), params.samples);
    let radius_uv = radius_texels / view.map_size_texels;
    let bias = receiver_bias_ndc(view, coord, radius_texels);
    let rotation = pixel_rotation(seed);
    var lit = 0.0;
    for (var i = 0u; i < n; i++) {
        let uv = coord.uv + kernel_offset(kernel(), FILTER_TABLE, i, seed, rotation) * radius_uv;
        lit += depth_test(view, coord, uv, bias);
    }
    return lit / f32(n);
}

struct BlockerSearch {
    radius_texels: f32,       // search radius on the map
    found: u32,               // taps closer to the light than the receiver
    avg_depth_linear: f32,    // d_blocker, world units (0 when none found)
}

// The blocker search's radius in uv: the cone from the receiver to the light's area, cut at
// the near plane, times `search_radius_scale`. On a cube face off its axis, times sec²(theta),
// the disk around the region's ellipse in uv (`off_axis_sec`, shaders/shadow_lookup.wgsl).
fn blocker_search_radius_uv(light: LightGpu, view: ShadowViewGpu, coord: ShadowCoord) -> f32 {
    let d_r = coord.depth_linear;
    var radius_world = 0.0;
    if is_angular(light) {
        radius_world = (d_r - view.near) * light.tan_half_angle;
    } else {
        radius_world = 0.5 * light.light_width_world * (d_r - view.near) / d_r;
    }
    let sec = off_axis_sec(view, coord.uv);
    return max(radius_world, 0.0) * params.search_radius_scale * sec * sec / view.frustum_width_world;
}

fn blocker_search_radius_texels(light: LightGpu, view: ShadowViewGpu, coord: ShadowCoord) -> f32 {
    return blocker_search_radius_uv(light, view, coord) * view.map_size_texels;
}

// PCSS step 1: blocker search. The region is the cone from the receiver to the light's area,
// cut at the near plane: w_search = w_light * (d_r - near) / d_r, in uv / W_near [NVIDIA-2008].
fn search_blockers(light: LightGpu, view: ShadowViewGpu, coord: ShadowCoord, seed: u32) -> BlockerSearch {
    var out: BlockerSearch;
    // No map data for this receiver: nothing to search (and nothing to report).
    if clamp_outside() == 1u && no_map_data(view, coord) {
        return out;
    }
    let radius_uv = blocker_search_radius_uv(light, view, coord);
    out.radius_texels = radius_uv * view.map_size_texels;
    let search_kernel = select(kernel(), KERNEL_VOGEL, kernel() == KERNEL_HARDWARE);
    let n = filter_taps(search_kernel, params.blocker_samples);
    let bias = receiver_bias_ndc(view, coord, 0.0);
    let rotation = pixel_rotation(seed);
    var sum = 0.0;
    for (var i = 0u; i < n; i++) {
        let uv = coord.uv + kernel_offset(search_kernel, SEARCH_TABLE, i, seed, rotation) * radius_uv;
        let tap = map_tap(view, uv);
        if clamp_outside() == 1u && outside_map(tap.uv) {
            continue;
        }
        let z = stored_depth_ndc(tap.view, tap.uv);
        if z < tap_reference_ndc(view, coord, uv, bias, true) {
            out.found += 1u;
            sum += depth_linear_from_ndc(view, z);
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

// PCSS step 2: penumbra by similar triangles [Fernando-2005].
// Width model: w_p = w_light * (d_r - d_b) / d_b. Angular model: w_p = (d_r - d_b) * 2 tan(theta/2).
// The filter radius is half the penumbra width, mapped to the map: orthographic / W,
// perspective projected to the near plane first (* near / d_r) and then / W_near; on a cube face
// off its axis, times sec^1.5(theta), the disk of the width's ellipse in uv (`off_axis_sec`).
fn estimate_penumbra(light: LightGpu, view: ShadowViewGpu, coord: ShadowCoord, d_blocker: f32) -> Penumbra {
    var out: Penumbra;
    let d_r = coord.depth_linear;
    let gap = max(d_r - d_blocker, 0.0);
    if is_angular(light) {
        out.width_world = gap * 2.0 * light.tan_half_angle;
    } else {
        out.width_world = light.light_width_world * gap / max(d_blocker, 1e-6);
    }
    var radius_uv = 0.5 * out.width_world / view.frustum_width_world;
    if !is_orthographic(view) || params.ortho_near_factor == 1u {
        radius_uv = radius_uv * view.near / d_r;
    }
    let sec = off_axis_sec(view, coord.uv);
    radius_uv = radius_uv * sec * sqrt(sec);
    out.filter_radius_texels = max(radius_uv * view.map_size_texels, params.min_filter_radius_texels);
    return out;
}

struct ShadowVisibility {
    visibility: f32,
    search: BlockerSearch,
    penumbra: Penumbra,
}

// PCSS step 3: filter with the estimated radius. No blockers: fully lit (saves the filter).
fn visibility_pcss(light: LightGpu, view: ShadowViewGpu, coord: ShadowCoord, seed: u32) -> ShadowVisibility {
    var out: ShadowVisibility;
    out.search = search_blockers(light, view, coord, seed);
    if out.search.found == 0u {
        out.visibility = 1.0;
        return out;
    }
    out.penumbra = estimate_penumbra(light, view, coord, out.search.avg_depth_linear);
    out.visibility = visibility_pcf(view, coord, out.penumbra.filter_radius_texels, seed);
    return out;
}

// ---------------------------------------------------------------- variance shadow maps

// Mean depth and mean squared depth around uv for a filter of radius r map texels: the moments
// at the (fractional) level whose texels span r map texels (level 0 spans `moments_block` map
// texels, each level twice the one before), bilinear within the two nearest levels and linear
// between them; a tent about as wide as the disk PCF uses, without seams where the level changes.
fn filtered_moments(view: ShadowViewGpu, uv: vec2<f32>, radius_texels: f32) -> vec2<f32> {
    let widest = f32(textureNumLevels(moments) - 1u);
    let level = clamp(log2(max(radius_texels / f32(view.moments_block), 1.0)), 0.0, widest);
    let finer = floor(level);
    let coarser = min(finer + 1.0, widest);
    return mix(moments_at_level(view, uv, finer), moments_at_level(view, uv, coarser), level - finer);
}

// The moments at one level, bilinear between its four texels nearest to uv.
fn moments_at_level(view: ShadowViewGpu, uv: vec2<f32>, level_f: f32) -> vec2<f32> {
    let level = i32(level_f);
    let texel_span = f32(view.moments_block) * exp2(level_f);
    let p = uv * view.map_size_texels / texel_span - 0.5;
    let i0 = vec2<i32>(floor(p));
    let f = p - floor(p);
    let last = vec2<i32>(textureDimensions(moments, level)) - 1;
    let layer = i32(view.layer);
    let m00 = textureLoad(moments, clamp(i0, vec2<i32>(0), last), layer, level).xy;
    let m10 = textureLoad(moments, clamp(i0 + vec2<i32>(1, 0), vec2<i32>(0), last), layer, level).xy;
    let m01 = textureLoad(moments, clamp(i0 + vec2<i32>(0, 1), vec2<i32>(0), last), layer, level).xy;
    let m11 = textureLoad(moments, clamp(i0 + vec2<i32>(1, 1), vec2<i32>(0), last), layer, level).xy;
    let top = m00 * (1.0 - f.x) + m10 * f.x;
    let bottom = m01 * (1.0 - f.x) + m11 * f.x;
    return top * (1.0 - f.y) + bottom * f.y;
}

// VSM [Donnelly-2006]: with mean mu and variance sigma² of the depths around the
// lookup, Chebyshev's one-sided bound P(depth >= t) <= sigma² / (sigma² + (t - mu)²) for t > mu
// is taken as the lit fraction; t <= mu is lit.
fn visibility_vsm(view: ShadowViewGpu, coord: ShadowCoord, radius_texels: f32) -> f32 {
    if clamp_outside() == 1u && no_map_data(view, coord) {
        return 1.0;
    }
    let m = filtered_moments(view, coord.uv, radius_texels);
    let t = coord.depth_ndc - receiver_bias_ndc(view, coord, radius_texels);
    return reduce_light_bleeding(chebyshev_upper_bound(m, t));
}

// Light-bleeding reduction [Lauritzen-2007]: bounds up to a are taken as shadow
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

// VSSM [Yang-2010]: over PCSS's search region, the moments give the mean depth z_avg
// and Chebyshev's bound P of the unoccluded share; with the unoccluded depths taken as the
// receiver's, z_avg = P t + (1 - P) z_occ gives z_occ = (z_avg - P t) / (1 - P), the average
// blocker depth (NDC, then linear). Then PCSS's similar triangles, and a VSM filter of half the
// penumbra. `found` is 1 where blockers were estimated (the count has no meaning here).
fn visibility_vssm(light: LightGpu, view: ShadowViewGpu, coord: ShadowCoord) -> ShadowVisibility {
    var out: ShadowVisibility;
    out.visibility = 1.0;
    if clamp_outside() == 1u && no_map_data(view, coord) {
        return out;
    }
    out.search.radius_texels = blocker_search_radius_texels(light, view, coord);
    let m = filtered_moments(view, coord.uv, out.search.radius_texels);
    let t = coord.depth_ndc - receiver_bias_ndc(view, coord, 0.0);
    let unoccluded = chebyshev_upper_bound(m, t);
    if unoccluded >= 1.0 {
        return out;
    }
    let z_occ = (m.x - unoccluded * t) / (1.0 - unoccluded);
    out.search.found = 1u;
    out.search.avg_depth_linear = depth_linear_from_ndc(view, clamp(z_occ, 0.0, 1.0));
    out.penumbra = estimate_penumbra(light, view, coord, out.search.avg_depth_linear);
    out.visibility = visibility_vsm(view, coord, out.penumbra.filter_radius_texels);
    return out;
}

// What `shadow_visibility` returns for a technique id it does not know (mirrors the twin's).
const VISIBILITY_UNKNOWN_TECHNIQUE: f32 = -1.0;

// The selected technique, with PCSS's intermediate values for the debug views.
fn shadow_visibility(light: LightGpu, view: ShadowViewGpu, coord: ShadowCoord, seed: u32) -> ShadowVisibility {
    var out: ShadowVisibility;
    switch technique() {
        case TECHNIQUE_PCF: {
            out.visibility = visibility_pcf(view, coord, params.radius_texels, seed);
        }
        case TECHNIQUE_PCSS: {
            out = visibility_pcss(light, view, coord, seed);
        }
        case TECHNIQUE_NONE: {
            out.visibility = 1.0;
        }
        case TECHNIQUE_VSM: {
            out.visibility = visibility_vsm(view, coord, params.radius_texels);
        }
        case TECHNIQUE_VSSM: {
            out = visibility_vssm(light, view, coord);
        }
        case TECHNIQUE_HARD: {
            out.visibility = visibility_hard(view, coord);
        }
        // An id no case knows is an impossible visibility that the GPU = twin test and the
        // views show, never a quiet hard shadow.
        default: {
            out.visibility = VISIBILITY_UNKNOWN_TECHNIQUE;
        }
    }
    return out;
}

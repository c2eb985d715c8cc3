// What to sample: where a surface point lands in a shadow view's map (light-space lookup, normal
// offset), at which depth, with which bias, and one tap's depth test. How to filter those taps is
// shaders/shadow_filter.wgsl. The CPU twin's src/shadow/light_space.rs has the same functions with
// the same names; fix a formula in both.
//
// Units: `depth_ndc` is what the map stores (0..1); `depth_linear` is world units from the light
// along its axis (a cube face: the straight distance to the light); `_uv` is shadow-map uv (0..1
// over the shadow view's map); `_texels` is map texels.
// `technique()`, `kernel()`, `bias_mode()` and the like are shaders/specialisation.wgsl's.

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

// ---------------------------------------------------------------- what to sample

struct ShadowCoord {
    uv: vec2<f32>,          // wgpu: uv = ndc.xy * (0.5, -0.5) + 0.5 [WebGPU-Coordinates]
    depth_ndc: f32,         // receiver depth as the map would store it
    depth_linear: f32,      // receiver distance from the light, world units
    n_dot_l: f32,
    // Receiver-plane bias only (else 0): the receiver's plane in the map, as NDC depth per uv,
    // so that the plane's depth at uv + delta is depth_ndc + dot(depth_gradient, delta).
    depth_gradient: vec2<f32>,
}

// A cube face stores (distance - near) / (far - near): linear, like an orthographic map.
fn stores_linear_depth(view: ShadowViewGpu) -> bool {
    return is_orthographic(view) || is_cube(view);
}

fn depth_linear_from_ndc(view: ShadowViewGpu, z: f32) -> f32 {
    if stores_linear_depth(view) {
        return view.near + z * (view.far - view.near);
    }
    return view.near * view.far / (view.far - z * (view.far - view.near));
}

// dz/dd at distance d: turns a world-unit bias into NDC depth units.
fn ndc_per_world(view: ShadowViewGpu, depth_linear: f32) -> f32 {
    if stores_linear_depth(view) {
        return 1.0 / (view.far - view.near);
    }
    return view.far * view.near / (depth_linear * depth_linear * (view.far - view.near));
}

// A cube face off its axis. The direction at angle theta from the face's axis lands at
// |uv - 0.5| = 0.5 tan(theta) / tan_half_fov; a small angle delta (radians; delta = w / d for a
// width w in world units across the ray at straight distance d) moves uv by
// 0.5 sec²(theta) delta / tan_half_fov radially (away from the face's centre) and
// 0.5 sec(theta) delta / tan_half_fov tangentially: the centre's uv per world unit,
// 0.5 / (d tan_half_fov), times sec² and sec (at the middle of an edge 2 and 1.41, at a corner 3
// and 1.73). A width becomes an ellipse in uv; the filters are disks, so each takes one radius:
// the blocker search, a region to cover, the disk around the ellipse (sec²); a filter and a
// texel's footprint, widths, the disk of the ellipse's area (sec^1.5), at most sec^0.5 off the
// width along either axis (19% at the middle of an edge, 32% at a corner).
// A spot light needs none of it: its light is a disk facing along its axis and its depths are
// along that axis, so its similar triangles hold in planes parallel to the map, which the
// projection takes to uv linearly, at any angle off the axis.
// This returns sec(theta) for the direction that lands at `uv` of a cube face; 1 for any other view.
fn off_axis_sec(view: ShadowViewGpu, uv: vec2<f32>) -> f32 {
    if !is_cube(view) {
        return 1.0;
    }
    let tan_theta = (2.0 * uv - vec2<f32>(1.0)) * view.tan_half_fov;
    return sqrt(1.0 + dot(tan_theta, tan_theta));
}

// One texel's footprint at `uv`, world units, on a surface at `depth_linear`: orthographic, the
// map's texel; a spot light, on a plane parallel to the map (2 d tan_half_fov / N); a cube face,
// across the ray at straight distance d, the disk of the texel's area: 2 d tan_half_fov / N
// divided by sec^1.5(theta) (`off_axis_sec`).
fn texel_world_at(view: ShadowViewGpu, depth_linear: f32, uv: vec2<f32>) -> f32 {
    if is_orthographic(view) {
        return view.frustum_width_world / view.map_size_texels;
    }
    let sec = off_axis_sec(view, uv);
    return 2.0 * depth_linear * view.tan_half_fov / (view.map_size_texels * sec * sqrt(sec));
}

// The largest footprint a texel has at `depth_linear`, world units: at the map's centre
// (`texel_world_at` shrinks off a cube face's axis). The normal offset and the adaptive bias take
// it: they have to cover a texel's depth error, footprint times the receiver's slope, and neither
// follows the slope; off a face's axis, where a room's floor and walls meet the lamp at grazing
// angles, the true footprint lets acne through.
fn texel_world_bound(view: ShadowViewGpu, depth_linear: f32) -> f32 {
    return texel_world_at(view, depth_linear, vec2<f32>(0.5));
}

fn light_dir_to(light: LightGpu, world_pos: vec3<f32>) -> vec3<f32> {
    if is_directional(light) {
        return -light.direction.xyz;
    }
    return normalize(light.position.xyz - world_pos);
}

// ---------------------------------------------------------------- cube faces

// Face `face`'s axes as columns (forward, up, right = forward x up): src/scene/light.rs's
// CUBE_FACES.
fn cube_face_axes(face: u32) -> mat3x3<f32> {
    switch face {
        case 0u: { return mat3x3<f32>(vec3<f32>(1.0, 0.0, 0.0), vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(0.0, 0.0, 1.0)); }
        case 1u: { return mat3x3<f32>(vec3<f32>(-1.0, 0.0, 0.0), vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(0.0, 0.0, -1.0)); }
        case 2u: { return mat3x3<f32>(vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(0.0, 0.0, -1.0), vec3<f32>(-1.0, 0.0, 0.0)); }
        case 3u: { return mat3x3<f32>(vec3<f32>(0.0, -1.0, 0.0), vec3<f32>(0.0, 0.0, 1.0), vec3<f32>(-1.0, 0.0, 0.0)); }
        case 4u: { return mat3x3<f32>(vec3<f32>(0.0, 0.0, 1.0), vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(-1.0, 0.0, 0.0)); }
        default: { return mat3x3<f32>(vec3<f32>(0.0, 0.0, -1.0), vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(1.0, 0.0, 0.0)); }
    }
}

// The face a direction from the light falls in: its largest axis, signed (ties: the earlier axis).
fn cube_face_of(direction: vec3<f32>) -> u32 {
    let a = abs(direction);
    if a.x >= a.y && a.x >= a.z {
        return select(0u, 1u, direction.x < 0.0);
    }
    if a.y >= a.z {
        return select(2u, 3u, direction.y < 0.0);
    }
    return select(4u, 5u, direction.z < 0.0);
}

// The same light's view on face `face` (its layer follows; lookups of a cube face read its axes,
// never clip_from_world).
fn cube_face_view(view: ShadowViewGpu, face: u32) -> ShadowViewGpu {
    var out = view;
    out.layer = view.layer - view.face + face;
    out.face = face;
    return out;
}

// The view of a light's maps that covers a point: a cube's face towards it, else the view itself.
fn face_covering(view: ShadowViewGpu, world_pos: vec3<f32>) -> ShadowViewGpu {
    if is_cube(view) {
        return cube_face_view(view, cube_face_of(world_pos - view.origin.xyz));
    }
    return view;
}

// A sun's cascade holds a point landing CASCADE_BORDER_TEXELS inside its map's edge (a filter's
// nearest taps stay on the map).
fn cascade_holds(view: ShadowViewGpu, world_pos: vec3<f32>) -> bool {
    let uv = project_to_light(view, world_pos).xy;
    let border = f32(CASCADE_BORDER_TEXELS) / view.map_size_texels;
    return all(uv >= vec2<f32>(border)) && all(uv <= vec2<f32>(1.0 - border));
}

// A cascade's slice holds a point nearer than its far split along the camera's view axis (the
// nearer slices were tried first): depth = axis . p + w, world units.
fn in_cascade_slice(view: ShadowViewGpu, world_pos: vec3<f32>) -> bool {
    let depth_world = dot(view.view_axis_world.xyz, world_pos) + view.view_axis_world.w;
    return depth_world < view.split_far_world;
}

// Where direction d from the light lands on face `face`'s map (uv; behind the face: outside).
fn cube_face_uv(face: u32, d: vec3<f32>) -> vec2<f32> {
    let axes = cube_face_axes(face);
    let ahead = dot(d, axes[0]);
    if !(ahead > 0.0) {
        return vec2<f32>(-1.0);
    }
    return vec2<f32>(0.5 + 0.5 * dot(d, axes[2]) / ahead, 0.5 - 0.5 * dot(d, axes[1]) / ahead);
}

// A tap of a lookup: which view's map it reads, at which uv.
struct MapTap {
    view: ShadowViewGpu,
    uv: vec2<f32>,
}

// A tap at `uv` of `view`'s map. On a cube face, a tap past the face's edge is a direction from
// the light, read on the face it falls in: a filter crosses the seam instead of stopping there.
fn map_tap(view: ShadowViewGpu, uv: vec2<f32>) -> MapTap {
    if !is_cube(view) || !outside_map(uv) {
        return MapTap(view, uv);
    }
    let axes = cube_face_axes(view.face);
    let d = axes[0] + axes[2] * (2.0 * uv.x - 1.0) + axes[1] * (1.0 - 2.0 * uv.y);
    let face = cube_face_of(d);
    return MapTap(cube_face_view(view, face), clamp(cube_face_uv(face, d), vec2<f32>(0.0), vec2<f32>(1.0)));
}

// The receiver has no map data: outside the view's map or past its depth range. A cube face's
// neighbours hold what lies past its edge, so there only the depth range counts.
fn no_map_data(view: ShadowViewGpu, coord: ShadowCoord) -> bool {
    if is_cube(view) {
        return outside_depth(coord.depth_ndc);
    }
    return outside_frustum(coord);
}

fn project_to_light(view: ShadowViewGpu, world_pos: vec3<f32>) -> vec3<f32> {
    if is_cube(view) {
        let d = world_pos - view.origin.xyz;
        return vec3<f32>(cube_face_uv(view.face, d), (length(d) - view.near) / (view.far - view.near));
    }
    let clip = view.clip_from_world * vec4<f32>(world_pos, 1.0);
    let ndc = clip.xyz / clip.w;
    return vec3<f32>(ndc.xy * vec2<f32>(0.5, -0.5) + vec2<f32>(0.5), ndc.z);
}

// Light-space lookup of a surface point, with the normal offset applied: move along the normal
// by k texels in world units [ThreeJS-NormalBias] [Bevy-DirectionalLight].
fn light_space_lookup(light: LightGpu, view: ShadowViewGpu, world_pos: vec3<f32>, normal: vec3<f32>) -> ShadowCoord {
    var out: ShadowCoord;
    out.n_dot_l = dot(normal, light_dir_to(light, world_pos));
    var p = world_pos;
    if params.normal_offset_texels > 0.0 {
        let d = depth_linear_from_ndc(view, project_to_light(view, world_pos).z);
        p = world_pos + normal * (params.normal_offset_texels * texel_world_bound(view, d));
    }
    let s = project_to_light(view, p);
    out.uv = s.xy;
    out.depth_ndc = s.z;
    out.depth_linear = depth_linear_from_ndc(view, s.z);
    if bias_mode() == BIAS_RECEIVER_PLANE {
        out.depth_gradient = receiver_plane_gradient(view, p, normal, s);
    }
    return out;
}

// Two unit vectors that span the plane with unit normal n, branchless [Duff-2017].
fn tangents_of(n: vec3<f32>) -> array<vec3<f32>, 2> {
    let sign = select(-1.0, 1.0, n.z >= 0.0);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    return array<vec3<f32>, 2>(
        vec3<f32>(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        vec3<f32>(b, sign + n.y * n.y * a, -n.y),
    );
}

// The receiver's plane (through p, normal n) as NDC depth per uv of the map [Isidoro-2006]: two
// points of the plane a texel from p, projected like p (at s), fix it. A light's projection maps
// planes to planes, so this is exact for spot lights too. Edge-on to the light (the two projected
// steps parallel) there is no such plane: 0, the constant bias alone.
fn receiver_plane_gradient(view: ShadowViewGpu, p: vec3<f32>, n: vec3<f32>, s: vec3<f32>) -> vec2<f32> {
    let step = texel_world_at(view, depth_linear_from_ndc(view, s.z), s.xy);
    let t = tangents_of(n);
    let a = project_to_light(view, p + t[0] * step) - s;
    let b = project_to_light(view, p + t[1] * step) - s;
    let det = a.x * b.y - a.y * b.x;
    if !(abs(det) > 1e-3 * length(a.xy) * length(b.xy)) {
        return vec2<f32>(0.0);
    }
    return vec2<f32>(a.z * b.y - a.y * b.z, a.x * b.z - a.z * b.x) / det;
}

// Depth bias in NDC units. `filter_radius_texels` grows the adaptive bias.
fn receiver_bias_ndc(view: ShadowViewGpu, coord: ShadowCoord, filter_radius_texels: f32) -> f32 {
    switch bias_mode() {
        case BIAS_CONSTANT: {
            return params.bias;
        }
        case BIAS_SLOPE: {
            // [LearnOpenGL-ShadowMapping]: max(0.05 * (1 - N.L), 0.005)
            return max(params.slope_bias * (1.0 - coord.n_dot_l), params.bias);
        }
        case BIAS_RECEIVER_PLANE: {
            // The plane does the rest, per tap (`tap_reference_ndc`); this is the margin for
            // depth precision.
            return params.bias;
        }
        case BIAS_ADAPTIVE: {
            // [DrFlower-HW1]: A = (1 + ceil(R)) * W / (2 * map_size) is half a texel in world
            // units, grown with the filter; B = 1 - N.L; bias = c * max(A, A * B). As published,
            // max(A, A*B) is A wherever the light reaches (N.L >= 0, so B <= 1): texel-aware,
            // not slope-aware.
            let a = (1.0 + ceil(filter_radius_texels)) * 0.5 * texel_world_bound(view, coord.depth_linear);
            let b = 1.0 - coord.n_dot_l;
            let bias_world = params.adaptive_c * max(a, a * b);
            return bias_world * ndc_per_world(view, coord.depth_linear);
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

// The GAMES202 framework's RGBA8 depth [GAMES202-HW1]: `pack` splits the depth over the four
// 8-bit channels of a colour target, which keeps each as round(255 v) / 255 like any RGBA8
// target, and `unpack` sums them back. Without three.js's 256/255 correction [ThreeJS-Packing]
// the round trip is off by up to about 1/255: too far below half the depth range, too near above
// it. shadowlab clears its map to white (unpack(1, 1, 1, 1), beyond the far plane) before every
// frame; the framework never clears its own, so there texels nothing was drawn to read 0
// (src/homework runs a student's shader so).
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
fn stored_depth_ndc(view: ShadowViewGpu, uv: vec2<f32>) -> f32 {
    var lookup = uv;
    if clamp_outside() == 0u {
        lookup = fract(uv);
    }
    let size = i32(view.map_size_texels);
    let texel = clamp(vec2<i32>(floor(lookup * view.map_size_texels)), vec2<i32>(0), vec2<i32>(size - 1));
    let depth = textureLoad(shadow_maps, texel, i32(view.layer), 0);
    if depth_storage() == DEPTH_RGBA8 {
        return rgba8_round_trip(depth);
    }
    return depth;
}

// The centre of the texel a point-sampled tap at `uv` of `view` reads, in uv of `view`: on the
// map, its texel's (the last texel holds uv = 1); past a cube face's edge, the centre of the
// texel read on the neighbouring face (`map_tap`), seen from the light on this face's plane gone
// on past its edge, up to about a texel from this face's own grid. Elsewhere past the edge (a
// map that wraps), the texel the grid would have there.
fn read_texel_centre_uv(view: ShadowViewGpu, uv: vec2<f32>) -> vec2<f32> {
    let size = view.map_size_texels;
    if !outside_map(uv) {
        return (min(floor(uv * size), vec2<f32>(size - 1.0)) + 0.5) / size;
    }
    if !is_cube(view) {
        return (floor(uv * size) + 0.5) / size;
    }
    let tap = map_tap(view, uv);
    var lookup = tap.uv;
    if clamp_outside() == 0u {
        lookup = fract(lookup);
    }
    let centre = (clamp(floor(lookup * size), vec2<f32>(0.0), vec2<f32>(size - 1.0)) + 0.5) / size;
    let there = cube_face_axes(tap.view.face);
    let d = there[0] + there[2] * (2.0 * centre.x - 1.0) + there[1] * (1.0 - 2.0 * centre.y);
    let here = cube_face_axes(view.face);
    let ahead = dot(d, here[0]);
    return vec2<f32>(0.5 + 0.5 * dot(d, here[2]) / ahead, 0.5 - 0.5 * dot(d, here[1]) / ahead);
}

// The depth a tap at `uv` compares the map's with: the receiver's, less the bias. With the
// receiver-plane bias it is the receiver's plane at the centre of the texel the tap reads (where
// that texel's depth was rendered, `read_texel_centre_uv`; across a cube's seam, on the
// neighbouring face), so a flat receiver never shadows itself however far the tap lands from the
// pixel; a bilinear tap of the sampler (not `point_sampled`) uses the plane at the tap itself.
fn tap_reference_ndc(
    view: ShadowViewGpu,
    coord: ShadowCoord,
    uv: vec2<f32>,
    bias_ndc: f32,
    point_sampled: bool,
) -> f32 {
    if bias_mode() == BIAS_RECEIVER_PLANE {
        var at = uv;
        if point_sampled {
            at = read_texel_centre_uv(view, uv);
        }
        return coord.depth_ndc + dot(coord.depth_gradient, at - coord.uv) - bias_ndc;
    }
    return coord.depth_ndc - bias_ndc;
}

// 1 = lit, 0 = shadowed, for one tap. Outside the light frustum counts as lit when clamped.
// The receiver-plane reference is taken at the tap's uv on the receiver's own view (a cube
// face's plane goes on past its edge); the map read is the tap's (`map_tap`).
fn depth_test(view: ShadowViewGpu, coord: ShadowCoord, uv: vec2<f32>, bias_ndc: f32) -> f32 {
    let tap = map_tap(view, uv);
    if clamp_outside() == 1u && (outside_map(tap.uv) || outside_depth(coord.depth_ndc)) {
        return 1.0;
    }
    let bilinear = kernel() == KERNEL_HARDWARE && technique() != TECHNIQUE_HARD;
    let reference = tap_reference_ndc(view, coord, uv, bias_ndc, !bilinear);
    if bilinear {
        var lookup = tap.uv;
        if clamp_outside() == 0u {
            lookup = fract(tap.uv);
        }
        // Bilinear 2x2 comparison in the sampler (LessEqual: lit where reference <= stored).
        return textureSampleCompareLevel(shadow_maps, shadow_compare_sampler, lookup * tap.view.atlas_scale,
                                         i32(tap.view.layer), reference);
    }
    return select(0.0, 1.0, reference <= stored_depth_ndc(tap.view, tap.uv));
}

// Pipeline specialisation: which technique, kernel, bias mode, clamping, depth storage and light
// models a pipeline draws with, read through accessors (`technique()`, `kernel()`, ...) that the
// lookup and the filters call. Plumbing for speed only: each accessor answers what `params` says.
//
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
const SPEC_ALL_CUBE: u32 = 3u;
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

fn is_orthographic(view: ShadowViewGpu) -> bool {
    if SPECIALISED && SPEC_PROJECTION != SPEC_MIXED {
        return SPEC_PROJECTION == SPEC_ALL_ORTHOGRAPHIC;
    }
    return view.orthographic == 1u;
}

// A point light's views are cube faces: perspective, storing the distance to the light.
fn is_cube(view: ShadowViewGpu) -> bool {
    if SPECIALISED && SPEC_PROJECTION != SPEC_MIXED {
        return SPEC_PROJECTION == SPEC_ALL_CUBE;
    }
    return view.cube == 1u;
}

// A sun's views are orthographic, every other light's perspective: one constant says both.
fn is_directional(light: LightGpu) -> bool {
    if SPECIALISED && SPEC_PROJECTION != SPEC_MIXED {
        return SPEC_PROJECTION == SPEC_ALL_ORTHOGRAPHIC;
    }
    return light.directional == 1u;
}

fn is_angular(light: LightGpu) -> bool {
    if SPECIALISED && SPEC_SIZE_MODEL != SPEC_MIXED {
        return SPEC_SIZE_MODEL == SPEC_ALL_ANGULAR;
    }
    return light.size_model == SIZE_MODEL_ANGULAR;
}

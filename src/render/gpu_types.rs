//! `#[repr(C)]` mirrors of the WGSL structs in shaders/common.wgsl that only the renderer uses
//! (keep in sync; sizes asserted below). The light and parameter structs the twin shares are the
//! shadow model's: src/shadow/gpu.rs.

use bytemuck::{Pod, Zeroable};

#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct FrameGpu {
    pub clip_from_world: [[f32; 4]; 4],
    pub camera_position: [f32; 4],
    pub ambient: [f32; 4],
    pub light_count: u32,
    pub selected_light: u32,
    pub _pad: [u32; 2],
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct ObjectGpu {
    pub world_from_object: [[f32; 4]; 4],
    pub normal_from_object: [[f32; 4]; 4],
    pub base_color: [f32; 4],
    pub object_index: u32,
    pub _pad: [u32; 3],
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct ReferenceInfoGpu {
    pub width: u32,
    pub height: u32,
    pub weight: f32,
    pub _pad: u32,
}

const _: () = assert!(std::mem::size_of::<FrameGpu>() == 112);
const _: () = assert!(std::mem::size_of::<ObjectGpu>() == 160);
const _: () = assert!(std::mem::size_of::<ReferenceInfoGpu>() == 16);

/// Uniform buffers indexed with dynamic offsets use this stride (wgpu's minimum alignment limit).
pub const DYNAMIC_STRIDE: u64 = 256;

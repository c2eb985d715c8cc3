//! Copy textures back to the CPU (the CLI writes PNGs from them, the tests compare them).

use super::RenderError;

/// Read a whole 2D texture (or one array layer) as tightly packed rows of `bytes_per_texel`.
pub fn read_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
    layer: u32,
    size: (u32, u32),
    bytes_per_texel: u32,
    aspect: wgpu::TextureAspect,
) -> Result<Vec<u8>, RenderError> {
    read_texture_region(device, queue, texture, layer, (0, 0), size, bytes_per_texel, aspect)
}

/// Read the `size` texels from `origin` of a 2D texture (or one array layer), tightly packed.
#[allow(clippy::too_many_arguments)]
pub fn read_texture_region(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
    layer: u32,
    origin: (u32, u32),
    size: (u32, u32),
    bytes_per_texel: u32,
    aspect: wgpu::TextureAspect,
) -> Result<Vec<u8>, RenderError> {
    let mut out = Vec::with_capacity((size.0 * size.1 * bytes_per_texel) as usize);
    let region = Region { layer, mip_level: 0, origin, size, bytes_per_texel, aspect };
    for_each_row(device, queue, texture, region, |row| out.extend_from_slice(row))?;
    Ok(out)
}

/// Which texels of a texture to read.
#[derive(Clone, Copy)]
pub struct Region {
    pub layer: u32,
    pub mip_level: u32,
    pub origin: (u32, u32),
    pub size: (u32, u32),
    pub bytes_per_texel: u32,
    pub aspect: wgpu::TextureAspect,
}

/// Copy `region` to a buffer and hand each row, unpadded, to `row`, straight from the mapped
/// buffer: one copy on the CPU, whatever the caller makes of the rows (a depth map is 16 MB).
pub fn for_each_row(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
    region: Region,
    mut row: impl FnMut(&[u8]),
) -> Result<(), RenderError> {
    let (width, height) = region.size;
    let unpadded = width * region.bytes_per_texel;
    let padded = unpadded.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let len = u64::from(padded) * u64::from(height);
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size: len,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder =
        device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("readback") });
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: region.mip_level,
            origin: wgpu::Origin3d { x: region.origin.0, y: region.origin.1, z: region.layer },
            aspect: region.aspect,
        },
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded),
                rows_per_image: Some(height),
            },
        },
        wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
    );
    queue.submit([encoder.finish()]);
    with_mapped(device, &buffer, len, |bytes| {
        for padded_row in bytes.chunks_exact(padded as usize) {
            row(&padded_row[..unpadded as usize]);
        }
    })
}

/// Map a MAP_READ buffer and let `read` see its first `len` bytes.
fn with_mapped<T>(
    device: &wgpu::Device,
    buffer: &wgpu::Buffer,
    len: u64,
    read: impl FnOnce(&[u8]) -> T,
) -> Result<T, RenderError> {
    let slice = buffer.slice(..len);
    let (sender, receiver) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |result| {
        let _ = sender.send(result);
    });
    device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| RenderError::Readback(e.to_string()))?;
    receiver
        .recv()
        .map_err(|e| RenderError::Readback(e.to_string()))?
        .map_err(|e| RenderError::Readback(e.to_string()))?;
    let out = read(&slice.get_mapped_range().map_err(|e| RenderError::Readback(e.to_string()))?);
    buffer.unmap();
    Ok(out)
}

/// Map a MAP_READ buffer and copy out its first `len` bytes.
pub fn read_buffer(device: &wgpu::Device, buffer: &wgpu::Buffer, len: u64) -> Result<Vec<u8>, RenderError> {
    with_mapped(device, buffer, len, <[u8]>::to_vec)
}

/// Little-endian 32-bit floats.
pub fn f32s(bytes: &[u8]) -> impl Iterator<Item = f32> + '_ {
    bytes.chunks_exact(4).map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
}

pub fn f32s_from_bytes(bytes: &[u8]) -> Vec<f32> {
    f32s(bytes).collect()
}

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
    let (width, height) = size;
    let unpadded = width * bytes_per_texel;
    let padded = unpadded.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size: u64::from(padded) * u64::from(height),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder =
        device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("readback") });
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: 0,
            origin: wgpu::Origin3d { x: origin.0, y: origin.1, z: layer },
            aspect,
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
    read_buffer(device, &buffer, u64::from(padded) * u64::from(height)).map(|bytes| {
        let mut out = Vec::with_capacity((unpadded * height) as usize);
        for row in bytes.chunks_exact(padded as usize) {
            out.extend_from_slice(&row[..unpadded as usize]);
        }
        out
    })
}

/// Map a MAP_READ buffer and copy out its first `len` bytes.
pub fn read_buffer(device: &wgpu::Device, buffer: &wgpu::Buffer, len: u64) -> Result<Vec<u8>, RenderError> {
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
    let bytes = slice.get_mapped_range().map_err(|e| RenderError::Readback(e.to_string()))?.to_vec();
    buffer.unmap();
    Ok(bytes)
}

pub fn f32s_from_bytes(bytes: &[u8]) -> Vec<f32> {
    bytes.chunks_exact(4).map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect()
}

//! Copy textures and buffers back to the CPU. A [`Readback`] is one on its way: the copy
//! submitted and the buffer's mapping asked for, then asked after without blocking (a browser
//! cannot wait for the GPU inside a frame) or waited for (a thread, the command line, the tests).
//! Every read-back goes through it; the blocking ones are `Readback::wait`.

use super::RenderError;
use std::cell::Cell;
use std::sync::{Arc, OnceLock};

/// How to ask after work submitted to the GPU.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GpuWait {
    /// Look and return at once (what has not arrived comes on a later look).
    Poll,
    /// Block until the GPU has done everything submitted so far.
    Block,
}

impl GpuWait {
    /// Ask the device: finished work fires its callbacks (the mappings asked for) here. Every
    /// wait for the GPU goes through this.
    pub fn poll(self, device: &wgpu::Device) -> Result<(), RenderError> {
        let poll = match self {
            GpuWait::Poll => wgpu::PollType::Poll,
            GpuWait::Block => {
                BLOCKING_WAITS.set(BLOCKING_WAITS.get() + 1);
                wgpu::PollType::wait_indefinitely()
            }
        };
        device.poll(poll).map(|_| ()).map_err(|e| RenderError::Readback(e.to_string()))
    }
}

thread_local! {
    static BLOCKING_WAITS: Cell<u64> = const { Cell::new(0) };
}

/// How many times this thread has blocked waiting for the GPU (`GpuWait::Block`): what must
/// never block (a page's frames) is held to it.
pub fn blocking_waits_on_this_thread() -> u64 {
    BLOCKING_WAITS.get()
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

impl Region {
    /// All of mip level 0 of one layer, `size` texels of `bytes_per_texel`.
    pub fn whole(layer: u32, size: (u32, u32), bytes_per_texel: u32, aspect: wgpu::TextureAspect) -> Self {
        Self { layer, mip_level: 0, origin: (0, 0), size, bytes_per_texel, aspect }
    }
}

/// One copy into a MAP_READ buffer whose mapping has been asked for.
struct MappedCopy {
    buffer: wgpu::Buffer,
    len: u64,
    /// Bytes per row in the buffer (a texture's rows are padded to
    /// `COPY_BYTES_PER_ROW_ALIGNMENT`) and of them the texels'; a buffer's copy is one row.
    row_bytes: (usize, usize),
    /// Set by the mapping's callback: during a device poll natively, by the event loop in a
    /// browser.
    mapped: Arc<OnceLock<Result<(), wgpu::BufferAsyncError>>>,
}

impl MappedCopy {
    /// Submit `encoder` (which copies into `buffer`) and ask for `buffer`'s first `len` bytes.
    fn submit(
        queue: &wgpu::Queue,
        encoder: wgpu::CommandEncoder,
        buffer: wgpu::Buffer,
        len: u64,
        row_bytes: (usize, usize),
    ) -> Self {
        queue.submit([encoder.finish()]);
        let mapped = Arc::new(OnceLock::new());
        let flag = mapped.clone();
        buffer.map_async(wgpu::MapMode::Read, ..len, move |result| {
            let _ = flag.set(result);
        });
        Self { buffer, len, row_bytes, mapped }
    }

    fn settled(&self) -> bool {
        self.mapped.get().is_some()
    }
}

/// A copy's bytes once mapped.
pub struct Mapped<'a> {
    bytes: &'a [u8],
    row_bytes: (usize, usize),
}

impl<'a> Mapped<'a> {
    /// Row after row, without the row padding (a buffer's copy is one row).
    pub fn rows(&self) -> impl Iterator<Item = &'a [u8]> + use<'a> {
        let (padded, unpadded) = self.row_bytes;
        self.bytes.chunks_exact(padded.max(1)).map(move |row| &row[..unpadded])
    }

    /// All the rows, tightly packed.
    pub fn to_vec(&self) -> Vec<u8> {
        self.rows().flatten().copied().collect()
    }
}

type Decode<T> = Box<dyn FnOnce(&[Mapped<'_>]) -> Result<T, RenderError> + Send>;

/// A value made from copies on their way back from the GPU: submitted, their mappings asked
/// for; `arrived` says when they are there and `finish` makes the value (straight from the
/// mapped buffers: one copy on the CPU, whatever is made of them, and a depth map is 16 MB).
pub struct Readback<T> {
    copies: Vec<MappedCopy>,
    decode: Decode<T>,
}

impl<T: Send + 'static> Readback<T> {
    /// A value that needs nothing from the GPU: it has arrived already.
    pub fn ready(value: T) -> Self {
        Self { copies: Vec::new(), decode: Box::new(move |_| Ok(value)) }
    }

    /// Copy `region` of `texture` back; `decode` makes the value of its rows.
    pub fn texture(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        texture: &wgpu::Texture,
        region: Region,
        decode: impl FnOnce(Mapped<'_>) -> Result<T, RenderError> + Send + 'static,
    ) -> Self {
        let (width, height) = region.size;
        let unpadded = width * region.bytes_per_texel;
        let padded =
            unpadded.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
        let len = u64::from(padded) * u64::from(height);
        let buffer = readback_buffer(device, len);
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
        let copy = MappedCopy::submit(queue, encoder, buffer, len, (padded as usize, unpadded as usize));
        Self::single(copy, decode)
    }

    /// Copy the first `len` bytes of `source` back, after the work recorded in `encoder`
    /// (submitted here with the copy); `decode` makes the value of them.
    pub fn buffer(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        mut encoder: wgpu::CommandEncoder,
        source: &wgpu::Buffer,
        len: u64,
        decode: impl FnOnce(Mapped<'_>) -> Result<T, RenderError> + Send + 'static,
    ) -> Self {
        let buffer = readback_buffer(device, len);
        encoder.copy_buffer_to_buffer(source, 0, &buffer, 0, len);
        let copy = MappedCopy::submit(queue, encoder, buffer, len, (len as usize, len as usize));
        Self::single(copy, decode)
    }

    fn single(
        copy: MappedCopy,
        decode: impl FnOnce(Mapped<'_>) -> Result<T, RenderError> + Send + 'static,
    ) -> Self {
        let decode: Decode<T> = Box::new(move |mapped| {
            let [one] = mapped else {
                return Err(RenderError::Readback("one copy expected".into()));
            };
            decode(Mapped { bytes: one.bytes, row_bytes: one.row_bytes })
        });
        Self { copies: vec![copy], decode }
    }

    /// The value made into another once it is there.
    pub fn map<U: Send + 'static>(
        self,
        then: impl FnOnce(T) -> Result<U, RenderError> + Send + 'static,
    ) -> Readback<U> {
        let decode = self.decode;
        Readback { copies: self.copies, decode: Box::new(move |mapped| then(decode(mapped)?)) }
    }

    /// This value and `other`'s, once both are there.
    pub fn zip<U: Send + 'static>(self, other: Readback<U>) -> Readback<(T, U)> {
        let split = self.copies.len();
        let (first, second) = (self.decode, other.decode);
        let mut copies = self.copies;
        copies.extend(other.copies);
        Readback {
            copies,
            decode: Box::new(move |mapped| {
                let (a, b) = mapped.split_at(split);
                Ok((first(a)?, second(b)?))
            }),
        }
    }

    /// Whether every copy has arrived (or failed: `finish` says so), asking the device as `wait`
    /// says; with `GpuWait::Block` they all have.
    pub fn arrived(&self, device: &wgpu::Device, wait: GpuWait) -> Result<bool, RenderError> {
        if self.copies.iter().all(MappedCopy::settled) {
            return Ok(true);
        }
        wait.poll(device)?;
        Ok(self.copies.iter().all(MappedCopy::settled))
    }

    /// The value, once `arrived` (an error before).
    pub fn finish(self) -> Result<T, RenderError> {
        for copy in &self.copies {
            match copy.mapped.get() {
                Some(Ok(())) => {}
                Some(Err(e)) => return Err(RenderError::Readback(e.to_string())),
                None => return Err(RenderError::Readback("the copy has not arrived yet".into())),
            }
        }
        let views = (self.copies.iter())
            .map(|c| c.buffer.get_mapped_range(..c.len))
            .collect::<Result<Vec<_>, _>>()
            .map_err(|e| RenderError::Readback(e.to_string()))?;
        let mapped: Vec<Mapped<'_>> = (views.iter().zip(&self.copies))
            .map(|(view, copy)| Mapped { bytes: view, row_bytes: copy.row_bytes })
            .collect();
        let value = (self.decode)(&mapped);
        drop(mapped);
        drop(views);
        for copy in &self.copies {
            copy.buffer.unmap();
        }
        value
    }

    /// Block until the value is there.
    pub fn wait(self, device: &wgpu::Device) -> Result<T, RenderError> {
        self.arrived(device, GpuWait::Block)?;
        self.finish()
    }
}

fn readback_buffer(device: &wgpu::Device, len: u64) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size: len,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    })
}

/// Little-endian 32-bit floats.
pub fn f32s(bytes: &[u8]) -> impl Iterator<Item = f32> + '_ {
    bytes.chunks_exact(4).map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
}

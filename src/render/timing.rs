//! GPU timestamps around the shadow passes and the camera passes (for `shadowlab bench`).

use super::readback::Readback;

/// Milliseconds of GPU time.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PassTimes {
    pub shadow_ms: f64,
    pub camera_ms: f64,
}

pub struct Timer {
    queries: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    period_ns: f32,
}

/// Two spans (shadow, camera), each a begin and an end query.
const QUERY_COUNT: u32 = 4;
const BYTES: u64 = QUERY_COUNT as u64 * 8;

impl Timer {
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue) -> Self {
        Self {
            queries: device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("pass times"),
                ty: wgpu::QueryType::Timestamp,
                count: QUERY_COUNT,
            }),
            resolve: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("timestamps"),
                size: BYTES,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }),
            period_ns: queue.get_timestamp_period(),
        }
    }

    /// Timestamp writes for a pass inside span `span`: the first pass writes the begin, the last the end.
    pub fn span_writes(
        &self,
        span: u32,
        first: bool,
        last: bool,
    ) -> Option<wgpu::RenderPassTimestampWrites<'_>> {
        (first || last).then_some(wgpu::RenderPassTimestampWrites {
            query_set: &self.queries,
            beginning_of_pass_write_index: first.then_some(2 * span),
            end_of_pass_write_index: last.then_some(2 * span + 1),
        })
    }

    /// The same for a compute pass.
    pub fn compute_span_writes(
        &self,
        span: u32,
        first: bool,
        last: bool,
    ) -> Option<wgpu::ComputePassTimestampWrites<'_>> {
        (first || last).then_some(wgpu::ComputePassTimestampWrites {
            query_set: &self.queries,
            beginning_of_pass_write_index: first.then_some(2 * span),
            end_of_pass_write_index: last.then_some(2 * span + 1),
        })
    }

    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        encoder.resolve_query_set(&self.queries, 0..QUERY_COUNT, &self.resolve, 0);
    }

    /// The times the last `resolve` recorded, on their way back (a buffer of their own each
    /// time: one still being mapped cannot be written by the next frame).
    pub fn readback(&self, device: &wgpu::Device, queue: &wgpu::Queue) -> Readback<PassTimes> {
        let encoder =
            device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("timestamps") });
        let period_ns = self.period_ns;
        Readback::buffer(device, queue, encoder, &self.resolve, BYTES, move |mapped| {
            let bytes = mapped.to_vec();
            let ticks: Vec<u64> = bytes
                .chunks_exact(8)
                .map(|c| u64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]]))
                .collect();
            let ms = |a: u64, b: u64| b.saturating_sub(a) as f64 * f64::from(period_ns) / 1e6;
            Ok(PassTimes { shadow_ms: ms(ticks[0], ticks[1]), camera_ms: ms(ticks[2], ticks[3]) })
        })
    }
}

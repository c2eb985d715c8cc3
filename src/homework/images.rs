//! What a homework's camera pass leaves per pixel, read back: the student's colour, what their
//! recorded functions returned and which ran, and where those functions read the map.

use crate::render::readback;

/// The camera pass read back, per pixel, rows top first.
#[derive(Clone, Debug)]
pub struct HomeworkImages {
    pub width: u32,
    pub height: u32,
    /// What the student's shader wrote to `gl_FragColor` (gamma-encoded, as they computed it).
    pub color: Vec<[f32; 4]>,
    /// The last value each of `RECORDED_FUNCTIONS` returned there.
    pub returned: Vec<[f32; 4]>,
    /// A bit per recorded function that ran, the visibility function + 1, calls (at most 255),
    /// and 1 where the student's shader ran at all.
    pub calls: Vec<[u8; 4]>,
}

impl HomeworkImages {
    /// The student's shader ran at pixel `i` (a surface is there).
    pub fn covered(&self, i: usize) -> bool {
        self.calls[i][3] != 0
    }

    /// The visibility at pixel `i`: what the last `useShadowMap` / `PCF` / `PCSS` called from
    /// the level of `main` returned; None where none was.
    pub fn visibility(&self, i: usize) -> Option<f32> {
        let function = self.calls[i][1] as usize;
        (self.covered(i) && (1..=3).contains(&function)).then(|| self.returned[i][function - 1])
    }

    /// Recorded function `k` (in `RECORDED_FUNCTIONS` order) ran at pixel `i`.
    pub fn ran(&self, i: usize, k: usize) -> bool {
        self.calls[i][0] & (1 << k) != 0
    }

    /// Which recorded functions ran anywhere (bits in `RECORDED_FUNCTIONS` order).
    pub fn ran_anywhere(&self) -> u8 {
        self.calls.iter().fold(0, |bits, c| bits | c[0])
    }
}

/// Where one recorded function read the map at one pixel, offsets from the receiver's own uv
/// (uv units of the map).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Taps {
    pub reads: f32,
    /// |mean offset|: 0 for samples spread around the receiver.
    pub mean_offset_uv: f32,
    /// Root mean square offset.
    pub rms_offset_uv: f32,
    /// The farthest read: the search or filter radius.
    pub max_offset_uv: f32,
    /// How the taps stretch: the offsets' second moments without their trace, over it,
    /// ((xx - yy), 2 xy) / (xx + yy): 0 for taps spread over a disk, a unit vector at twice the
    /// angle of a line (recorded for PCF and PCSS).
    pub stretch: glam::Vec2,
}

/// Where the recorded functions read, per pixel (rows top first), one `Taps` per function in
/// `RECORDED_FUNCTIONS` order (useShadowMap's is not recorded: it reads once).
#[derive(Clone, Debug)]
pub struct TapImages {
    pub width: u32,
    pub height: u32,
    pub taps: Vec<[Taps; 4]>,
}

fn half(b: &[u8]) -> f32 {
    half::f16::from_bits(u16::from_le_bytes([b[0], b[1]])).to_f32()
}

/// The camera pass's targets as read back: half-float colour, f32 returns, u8 calls.
pub(super) fn decode(w: u32, h: u32, color: &[u8], returned: &[u8], calls: &[u8]) -> HomeworkImages {
    HomeworkImages {
        width: w,
        height: h,
        color: color
            .chunks_exact(8)
            .map(|c| [half(&c[0..]), half(&c[2..]), half(&c[4..]), half(&c[6..])])
            .collect(),
        returned: readback::f32s(returned)
            .collect::<Vec<_>>()
            .chunks_exact(4)
            .map(|c| [c[0], c[1], c[2], c[3]])
            .collect(),
        calls: calls.chunks_exact(4).map(|c| [c[0], c[1], c[2], c[3]]).collect(),
    }
}

/// The taps pass's four half-float targets (see `TAPS_OUTPUT`; four of them fit the 32 bytes a
/// pixel's targets may take; half floats keep a count to 2048 and an offset to 1/1000 of itself).
pub(super) fn decode_taps(w: u32, h: u32, targets: [&[u8]; 4]) -> TapImages {
    let per_function: Vec<Vec<f32>> = targets.iter().map(|t| t.chunks_exact(2).map(half).collect()).collect();
    let taps = (0..(w * h) as usize)
        .map(|i| {
            let extra = &per_function[3][4 * i..4 * i + 4];
            let filtered = |target: usize, stretch: glam::Vec2| {
                let v = &per_function[target][4 * i..4 * i + 4];
                Taps { reads: v[0], mean_offset_uv: v[1], rms_offset_uv: v[2], max_offset_uv: v[3], stretch }
            };
            let (pcf, pcss) = (glam::Vec2::new(extra[0], extra[1]), glam::Vec2::new(extra[2], extra[3]));
            [Taps::default(), filtered(0, pcf), filtered(1, pcss), filtered(2, glam::Vec2::ZERO)]
        })
        .collect();
    TapImages { width: w, height: h, taps }
}

/// A lossless map as the light pass wrote it: each texel's four packed channels, rows in the
/// order the student's uv reads them (v = 0 first).
#[derive(Clone, Debug)]
pub struct PackedMap {
    pub size: u32,
    pub texels: Vec<[f32; 4]>,
}

impl PackedMap {
    pub(super) fn decode(size: u32, bytes: &[u8]) -> Self {
        let values: Vec<f32> = crate::render::readback::f32s(bytes).collect();
        Self { size, texels: values.chunks_exact(4).map(|c| [c[0], c[1], c[2], c[3]]).collect() }
    }

    /// The texel the student's lookup at `uv` reads (REPEAT, NEAREST).
    pub fn at(&self, uv: glam::Vec2) -> [f32; 4] {
        let n = self.size as f32;
        let wrap = |c: f32| ((c - c.floor()) * n).floor().clamp(0.0, n - 1.0) as usize;
        self.texels[wrap(uv.y) * self.size as usize + wrap(uv.x)]
    }
}

//! The analysis pass (`fs_analysis` in shaders/camera.wgsl) read back: per pixel the selected
//! light's visibility, blocker-search radius, penumbra width and blockers found, with the
//! surface's position and normal; and the VSM moments its filter reads.

use super::readback;
use super::{RenderError, Renderer};

/// The analysis pass at one pixel: the three targets' values there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AnalysisPixel {
    /// visibility, blocker-search radius (texels), penumbra width (texels), blockers found.
    pub shadow: [f32; 4],
    /// World position; w = 1 where a surface was hit.
    pub position: [f32; 4],
    /// Shading normal; w = object index.
    pub normal: [f32; 4],
}

/// The analysis pass read back: per pixel, row-major, top row first.
#[derive(Clone, Debug)]
pub struct Analysis {
    pub width: u32,
    pub height: u32,
    /// visibility, blocker-search radius (texels), penumbra width (texels), blockers found.
    pub shadow: Vec<[f32; 4]>,
    /// World position; w = 1 where a surface was hit.
    pub position: Vec<[f32; 4]>,
    /// Shading normal; w = object index.
    pub normal: Vec<[f32; 4]>,
    /// The level of the selected light's VSM moments the filter reads, when it was asked for
    /// (`Renderer::read_moments_for_radius`).
    pub moments: Option<MomentsLevel>,
    /// VSM's light bleeding per pixel, when it was asked for (`views::overlays::vsm_light_bleeding`).
    pub bleeding: Option<Vec<f32>>,
}

/// One level of one light's VSM moments, read back.
#[derive(Clone, Debug)]
pub struct MomentsLevel {
    pub level: u32,
    /// Map texels per side of one texel of this level.
    pub span_texels: u32,
    /// The filter radius (map texels) whose lookups read this level.
    pub radius_texels: f32,
    /// Texels per side of the light's part.
    pub side: u32,
    /// (mean depth, mean squared depth) per texel, NDC, rows first.
    pub texels: Vec<[f32; 2]>,
}

impl Analysis {
    pub fn index(&self, x: u32, y: u32) -> usize {
        (y * self.width + x) as usize
    }
    pub fn hit(&self, i: usize) -> bool {
        self.position[i][3] > 0.5
    }
}

impl Renderer {
    pub fn read_analysis(&self) -> Result<Analysis, RenderError> {
        let targets = self.targets()?;
        let (width, height) = targets.size;
        let mut planes = Vec::with_capacity(targets.analysis.len());
        for texture in &targets.analysis {
            let mut plane = Vec::with_capacity((width * height) as usize);
            let region = readback::Region {
                layer: 0,
                mip_level: 0,
                origin: (0, 0),
                size: targets.size,
                bytes_per_texel: 16,
                aspect: wgpu::TextureAspect::All,
            };
            readback::for_each_row(&self.device, &self.queue, texture, region, |row| {
                plane.extend(row.chunks_exact(16).map(|t| {
                    let mut texel = readback::f32s(t);
                    std::array::from_fn(|_| texel.next().unwrap_or_default())
                }));
            })?;
            planes.push(plane);
        }
        let normal = planes.pop().unwrap_or_default();
        let position = planes.pop().unwrap_or_default();
        let shadow = planes.pop().unwrap_or_default();
        Ok(Analysis { width, height, shadow, position, normal, moments: None, bleeding: None })
    }

    /// The analysis targets at one pixel of the last frame (a 1x1 read-back each).
    pub fn read_analysis_pixel(&self, x: u32, y: u32) -> Result<AnalysisPixel, RenderError> {
        let targets = self.targets()?;
        let (width, height) = targets.size;
        if x >= width || y >= height {
            return Err(RenderError::Usage(format!("pixel {x},{y} is outside the {width}x{height} image")));
        }
        let mut values = [[0.0f32; 4]; 3];
        for (value, texture) in values.iter_mut().zip(&targets.analysis) {
            let bytes = readback::read_texture_region(
                &self.device,
                &self.queue,
                texture,
                0,
                (x, y),
                (1, 1),
                16,
                wgpu::TextureAspect::All,
            )?;
            let floats = readback::f32s_from_bytes(&bytes);
            value.copy_from_slice(&floats[..4]);
        }
        let [shadow, position, normal] = values;
        Ok(AnalysisPixel { shadow, position, normal })
    }

    /// The finer of the two levels of light `index`'s moments a VSM filter of `radius_texels`
    /// reads (`filtered_moments` in shaders/shadow_filter.wgsl), as the last frame left it.
    pub fn read_moments_for_radius(
        &self,
        index: usize,
        radius_texels: f32,
    ) -> Result<MomentsLevel, RenderError> {
        let moments = self.moments.as_ref().filter(|m| !m.is_placeholder());
        let (block, levels) = moments.map_or((1, 1), |m| (m.block, m.texture.mip_level_count()));
        let level = crate::shadow::moments::level_for_radius(radius_texels, block, levels).floor() as u32;
        let (side, texels) = self.read_moments(index, level)?;
        Ok(MomentsLevel { level, span_texels: block << level, radius_texels, side, texels })
    }

    /// Level `level` of light `index`'s VSM moments as the last frame left them: the side of
    /// the light's part in texels, and (mean depth, mean squared depth) per texel, NDC, rows
    /// first. Each texel covers `moments_block << level` map texels per side.
    pub fn read_moments(&self, index: usize, level: u32) -> Result<(u32, Vec<[f32; 2]>), RenderError> {
        // Only for a frame that filtered with them: the view shows what VSM's lookups read.
        let vsm_frame = self.last_frame.as_ref().is_some_and(|f| f.params.uses_moments());
        let moments = self.moments.as_ref().filter(|m| vsm_frame && m.current && !m.is_placeholder());
        let moments = moments.ok_or_else(|| {
            RenderError::Usage("the moments exist for the vsm and vssm techniques only".into())
        })?;
        let lights = self.last_frame.as_ref().map_or(&[][..], |f| &f.lights[..]);
        let light = lights.get(index).ok_or_else(|| {
            RenderError::Usage(format!("light {index} does not exist (the scene has {})", lights.len()))
        })?;
        let levels = moments.texture.mip_level_count();
        if level >= levels {
            return Err(RenderError::Usage(format!(
                "the moments have levels 0..{}, not {level}",
                levels - 1
            )));
        }
        let level_side = (moments.texture.width() >> level).max(1);
        let side = (light.map_size_texels as u32).div_ceil(moments.block << level).clamp(1, level_side);
        let region = readback::Region {
            layer: index as u32,
            mip_level: level,
            origin: (0, 0),
            size: (side, side),
            bytes_per_texel: 8,
            aspect: wgpu::TextureAspect::All,
        };
        let mut texels = Vec::with_capacity((side * side) as usize);
        readback::for_each_row(&self.device, &self.queue, &moments.texture, region, |row| {
            texels.extend(row.chunks_exact(8).map(|t| {
                let mut m = readback::f32s(t);
                [m.next().unwrap_or_default(), m.next().unwrap_or_default()]
            }));
        })?;
        Ok((side, texels))
    }
}

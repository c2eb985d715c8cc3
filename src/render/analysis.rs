//! The analysis pass (`fs_analysis` in shaders/camera.wgsl) read back: per pixel the selected
//! light's visibility, blocker-search radius, penumbra width and blockers found, with the
//! surface's position and normal; and the VSM moments its filter reads.

use super::readback::{self, Readback};
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
        self.analysis_readback()?.wait(&self.device)
    }

    /// `read_analysis`, on its way back.
    pub fn analysis_readback(&self) -> Result<Readback<Analysis>, RenderError> {
        let (width, height) = self.targets()?.size;
        let [shadow, position, normal] = self.analysis_planes((0, 0), (width, height))?;
        Ok(shadow.zip(position).zip(normal).map(move |((shadow, position), normal)| {
            Ok(Analysis { width, height, shadow, position, normal, moments: None, bleeding: None })
        }))
    }

    /// Which pixels of the last analysis frame hit a surface (its positions' w), on their way
    /// back.
    pub(crate) fn hits_readback(&self) -> Result<Readback<Vec<bool>>, RenderError> {
        let targets = self.targets()?;
        let [_, position, _] = self.analysis_planes((0, 0), targets.size)?;
        Ok(position.map(|position| Ok(position.iter().map(|p| p[3] > 0.5).collect())))
    }

    /// The three analysis targets' texels in `size` from `origin`, rows first, on their way back.
    fn analysis_planes(
        &self,
        origin: (u32, u32),
        size: (u32, u32),
    ) -> Result<[Readback<Vec<[f32; 4]>>; 3], RenderError> {
        let targets = self.targets()?;
        let region =
            readback::Region { origin, ..readback::Region::whole(0, size, 16, wgpu::TextureAspect::All) };
        let plane = |texture| {
            Readback::texture(&self.device, &self.queue, texture, region, move |mapped| {
                let mut plane = Vec::with_capacity((size.0 * size.1) as usize);
                for row in mapped.rows() {
                    plane.extend(row.chunks_exact(16).map(|t| {
                        let mut texel = readback::f32s(t);
                        std::array::from_fn(|_| texel.next().unwrap_or_default())
                    }));
                }
                Ok(plane)
            })
        };
        let [shadow, position, normal] = &targets.analysis[..] else {
            return Err(RenderError::Usage("the analysis pass has three targets".into()));
        };
        Ok([plane(shadow), plane(position), plane(normal)])
    }

    /// The analysis targets at one pixel of the last frame (a 1x1 read-back each).
    pub fn read_analysis_pixel(&self, x: u32, y: u32) -> Result<AnalysisPixel, RenderError> {
        self.analysis_pixel_readback(x, y)?.wait(&self.device)
    }

    /// `read_analysis_pixel`, on its way back.
    pub fn analysis_pixel_readback(&self, x: u32, y: u32) -> Result<Readback<AnalysisPixel>, RenderError> {
        let (width, height) = self.targets()?.size;
        if x >= width || y >= height {
            return Err(RenderError::Usage(format!("pixel {x},{y} is outside the {width}x{height} image")));
        }
        let [shadow, position, normal] = self.analysis_planes((x, y), (1, 1))?;
        let first = |plane: Vec<[f32; 4]>| {
            plane.first().copied().ok_or_else(|| RenderError::Readback("an empty analysis texel".into()))
        };
        Ok(shadow.zip(position).zip(normal).map(move |((shadow, position), normal)| {
            Ok(AnalysisPixel { shadow: first(shadow)?, position: first(position)?, normal: first(normal)? })
        }))
    }

    /// The finer of the two levels of light `index`'s moments a VSM filter of `radius_texels`
    /// reads (`filtered_moments` in shaders/shadow_filter.wgsl), as the last frame left it.
    pub fn read_moments_for_radius(
        &self,
        index: usize,
        radius_texels: f32,
    ) -> Result<MomentsLevel, RenderError> {
        self.moments_for_radius_readback(index, radius_texels)?.wait(&self.device)
    }

    /// `read_moments_for_radius`, on its way back.
    pub fn moments_for_radius_readback(
        &self,
        index: usize,
        radius_texels: f32,
    ) -> Result<Readback<MomentsLevel>, RenderError> {
        let moments = self.moments.as_ref().filter(|m| !m.is_placeholder());
        let (block, levels) = moments.map_or((1, 1), |m| (m.block, m.texture.mip_level_count()));
        let level = crate::shadow::moments::level_for_radius(radius_texels, block, levels).floor() as u32;
        Ok(self.moments_readback(index, level)?.map(move |(side, texels)| {
            Ok(MomentsLevel { level, span_texels: block << level, radius_texels, side, texels })
        }))
    }

    /// Level `level` of shadow view `index`'s VSM moments as the last frame left them: the side of
    /// the view's part in texels, and (mean depth, mean squared depth) per texel, NDC, rows
    /// first. Each texel covers `moments_block << level` map texels per side.
    pub fn read_moments(&self, index: usize, level: u32) -> Result<(u32, Vec<[f32; 2]>), RenderError> {
        self.moments_readback(index, level)?.wait(&self.device)
    }

    /// `read_moments`, on its way back.
    #[allow(clippy::type_complexity)]
    pub fn moments_readback(
        &self,
        index: usize,
        level: u32,
    ) -> Result<Readback<(u32, Vec<[f32; 2]>)>, RenderError> {
        // Only for a frame that filtered with them: the view shows what VSM's lookups read.
        let vsm_frame = self.last_frame.as_ref().is_some_and(|f| f.params.uses_moments());
        let moments = self.moments.as_ref().filter(|m| vsm_frame && m.current && !m.is_placeholder());
        let moments = moments.ok_or_else(|| {
            RenderError::Usage("the moments exist for the vsm and vssm techniques only".into())
        })?;
        let views = self.last_frame.as_ref().map_or(&[][..], |f| &f.views[..]);
        let view = views.get(index).ok_or_else(|| {
            RenderError::Usage(format!("shadow view {index} does not exist (the frame has {})", views.len()))
        })?;
        let levels = moments.texture.mip_level_count();
        if level >= levels {
            return Err(RenderError::Usage(format!(
                "the moments have levels 0..{}, not {level}",
                levels - 1
            )));
        }
        let level_side = (moments.texture.width() >> level).max(1);
        let side = (view.map_size_texels as u32).div_ceil(moments.block << level).clamp(1, level_side);
        let region = readback::Region {
            mip_level: level,
            ..readback::Region::whole(view.layer, (side, side), 8, wgpu::TextureAspect::All)
        };
        Ok(Readback::texture(&self.device, &self.queue, &moments.texture, region, move |mapped| {
            let mut texels = Vec::with_capacity((side * side) as usize);
            for row in mapped.rows() {
                texels.extend(row.chunks_exact(8).map(|t| {
                    let mut m = readback::f32s(t);
                    [m.next().unwrap_or_default(), m.next().unwrap_or_default()]
                }));
            }
            Ok((side, texels))
        }))
    }
}

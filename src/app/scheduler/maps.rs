//! The maps stage: the selected light's map picture (unless it is the one sent last) and the
//! thumbnails, read back one after another (a depth map of 8192 texels a side is 256 MB).

use super::keys::MapKey;
use super::renderers::Renderers;
use super::{MapView, Maps, RenderEvent, RenderJob, Stage};
use crate::render::{GpuWait, Readback, RenderError};
use crate::shadow::{DepthImage, ShadowViewGpu};
use crate::views;
use std::collections::VecDeque;

/// While dragging the map picture is built at this size at most.
const MAP_PREVIEW_TEXELS: u32 = 512;
/// Texels per side of a light's thumbnail.
const THUMBNAIL_TEXELS: u32 = 96;

/// A picture made of one light's map.
#[derive(Clone, Copy)]
enum Picture {
    /// The selected light's, at most this many texels a side.
    Selected {
        texels: u32,
    },
    /// One of the selected light's several maps (a cube's face, a sun's cascade), read in view
    /// order: the picture is made once all `of` are back.
    Tile {
        texels: u32,
        of: usize,
    },
    Thumbnail,
}

/// A picture made, once its map is back.
enum Made {
    Selected(MapView),
    /// A tile's map, its view and the view's index in the frame.
    Tile(DepthImage, ShadowViewGpu, usize, Picture),
    Thumbnail(image::RgbaImage),
}

/// The maps stage under way.
pub(super) struct MapsComing {
    /// What is sent once every picture is there.
    maps: Maps,
    /// The pictures still to read: the shadow view (its index in the frame) and which picture.
    to_read: VecDeque<(usize, ShadowViewGpu, Picture)>,
    /// The one being read.
    reading: Option<Readback<Made>>,
    /// What the selected light's picture is drawn from: the views have it once it is sent.
    map_key: Option<MapKey>,
    /// The tiles of a light with several maps read so far, with their views.
    tiles: Vec<(DepthImage, ShadowViewGpu, usize)>,
}

impl Renderers {
    /// The pictures the frame `submit_image` just rendered needs: the selected light's map
    /// (unless it is the one sent last) and the thumbnails.
    pub(super) fn maps_to_read(&mut self, id: u64, job: &RenderJob) -> MapsComing {
        let texels = if job.preview { MAP_PREVIEW_TEXELS.min(job.map_texels) } else { job.map_texels };
        let selected = job.request.selected_light;
        // A light's picture is its first view's map.
        let first_views: Vec<(usize, ShadowViewGpu)> = self.a.last_frame().map_or_else(Vec::new, |f| {
            (0..f.lights.len()).filter_map(|l| f.first_view_of(l).map(|(i, v)| (i, *v))).collect()
        });
        let light_views = self.a.last_frame().and_then(|f| f.views_of(selected).map(|(_, v)| v.to_vec()));
        let light_views = light_views.unwrap_or_default();
        let map_key = (!light_views.is_empty())
            .then(|| MapKey::new(&job.scene, &light_views, job.request.time_s, texels));
        let map_unchanged = map_key.is_some() && map_key == self.last_map;
        let mut to_read = VecDeque::new();
        if let Some(&(index, view)) = first_views.get(selected).filter(|_| !map_unchanged) {
            if light_views.len() > 1 {
                let of = light_views.len();
                for (i, view) in light_views.into_iter().enumerate() {
                    to_read.push_back((index + i, view, Picture::Tile { texels, of }));
                }
            } else {
                to_read.push_back((index, view, Picture::Selected { texels }));
            }
        }
        if job.thumbnails && first_views.len() > 1 {
            to_read.extend(first_views.iter().map(|&(index, view)| (index, view, Picture::Thumbnail)));
        }
        let maps = Maps { job: id, map: None, thumbnails: Vec::new() };
        MapsComing { maps, to_read, reading: None, map_key, tiles: Vec::new() }
    }

    /// Take the picture being read once it is there, then submit the next read-back; once all
    /// are there, send the maps.
    pub(super) fn maps_step(
        &mut self,
        job: &RenderJob,
        mut coming: MapsComing,
        send: &mut dyn FnMut(RenderEvent),
        wait: GpuWait,
    ) -> Result<Stage, RenderError> {
        if let Some(reading) = coming.reading.take() {
            if !reading.arrived(&self.device, wait)? {
                coming.reading = Some(reading);
                return Ok(Stage::Maps(Box::new(coming)));
            }
            match reading.finish()? {
                Made::Selected(view) => coming.maps.map = Some(view),
                Made::Tile(depth, view, index, Picture::Tile { texels, of }) => {
                    coming.tiles.push((depth, view, index));
                    if coming.tiles.len() == of {
                        let tiles = std::mem::take(&mut coming.tiles);
                        coming.maps.map = Some(tiled_picture(tiles, texels));
                    }
                }
                Made::Tile(..) => {}
                Made::Thumbnail(image) => coming.maps.thumbnails.push(image),
            }
        }
        if let Some((index, view, picture)) = coming.to_read.pop_front() {
            let made =
                self.a.shadow_map_readback(index)?.map(move |depth| Ok(make(depth, (index, view), picture)));
            coming.reading = Some(made);
            return Ok(Stage::Maps(Box::new(coming)));
        }
        // Not before: a newer job may replace this one before its maps are sent.
        self.last_map = coming.map_key;
        send(RenderEvent::Maps(Box::new(coming.maps)));
        Ok(if job.wants_details() { Stage::Details } else { job.after_probe() })
    }
}

/// The picture of a light with several maps, tiled by `MapsLayout` (a cube's cross, a sun's
/// cascades in a row), the whole at most `texels` wide.
fn tiled_picture(read: Vec<(DepthImage, ShadowViewGpu, usize)>, texels: u32) -> MapView {
    let (view, index) = (read[0].1, read[0].2);
    let views: Vec<ShadowViewGpu> = read.iter().map(|r| r.1).collect();
    let columns = views::MapsLayout::of(&views).columns;
    let small: Vec<DepthImage> = read.iter().map(|r| subsample(&r.0, (texels / columns).max(16))).collect();
    let (image, legend) = views::light_maps_image(&small, &views);
    MapView {
        depth: read[0].0.clone(),
        view,
        index,
        tiles: read.into_iter().map(|(depth, view, _)| (depth, view)).collect(),
        image,
        range: (legend.min, legend.max),
    }
}

fn make(depth: DepthImage, (index, view): (usize, ShadowViewGpu), picture: Picture) -> Made {
    match picture {
        Picture::Selected { texels } => {
            let (image, legend) = views::shadow_map_image(&subsample(&depth, texels), &view);
            let range = (legend.min, legend.max);
            Made::Selected(MapView { depth, view, index, tiles: Vec::new(), image, range })
        }
        Picture::Tile { .. } => Made::Tile(depth, view, index, picture),
        Picture::Thumbnail => {
            let (image, _) = views::shadow_map_image(&subsample(&depth, 4 * THUMBNAIL_TEXELS), &view);
            Made::Thumbnail(image::imageops::resize(
                &image,
                THUMBNAIL_TEXELS,
                THUMBNAIL_TEXELS,
                image::imageops::FilterType::Triangle,
            ))
        }
    }
}

/// Every `step`-th texel of a map, so that its picture is at most `limit` texels a side.
fn subsample(map: &DepthImage, limit: u32) -> DepthImage {
    let step = map.size.div_ceil(limit.max(1)).max(1);
    if step == 1 {
        return map.clone();
    }
    let size = map.size / step;
    let mut depth_ndc = Vec::with_capacity((size * size) as usize);
    for y in 0..size {
        let row = (y * step * map.size) as usize;
        depth_ndc.extend((0..size).map(|x| map.depth_ndc[row + (x * step) as usize]));
    }
    DepthImage { size, depth_ndc }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn subsampling_keeps_every_nth_texel() {
        let map = DepthImage { size: 8, depth_ndc: (0..64).map(|i| i as f32).collect() };
        let small = subsample(&map, 4);
        assert_eq!(small.size, 4);
        assert_eq!(small.depth_ndc[..4], [0.0, 2.0, 4.0, 6.0]);
        assert_eq!(small.depth_ndc[4], 16.0);
        assert_eq!(subsample(&map, 8).depth_ndc, map.depth_ndc);
    }
}

//! The homework's pictures as textures for the camera view, made from the check's outcome when
//! first shown (one per picture kind, made again for a new outcome).

use crate::app::homework::HomeworkPicture;
use crate::homework::CheckOutcome;
use std::sync::Arc;

#[derive(Default)]
pub struct HomeworkTextures {
    /// The outcome the textures were made from.
    outcome: Option<Arc<CheckOutcome>>,
    textures: Vec<(HomeworkPicture, egui::TextureHandle)>,
}

fn image_of(outcome: &CheckOutcome, picture: HomeworkPicture) -> image::RgbaImage {
    match picture {
        HomeworkPicture::Student => outcome.student_picture(),
        HomeworkPicture::WhiteMap => outcome.student_picture_white_map(),
        HomeworkPicture::Shadowlab => outcome.shadowlab_picture.clone(),
        HomeworkPicture::Visibility => outcome.visibility_picture(false),
        HomeworkPicture::GroundTruth => outcome.visibility_picture(true),
        HomeworkPicture::Difference => outcome.difference_picture(),
    }
}

impl HomeworkTextures {
    /// The texture of `picture` of `outcome`.
    pub fn get(
        &mut self,
        ctx: &egui::Context,
        outcome: &Arc<CheckOutcome>,
        picture: HomeworkPicture,
    ) -> egui::TextureId {
        if !self.outcome.as_ref().is_some_and(|o| Arc::ptr_eq(o, outcome)) {
            self.outcome = Some(outcome.clone());
            self.textures.clear();
        }
        if let Some((_, t)) = self.textures.iter().find(|(p, _)| *p == picture) {
            return t.id();
        }
        let image = image_of(outcome, picture);
        let size = [image.width() as usize, image.height() as usize];
        let color = egui::ColorImage::from_rgba_unmultiplied(size, image.as_raw());
        let texture = ctx.load_texture(format!("homework {picture:?}"), color, egui::TextureOptions::LINEAR);
        let id = texture.id();
        self.textures.push((picture, texture));
        id
    }
}

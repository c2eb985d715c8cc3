//! The CJK font Chinese text is drawn with, in the app's panels, the diagrams and the slides: a
//! system font where one is installed (the desktop, as before), else the subset of Noto Sans CJK
//! SC built into shadowlab (a page has no system fonts; nor has a machine without
//! fonts-noto-cjk). The subset holds every character of shadowlab's own text; text of one's own
//! (a lesson file) may need the system font. `assets/tools/subset_cjk_font.py` makes it and
//! `assets/fonts/OFL.txt` is its licence.

use std::sync::{Arc, OnceLock};

use cosmic_text::fontdb;

/// The bytes of a font file, shared rather than copied (a CJK collection is about 20 MB).
pub type FontBytes = Arc<dyn AsRef<[u8]> + Send + Sync>;

/// Usual Debian/Ubuntu locations of CJK fonts (fonts-noto-cjk, fonts-wqy-*, fonts-arphic-*, ...).
pub const CJK_FONT_PATHS: [&str; 12] = [
    "/usr/share/fonts/opentype/noto/NotoSansCJK-Regular.ttc",
    "/usr/share/fonts/opentype/noto/NotoSansCJKsc-Regular.otf",
    "/usr/share/fonts/opentype/noto/NotoSerifCJK-Regular.ttc",
    "/usr/share/fonts/truetype/noto/NotoSansCJK-Regular.ttc",
    "/usr/share/fonts/noto-cjk/NotoSansCJK-Regular.ttc",
    "/usr/share/fonts/google-noto-cjk/NotoSansCJK-Regular.ttc",
    "/usr/share/fonts/truetype/wqy/wqy-microhei.ttc",
    "/usr/share/fonts/truetype/wqy/wqy-zenhei.ttc",
    "/usr/share/fonts/wqy-microhei/wqy-microhei.ttc",
    "/usr/share/fonts/truetype/arphic/uming.ttc",
    "/usr/share/fonts/truetype/arphic/ukai.ttc",
    "/usr/share/fonts/truetype/droid/DroidSansFallbackFull.ttf",
];

/// Noto Sans CJK SC cut down to shadowlab's own text (`assets/tools/subset_cjk_font.py`).
#[cfg(not(target_arch = "wasm32"))]
pub const BUILT_IN_CJK_FONT: &[u8] =
    include_bytes!(concat!(env!("CARGO_MANIFEST_DIR"), "/assets/fonts/NotoSansCJKsc-Regular-subset.otf"));

/// In a page the same subset is served beside the wasm (`fonts/`), not built into it: index.html
/// starts fetching it with the wasm, and the page hands it over before the app starts.
#[cfg(target_arch = "wasm32")]
static SERVED_CJK_FONT: OnceLock<Vec<u8>> = OnceLock::new();

/// The page's copy of the subset, as fetched (set once, before the app starts).
#[cfg(target_arch = "wasm32")]
pub fn set_served_cjk_font(bytes: Vec<u8>) {
    let _ = SERVED_CJK_FONT.set(bytes);
}

/// The subset's bytes: built in on the desktop; in a page, as served (empty where the fetch
/// failed: Chinese text then has no glyphs, and nothing else changes).
#[cfg(not(target_arch = "wasm32"))]
fn built_in_bytes() -> &'static [u8] {
    BUILT_IN_CJK_FONT
}

#[cfg(target_arch = "wasm32")]
fn built_in_bytes() -> &'static [u8] {
    SERVED_CJK_FONT.get().map_or(&[], Vec::as_slice)
}

/// A CJK font file and the face in it meant for Simplified Chinese (a `.ttc` such as Noto Sans
/// CJK holds the Japanese, Korean and Chinese forms of the same characters as separate faces).
pub struct CjkFont {
    pub bytes: FontBytes,
    pub face_index: u32,
    /// The subset built into shadowlab, not a system font.
    pub built_in: bool,
}

impl CjkFont {
    /// The font file's bytes.
    pub fn data(&self) -> &[u8] {
        (*self.bytes).as_ref()
    }

    /// There is a font: a page whose served copy did not arrive has none.
    pub fn is_present(&self) -> bool {
        !self.data().is_empty()
    }
}

impl std::fmt::Debug for CjkFont {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("CjkFont")
            .field("bytes", &self.data().len())
            .field("face_index", &self.face_index)
            .field("built_in", &self.built_in)
            .finish()
    }
}

/// The font Chinese text is drawn with: [`system_cjk_font`] where there is one, else
/// [`built_in_cjk_font`].
pub fn cjk_font() -> &'static CjkFont {
    system_cjk_font().unwrap_or_else(built_in_cjk_font)
}

/// The first CJK font found in [`CJK_FONT_PATHS`], with its Simplified Chinese face, read once
/// per process; `None` when none is installed (on Debian: `apt-get install fonts-noto-cjk`)
/// and always in a page.
pub fn system_cjk_font() -> Option<&'static CjkFont> {
    static CJK: OnceLock<Option<CjkFont>> = OnceLock::new();
    CJK.get_or_init(|| {
        if cfg!(target_arch = "wasm32") {
            return None;
        }
        CJK_FONT_PATHS.iter().find_map(|path| {
            let bytes: FontBytes = Arc::new(std::fs::read(path).ok()?);
            let face_index = simplified_chinese_face(&bytes)?;
            Some(CjkFont { bytes, face_index, built_in: false })
        })
    })
    .as_ref()
}

/// The subset of Noto Sans CJK SC built into shadowlab.
pub fn built_in_cjk_font() -> &'static CjkFont {
    static BUILT_IN: OnceLock<CjkFont> = OnceLock::new();
    BUILT_IN.get_or_init(|| CjkFont { bytes: Arc::new(built_in_bytes()), face_index: 0, built_in: true })
}

/// Index of the face named "... SC" (Simplified Chinese), else of the first face; `None` when
/// the data holds no font.
fn simplified_chinese_face(bytes: &FontBytes) -> Option<u32> {
    let mut db = fontdb::Database::new();
    db.load_font_source(fontdb::Source::Binary(Arc::clone(bytes)));
    let faces: Vec<_> =
        db.faces().map(|f| (f.index, f.families.iter().any(|(n, _)| n.ends_with(" SC")))).collect();
    faces.iter().find(|(_, sc)| *sc).or(faces.first()).map(|(i, _)| *i)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagrams::{TextRenderer, TextStyle, is_cjk};
    use std::collections::BTreeMap;
    use std::path::{Path, PathBuf};

    /// The text shadowlab ships, file by file, as the subsetting script reads it: src/ without
    /// its tests, the lessons and the scene files.
    fn shipped_text() -> Vec<(PathBuf, String)> {
        fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
            for entry in std::fs::read_dir(dir).expect("readable").flatten() {
                let path = entry.path();
                if path.is_dir() {
                    walk(&path, out);
                } else {
                    out.push(path);
                }
            }
        }
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let mut files = Vec::new();
        for dir in ["src", "lessons", "assets"] {
            walk(&root.join(dir), &mut files);
        }
        files.sort();
        files
            .into_iter()
            .filter_map(|path| {
                let name = path.file_name()?.to_str()?.to_owned();
                let rel = path.strip_prefix(root).ok()?.to_path_buf();
                let text = if rel.starts_with("src") && name.ends_with(".rs") {
                    if name == "tests.rs" || name.ends_with("_tests.rs") {
                        return None;
                    }
                    let text = std::fs::read_to_string(&path).ok()?;
                    text.split("#[cfg(test)]\nmod tests").next().unwrap_or_default().to_owned()
                } else if !rel.starts_with("src") && name.ends_with(".toml") {
                    std::fs::read_to_string(&path).ok()?
                } else {
                    return None;
                };
                Some((rel, text))
            })
            .collect()
    }

    fn renderer(cjk: &CjkFont) -> TextRenderer {
        let faces: Vec<(FontBytes, u32)> = vec![
            (Arc::new(epaint_default_fonts::UBUNTU_LIGHT), 0),
            (Arc::new(epaint_default_fonts::HACK_REGULAR), 0),
            (Arc::clone(&cjk.bytes), cjk.face_index),
        ];
        TextRenderer::from_faces(faces).expect("the fonts load")
    }

    #[test]
    fn the_built_in_cjk_font_holds_every_character_of_the_shipped_text() {
        let subset_alone = TextRenderer::from_faces(vec![(Arc::clone(&built_in_cjk_font().bytes), 0)])
            .expect("the subset loads");
        let with_ui_fonts = renderer(built_in_cjk_font());
        let mut missing: BTreeMap<char, PathBuf> = BTreeMap::new();
        let files = shipped_text();
        assert!(files.len() > 20, "found only {} files of text", files.len());
        for (path, text) in &files {
            for c in text.chars().filter(|c| !c.is_ascii() && !c.is_control()) {
                let drawn = if is_cjk(c) { subset_alone.covers(c) } else { with_ui_fonts.covers(c) };
                if !drawn {
                    missing.entry(c).or_insert_with(|| path.clone());
                }
            }
        }
        let listed: Vec<String> =
            missing.iter().map(|(c, path)| format!("{c} ({})", path.display())).collect();
        assert!(
            missing.is_empty(),
            "the built-in CJK font lacks {}: remake it (pip install fonttools; \
             python3 assets/tools/subset_cjk_font.py)",
            listed.join(", ")
        );
    }

    #[test]
    fn the_built_in_cjk_font_is_the_simplified_chinese_face_at_the_latin_em() {
        let font = built_in_cjk_font();
        let mut db = fontdb::Database::new();
        db.load_font_source(fontdb::Source::Binary(Arc::clone(&font.bytes)));
        let face = db.faces().next().expect("a face");
        assert!(face.families.iter().any(|(n, _)| n == "Noto Sans CJK SC"), "{:?}", face.families);
        // Full-width characters advance by one em, as with the system font.
        let w = renderer(font).measure("阴影贴图", 20.0).width_px;
        assert!((w - 80.0).abs() < 1.0, "four ideographs at 20 px are {w} px wide");
        assert!(BUILT_IN_CJK_FONT.len() < 600_000, "the subset grew to {} bytes", BUILT_IN_CJK_FONT.len());
    }

    /// Where Noto Sans CJK is installed, the subset draws shipped Chinese exactly as it does.
    #[test]
    fn the_built_in_cjk_font_draws_as_the_full_face() {
        let Some(system) = system_cjk_font() else { return };
        if !CJK_FONT_PATHS[..2].iter().any(|p| Path::new(p).exists()) {
            return; // another CJK font: other glyphs
        }
        let text = "阴影贴图（PCSS）：半影宽度 ≈ 1.5 texels，“遮挡物”。";
        let style = TextStyle { px: 22.0, color: tiny_skia::Color::BLACK, bold: false };
        let draw = |cjk: &CjkFont| {
            let mut pixmap = tiny_skia::Pixmap::new(640, 40).expect("pixmap");
            pixmap.fill(tiny_skia::Color::WHITE);
            renderer(cjk).draw(&mut pixmap, text, 4.0, 30.0, style);
            pixmap
        };
        let full = draw(system);
        let ink = full.pixels().iter().filter(|p| p.red() < 128).count();
        assert!(ink > 500, "the line drew {ink} dark pixels");
        assert!(full == draw(built_in_cjk_font()), "the subset draws other glyphs than the full face");
    }

    #[test]
    fn chinese_is_drawn_with_the_system_font_where_one_is_installed() {
        match system_cjk_font() {
            Some(system) => assert!(std::ptr::eq(cjk_font(), system) && !cjk_font().built_in),
            None => assert!(cjk_font().built_in),
        }
    }
}

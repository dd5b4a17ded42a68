//! Pictures of an environment as numpy images: the renderer's SVG
//! rasterised with resvg, the system's fonts loaded once.

use resvg::{tiny_skia, usvg};
use std::sync::{Arc, OnceLock};

/// The system's fonts (without any, text is left out of the picture).
fn fonts() -> Arc<usvg::fontdb::Database> {
    static FONTS: OnceLock<Arc<usvg::fontdb::Database>> = OnceLock::new();
    FONTS
        .get_or_init(|| {
            let mut db = usvg::fontdb::Database::new();
            db.load_system_fonts();
            Arc::new(db)
        })
        .clone()
}

/// An RGB image: rows of `width` pixels of 3 bytes.
pub(crate) struct Rgb {
    /// The pixels, row after row.
    pub(crate) pixels: Vec<u8>,
    /// Rows.
    pub(crate) height: usize,
    /// Pixels per row.
    pub(crate) width: usize,
}

/// Rasterises `svg` at its own size over a white background.
pub(crate) fn rasterise(svg: &str) -> Result<Rgb, String> {
    let options = usvg::Options {
        fontdb: fonts(),
        ..usvg::Options::default()
    };
    let tree = usvg::Tree::from_str(svg, &options).map_err(|e| e.to_string())?;
    let size = tree.size().to_int_size();
    let mut pixmap = tiny_skia::Pixmap::new(size.width(), size.height())
        .ok_or_else(|| format!("bad picture size {}x{}", size.width(), size.height()))?;
    resvg::render(&tree, tiny_skia::Transform::default(), &mut pixmap.as_mut());
    // Premultiplied RGBA over white.
    let pixels = pixmap
        .data()
        .chunks_exact(4)
        .flat_map(|p| {
            let white = 255 - p[3];
            [
                p[0].saturating_add(white),
                p[1].saturating_add(white),
                p[2].saturating_add(white),
            ]
        })
        .collect();
    Ok(Rgb {
        pixels,
        height: size.height() as usize,
        width: size.width() as usize,
    })
}

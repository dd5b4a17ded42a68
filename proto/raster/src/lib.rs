//! SVG documents to pixels, written once for everything that draws: the
//! coordinator's figures and `env-server render` as PNG ([`png`]), the
//! Python package's `render_rgb` as an RGB image ([`rgb`]). Rendered by
//! resvg at the document's own size, with the system's fonts, loaded once
//! per process (without any, text is left out).
//!
//! Its own crate, not a feature of `env-server`'s tools nor a module of
//! `node`: loading the system's fonts reads files, which the pure
//! `env-server` never does (docs/ARCHITECTURE.md, "Pure libraries"), and
//! `node` brings zenoh, which the Python binding must not. This crate
//! depends on resvg alone, so each of them can use it.
//!
//! ```
//! let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="2" height="1">
//!     <rect width="1" height="1" fill="red"/></svg>"#;
//! let image = raster::rgb(svg)?;
//! assert_eq!((image.width, image.height), (2, 1));
//! assert_eq!(image.pixels, [255, 0, 0, 255, 255, 255]);
//! assert!(raster::png(svg)?.starts_with(b"\x89PNG"));
//! # Ok::<(), raster::RasterError>(())
//! ```

#![warn(missing_docs)]

use std::sync::{Arc, OnceLock};

use resvg::{tiny_skia, usvg};

/// An SVG document that could not be rasterised, and why.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("cannot rasterise the picture: {0}")]
pub struct RasterError(String);

/// An RGB image: rows of `width` pixels of 3 bytes, top row first.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Rgb {
    /// The pixels, row after row.
    pub pixels: Vec<u8>,
    /// Rows.
    pub height: usize,
    /// Pixels per row.
    pub width: usize,
}

/// Rasterises `svg` at its own size into PNG bytes (transparent where the
/// document draws nothing).
pub fn png(svg: &str) -> Result<Vec<u8>, RasterError> {
    render(svg)?
        .encode_png()
        .map_err(|e| RasterError(e.to_string()))
}

/// Rasterises `svg` at its own size into an RGB image over a white
/// background.
pub fn rgb(svg: &str) -> Result<Rgb, RasterError> {
    let pixmap = render(svg)?;
    // Premultiplied RGBA over white.
    let pixels = (pixmap.data().chunks_exact(4))
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
        height: pixmap.height() as usize,
        width: pixmap.width() as usize,
    })
}

/// The premultiplied RGBA pixels of `svg` at its own size.
fn render(svg: &str) -> Result<tiny_skia::Pixmap, RasterError> {
    let options = usvg::Options {
        fontdb: fonts(),
        ..usvg::Options::default()
    };
    let tree = usvg::Tree::from_str(svg, &options).map_err(|e| RasterError(e.to_string()))?;
    let size = tree.size().to_int_size();
    let mut pixmap = tiny_skia::Pixmap::new(size.width(), size.height())
        .ok_or_else(|| RasterError(format!("bad size {}x{}", size.width(), size.height())))?;
    resvg::render(&tree, tiny_skia::Transform::default(), &mut pixmap.as_mut());
    Ok(pixmap)
}

/// The system's fonts, loaded on first use and shared after.
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A 4x3 picture: its left half red, its right half blank.
    const HALF_RED: &str = r#"<svg xmlns="http://www.w3.org/2000/svg" width="4" height="3"><rect width="2" height="3" fill="red"/></svg>"#;

    #[test]
    fn png_keeps_the_size_and_what_is_blank_stays_transparent() {
        let png = png(HALF_RED).unwrap();
        assert!(png.starts_with(b"\x89PNG\r\n\x1a\n"));
        let pixmap = tiny_skia::Pixmap::decode_png(&png).unwrap();
        assert_eq!((pixmap.width(), pixmap.height()), (4, 3));
        let red = pixmap.pixel(0, 0).unwrap();
        let blank = pixmap.pixel(3, 2).unwrap();
        assert_eq!((red.red(), red.alpha()), (255, 255));
        assert_eq!(blank.alpha(), 0);
    }

    #[test]
    fn rgb_lays_rows_of_pixels_over_white() {
        let image = rgb(HALF_RED).unwrap();
        assert_eq!((image.width, image.height), (4, 3));
        assert_eq!(image.pixels.len(), 4 * 3 * 3);
        for row in image.pixels.chunks_exact(4 * 3) {
            assert_eq!(row, [255, 0, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255]);
        }
    }

    #[test]
    fn what_is_not_svg_is_an_error() {
        for bad in ["not svg", "", "<svg"] {
            assert!(png(bad).is_err(), "{bad:?}");
            assert!(rgb(bad).is_err(), "{bad:?}");
        }
        let empty = r#"<svg xmlns="http://www.w3.org/2000/svg" width="0" height="0"/>"#;
        assert!(png(empty).is_err());
    }

    #[test]
    fn fonts_are_loaded_once() {
        assert!(Arc::ptr_eq(&fonts(), &fonts()));
    }
}

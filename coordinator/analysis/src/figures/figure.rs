//! A drawn figure: its SVG and PNG, and why drawing one can fail.

use super::draw;

/// One figure, drawn.
#[derive(Clone, Debug, PartialEq)]
pub struct Figure {
    /// File name without extension, e.g. `goal_pct`.
    pub name: &'static str,
    /// The SVG document.
    pub svg: String,
    /// The PNG image.
    pub png: Vec<u8>,
}

impl Figure {
    /// The figure `name` of the SVG document `svg` (or what went wrong in
    /// drawing it), with its PNG.
    pub(super) fn drawn(
        name: &'static str,
        svg: Result<String, String>,
    ) -> Result<Self, FigureError> {
        let svg = svg.map_err(|message| FigureError::Draw { name, message })?;
        let png = draw::png(&svg).map_err(|message| FigureError::Raster { name, message })?;
        Ok(Self { name, svg, png })
    }

    /// The figure's files: `<name>.svg` and `<name>.png` with their bytes.
    pub fn files(&self) -> [(String, &[u8]); 2] {
        [
            (format!("{}.svg", self.name), self.svg.as_bytes()),
            (format!("{}.png", self.name), &self.png),
        ]
    }
}

/// Why a figure could not be made.
#[derive(Debug, thiserror::Error)]
pub enum FigureError {
    /// Plotting failed.
    #[error("cannot draw figure {name}: {message}")]
    Draw {
        /// The figure.
        name: &'static str,
        /// What went wrong.
        message: String,
    },
    /// The SVG could not be rasterised.
    #[error("cannot rasterise figure {name}: {message}")]
    Raster {
        /// The figure.
        name: &'static str,
        /// What went wrong.
        message: String,
    },
}

//! `env-server render`'s output: an episode's picture written as SVG or PNG,
//! or its rcssserver game log (`.rcg`) for the monitors (told by the file
//! name's extension), atomically.

use std::path::Path;

use anyhow::{Context, Result, bail};
use env_server::tools::rcg;
use env_server::tools::render::Trace;

/// Picture formats, told by the file name's extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// `.svg`
    Svg,
    /// `.png`
    Png,
    /// `.rcg`: an rcssserver game log.
    Rcg,
}

impl Format {
    /// The format of `path`, from its extension (either case).
    pub fn of(path: &Path) -> Result<Format> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("svg") => Ok(Format::Svg),
            Some("png") => Ok(Format::Png),
            Some("rcg") => Ok(Format::Rcg),
            _ => bail!(
                "cannot tell the picture format of {}: the file name must end in .svg, .png or .rcg",
                path.display()
            ),
        }
    }
}

/// Writes the picture of `trace` to `path` (SVG, PNG or a game log by
/// extension), atomically.
pub fn write_picture(trace: &Trace, path: &Path) -> Result<()> {
    let bytes = match Format::of(path)? {
        Format::Svg => trace.to_svg().into_bytes(),
        Format::Png => raster::png(&trace.to_svg())?,
        Format::Rcg => rcg::to_rcg(trace).into_bytes(),
    };
    node::files::write_atomically(path, &bytes)
        .with_context(|| format!("cannot write {}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use env_server::tools::render::record_episode;
    use env_server::{EnvConfig, ScriptedPolicy};

    fn trace(seed: u64) -> Trace {
        record_episode(EnvConfig::default(), ScriptedPolicy::Random, seed, 1).unwrap()
    }

    #[test]
    fn png_output_is_a_png() {
        let dir = std::env::temp_dir().join(format!("env-server-picture-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("episode.png");
        write_picture(&trace(2), &path).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        assert!(bytes.starts_with(b"\x89PNG\r\n\x1a\n"));
        let files = std::fs::read_dir(&dir).unwrap().count();
        assert_eq!(files, 1, "only the picture is left");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn bad_paths_are_errors() {
        let t = trace(3);
        let err = write_picture(&t, Path::new("/nonexistent-dir/x.svg")).unwrap_err();
        assert!(
            format!("{err:#}").contains("cannot write /nonexistent-dir/x.svg"),
            "{err:#}"
        );
        let err = write_picture(&t, Path::new("x.gif")).unwrap_err();
        assert!(err.to_string().contains(".svg, .png or .rcg"), "{err}");
    }
}

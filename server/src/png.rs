//! Writing an RGBA image as a PNG file (screenshots, the demo's output).

use anyhow::{Context, Result};

/// Writes `rgba` (`width`×`height`, rows top first) to `path` as a PNG.
pub(crate) fn save_png(path: &std::path::Path, width: u32, height: u32, rgba: Vec<u8>) -> Result<()> {
    let img = image::RgbaImage::from_raw(width, height, rgba).context("screenshot has the wrong size")?;
    img.save(path).with_context(|| format!("writing {}", path.display()))?;
    Ok(())
}

//! What the execute benchmark compares: sides that draw frames and read the last one back.

use anyhow::Result;
use indicatif::ProgressBar;

/// What a side is set up with.
pub(crate) struct Setup {
    /// Square framebuffer size.
    pub(crate) size: u32,
    /// Rasterizer threads of the client's device (0: the driver's).
    pub(crate) client_rasterizer_threads: u32,
}

/// The two sides of a comparison (through `stratad`, then the baseline) and what they draw.
pub(crate) type Sides = (Box<dyn Side>, Box<dyn Side>, String);

/// One side of the comparison.
pub(crate) trait Side {
    /// Draws frames `range` and waits for them: the seconds it took.
    fn frames(&mut self, range: std::ops::Range<u32>, pb: Option<&ProgressBar>) -> Result<f64>;
    /// Frame `f` again, read back (RGBA8, bottom row first).
    fn image(&mut self, f: u32) -> Result<Vec<u8>>;
    /// The executor's counters, for the side through `stratad`.
    fn stats(&mut self) -> Result<Option<strata_protocol::ExecStats>> {
        Ok(None)
    }
}

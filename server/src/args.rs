//! The value types of `stratad`'s command line that several subcommands share.

use strata_compositor::NormalSource;

/// The demo's scene.
#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub(crate) enum Scene {
    /// An instrument cluster's dial and a head unit's map, tilted through each other, lit.
    Dial,
    /// Two planes under different perspective projections, meeting along a known line, unlit.
    Planes,
}

/// Whether the planes' clients declare their projections.
#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub(crate) enum Projections {
    /// Through EGL_STRATA_surface_projection.
    Declared,
    /// Not at all: depth compared raw.
    Raw,
}

/// On or off.
#[derive(Clone, Copy, clap::ValueEnum)]
pub(crate) enum Switch {
    On,
    Off,
}

/// Where lighting takes its normals.
#[derive(Clone, Copy, clap::ValueEnum)]
pub(crate) enum Normals {
    PerSurface,
    FromDepth,
}

impl From<Normals> for NormalSource {
    fn from(n: Normals) -> Self {
        match n {
            Normals::PerSurface => NormalSource::PerSurface,
            Normals::FromDepth => NormalSource::FromDepth,
        }
    }
}

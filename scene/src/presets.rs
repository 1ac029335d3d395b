//! The configuration's `[[surface]]` and `[[layer]]` entries: what the scene gives a surface
//! with a stable ID when it appears, and the layers it creates at start-up.

use serde::{Deserialize, Serialize};

fn yes() -> bool {
    true
}

fn one() -> f32 {
    1.0
}

/// A surface's placement and properties in the configuration (`[[surface]]`), by stable ID.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SurfaceEntry {
    /// Its stable ID.
    pub id: u64,
    /// Left edge and top edge in the output space, and depth layer (each where given).
    #[serde(default)]
    pub x: Option<i32>,
    /// Top edge.
    #[serde(default)]
    pub y: Option<i32>,
    /// Depth layer.
    #[serde(default)]
    pub z: Option<f32>,
    /// Shown (default true).
    #[serde(default = "yes")]
    pub visible: bool,
    /// Opacity in [0, 1] (default 1).
    #[serde(default = "one")]
    pub opacity: f32,
    /// The part of its image shown: x, y (from the image's top), width, height.
    #[serde(default)]
    pub source: Option<[i32; 4]>,
    /// Where it shows, scaled: x, y, width, height.
    #[serde(default)]
    pub destination: Option<[i32; 4]>,
    /// Its normal for per-surface lighting.
    #[serde(default)]
    pub normal: Option<[f32; 3]>,
    /// Whether it accepts input (default true).
    #[serde(default = "yes")]
    pub input: bool,
}

/// A layer in the configuration (`[[layer]]`).
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct LayerEntry {
    /// Its name.
    pub name: String,
    /// Whether its members may show (default true).
    #[serde(default = "yes")]
    pub visible: bool,
    /// Multiplies its members' opacity (default 1).
    #[serde(default = "one")]
    pub opacity: f32,
    /// Its members' stable surface IDs.
    #[serde(default)]
    pub surfaces: Vec<u64>,
}

impl SurfaceEntry {
    /// The property changes it makes to its surface.
    pub fn changes(&self) -> Vec<strata_protocol::properties::Change> {
        use strata_protocol::properties::Change;
        let surface = self.id;
        let mut v = vec![
            Change::Visibility { surface, visible: self.visible },
            Change::Opacity { surface, opacity: self.opacity },
            Change::InputAcceptance { surface, accepts: self.input },
        ];
        if let Some(region) = self.source {
            v.push(Change::SourceRegion { surface, region });
        }
        if let Some(region) = self.destination {
            v.push(Change::DestinationRegion { surface, region });
        }
        v
    }
}

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
    // As on [[layout]] and [[quota]] entries: the credentials a client needs to take this ID.
    /// The user ID a client must connect as to take this ID (none: any client may).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub uid: Option<u32>,
    /// The user a client must connect as (resolved into `uid` when the configuration is read).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub user: Option<String>,
    /// The primary group ID a client must connect with.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gid: Option<u32>,
    /// The primary group a client must connect with (resolved into `gid`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub group: Option<String>,
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
    /// The credentials a client needs to take this entry's ID.
    pub fn requirement(&self) -> strata_protocol::control::Requirement {
        strata_protocol::control::Requirement { uid: self.uid, gid: self.gid }
    }

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

//! Compositing properties of surfaces and of layers (named groups of surfaces), and the
//! changes `stratad ctl surface`, `ctl layer` and `ctl apply` make to them. A batch of changes
//! is checked whole and then applied in one step, so that no composite shows part of it.

use serde::{Deserialize, Serialize};

/// A rectangle: x, y (from the top), width, height, in pixels.
pub type Rect = [i32; 4];

/// A surface's own compositing properties, as `ctl list` shows them.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SurfaceProps {
    /// Whether it is shown; an invisible surface takes no part in the depth select.
    pub visible: bool,
    /// Multiplies its premultiplied colour, in [0, 1].
    pub opacity: f32,
    /// The part of its image shown (x, y from the image's top, width, height); `None`: all of
    /// it.
    pub source: Option<Rect>,
    /// Where it shows, in the output space, its source scaled to fit; `None`: at its placement,
    /// at its image's size.
    pub destination: Option<Rect>,
    /// Whether it accepts input; a surface that does not is passed over when input is routed,
    /// as if it were not there.
    #[serde(default = "accepts_input")]
    pub input: bool,
}

fn accepts_input() -> bool {
    true
}

impl Default for SurfaceProps {
    fn default() -> Self {
        SurfaceProps { visible: true, opacity: 1.0, source: None, destination: None, input: true }
    }
}

/// A layer: a named group of surfaces with a visibility and an opacity of its own, which
/// combine with each member's (a member shows only if it and every layer holding it are
/// visible; its opacity is the product).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LayerRow {
    /// Its name.
    pub name: String,
    /// Whether its members may show.
    pub visible: bool,
    /// Multiplies its members' opacity, in [0, 1].
    pub opacity: f32,
    /// Its members' surface IDs, ascending (a stable ID may be listed before its surface
    /// exists).
    pub surfaces: Vec<u64>,
}

/// One property change.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub enum Change {
    /// Shows or hides a surface.
    Visibility {
        /// Surface ID.
        surface: u64,
        /// Shown.
        visible: bool,
    },
    /// Sets a surface's opacity.
    Opacity {
        /// Surface ID.
        surface: u64,
        /// In [0, 1].
        opacity: f32,
    },
    /// Sets the part of a surface's image that is shown.
    SourceRegion {
        /// Surface ID.
        surface: u64,
        /// x, y (from the image's top), width, height.
        region: Rect,
    },
    /// Sets where a surface shows, in the output space (its source scaled to fit).
    DestinationRegion {
        /// Surface ID.
        surface: u64,
        /// x, y, width, height.
        region: Rect,
    },
    /// Sets whether a surface accepts input (`ctl surface ID input on|off`).
    InputAcceptance {
        /// Surface ID.
        surface: u64,
        /// Accepts input.
        accepts: bool,
    },
    /// Creates an empty, visible, opaque layer.
    LayerCreate {
        /// Its name.
        layer: String,
    },
    /// Removes a layer (its members stay, without it).
    LayerDestroy {
        /// Its name.
        layer: String,
    },
    /// Adds a surface to a layer.
    LayerAdd {
        /// The layer's name.
        layer: String,
        /// Surface ID.
        surface: u64,
    },
    /// Takes a surface out of a layer.
    LayerRemove {
        /// The layer's name.
        layer: String,
        /// Surface ID.
        surface: u64,
    },
    /// Shows or hides a layer's members.
    LayerVisibility {
        /// The layer's name.
        layer: String,
        /// Shown.
        visible: bool,
    },
    /// Sets a layer's opacity.
    LayerOpacity {
        /// The layer's name.
        layer: String,
        /// In [0, 1].
        opacity: f32,
    },
}

/// A change that cannot apply.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ChangeError {
    /// An opacity outside [0, 1] (or not a number).
    #[error("opacity {0} is outside [0, 1]")]
    Opacity(f32),
    /// A region with a negative width or height.
    #[error("region {0:?} has a negative size")]
    NegativeRegion(Rect),
    /// A region whose far edge lies beyond the i32 range.
    #[error("region {0:?} reaches beyond the coordinate range")]
    RegionRange(Rect),
    /// A layer name that is empty or has characters other than letters, digits, `-`, `_`, `.`.
    #[error("layer name {0:?} must be 1 to 64 letters, digits, '-', '_' or '.'")]
    LayerName(String),
    /// No live surface has this ID.
    #[error("no surface {0}; `stratad ctl list` shows them")]
    NoSurface(u64),
    /// No layer has this name.
    #[error("no layer {0:?}; `stratad ctl list` shows them")]
    NoLayer(String),
    /// The surface is not a member of the layer.
    #[error("surface {surface} is not in layer {layer:?}")]
    NotMember {
        /// The layer's name.
        layer: String,
        /// Surface ID.
        surface: u64,
    },
    /// The scene cannot be changed (the daemon is shutting down after a fault).
    #[error("the scene is unavailable")]
    Unavailable,
    /// A layer of this name exists already.
    #[error("layer {0:?} exists already")]
    LayerExists(String),
    /// A change of a batch failed, so none of it applied.
    #[error("change {index} of the batch: {error}; nothing of the batch applied")]
    InBatch {
        /// Its position in the batch, from 0.
        index: usize,
        /// Why.
        error: Box<ChangeError>,
    },
}

/// Checks a region's size and range.
fn check_region(r: Rect) -> Result<(), ChangeError> {
    if r[2] < 0 || r[3] < 0 {
        return Err(ChangeError::NegativeRegion(r));
    }
    if r[0].checked_add(r[2]).is_none() || r[1].checked_add(r[3]).is_none() {
        return Err(ChangeError::RegionRange(r));
    }
    Ok(())
}

/// Checks an opacity.
fn check_opacity(a: f32) -> Result<(), ChangeError> {
    if (0.0..=1.0).contains(&a) {
        Ok(())
    } else {
        Err(ChangeError::Opacity(a))
    }
}

/// Checks a layer name.
pub fn check_layer_name(name: &str) -> Result<(), ChangeError> {
    let ok = (1..=64).contains(&name.len())
        && name.chars().all(|c| c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.'));
    if ok {
        Ok(())
    } else {
        Err(ChangeError::LayerName(name.to_string()))
    }
}

impl Change {
    /// Checks what the change carries, without the scene: opacities, regions, names.
    pub fn validate(&self) -> Result<(), ChangeError> {
        match self {
            Change::Opacity { opacity, .. } | Change::LayerOpacity { opacity, .. } => check_opacity(*opacity)?,
            Change::SourceRegion { region, .. } | Change::DestinationRegion { region, .. } => check_region(*region)?,
            _ => {}
        }
        if let Some(layer) = self.layer() {
            check_layer_name(layer)?;
        }
        Ok(())
    }

    /// The surface it changes, if any.
    pub fn surface(&self) -> Option<u64> {
        match self {
            Change::Visibility { surface, .. }
            | Change::Opacity { surface, .. }
            | Change::SourceRegion { surface, .. }
            | Change::DestinationRegion { surface, .. }
            | Change::InputAcceptance { surface, .. }
            | Change::LayerAdd { surface, .. }
            | Change::LayerRemove { surface, .. } => Some(*surface),
            _ => None,
        }
    }

    /// The layer it changes, if any.
    pub fn layer(&self) -> Option<&str> {
        match self {
            Change::LayerCreate { layer }
            | Change::LayerDestroy { layer }
            | Change::LayerAdd { layer, .. }
            | Change::LayerRemove { layer, .. }
            | Change::LayerVisibility { layer, .. }
            | Change::LayerOpacity { layer, .. } => Some(layer),
            _ => None,
        }
    }
}

impl ChangeError {
    /// `self`, from change `index` of a batch of `len`: named by its position unless the batch
    /// is that one change.
    pub fn at(self, index: usize, len: usize) -> ChangeError {
        if len == 1 {
            self
        } else {
            ChangeError::InBatch { index, error: Box::new(self) }
        }
    }
}

/// Checks every change of a batch without the scene (values and names); the error names the
/// change that fails.
pub fn validate_batch(changes: &[Change]) -> Result<(), ChangeError> {
    for (i, c) in changes.iter().enumerate() {
        c.validate().map_err(|e| e.at(i, changes.len()))?;
    }
    Ok(())
}

/// A batch as `stratad ctl apply FILE.json` reads it: `{"changes": [...]}`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Batch {
    /// The changes, applied in order, all in one step.
    pub changes: Vec<Change>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_values_are_refused() {
        let op = |opacity| Change::Opacity { surface: 1, opacity }.validate();
        assert_eq!(op(0.0), Ok(()));
        assert_eq!(op(1.0), Ok(()));
        assert_eq!(op(1.01), Err(ChangeError::Opacity(1.01)));
        assert_eq!(op(-0.1), Err(ChangeError::Opacity(-0.1)));
        assert!(op(f32::NAN).is_err());
        let reg = |region| Change::SourceRegion { surface: 1, region }.validate();
        assert_eq!(reg([0, 0, 0, 0]), Ok(()));
        assert_eq!(reg([0, 0, -1, 4]), Err(ChangeError::NegativeRegion([0, 0, -1, 4])));
        assert_eq!(reg([i32::MAX, 0, 1, 4]), Err(ChangeError::RegionRange([i32::MAX, 0, 1, 4])));
        let name = |layer: &str| Change::LayerCreate { layer: layer.into() }.validate();
        assert_eq!(name("ic.main-1_a"), Ok(()));
        assert!(name("").is_err());
        assert!(name("a b").is_err());
        assert!(name(&"x".repeat(65)).is_err());
    }

    #[test]
    fn a_batch_reads_as_documented() {
        let text = r#"{"changes": [
            {"opacity": {"surface": 1000, "opacity": 0.5}},
            {"destination-region": {"surface": 1000, "region": [0, 0, 64, 32]}},
            {"layer-create": {"layer": "ic"}},
            {"layer-add": {"layer": "ic", "surface": 1000}}
        ]}"#;
        let b: Batch = serde_json::from_str(text).expect("the documented form parses");
        assert_eq!(b.changes.len(), 4);
        assert_eq!(b.changes[1], Change::DestinationRegion { surface: 1000, region: [0, 0, 64, 32] });
        assert!(serde_json::from_str::<Batch>(r#"{"changes": [{"opacity": {"surface": 1, "alpha": 1}}]}"#).is_err());
    }
}

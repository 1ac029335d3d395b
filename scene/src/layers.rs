//! Layers: named groups of surfaces with a visibility and an opacity of their own.

use std::collections::{BTreeMap, BTreeSet};

/// A layer's own state.
#[derive(Debug, Clone)]
pub struct LayerState {
    /// Whether its members may show.
    pub visible: bool,
    /// Multiplies its members' opacity.
    pub opacity: f32,
    /// Its members' surface IDs (live or not).
    pub surfaces: BTreeSet<u64>,
}

impl Default for LayerState {
    fn default() -> Self {
        LayerState { visible: true, opacity: 1.0, surfaces: BTreeSet::new() }
    }
}

/// The layers, by name.
pub type Layers = BTreeMap<String, LayerState>;

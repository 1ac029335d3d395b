//! `stratad ctl export`: the whole scene in the daemon's configuration format (JSON), which
//! `--config FILE.json` reads back: outputs, the layout and quotas it was started with, every
//! stable-ID surface's placement and properties, the layers and the lighting. Surfaces with
//! runtime IDs are left out: their IDs do not survive a restart.

use crate::layout::{Config, LayerEntry, SurfaceEntry};

use super::shared::Shared;

/// The scene as a configuration.
pub(super) fn export(shared: &Shared) -> serde_json::Value {
    let output = match &shared.root {
        Some(root) => root
            .rows()
            .into_iter()
            .map(|o| format!("{}:{}={}x{}+{}+{}", o.kind, o.name, o.rect[2], o.rect[3], o.rect[0], o.rect[1]))
            .collect(),
        None => Vec::new(),
    };
    let rows: Vec<_> = shared.scene.rows().into_iter().filter(|r| r.stable).collect();
    let configured = |id: u64| shared.opts.surfaces.iter().find(|s| s.id == id);
    // Entries for IDs no live surface holds stay as configured, so that their credentials
    // survive the round trip.
    let waiting: Vec<_> = shared.opts.surfaces.iter().filter(|s| !rows.iter().any(|r| r.id == s.id)).cloned().collect();
    let surface = rows
        .into_iter()
        .map(|r| SurfaceEntry {
            id: r.id,
            x: Some(r.rect[0]),
            y: Some(r.rect[1]),
            z: Some(r.z),
            visible: r.props.visible,
            opacity: r.props.opacity,
            source: r.props.source,
            destination: r.props.destination,
            normal: Some(r.normal),
            input: r.props.input,
            uid: configured(r.id).and_then(|s| s.uid),
            user: configured(r.id).and_then(|s| s.user.clone()),
            gid: configured(r.id).and_then(|s| s.gid),
            group: configured(r.id).and_then(|s| s.group.clone()),
        })
        .chain(waiting)
        .collect();
    let layer = shared
        .scene
        .layers()
        .into_iter()
        .map(|l| LayerEntry { name: l.name, visible: l.visible, opacity: l.opacity, surfaces: l.surfaces })
        .collect();
    let config = Config {
        output,
        layout: shared.opts.layout.clone(),
        quota: shared.opts.quotas.clone(),
        surface,
        layer,
        lighting: Some(shared.scene.lighting()),
    };
    serde_json::to_value(config).unwrap_or_else(|e| serde_json::json!({ "error": e.to_string() }))
}

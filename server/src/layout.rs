//! Where window surfaces go when the application does not say: the daemon's layout, one entry
//! per client name (by default a client's process name). This is how an instrument cluster
//! and a head unit are placed without changing their code.
//!
//! Precedence: a placement the client states (`STRATA_WINDOW`) wins; otherwise the first
//! layout entry whose `client` equals the client's name; otherwise the surface's own request.
//! An entry's `priority`, `deadline` and `projection` apply whatever the client states, and win
//! over what its EGL context or surfaces ask for.

use std::path::Path;
use std::str::FromStr;

use serde::{Deserialize, Serialize};
use strata_protocol::projection::{Projection, ProjectionError};
pub use strata_scene::presets::{LayerEntry, SurfaceEntry};

/// One layout entry.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct LayoutEntry {
    /// The client name it applies to; empty or absent: every client whose credentials the
    /// entry's `uid`/`user`/`gid`/`group` admit, whatever it calls itself.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub client: String,
    /// Left edge in the output space.
    pub x: i32,
    /// Top edge in the output space.
    pub y: i32,
    /// Depth layer (larger is farther).
    pub z: f32,
    /// Width, if the layout sets it (else the window's own).
    pub width: Option<u32>,
    /// Height, if the layout sets it (else the window's own).
    pub height: Option<u32>,
    /// The client's scheduling class (`"high"`, `"normal"` or `"low"`); wins over what its EGL
    /// context asks for.
    #[serde(default)]
    pub priority: Option<strata_protocol::control::Priority>,
    /// Whether the compositor watches its surfaces' frame deadlines (`ctl stats` and
    /// `ctl list` count the misses).
    #[serde(default)]
    pub deadline: bool,
    /// The projection of the client's window surfaces' depth
    /// (`{ kind = "perspective", near = 0.1, far = 100.0, reversed = false }`); wins over what
    /// their `EGL_STRATA_surface_projection` attributes declare.
    #[serde(default)]
    pub projection: Option<Projection>,
    /// Stable IDs of the client's window surfaces, in the order it creates them (`id = 1000`,
    /// or `id = [1000, 1001]`); surfaces beyond the list get runtime IDs.
    #[serde(default)]
    pub id: SurfaceIds,
    // The same four fields stand on [[quota]] entries: serde cannot flatten a shared struct into
    // one that denies unknown fields.
    /// The user ID a client must connect as to get this entry (see [`crate::identity`]).
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
    /// Whose placement wins: `"fixed"` (this entry's, whatever the client states) or
    /// `"client"` (a placement the client states, `STRATA_WINDOW`); by default fixed when the
    /// entry requires credentials, else client.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub placement: Option<PlacementPolicy>,
}

/// Whose placement wins for a layout entry's client.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum PlacementPolicy {
    /// The entry's rectangle and z, whatever the client states.
    Fixed,
    /// A placement the client states wins over the entry's.
    Client,
}

/// A layout entry's stable surface IDs: one number or a list.
#[derive(Debug, Clone, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(from = "OneOrMany")]
pub struct SurfaceIds(pub Vec<u32>);

/// How the configuration writes [`SurfaceIds`].
#[derive(Deserialize)]
#[serde(untagged)]
enum OneOrMany {
    One(u32),
    Many(Vec<u32>),
}

impl From<OneOrMany> for SurfaceIds {
    fn from(v: OneOrMany) -> Self {
        match v {
            OneOrMany::One(id) => SurfaceIds(vec![id]),
            OneOrMany::Many(ids) => SurfaceIds(ids),
        }
    }
}

impl SurfaceIds {
    /// The stable ID of the client's `n`th window surface (0: its first), if the entry gives one.
    pub fn nth(&self, n: usize) -> Option<u64> {
        self.0.get(n).map(|&id| u64::from(id))
    }
}

/// The daemon's configuration file, TOML (or JSON, as `stratad ctl export` writes it, when its
/// name ends in `.json`): `[[layout]]` tables with `client`, `x`, `y`, `z` and optionally
/// `width`, `height`, `priority`, `deadline`, `projection`, `id`; `[[quota]]` tables with
/// `client` and limits; `output` strings in `--output` form; `[[surface]]` tables with a
/// stable `id` and properties; `[[layer]]` tables; and a `[lighting]` table.
#[derive(Debug, Clone, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Config {
    /// Outputs in `--output` form (`headless:NAME=WxH+X+Y`), used when no `--output` is given.
    #[serde(default)]
    pub output: Vec<String>,
    /// Layout entries, first match wins.
    #[serde(default)]
    pub layout: Vec<LayoutEntry>,
    /// Per-client quotas (`[[quota]]` with `client` and any of the `--quota-*` names without
    /// the prefix), first match wins.
    #[serde(default)]
    pub quota: Vec<crate::quota::QuotaEntry>,
    /// Placement and properties of surfaces by stable ID, given to such a surface when it
    /// appears.
    #[serde(default)]
    pub surface: Vec<SurfaceEntry>,
    /// Layers, created at start.
    #[serde(default)]
    pub layer: Vec<LayerEntry>,
    /// The lighting at start (wins over `--lighting` and `--normals`).
    #[serde(default)]
    pub lighting: Option<strata_protocol::control::Lighting>,
}

/// A layout or configuration that cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum LayoutError {
    /// The file could not be read.
    #[error("reading {path}: {source}")]
    Read {
        /// The file.
        path: String,
        /// The OS error.
        source: std::io::Error,
    },
    /// The file is not valid TOML of the expected shape.
    #[error("{path}: {message}")]
    Parse {
        /// The file.
        path: String,
        /// What is wrong.
        message: String,
    },
    /// An entry has values out of range.
    #[error("layout entry for {client:?}: {why}")]
    Invalid {
        /// The entry's client.
        client: String,
        /// What is wrong.
        why: String,
    },
    /// An entry's projection cannot be used.
    #[error("layout entry for {client:?}: projection: {source}")]
    Projection {
        /// The entry's client.
        client: String,
        /// What is wrong with it.
        source: ProjectionError,
    },
    /// An entry names a user or group this machine does not have.
    #[error("{section} entry for {client:?}: {source}")]
    Identity {
        /// `[[layout]]` or `[[quota]]`.
        section: &'static str,
        /// The entry's client.
        client: String,
        /// What is wrong.
        source: crate::credentials::IdentityError,
    },
    /// A `--layout` entry names a client whose configuration entry requires credentials.
    #[error(
        "--layout {client:?} would shadow the configuration's [[layout]] entry for {client:?}, which requires \
         {requires}: give that client's placement in the configuration file"
    )]
    Shadows {
        /// The client.
        client: String,
        /// What the configuration's entry requires.
        requires: crate::credentials::Requirement,
    },
    /// A `--layout` argument does not parse.
    #[error("--layout {0:?} is not CLIENT=X,Y,Z[,WxH]")]
    Syntax(String),
}

impl LayoutEntry {
    /// The credentials a client needs to get this entry.
    pub fn requirement(&self) -> crate::credentials::Requirement {
        crate::credentials::Requirement { uid: self.uid, gid: self.gid }
    }

    /// Whether the entry's placement wins over one the client states.
    pub fn fixed_placement(&self) -> bool {
        self.placement.unwrap_or(if self.requirement().any() {
            PlacementPolicy::Fixed
        } else {
            PlacementPolicy::Client
        }) == PlacementPolicy::Fixed
    }

    /// Checks the values: a finite z, sizes within 1..=8192 when given, a usable projection.
    pub fn validate(&self) -> Result<(), LayoutError> {
        let bad = |why: String| LayoutError::Invalid { client: self.client.clone(), why };
        if self.client.is_empty() && !self.requirement().any() {
            return Err(bad(
                "it names no client and requires no credentials: give client, or uid/user/gid/group".into()
            ));
        }
        if !self.z.is_finite() {
            return Err(bad(format!("z {} is not finite", self.z)));
        }
        for (what, v) in [("width", self.width), ("height", self.height)] {
            if v.is_some_and(|v| !(1..=8192).contains(&v)) {
                return Err(bad(format!("{what} must lie in 1..=8192")));
            }
        }
        if self.width.is_some() != self.height.is_some() {
            return Err(bad("give both width and height, or neither".into()));
        }
        if let Some(p) = &self.projection {
            p.validate().map_err(|source| LayoutError::Projection { client: self.client.clone(), source })?;
        }
        for &id in &self.id.0 {
            strata_protocol::surface_id::check(i64::from(id)).map_err(|e| bad(e.to_string()))?;
        }
        Ok(())
    }
}

impl FromStr for LayoutEntry {
    type Err = LayoutError;

    /// Parses `CLIENT=X,Y,Z[,WxH]`.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let bad = || LayoutError::Syntax(s.to_string());
        let (client, rest) = s.split_once('=').ok_or_else(bad)?;
        let parts: Vec<&str> = rest.split(',').map(str::trim).collect();
        let [x, y, z, size @ ..] = parts.as_slice() else { return Err(bad()) };
        let (width, height) = match size {
            [] => (None, None),
            [wh] => {
                let (w, h) = wh.split_once('x').ok_or_else(bad)?;
                (Some(w.parse().map_err(|_| bad())?), Some(h.parse().map_err(|_| bad())?))
            }
            _ => return Err(bad()),
        };
        let e = LayoutEntry {
            client: client.to_string(),
            x: x.parse().map_err(|_| bad())?,
            y: y.parse().map_err(|_| bad())?,
            z: z.parse().map_err(|_| bad())?,
            width,
            height,
            priority: None,
            deadline: false,
            projection: None,
            id: SurfaceIds::default(),
            uid: None,
            user: None,
            gid: None,
            group: None,
            placement: None,
        };
        e.validate()?;
        Ok(e)
    }
}

impl Config {
    /// Reads and checks a configuration file.
    pub fn load(path: &Path) -> Result<Config, LayoutError> {
        let p = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|source| LayoutError::Read { path: p.clone(), source })?;
        let json = path.extension().is_some_and(|e| e == "json");
        let config: Config = if json {
            serde_json::from_str(&text).map_err(|e| LayoutError::Parse { path: p.clone(), message: e.to_string() })?
        } else {
            toml::from_str(&text).map_err(|e| LayoutError::Parse { path: p.clone(), message: e.to_string() })?
        };
        let mut config = config;
        for e in &mut config.layout {
            crate::credentials::resolve(&mut e.uid, e.user.as_deref(), &mut e.gid, e.group.as_deref())
                .map_err(|source| LayoutError::Identity { section: "[[layout]]", client: e.client.clone(), source })?;
        }
        for e in &mut config.quota {
            crate::credentials::resolve(&mut e.uid, e.user.as_deref(), &mut e.gid, e.group.as_deref())
                .map_err(|source| LayoutError::Identity { section: "[[quota]]", client: e.client.clone(), source })?;
        }
        for e in &mut config.surface {
            crate::credentials::resolve(&mut e.uid, e.user.as_deref(), &mut e.gid, e.group.as_deref())
                .map_err(|source| LayoutError::Identity { section: "[[surface]]", client: e.id.to_string(), source })?;
        }
        for e in &config.layout {
            e.validate()?;
        }
        let invalid = |what: String, why: String| LayoutError::Invalid { client: what, why };
        for s in &config.surface {
            for c in s.changes() {
                c.validate().map_err(|e| invalid(format!("surface {}", s.id), e.to_string()))?;
            }
            if s.z.is_some_and(|z| !z.is_finite()) {
                return Err(invalid(format!("surface {}", s.id), "z is not finite".into()));
            }
        }
        for l in &config.layer {
            strata_protocol::properties::check_layer_name(&l.name)
                .map_err(|e| invalid(l.name.clone(), e.to_string()))?;
            if !(0.0..=1.0).contains(&l.opacity) {
                return Err(invalid(l.name.clone(), format!("opacity {} is outside [0, 1]", l.opacity)));
            }
        }
        if let Some(l) = &config.lighting {
            strata_protocol::control::LightChange::from(*l).validate().map_err(|e| invalid("lighting".into(), e))?;
        }
        for o in &config.output {
            o.parse::<strata_compositor::root::OutputSpec>().map_err(|e| invalid("output".into(), e.to_string()))?;
        }
        let mut seen = std::collections::HashMap::new();
        for e in &config.layout {
            for &id in &e.id.0 {
                if let Some(first) = seen.insert(id, e.client.as_str()) {
                    return Err(LayoutError::Invalid {
                        client: e.client.clone(),
                        why: format!("surface id {id} is also given to {first:?}"),
                    });
                }
            }
        }
        if let Some(q) = config.quota.iter().find(|q| q.client.is_empty() && !q.requirement().any()) {
            return Err(LayoutError::Invalid {
                client: q.client.clone(),
                why: "a [[quota]] entry names no client and requires no credentials: give client, or \
                      uid/user/gid/group"
                    .into(),
            });
        }
        Ok(config)
    }
}

/// The `--layout` entries (first) and the configuration's; refuses a `--layout` entry that
/// would shadow a configuration entry of the same name that requires credentials (its
/// placement is the configuration's to give).
pub fn merge(cli: Vec<LayoutEntry>, config: Vec<LayoutEntry>) -> Result<Vec<LayoutEntry>, LayoutError> {
    for e in &cli {
        if let Some(c) = config.iter().find(|c| c.client == e.client && c.requirement().any()) {
            return Err(LayoutError::Shadows { client: e.client.clone(), requires: c.requirement() });
        }
    }
    Ok(cli.into_iter().chain(config).collect())
}

/// The first entry naming client `name`, if any (whatever credentials it requires).
pub fn find<'a>(layout: &'a [LayoutEntry], name: &str) -> Option<&'a LayoutEntry> {
    layout.iter().find(|e| e.client == name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_layout_argument_may_not_shadow_an_entry_that_requires_credentials() {
        let ic: LayoutEntry = "ic=0,0,0.5".parse().expect("entry");
        let mut bound = ic.clone();
        bound.uid = Some(1);
        let cli: LayoutEntry = "ic=9,9,0.5".parse().expect("entry");
        let e = merge(vec![cli.clone()], vec![bound]).expect_err("shadows");
        assert!(matches!(e, LayoutError::Shadows { ref client, .. } if client == "ic"), "{e}");
        let merged = merge(vec![cli], vec![ic]).expect("an entry without credentials may be shadowed");
        assert_eq!(merged.iter().map(|e| e.x).collect::<Vec<_>>(), vec![9, 0]);
    }

    #[test]
    fn layout_arguments_parse_and_bad_ones_are_refused() {
        let e: LayoutEntry = "ic=10,20,0.5".parse().expect("parses");
        assert_eq!((e.x, e.y, e.z, e.width), (10, 20, 0.5, None));
        let e: LayoutEntry = "hu=-5,0,1,640x480".parse().expect("parses");
        assert_eq!((e.width, e.height), (Some(640), Some(480)));
        for bad in ["ic", "ic=1,2", "ic=1,2,nan", "ic=1,2,3,0x10", "=1,2,3", "ic=1,2,3,4", "ic=a,2,3"] {
            assert!(bad.parse::<LayoutEntry>().is_err(), "{bad} parsed");
        }
    }

    #[test]
    fn config_files_parse_and_bad_ones_say_why() {
        let dir = std::env::temp_dir().join(format!("strata-layout-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("dir");
        let good = dir.join("good.toml");
        std::fs::write(&good, "[[layout]]\nclient = \"ic\"\nx = 0\ny = 0\nz = 0.5\n\n[[layout]]\nclient = \"hu\"\nx = 960\ny = 0\nz = 0.5\nwidth = 960\nheight = 720\n").expect("write");
        let c = Config::load(&good).expect("loads");
        assert_eq!(c.layout.len(), 2);
        assert_eq!(find(&c.layout, "hu").map(|e| e.x), Some(960));
        assert!(find(&c.layout, "other").is_none());
        let bad = dir.join("bad.toml");
        std::fs::write(&bad, "[[layout]]\nclient = \"ic\"\nx = 0\ny = 0\nz = 0.5\nwidth = 10\n").expect("write");
        let e = Config::load(&bad).expect_err("width without height");
        assert!(e.to_string().contains("give both width and height"), "{e}");
        std::fs::write(&bad, "[[layout]]\nclient = \"ic\"\nx = 0\nwhere = 1\n").expect("write");
        assert!(matches!(Config::load(&bad), Err(LayoutError::Parse { .. })));
        assert!(matches!(Config::load(&dir.join("missing.toml")), Err(LayoutError::Read { .. })));
        // Classes and deadlines; an unknown class names the valid ones.
        let classes = dir.join("classes.toml");
        std::fs::write(&classes, "[[layout]]\nclient = \"ic\"\nx = 0\ny = 0\nz = 0.5\npriority = \"high\"\ndeadline = true\n\n[[layout]]\nclient = \"hu\"\nx = 0\ny = 0\nz = 1\npriority = \"low\"\n").expect("write");
        let c = Config::load(&classes).expect("loads");
        use strata_protocol::control::Priority;
        assert_eq!(find(&c.layout, "ic").map(|e| (e.priority, e.deadline)), Some((Some(Priority::High), true)));
        assert_eq!(find(&c.layout, "hu").map(|e| (e.priority, e.deadline)), Some((Some(Priority::Low), false)));
        std::fs::write(&bad, "[[layout]]\nclient = \"ic\"\nx = 0\ny = 0\nz = 0.5\npriority = \"urgent\"\n")
            .expect("write");
        let e = Config::load(&bad).expect_err("unknown class").to_string();
        assert!(e.contains("urgent") && e.contains("high") && e.contains("normal") && e.contains("low"), "{e}");
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn stable_surface_ids_parse_and_clashes_are_refused() {
        let dir = std::env::temp_dir().join(format!("strata-layout-ids-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("dir");
        let file = dir.join("ids.toml");
        let entry =
            |client: &str, id: &str| format!("[[layout]]\nclient = \"{client}\"\nx = 0\ny = 0\nz = 0.5\nid = {id}\n\n");
        std::fs::write(&file, entry("ic", "1000") + &entry("hu", "[2000, 2001]")).expect("write");
        let c = Config::load(&file).expect("loads");
        let ic = find(&c.layout, "ic").map(|e| (e.id.nth(0), e.id.nth(1)));
        assert_eq!(ic, Some((Some(1000), None)));
        let hu = find(&c.layout, "hu").map(|e| (e.id.nth(0), e.id.nth(1)));
        assert_eq!(hu, Some((Some(2000), Some(2001))));
        for (body, says) in [
            (entry("ic", "1000") + &entry("hu", "[2000, 1000]"), "surface id 1000 is also given to \"ic\""),
            (entry("ic", "0"), "outside 1..="),
            (entry("ic", "[1, 2147483648]"), "outside 1..="),
        ] {
            std::fs::write(&file, body).expect("write");
            let e = Config::load(&file).expect_err(says).to_string();
            assert!(e.contains(says), "{e}");
        }
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn projections_parse_and_bad_ones_name_the_client_and_the_problem() {
        use strata_protocol::projection::ProjectionKind;
        let dir = std::env::temp_dir().join(format!("strata-layout-proj-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("dir");
        let file = dir.join("p.toml");
        let entry = |client: &str, projection: &str| {
            format!("[[layout]]\nclient = \"{client}\"\nx = 0\ny = 0\nz = 0.5\nprojection = {projection}\n\n")
        };
        let good = entry("ic", "{ kind = \"perspective\", near = 0.1, far = 100.0, reversed = false }")
            + &entry("hu", "{ kind = \"orthographic\", near = -1, far = 1, reversed = true }")
            + &entry("sky", "{ kind = \"perspective\", near = 1.0, far = inf }")
            + "[[layout]]\nclient = \"plain\"\nx = 0\ny = 0\nz = 1\n";
        std::fs::write(&file, good).expect("write");
        let c = Config::load(&file).expect("loads");
        let p = |name| find(&c.layout, name).and_then(|e| e.projection);
        assert_eq!(
            p("ic"),
            Some(Projection { kind: ProjectionKind::Perspective, near: 0.1, far: 100.0, reversed: false })
        );
        assert_eq!(
            p("hu"),
            Some(Projection { kind: ProjectionKind::Orthographic, near: -1.0, far: 1.0, reversed: true })
        );
        assert_eq!(p("sky").map(|p| (p.far, p.reversed)), Some((f32::INFINITY, false)), "reversed defaults to false");
        assert_eq!(p("plain"), None);
        // Planes out of order, or a perspective near plane at 0: a start-up error naming the
        // client and the problem.
        for (projection, problem) in [
            ("{ kind = \"perspective\", near = 10.0, far = 1.0 }", "near 10 must be less than far 1"),
            ("{ kind = \"perspective\", near = 0.0, far = 1.0 }", "needs near > 0"),
            ("{ kind = \"orthographic\", near = 0.0, far = inf }", "must be finite"),
        ] {
            std::fs::write(
                &file,
                entry("plain", "{ kind = \"perspective\", near = 1.0, far = 2.0 }") + &entry("cluster", projection),
            )
            .expect("write");
            let e = Config::load(&file).expect_err(projection);
            assert!(matches!(&e, LayoutError::Projection { client, .. } if client == "cluster"), "{e:?}");
            let e = e.to_string();
            assert!(e.contains("\"cluster\"") && e.contains(problem), "{e}");
        }
        // An unknown kind names the valid kinds; a missing plane is named.
        std::fs::write(&file, entry("ic", "{ kind = \"fisheye\", near = 1.0, far = 2.0 }")).expect("write");
        let e = Config::load(&file).expect_err("unknown kind").to_string();
        assert!(e.contains("fisheye") && e.contains("perspective") && e.contains("orthographic"), "{e}");
        std::fs::write(&file, entry("ic", "{ kind = \"perspective\", near = 1.0 }")).expect("write");
        let e = Config::load(&file).expect_err("no far plane").to_string();
        assert!(e.contains("far"), "{e}");
        let _ = std::fs::remove_dir_all(&dir);
    }
}

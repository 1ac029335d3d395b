//! The layers of `docs/architecture.md`: its `## Layers` table names, for every member
//! package, the workspace packages it depends on; the packages' manifests must say the same, so
//! that the crate graph the document describes is the one cargo builds (a back edge between
//! layers must change the document first, where it shows).

use std::collections::{BTreeMap, BTreeSet};

use crate::workspace::Member;

/// What the layers table gets wrong.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct LayerCheck {
    /// Each disagreement, in words.
    pub problems: Vec<String>,
}

/// The short name the table uses for package `name`: without the `strata-` prefix.
fn short(name: &str) -> &str {
    name.strip_prefix("strata-").unwrap_or(name)
}

/// The cells of a table line (`| a | b |`), trimmed; `None` for a line that is not a row.
fn cells(line: &str) -> Option<Vec<&str>> {
    let inner = line.trim().strip_prefix('|')?.strip_suffix('|')?;
    Some(inner.split('|').map(str::trim).collect())
}

/// The layers table of `doc`: each package (as its first cell names it, backticked) and the
/// short names in its `depends on` column; `None` where the document has no such table.
pub fn layer_table(doc: &str) -> Option<BTreeMap<String, BTreeSet<String>>> {
    let section = doc.split("\n## ").find(|s| s.starts_with("Layers"))?;
    let mut lines = section.lines().filter_map(cells);
    let header = lines.next()?;
    let column = header.iter().position(|c| c.eq_ignore_ascii_case("depends on"))?;
    let mut table = BTreeMap::new();
    for row in lines {
        let Some(name) = row.first().and_then(|c| c.strip_prefix('`')?.strip_suffix('`')) else { continue };
        let deps = row.get(column).copied().unwrap_or_default();
        let listed = if deps.starts_with('(') {
            BTreeSet::new()
        } else {
            deps.split(',').map(|d| d.trim().to_string()).filter(|d| !d.is_empty()).collect()
        };
        table.insert(name.to_string(), listed);
    }
    Some(table)
}

/// Checks the layers table of `doc` against the members' manifests.
pub fn check_layers(doc: &str, members: &[Member]) -> LayerCheck {
    let Some(table) = layer_table(doc) else {
        return LayerCheck { problems: vec!["no `## Layers` table with a `depends on` column".to_string()] };
    };
    let packages: BTreeSet<&str> = members.iter().map(|m| m.name.as_str()).collect();
    let mut problems = Vec::new();
    for m in members {
        let actual: BTreeSet<String> =
            m.dependencies.iter().filter(|d| packages.contains(d.as_str())).map(|d| short(d).to_string()).collect();
        match table.get(&m.name) {
            None => problems.push(format!("`{}` has no row in the layers table", m.name)),
            Some(listed) if *listed != actual => problems.push(format!(
                "`{}` depends on {} but the layers table says {}",
                m.name,
                words(&actual),
                words(listed)
            )),
            Some(_) => {}
        }
    }
    for name in table.keys().filter(|n| !packages.contains(n.as_str())) {
        problems.push(format!("the layers table names `{name}`, which is no member package"));
    }
    LayerCheck { problems }
}

/// A set of short names as the table writes them.
fn words(set: &BTreeSet<String>) -> String {
    if set.is_empty() {
        "no workspace crate".to_string()
    } else {
        set.iter().cloned().collect::<Vec<_>>().join(", ")
    }
}

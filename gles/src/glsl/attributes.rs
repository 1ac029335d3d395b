//! A program's vertex inputs: their locations (the shader's, then the application's bindings,
//! then the lowest free ones, a matrix taking one per column) and their declarations in the
//! generated vertex stage.

use std::collections::HashMap;
use std::fmt::Write;

use crate::glsl::types::{Shader, Var};

/// Each input with its (first) location.
pub(super) type Placed = Vec<(Var, u32)>;

/// The vertex shader `vs`'s inputs with their locations, given the application's `bindings`
/// and `max_attribs` locations, and which locations they take.
pub(super) fn place(
    vs: &Shader,
    bindings: &HashMap<String, u32>,
    max_attribs: u32,
) -> Result<(Placed, Vec<bool>), String> {
    let mut attributes: Placed = Vec::new();
    let mut used = vec![false; max_attribs as usize];
    let bindings: HashMap<String, u32> = bindings
        .iter()
        .filter(|(name, _)| !vs.attributes.iter().any(|a| &a.name == *name && a.location.is_some()))
        .map(|(n, l)| (n.clone(), *l))
        .chain(vs.attributes.iter().filter_map(|a| a.location.map(|l| (a.name.clone(), l))))
        .collect();
    // A matrix takes a location per column.
    let width = |a: &Var| a.ty.columns().max(1);
    for a in &vs.attributes {
        let Some(&loc) = bindings.get(&a.name) else { continue };
        let slots = loc as usize..loc as usize + width(a);
        if slots.end > max_attribs as usize {
            return Err(format!("error: attribute '{}' bound to location {loc} beyond the limit", a.name));
        }
        // GLSL ES 3.00 §12.46: no two inputs at one location (ES 1.00 allows the aliasing).
        if vs.version == 300 && used[slots.clone()].iter().any(|&u| u) {
            return Err(format!("error: vertex shader input '{}' shares location {loc} with another", a.name));
        }
        used[slots].iter_mut().for_each(|u| *u = true);
        attributes.push((a.clone(), loc));
    }
    // The others take the lowest free locations, the widest first (as on Mesa).
    let mut free: Vec<&Var> = vs.attributes.iter().filter(|a| !bindings.contains_key(&a.name)).collect();
    free.sort_by_key(|a| std::cmp::Reverse(width(a)));
    for a in free {
        let n = width(a);
        let loc = (0..used.len().saturating_sub(n - 1))
            .find(|&l| used[l..l + n].iter().all(|u| !u))
            .ok_or_else(|| "error: too many vertex attributes".to_string())?;
        used[loc..loc + n].iter_mut().for_each(|u| *u = true);
        attributes.push((a.clone(), loc as u32));
    }
    Ok((attributes, used))
}

/// Declares `attributes` in the vertex stage's source `vsrc`; the statements that assemble
/// each matrix input from its columns, which the generated `main` runs first.
pub(super) fn declare(attributes: &[(Var, u32)], vsrc: &mut String) -> String {
    // A matrix input arrives as its columns, which the generated `main` assembles first.
    let mut attribute_copy = String::new();
    for (a, loc) in attributes {
        let columns = a.ty.columns();
        if columns == 0 {
            let _ = writeln!(vsrc, "layout(location = {loc}) in {} {};", a.ty.glsl(false), a.name);
            continue;
        }
        let parts: Vec<String> = (0..columns).map(|i| format!("{}__col{i}", a.name)).collect();
        for (i, part) in parts.iter().enumerate() {
            let _ = writeln!(vsrc, "layout(location = {}) in vec{} {part};", loc + i as u32, a.ty.rows());
        }
        let ty = a.ty.glsl(false);
        let _ = writeln!(vsrc, "{ty} {};", a.name);
        let _ = writeln!(attribute_copy, "    {} = {ty}({});", a.name, parts.join(", "));
    }
    attribute_copy
}

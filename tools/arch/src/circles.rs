//! Import circles: the strongly connected components of a file graph (Tarjan's algorithm).

use std::collections::HashMap;
use std::path::PathBuf;

use crate::graph::{Edge, FileGraph};

/// A strongly connected component of more than one file, with the edges inside it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Circle {
    /// The files, sorted.
    pub files: Vec<PathBuf>,
    /// The edges between them, sorted by file pair.
    pub edges: Vec<Edge>,
}

/// The circles of a graph, largest first (then by first file).
pub fn find_circles(graph: &FileGraph) -> Vec<Circle> {
    let mut index_of: HashMap<&PathBuf, usize> = HashMap::new();
    let mut nodes: Vec<&PathBuf> = Vec::new();
    for file in graph.files.iter().chain(graph.edges.iter().flat_map(|e| [&e.from, &e.to])) {
        if !index_of.contains_key(file) {
            index_of.insert(file, nodes.len());
            nodes.push(file);
        }
    }
    let mut succ = vec![Vec::new(); nodes.len()];
    for e in &graph.edges {
        if let (Some(&a), Some(&b)) = (index_of.get(&e.from), index_of.get(&e.to)) {
            succ[a].push(b);
        }
    }
    let mut circles: Vec<Circle> = strongly_connected(&succ)
        .into_iter()
        .filter(|c| c.len() > 1)
        .map(|component| {
            let mut files: Vec<PathBuf> = component.iter().map(|&i| nodes[i].clone()).collect();
            files.sort();
            let edges =
                graph.edges.iter().filter(|e| files.contains(&e.from) && files.contains(&e.to)).cloned().collect();
            Circle { files, edges }
        })
        .collect();
    circles.sort_by(|a, b| b.files.len().cmp(&a.files.len()).then_with(|| a.files.cmp(&b.files)));
    circles
}

/// Tarjan's algorithm, iterative: the strongly connected components of `succ`.
pub fn strongly_connected(succ: &[Vec<usize>]) -> Vec<Vec<usize>> {
    const UNSEEN: usize = usize::MAX;
    let n = succ.len();
    let mut index = vec![UNSEEN; n];
    let mut low = vec![0; n];
    let mut on_stack = vec![false; n];
    let mut stack = Vec::new();
    let mut components = Vec::new();
    let mut next = 0;
    for start in 0..n {
        if index[start] != UNSEEN {
            continue;
        }
        let mut work: Vec<(usize, usize)> = vec![(start, 0)];
        index[start] = next;
        low[start] = next;
        next += 1;
        stack.push(start);
        on_stack[start] = true;
        while let Some(&mut (v, ref mut child)) = work.last_mut() {
            if let Some(&w) = succ[v].get(*child) {
                *child += 1;
                if index[w] == UNSEEN {
                    index[w] = next;
                    low[w] = next;
                    next += 1;
                    stack.push(w);
                    on_stack[w] = true;
                    work.push((w, 0));
                } else if on_stack[w] {
                    low[v] = low[v].min(index[w]);
                }
                continue;
            }
            work.pop();
            if let Some(&(parent, _)) = work.last() {
                low[parent] = low[parent].min(low[v]);
            }
            if low[v] == index[v] {
                let mut component = Vec::new();
                while let Some(w) = stack.pop() {
                    on_stack[w] = false;
                    component.push(w);
                    if w == v {
                        break;
                    }
                }
                components.push(component);
            }
        }
    }
    components
}

#[cfg(test)]
mod tests {
    use super::strongly_connected;

    /// The components, each sorted, in sorted order.
    fn sorted(succ: &[Vec<usize>]) -> Vec<Vec<usize>> {
        let mut c: Vec<Vec<usize>> = strongly_connected(succ)
            .into_iter()
            .map(|mut c| {
                c.sort();
                c
            })
            .collect();
        c.sort();
        c
    }

    #[test]
    fn components_of_small_graphs() {
        assert_eq!(sorted(&[vec![1], vec![2], vec![]]), [vec![0], vec![1], vec![2]]);
        assert_eq!(sorted(&[vec![1], vec![0], vec![1, 3], vec![2]]), [vec![0, 1], vec![2, 3]]);
        assert_eq!(sorted(&[vec![1], vec![2], vec![0, 3], vec![3]]), [vec![0, 1, 2], vec![3]]);
    }
}

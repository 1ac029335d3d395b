//! Benchmark meshes: glmark2's models when installed (Autodesk 3DS), otherwise a generated mesh
//! of the same size.

use std::path::Path;

use glam::Vec3;

/// An indexed triangle mesh with per-vertex normals, centred and scaled to fit [-1, 1].
pub struct Mesh {
    /// Interleaved position (xyz) and normal (xyz).
    pub vertices: Vec<f32>,
    /// Triangle indices.
    pub indices: Vec<u32>,
    /// Where it came from.
    pub source: String,
}

/// Why a model file could not be read.
#[derive(Debug, thiserror::Error)]
pub enum MeshError {
    /// The file could not be read.
    #[error("reading {0}: {1}")]
    Io(String, std::io::Error),
    /// The file is not a 3DS mesh this loader understands.
    #[error("{0}: {1}")]
    Format(String, &'static str),
}

fn u16_at(b: &[u8], at: usize) -> Option<u16> {
    Some(u16::from_le_bytes(b.get(at..at + 2)?.try_into().ok()?))
}

fn u32_at(b: &[u8], at: usize) -> Option<u32> {
    Some(u32::from_le_bytes(b.get(at..at + 4)?.try_into().ok()?))
}

fn f32_at(b: &[u8], at: usize) -> Option<f32> {
    Some(f32::from_le_bytes(b.get(at..at + 4)?.try_into().ok()?))
}

/// Walks 3DS chunks in `b[start..end]`, collecting every object's vertices and faces.
fn walk(
    b: &[u8],
    start: usize,
    end: usize,
    positions: &mut Vec<Vec3>,
    indices: &mut Vec<u32>,
    base: &mut u32,
) -> Option<()> {
    let mut at = start;
    while at + 6 <= end {
        let id = u16_at(b, at)?;
        let len = u32_at(b, at + 2)? as usize;
        if len < 6 || at + len > end {
            return None;
        }
        let body = at + 6;
        match id {
            0x4D4D | 0x3D3D | 0x4100 => walk(b, body, at + len, positions, indices, base)?,
            0x4000 => {
                // Object: a NUL-terminated name, then sub-chunks.
                let name_end = b[body..at + len].iter().position(|&c| c == 0)? + body + 1;
                *base = positions.len() as u32;
                walk(b, name_end, at + len, positions, indices, base)?;
            }
            0x4110 => {
                let n = u16_at(b, body)? as usize;
                for i in 0..n {
                    let p = body + 2 + i * 12;
                    positions.push(Vec3::new(f32_at(b, p)?, f32_at(b, p + 4)?, f32_at(b, p + 8)?));
                }
            }
            0x4120 => {
                let n = u16_at(b, body)? as usize;
                for i in 0..n {
                    let f = body + 2 + i * 8;
                    for k in 0..3 {
                        indices.push(*base + u32::from(u16_at(b, f + k * 2)?));
                    }
                }
            }
            _ => {}
        }
        at += len;
    }
    Some(())
}

fn finish(positions: Vec<Vec3>, indices: Vec<u32>, source: String) -> Mesh {
    let (mut lo, mut hi) = (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN));
    for p in &positions {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    let centre = (lo + hi) * 0.5;
    let scale = 2.0 / (hi - lo).max_element().max(1e-6);
    let mut normals = vec![Vec3::ZERO; positions.len()];
    for t in indices.chunks_exact(3) {
        let (a, b, c) = (positions[t[0] as usize], positions[t[1] as usize], positions[t[2] as usize]);
        let n = (b - a).cross(c - a);
        for &i in t {
            normals[i as usize] += n;
        }
    }
    let mut vertices = Vec::with_capacity(positions.len() * 6);
    for (p, n) in positions.iter().zip(&normals) {
        let p = (*p - centre) * scale;
        let n = n.normalize_or(Vec3::Z);
        vertices.extend_from_slice(&[p.x, p.y, p.z, n.x, n.y, n.z]);
    }
    Mesh { vertices, indices, source }
}

/// Loads a 3DS model.
pub fn load_3ds(path: &Path) -> Result<Mesh, MeshError> {
    let name = path.display().to_string();
    let b = std::fs::read(path).map_err(|e| MeshError::Io(name.clone(), e))?;
    let (mut positions, mut indices, mut base) = (Vec::new(), Vec::new(), 0);
    walk(&b, 0, b.len(), &mut positions, &mut indices, &mut base)
        .ok_or(MeshError::Format(name.clone(), "malformed chunk"))?;
    if indices.is_empty() || indices.iter().any(|&i| i as usize >= positions.len()) {
        return Err(MeshError::Format(name, "no valid triangles"));
    }
    Ok(finish(positions, indices, name))
}

/// A UV sphere with at least `triangles` triangles, for machines without glmark2-data.
pub fn sphere(triangles: usize) -> Mesh {
    let rings = ((triangles as f32 / 2.0).sqrt().ceil() as u32).max(3);
    let segments = rings;
    let mut positions = Vec::new();
    for r in 0..=rings {
        let theta = std::f32::consts::PI * r as f32 / rings as f32;
        for s in 0..=segments {
            let phi = 2.0 * std::f32::consts::PI * s as f32 / segments as f32;
            positions.push(Vec3::new(theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin()));
        }
    }
    let mut indices = Vec::new();
    for r in 0..rings {
        for s in 0..segments {
            let a = r * (segments + 1) + s;
            let b = a + segments + 1;
            indices.extend_from_slice(&[a, b, a + 1, a + 1, b, b + 1]);
        }
    }
    finish(positions, indices, format!("generated sphere ({rings}x{segments})"))
}

/// glmark2's model `name` if installed, else a generated mesh of `fallback_triangles`.
pub fn glmark2_model(name: &str, fallback_triangles: usize) -> Mesh {
    let path = Path::new("/usr/share/glmark2/models").join(name);
    match load_3ds(&path) {
        Ok(m) => m,
        Err(e) => {
            tracing::warn!("{e}; using a generated mesh");
            sphere(fallback_triangles)
        }
    }
}

//! Meshes of the fixture format: inline, or read from an OBJ file.

use oracle::geom::{P3, Triangle};
use std::path::Path;

/// A triangle soup: each face `[i, j, k]` indexes `vertices` and is oriented as a
/// `triangle` (face normal `(vj − vi) × (vk − vi)`).
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    /// Vertex positions.
    pub vertices: Vec<P3>,
    /// Faces, 0-based indices into `vertices`.
    pub triangles: Vec<[usize; 3]>,
}

impl Mesh {
    /// Checks and builds a mesh. The error is `(field, message)`, the field
    /// relative to the mesh (`triangles[3][1]`).
    pub fn new(vertices: Vec<P3>, triangles: Vec<[usize; 3]>) -> Result<Self, (String, String)> {
        if triangles.is_empty() {
            return Err(("triangles".into(), "empty mesh: no triangles".into()));
        }
        for (i, v) in vertices.iter().enumerate() {
            if let Some(j) = v.iter().position(|x| !x.is_finite()) {
                return Err((format!("vertices[{i}][{j}]"), "not a finite number".into()));
            }
        }
        for (f, tri) in triangles.iter().enumerate() {
            for (j, &ix) in tri.iter().enumerate() {
                if ix >= vertices.len() {
                    return Err((
                        format!("triangles[{f}][{j}]"),
                        format!("index {ix} out of range ({} vertices)", vertices.len()),
                    ));
                }
            }
        }
        Ok(Self { vertices, triangles })
    }

    /// Face `i` as a triangle.
    pub fn triangle(&self, i: usize) -> Triangle {
        let [a, b, c] = self.triangles[i];
        Triangle { vertices: [self.vertices[a], self.vertices[b], self.vertices[c]] }
    }

    /// Every face as a triangle, in order.
    pub fn faces(&self) -> impl Iterator<Item = Triangle> + '_ {
        (0..self.triangles.len()).map(|i| self.triangle(i))
    }
}

/// Reads a mesh file (`.obj`): every object's faces, which must all be triangles.
/// The error message names the file and what is wrong with it.
pub fn load_mesh_file(path: &Path) -> Result<Mesh, String> {
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
    if ext != "obj" {
        return Err(format!("{}: unsupported mesh format (expected .obj)", path.display()));
    }
    let opts = tobj::LoadOptions { single_index: true, triangulate: false, ..Default::default() };
    let (models, _) = tobj::load_obj(path, &opts).map_err(|e| format!("{}: cannot read mesh: {e}", path.display()))?;
    let mut vertices = Vec::new();
    let mut triangles = Vec::new();
    for m in &models {
        let mesh = &m.mesh;
        if let Some((f, k)) = mesh.face_arities.iter().enumerate().find(|(_, k)| **k != 3) {
            return Err(format!(
                "{}: object \"{}\" face {f} has {k} vertices; only triangles are supported",
                path.display(),
                m.name
            ));
        }
        let base = vertices.len();
        vertices.extend(mesh.positions.chunks_exact(3).map(|p| [p[0], p[1], p[2]]));
        triangles.extend(
            mesh.indices.chunks_exact(3).map(|t| [base + t[0] as usize, base + t[1] as usize, base + t[2] as usize]),
        );
    }
    Mesh::new(vertices, triangles).map_err(|(field, msg)| format!("{}: {field}: {msg}", path.display()))
}

//! A triangle mesh as engines receive it: vertices and index triples.

use crate::geom::{P3, Triangle};

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

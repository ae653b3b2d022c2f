//! Meshes of the fixture format: inline, or read from an OBJ file.

pub use crashtest_core::mesh::Mesh;
use std::path::Path;

/// Reads a mesh file (`.obj`): every object's faces, which must all be triangles.
/// The error message names the file and what is wrong with it.
pub fn load_mesh_file(path: &Path) -> Result<Mesh, String> {
    obj(path, |opts| tobj::load_obj(path, opts))
}

/// A mesh from an `.obj` file's bytes (a built-in fixture's, embedded in the
/// binary), named `path` in its messages, read as [`load_mesh_file`] reads a
/// file.
pub fn load_mesh_bytes(path: &Path, bytes: &[u8]) -> Result<Mesh, String> {
    obj(path, |opts| {
        tobj::load_obj_buf(&mut std::io::BufReader::new(bytes), opts, |_| Err(tobj::LoadError::OpenFileFailed))
    })
}

/// A built-in fixture's mesh when `path` names one (`fixtures/meshes/bunny.obj`,
/// [`crate::builtin::file`]), else the file at `path`.
pub fn load_mesh_builtin_or_file(path: &Path) -> Result<Mesh, String> {
    match crate::builtin::file(path) {
        Some(bytes) => load_mesh_bytes(path, bytes),
        None => load_mesh_file(path),
    }
}

/// The `.obj` reader behind both: `load` reads the models with the options given.
fn obj(path: &Path, load: impl FnOnce(&tobj::LoadOptions) -> tobj::LoadResult) -> Result<Mesh, String> {
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
    if ext != "obj" {
        return Err(format!("{}: unsupported mesh format (expected .obj)", path.display()));
    }
    let opts = tobj::LoadOptions { single_index: true, triangulate: false, ..Default::default() };
    let (models, _) = load(&opts).map_err(|e| format!("{}: cannot read mesh: {e}", path.display()))?;
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

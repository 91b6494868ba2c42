//! The meshes bundled in `assets/` (see the README for credits).

use std::path::PathBuf;

/// Every bundled mesh, by file stem.
pub const MESHES: [&str; 5] = ["stanford-bunny", "fandisk", "spot", "cow", "teapot"];

/// A mesh loaded into owned buffers.
#[derive(Clone, Debug)]
pub struct LoadedMesh {
    /// File stem.
    pub name: String,
    /// Vertex positions.
    pub positions: Vec<[f32; 3]>,
    /// Triangles (polygons fan-triangulated by the loader).
    pub triangles: Vec<[u32; 3]>,
}

impl LoadedMesh {
    /// The validated view.
    ///
    /// # Panics
    /// If the mesh is invalid (the bundled ones are not).
    #[must_use]
    pub fn valid(&self) -> meshq::mesh::ValidMesh<'_> {
        meshq::mesh::MeshRef::new(&self.positions, &self.triangles)
            .validate()
            .expect("bundled meshes are valid")
    }
}

/// The repository's `assets/` folder.
#[must_use]
pub fn assets_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../assets")
}

/// Loads `assets/<name>.obj` (positions and faces only; texture coordinates and normals are
/// ignored, polygons fan-triangulated).
///
/// # Panics
/// If the file is missing or unreadable.
#[must_use]
pub fn load_mesh(name: &str) -> LoadedMesh {
    load_obj(&assets_dir().join(format!("{name}.obj")))
}

/// Loads an OBJ file the way [`load_mesh`] does, named after its file stem.
///
/// # Panics
/// If the file is missing or unreadable.
#[must_use]
pub fn load_obj(path: &std::path::Path) -> LoadedMesh {
    let name = path
        .file_stem()
        .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: false,
        ignore_points: true,
        ignore_lines: true,
    };
    let (models, _) = tobj::load_obj(path, &options)
        .unwrap_or_else(|e| panic!("cannot load {}: {e}", path.display()));
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for m in models {
        let base = u32::try_from(positions.len()).expect("vertex count fits u32");
        positions.extend(m.mesh.positions.chunks_exact(3).map(|p| [p[0], p[1], p[2]]));
        triangles.extend(
            m.mesh
                .indices
                .chunks_exact(3)
                .map(|t| [t[0] + base, t[1] + base, t[2] + base]),
        );
    }
    LoadedMesh {
        name,
        positions,
        triangles,
    }
}

/// The "teapot in a stadium": `mesh` standing on a square ground plane a hundred times wider
/// than its largest extent (two triangles appended after the mesh's, at the mesh's lowest `y`).
/// Uneven on purpose: nearly all triangles crowd into a ten-thousandth of the ground's area.
#[must_use]
pub fn in_stadium(mesh: &LoadedMesh) -> LoadedMesh {
    let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
    for p in &mesh.positions {
        for a in 0..3 {
            lo[a] = lo[a].min(p[a]);
            hi[a] = hi[a].max(p[a]);
        }
    }
    let extent = (0..3).map(|a| hi[a] - lo[a]).fold(0.0f32, f32::max);
    let (cx, cz) = ((lo[0] + hi[0]) * 0.5, (lo[2] + hi[2]) * 0.5);
    let half = 50.0 * extent;
    let y = lo[1];
    let mut out = mesh.clone();
    out.name = format!("{}-in-stadium", mesh.name);
    let v = out.positions.len() as u32;
    out.positions.extend([
        [cx - half, y, cz - half],
        [cx + half, y, cz - half],
        [cx + half, y, cz + half],
        [cx - half, y, cz + half],
    ]);
    out.triangles.extend([[v, v + 2, v + 1], [v, v + 3, v + 2]]);
    out
}

/// `mesh` with every triangle cut into four through its edge midpoints (each midpoint made
/// once, shared by the triangles on both sides): four times the triangles, the same surface.
/// Twice on the bunny gives 1,111,216 triangles.
#[must_use]
pub fn subdivided(mesh: &LoadedMesh) -> LoadedMesh {
    let mut positions = mesh.positions.clone();
    let mut midpoints = std::collections::HashMap::new();
    let mut mid = |a: u32, b: u32, positions: &mut Vec<[f32; 3]>| {
        *midpoints.entry((a.min(b), a.max(b))).or_insert_with(|| {
            let (p, q) = (positions[a as usize], positions[b as usize]);
            positions.push([0, 1, 2].map(|k| (p[k] + q[k]) * 0.5));
            (positions.len() - 1) as u32
        })
    };
    let mut triangles = Vec::with_capacity(4 * mesh.triangles.len());
    for &[a, b, c] in &mesh.triangles {
        let ab = mid(a, b, &mut positions);
        let bc = mid(b, c, &mut positions);
        let ca = mid(c, a, &mut positions);
        triangles.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
    }
    LoadedMesh {
        name: format!("{}-x4", mesh.name),
        positions,
        triangles,
    }
}

/// A small real mesh: the triangles of spot within 0.15 of its first vertex, re-indexed
/// (about a hundred triangles; small enough to damage every byte of its blobs).
#[must_use]
pub fn spot_patch() -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let spot = load_mesh("spot");
    let centre = glam::Vec3::from_array(spot.positions[0]);
    let mut remap = vec![u32::MAX; spot.positions.len()];
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for t in &spot.triangles {
        let near = t
            .iter()
            .all(|&i| glam::Vec3::from_array(spot.positions[i as usize]).distance(centre) < 0.15);
        if !near {
            continue;
        }
        triangles.push(t.map(|i| {
            if remap[i as usize] == u32::MAX {
                remap[i as usize] = u32::try_from(positions.len()).unwrap_or(u32::MAX);
                positions.push(spot.positions[i as usize]);
            }
            remap[i as usize]
        }));
    }
    (positions, triangles)
}

/// A scene of `count` long thin boxes (1.2 × 0.02 × 0.02, twelve triangles each) at random
/// places and angles in `[-1, 1]³`, from a fixed seed: long triangles that cross each other,
/// the case spatial splits are for. Deterministic.
#[must_use]
pub fn sticks(count: usize) -> LoadedMesh {
    use glam::Vec3;
    let mut rng = meshq_workload::SplitMix64::new(0x2545_f491_4f6c_dd1d);
    let mut next = move || rng.next_f32() * 2.0 - 1.0;
    let (mut positions, mut triangles) = (Vec::new(), Vec::new());
    for _ in 0..count {
        let centre = Vec3::new(next(), next(), next());
        let along = Vec3::new(next(), next(), next()).normalize_or(Vec3::X);
        let side = along.any_orthonormal_vector();
        let up = along.cross(side);
        let base = u32::try_from(positions.len()).expect("a small scene");
        for corner in 0..8u32 {
            let sign = |bit: u32| if corner & bit == 0 { -1.0 } else { 1.0 };
            let p =
                centre + along * (0.6 * sign(4)) + side * (0.01 * sign(2)) + up * (0.01 * sign(1));
            positions.push(p.to_array());
        }
        // The six faces as corner quads (bit 4: along, 2: side, 1: up).
        for [a, b, c, d] in [
            [0, 1, 3, 2],
            [4, 6, 7, 5],
            [0, 4, 5, 1],
            [2, 3, 7, 6],
            [0, 2, 6, 4],
            [1, 5, 7, 3],
        ] {
            triangles.push([base + a, base + b, base + c]);
            triangles.push([base + a, base + c, base + d]);
        }
    }
    LoadedMesh {
        name: format!("sticks-{count}"),
        positions,
        triangles,
    }
}

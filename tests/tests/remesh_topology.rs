//! The remesher's half-edge mesh against an independent count of edges, neighbours and
//! boundary loops on every bundled mesh, and its refusal of non-manifold input, each case
//! named.

use std::collections::{BTreeMap, BTreeSet};

use meshq::advanced::HalfEdgeEdits;
use meshq::error::{RemeshBuffer, RemeshError};
use meshq::mesh::MeshRef;
use meshq::remesh::{HalfEdgeBuffers, HalfEdgeMesh};
use meshq_tests::{MESHES, load_mesh};

/// Buffers of exactly the documented lengths for `v` vertices and `t` triangles.
struct Buffers {
    positions: Vec<[f32; 3]>,
    origins: Vec<u32>,
    twins: Vec<u32>,
    vertex_half_edges: Vec<u32>,
    creases: Vec<bool>,
    scratch: Vec<u32>,
}

impl Buffers {
    fn new(v: usize, t: usize) -> Self {
        Self {
            positions: vec![[0.0; 3]; v],
            origins: vec![0; 3 * t],
            twins: vec![0; 3 * t],
            vertex_half_edges: vec![0; v],
            creases: vec![true; 3 * t],
            scratch: vec![0; (3 * t).max(v)],
        }
    }

    fn build<'a>(
        &'a mut self,
        mesh: &meshq::ValidMesh<'_>,
    ) -> Result<HalfEdgeMesh<'a>, RemeshError> {
        HalfEdgeMesh::from_mesh(
            mesh,
            HalfEdgeBuffers {
                positions: &mut self.positions,
                origins: &mut self.origins,
                twins: &mut self.twins,
                vertex_half_edges: &mut self.vertex_half_edges,
                creases: &mut self.creases,
            },
            &mut self.scratch,
        )
    }
}

fn half_edges_of(positions: &[[f32; 3]], triangles: &[[u32; 3]]) -> Result<(), RemeshError> {
    let mesh = MeshRef::new(positions, triangles).validate().unwrap();
    let mut buffers = Buffers::new(positions.len(), triangles.len());
    buffers.build(&mesh).map(|_| ())
}

/// Boundary loops counted independently: components of the graph of edges used by one
/// triangle.
fn boundary_loops(boundary: &[(u32, u32)]) -> usize {
    let mut parent: BTreeMap<u32, u32> = BTreeMap::new();
    fn find(parent: &mut BTreeMap<u32, u32>, v: u32) -> u32 {
        let p = *parent.entry(v).or_insert(v);
        if p == v {
            return v;
        }
        let root = find(parent, p);
        parent.insert(v, root);
        root
    }
    for &(a, b) in boundary {
        let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
        parent.insert(ra, rb);
    }
    let vertices: Vec<u32> = parent.keys().copied().collect();
    vertices
        .into_iter()
        .map(|v| find(&mut parent, v))
        .collect::<BTreeSet<_>>()
        .len()
}

/// The lowest vertex whose triangles form more than one fan, found independently: the edges
/// opposite a vertex in its triangles (its link) form one path or cycle exactly when it has
/// one fan.
fn first_vertex_with_several_fans(triangles: &[[u32; 3]]) -> Option<u32> {
    let mut links: BTreeMap<u32, Vec<(u32, u32)>> = BTreeMap::new();
    for t in triangles {
        for k in 0..3 {
            links
                .entry(t[k])
                .or_default()
                .push((t[(k + 1) % 3], t[(k + 2) % 3]));
        }
    }
    links
        .into_iter()
        .find(|(_, link)| boundary_loops(link) > 1)
        .map(|(v, _)| v)
}

#[test]
fn half_edges_of_every_bundled_mesh_match_an_independent_count() {
    for name in MESHES {
        let loaded = load_mesh(name);
        let mesh = loaded.valid();
        let triangles = mesh.triangles();
        // Independent: undirected edges with their use counts, and each vertex's neighbours.
        let mut uses: BTreeMap<(u32, u32), u32> = BTreeMap::new();
        let mut neighbours: BTreeMap<u32, BTreeSet<u32>> = BTreeMap::new();
        for t in triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                *uses.entry((a.min(b), a.max(b))).or_default() += 1;
                neighbours.entry(a).or_default().insert(b);
                neighbours.entry(b).or_default().insert(a);
            }
        }
        let boundary: Vec<(u32, u32)> = uses
            .iter()
            .filter(|&(_, &n)| n == 1)
            .map(|(&e, _)| e)
            .collect();
        let mut buffers = Buffers::new(mesh.positions().len(), triangles.len());
        let built = buffers.build(&mesh);
        // A mesh whose vertex has several fans (the cow has one, where two parts touch at a
        // point) must be refused naming the first such vertex.
        if let Some(v) = first_vertex_with_several_fans(triangles) {
            assert_eq!(
                built.err(),
                Some(RemeshError::NonManifoldVertex { vertex: v }),
                "{name}"
            );
            eprintln!("{name}: refused, vertex {v} has several fans");
            continue;
        }
        let he = built.unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(he.edge_count(), uses.len(), "{name}: edges");
        assert_eq!(
            he.boundary_half_edge_count(),
            boundary.len(),
            "{name}: boundary edges"
        );
        assert_eq!(
            he.boundary_loop_count(),
            boundary_loops(&boundary),
            "{name}: boundary loops"
        );
        let euler = neighbours.len() as i64 - uses.len() as i64 + triangles.len() as i64;
        assert_eq!(
            he.euler_characteristic(),
            euler,
            "{name}: Euler characteristic"
        );
        for v in 0..mesh.positions().len() as u32 {
            let expected = neighbours.get(&v).map_or(0, BTreeSet::len) as u32;
            assert_eq!(he.valence(v), expected, "{name}: valence of vertex {v}");
            let on_boundary = boundary.iter().any(|&(a, b)| a == v || b == v);
            assert_eq!(he.is_boundary_vertex(v), on_boundary, "{name}: vertex {v}");
            assert_eq!(
                he.position(v).to_array(),
                mesh.positions()[v as usize],
                "{name}: position {v}"
            );
        }
        for h in 0..he.half_edge_count() as u32 {
            let (a, b) = he.ends(h);
            match he.twin(h) {
                Some(t) => {
                    assert_eq!(he.ends(t), (b, a), "{name}: twin of {h}");
                    assert_eq!(he.twin(t), Some(h), "{name}: twin of twin of {h}");
                }
                None => assert_eq!(uses[&(a.min(b), a.max(b))], 1, "{name}: {h}"),
            }
        }
        eprintln!(
            "{name}: {} edges, {} boundary loops, Euler characteristic {}",
            he.edge_count(),
            he.boundary_loop_count(),
            he.euler_characteristic()
        );
    }
}

/// Four corners of a unit tetrahedron and its faces, oriented outward, offset by `o` vertices.
fn tetrahedron(o: u32) -> Vec<[u32; 3]> {
    vec![
        [o, o + 2, o + 1],
        [o, o + 1, o + 3],
        [o + 1, o + 2, o + 3],
        [o, o + 3, o + 2],
    ]
}

#[test]
fn a_closed_tetrahedron_has_valence_three_everywhere_and_no_boundary() {
    let positions = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];
    let triangles = tetrahedron(0);
    let mesh = MeshRef::new(&positions, &triangles).validate().unwrap();
    let mut buffers = Buffers::new(4, 4);
    let he = buffers.build(&mesh).unwrap();
    assert_eq!(he.edge_count(), 6);
    assert_eq!(he.boundary_loop_count(), 0);
    assert_eq!(he.euler_characteristic(), 2);
    assert!((0..4).all(|v| he.valence(v) == 3 && !he.is_boundary_vertex(v)));
}

#[test]
fn non_manifold_input_is_refused_naming_the_edge_or_vertex() {
    let spread: Vec<[f32; 3]> = (0..8).map(|i| [i as f32, (i * i) as f32, 1.0]).collect();
    // Three triangles on the edge 0–1.
    assert_eq!(
        half_edges_of(&spread, &[[0, 1, 2], [1, 0, 3], [0, 1, 4]]),
        Err(RemeshError::NonManifoldEdge {
            a: 0,
            b: 1,
            triangles: 3
        })
    );
    // Both triangles run 0 → 1.
    assert_eq!(
        half_edges_of(&spread, &[[0, 1, 2], [0, 1, 3]]),
        Err(RemeshError::InconsistentOrientation { a: 0, b: 1 })
    );
    // The same triangle twice.
    assert_eq!(
        half_edges_of(&spread, &[[0, 1, 2], [0, 1, 2]]),
        Err(RemeshError::InconsistentOrientation { a: 0, b: 1 })
    );
    // Two open fans meeting at vertex 0.
    assert_eq!(
        half_edges_of(&spread, &[[0, 1, 2], [0, 3, 4]]),
        Err(RemeshError::NonManifoldVertex { vertex: 0 })
    );
    // Two closed tetrahedra sharing vertex 0: each fan is closed, but there are two.
    let mut tets = tetrahedron(0);
    tets.extend(
        tetrahedron(3)
            .into_iter()
            .map(|t| t.map(|v| if v == 3 { 0 } else { v })),
    );
    assert_eq!(
        half_edges_of(&spread, &tets),
        Err(RemeshError::NonManifoldVertex { vertex: 0 })
    );
    // A triangle using a vertex twice.
    assert_eq!(
        half_edges_of(&spread, &[[0, 1, 2], [3, 4, 4]]),
        Err(RemeshError::RepeatedVertex {
            triangle: 1,
            vertex: 4
        })
    );
    // Unused vertices are fine: they keep no half-edge.
    assert_eq!(half_edges_of(&spread, &[[0, 1, 2]]), Ok(()));
}

#[test]
fn every_buffer_too_small_is_named() {
    let positions = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];
    let triangles = tetrahedron(0);
    let mesh = MeshRef::new(&positions, &triangles).validate().unwrap();
    type Shorten = fn(&mut Buffers);
    let shorten: [(RemeshBuffer, usize, Shorten); 6] = [
        (RemeshBuffer::Positions, 4, |b| {
            b.positions.pop();
        }),
        (RemeshBuffer::HalfEdges, 12, |b| {
            b.origins.pop();
        }),
        (RemeshBuffer::HalfEdges, 12, |b| {
            b.twins.pop();
        }),
        (RemeshBuffer::HalfEdges, 12, |b| {
            b.creases.pop();
        }),
        (RemeshBuffer::VertexHalfEdges, 4, |b| {
            b.vertex_half_edges.pop();
        }),
        (RemeshBuffer::Scratch, 12, |b| {
            b.scratch.pop();
        }),
    ];
    for (buffer, needed, shorten) in shorten {
        let mut buffers = Buffers::new(4, 4);
        shorten(&mut buffers);
        let err = buffers.build(&mesh).unwrap_err();
        assert_eq!(
            err,
            RemeshError::BufferTooSmall {
                buffer,
                needed,
                got: needed - 1
            }
        );
        assert!(!err.to_string().is_empty());
    }
}

/// What an edit must keep: checked from the triangle list alone, independently of the
/// half-edges, plus the half-edges' agreement with it.
fn assert_sound(he: &HalfEdgeMesh<'_>, euler: i64, loops: usize, what: &str) {
    let triangles: Vec<[u32; 3]> = (0..he.triangle_count() as u32)
        .map(|t| he.triangle(t))
        .collect();
    let mut directed: BTreeMap<(u32, u32), u32> = BTreeMap::new();
    for t in &triangles {
        assert!(
            t[0] != t[1] && t[1] != t[2] && t[0] != t[2],
            "{what}: {t:?}"
        );
        assert!(
            t.iter().all(|&v| (v as usize) < he.vertex_count()),
            "{what}"
        );
        for k in 0..3 {
            *directed.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
        }
    }
    assert!(
        directed.values().all(|&n| n == 1),
        "{what}: an edge repeats"
    );
    assert_eq!(first_vertex_with_several_fans(&triangles), None, "{what}");
    for h in 0..he.half_edge_count() as u32 {
        let (a, b) = he.ends(h);
        match he.twin(h) {
            Some(t) => {
                assert_eq!(he.ends(t), (b, a), "{what}: twin of {h}");
                assert_eq!(he.twin(t), Some(h), "{what}: twin of twin of {h}");
            }
            None => assert!(!directed.contains_key(&(b, a)), "{what}: lost twin of {h}"),
        }
    }
    let boundary: BTreeSet<u32> = directed
        .keys()
        .filter(|&&(a, b)| !directed.contains_key(&(b, a)))
        .flat_map(|&(a, b)| [a, b])
        .collect();
    for v in 0..he.vertex_count() as u32 {
        if let Some(h) = he.vertex_half_edge(v) {
            assert_eq!(he.origin(h), v, "{what}: half-edge of {v}");
            let on_boundary = boundary.contains(&v);
            assert_eq!(he.twin(h).is_none(), on_boundary, "{what}: boundary at {v}");
        }
    }
    assert_eq!(
        he.euler_characteristic(),
        euler,
        "{what}: Euler characteristic"
    );
    assert_eq!(he.boundary_loop_count(), loops, "{what}: boundary loops");
}

/// Random splits, flips and collapses on a closed mesh and on one with holes: after every
/// edit the mesh is manifold, oriented, compact, with the same Euler characteristic and
/// boundary loops.
#[test]
fn random_edits_keep_the_mesh_sound() {
    for (name, edits) in [("spot", 600), ("stanford-bunny", 150)] {
        let loaded = load_mesh(name);
        let mesh = loaded.valid();
        let (v, t) = (mesh.positions().len(), mesh.triangle_count());
        let mut buffers = Buffers::new(v + edits, t + 2 * edits);
        buffers.creases.iter_mut().for_each(|c| *c = false);
        let mut he = buffers.build(&mesh).unwrap();
        let (euler, loops) = (he.euler_characteristic(), he.boundary_loop_count());
        let mut rng = meshq_workload::SplitMix64::new(7);
        let (mut splits, mut flips, mut collapses) = (0, 0, 0);
        for i in 0..edits {
            let h = rng.below(he.half_edge_count() as u64) as u32;
            let (a, b) = he.ends(h);
            let mid = (he.position(a) + he.position(b)) * 0.5;
            let what = format!("{name} edit {i} on half-edge {h}");
            match rng.below(3) {
                0 => {
                    he.split_edge(h, mid).unwrap();
                    splits += 1;
                }
                1 => flips += usize::from(he.flip_edge(h)),
                _ => collapses += usize::from(he.collapse_edge(h, mid)),
            }
            // Full checks are slow on the bunny: every tenth edit there.
            if name == "spot" || i % 10 == 0 {
                assert_sound(&he, euler, loops, &what);
            }
        }
        assert_sound(&he, euler, loops, name);
        assert!(
            splits > 0 && flips > 0 && collapses > 0,
            "{name}: {splits} {flips} {collapses}"
        );
        eprintln!("{name}: {splits} splits, {flips} flips, {collapses} collapses");
    }
}

/// Splitting with no room left is refused and leaves the mesh as it was.
#[test]
fn a_split_without_room_changes_nothing() {
    let positions = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];
    let triangles = tetrahedron(0);
    let mesh = MeshRef::new(&positions, &triangles).validate().unwrap();
    let mut buffers = Buffers::new(4, 5);
    let mut he = buffers.build(&mesh).unwrap();
    let err = he.split_edge(0, meshq::Vec3::ZERO).unwrap_err();
    assert_eq!(
        err,
        RemeshError::OutOfCapacity {
            buffer: RemeshBuffer::Positions,
            capacity: 4
        }
    );
    assert_eq!((he.vertex_count(), he.triangle_count()), (4, 4));
    assert_sound(&he, 2, 0, "after the refused split");
}

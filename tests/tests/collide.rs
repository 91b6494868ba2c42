//! Mesh–mesh and self-intersection against brute force: every pair of triangles tested
//! directly (on small meshes, or on the triangles near the contact, or on a sample of one
//! side of a big mesh), with an independently written rule for neighbours.

use std::collections::BTreeSet;

use meshq::Traverse;
use meshq::Vec3;
use meshq::bvh::BuildConfig;
use meshq::collide::{
    Affine, CrossingSegment, PairBudget, TrianglePair, intersecting_pairs, intersection_segments,
    meshes_intersect, self_intersecting_pairs, self_intersects, touching_pairs_unfiltered,
};
use meshq::geom::{TriangleTriangle, intersect_triangle_triangle, triangles_meet};
use meshq::math::{Aabb, Triangle};
use meshq::mesh::{MeshRef, ValidMesh};
use meshq::owned::MeshBvh;
use meshq_tests::load_mesh;

fn triangles_of(mesh: &ValidMesh<'_>) -> Vec<Triangle> {
    (0..mesh.triangle_count() as u32)
        .map(|t| mesh.triangle(t).unwrap())
        .collect()
}

fn bounds_of(tris: &[Triangle]) -> Aabb {
    tris.iter().fold(Aabb::EMPTY, |b, t| b.union(t.bounds()))
}

/// Every meeting pair by brute force (with whether the pair has a crossing segment), over the triangles of `a` listed in `only_a` (all when
/// `None`); `b` placed by `place`. Triangles whose bounds miss the other mesh's bounds are
/// skipped first: they can meet nothing.
fn brute_pairs(
    a: &[Triangle],
    b: &[Triangle],
    place: &Affine,
    only_a: Option<&[u32]>,
) -> BTreeSet<(u32, u32, bool)> {
    let b: Vec<Triangle> = b.iter().map(|t| place.apply_triangle(t)).collect();
    let (bounds_a, bounds_b) = (bounds_of(a), bounds_of(&b));
    let near_b: Vec<u32> = (0..b.len() as u32)
        .filter(|&j| b[j as usize].bounds().overlaps(&bounds_a))
        .collect();
    let all: Vec<u32> = (0..a.len() as u32).collect();
    let mut out = BTreeSet::new();
    for &i in only_a.unwrap_or(&all) {
        let ta = a[i as usize];
        if !ta.bounds().overlaps(&bounds_b) {
            continue;
        }
        for &j in &near_b {
            // Meeting decided exactly; a segment where the tolerant test places one.
            let tb = &b[j as usize];
            if triangles_meet(&ta, tb) {
                let crossing = matches!(
                    intersect_triangle_triangle(&ta, tb),
                    TriangleTriangle::Segment { .. }
                );
                out.insert((i, j, crossing));
            }
        }
    }
    out
}

struct Case {
    name: &'static str,
    place: Affine,
}

/// A rotation about z by `degrees`, then a translation by `t`.
fn turned(degrees: f32, t: [f32; 3]) -> Affine {
    let (s, c) = degrees.to_radians().sin_cos();
    Affine {
        columns: [[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]],
        translation: t,
    }
}

/// Checks all three forms of the two-mesh query against `expected` (complete over the pairs
/// of `a` in `only_a`, or all).
fn check_two_meshes(
    label: &str,
    a: &MeshBvh,
    b: &MeshBvh,
    place: &Affine,
    expected: &BTreeSet<(u32, u32, bool)>,
    only_a: Option<&BTreeSet<u32>>,
) {
    let (mesh_a, mesh_b) = (a.mesh(), b.mesh());
    let (tree_a, tree_b) = (a.bvh(), b.bvh());
    let (with_a, with_b) = (tree_a.with(&mesh_a), tree_b.with(&mesh_b));
    let packed_b = b.packed();
    let with_b_packed = tree_b.with(&packed_b);
    // The default budget: meshes like these must be answered within it.
    let budget = PairBudget::for_triangles(mesh_a.triangle_count(), mesh_b.triangle_count());
    let mut pairs = vec![TrianglePair::default(); 1 << 20];
    let found = intersecting_pairs(with_a, with_b, Some(place), budget, &mut pairs).unwrap();
    assert!(!found.overflowed(), "{label}");
    let got: BTreeSet<TrianglePair> = pairs[..found.written].iter().copied().collect();
    assert_eq!(got.len(), found.written, "{label}: a pair reported twice");
    let keep = |p: &TrianglePair| only_a.is_none_or(|s| s.contains(&p.a));
    let got_kept: BTreeSet<(u32, u32)> =
        got.iter().filter(|p| keep(p)).map(|p| (p.a, p.b)).collect();
    let want: BTreeSet<(u32, u32)> = expected.iter().map(|&(i, j, _)| (i, j)).collect();
    assert_eq!(got_kept, want, "{label}: pairs against brute force");
    assert_eq!(
        meshes_intersect(with_a, with_b, Some(place), budget).unwrap(),
        found.total > 0,
        "{label}: yes/no"
    );
    // Packed triangles answer exactly as the mesh does, in the same order.
    let mut packed_pairs = vec![TrianglePair::default(); found.total + 1];
    let again = intersecting_pairs(
        with_a,
        with_b_packed,
        Some(place),
        budget,
        &mut packed_pairs,
    )
    .unwrap();
    assert_eq!(again, found, "{label}: packed");
    assert_eq!(
        packed_pairs[..again.written],
        pairs[..found.written],
        "{label}: packed order"
    );
    // A short buffer holds the first pairs of the same walk, and the count goes on.
    if found.total > 2 {
        let mut short = vec![TrianglePair::default(); found.total / 2];
        let part = intersecting_pairs(with_a, with_b, Some(place), budget, &mut short).unwrap();
        assert!(part.overflowed(), "{label}");
        assert_eq!(
            (part.total, part.written),
            (found.total, short.len()),
            "{label}"
        );
        assert_eq!(
            short[..],
            pairs[..short.len()],
            "{label}: first pairs first"
        );
    }
    // Segments: one per crossing pair (not per coplanar one), ends on both triangles.
    let mut segments = vec![
        CrossingSegment {
            pair: TrianglePair::default(),
            start: Vec3::ZERO,
            end: Vec3::ZERO,
        };
        found.total + 1
    ];
    let crossing =
        intersection_segments(with_a, with_b, Some(place), budget, &mut segments).unwrap();
    let crossing_pairs: BTreeSet<(u32, u32)> = segments[..crossing.written]
        .iter()
        .map(|s| (s.pair.a, s.pair.b))
        .filter(|&(i, _)| only_a.is_none_or(|s| s.contains(&i)))
        .collect();
    let want_crossing: BTreeSet<(u32, u32)> = expected
        .iter()
        .filter(|&&(_, _, crosses)| crosses)
        .map(|&(i, j, _)| (i, j))
        .collect();
    assert_eq!(crossing_pairs, want_crossing, "{label}: crossing segments");
    let scale = bounds_of(&triangles_of(&mesh_a)).extent().max_element();
    for s in &segments[..crossing.written] {
        let ta = mesh_a.triangle(s.pair.a).unwrap();
        let tb = place.apply_triangle(&mesh_b.triangle(s.pair.b).unwrap());
        for p in [s.start, s.end] {
            for t in [ta, tb] {
                let d = meshq::geom::closest_point_triangle(p, &t)
                    .distance_squared
                    .sqrt();
                assert!(
                    d <= 1e-4 * scale,
                    "{label}: segment end {p} off a triangle by {d}"
                );
            }
        }
    }
    eprintln!(
        "{label}: {} pairs ({} crossing)",
        found.total, crossing.total
    );
}

#[test]
fn two_overlapping_spots_match_brute_force_in_every_form() {
    let spot = load_mesh("spot");
    let mesh = spot.valid();
    let bvh = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
    let tris = triangles_of(&mesh);
    let extent = bounds_of(&tris).extent();
    let cases = [
        Case {
            name: "spot, shifted by a third",
            place: Affine::translation([extent.x / 3.0, extent.y / 7.0, 0.0]),
        },
        Case {
            name: "spot, turned 30° and shifted",
            place: turned(30.0, [extent.x / 5.0, 0.0, extent.z / 9.0]),
        },
        Case {
            name: "spot, apart",
            place: Affine::translation([extent.x * 1.5, 0.0, 0.0]),
        },
    ];
    for case in cases {
        let expected = brute_pairs(&tris, &tris, &case.place, None);
        check_two_meshes(case.name, &bvh, &bvh, &case.place, &expected, None);
    }
}

#[test]
fn a_copy_that_just_touches_matches_brute_force() {
    // The copy is moved so that its lowest vertex in x lands on the original's highest: the
    // plane x = that vertex's x keeps them apart everywhere else, so they meet only there
    // (touching, up to the rounding of the move).
    let bunny = load_mesh("stanford-bunny");
    let mesh = bunny.valid();
    let bvh = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
    let tris = triangles_of(&mesh);
    let by_x = |p: &&[f32; 3], q: &&[f32; 3]| p[0].total_cmp(&q[0]);
    let high = Vec3::from_array(*mesh.positions().iter().max_by(by_x).unwrap());
    let low = Vec3::from_array(*mesh.positions().iter().min_by(by_x).unwrap());
    let extent = bounds_of(&tris).extent().x;
    for (label, gap) in [
        ("touching", 0.0f32),
        ("a hair apart", 1e-3),
        ("a hair into", -1e-2),
    ] {
        let shift = high - low + Vec3::new(gap * extent, 0.0, 0.0);
        let place = Affine::translation(shift.to_array());
        let expected = brute_pairs(&tris, &tris, &place, None);
        check_two_meshes(
            &format!("bunny copy, {label}"),
            &bvh,
            &bvh,
            &place,
            &expected,
            None,
        );
        match label {
            "a hair apart" => assert!(expected.is_empty(), "{label}: {expected:?}"),
            "a hair into" => assert!(!expected.is_empty(), "{label}"),
            _ => {}
        }
    }
}

#[test]
fn two_overlapping_bunnies_match_brute_force_on_a_sample() {
    let bunny = load_mesh("stanford-bunny");
    let mesh = bunny.valid();
    let bvh = MeshBvh::build(&mesh, &BuildConfig::default()).unwrap();
    let tris = triangles_of(&mesh);
    let extent = bounds_of(&tris).extent();
    let place = turned(20.0, [extent.x / 4.0, extent.y / 10.0, 0.0]);
    // Every 97th triangle of the first bunny, against all of the second.
    let sample: Vec<u32> = (0..tris.len() as u32).step_by(97).collect();
    let expected = brute_pairs(&tris, &tris, &place, Some(&sample));
    assert!(!expected.is_empty());
    let only: BTreeSet<u32> = sample.into_iter().collect();
    check_two_meshes("two bunnies", &bvh, &bvh, &place, &expected, Some(&only));
}

/// The independent rule for a self-intersection oracle: do triangles `i < j` of `mesh` meet
/// other than where they share corners (by index or position, within 2⁻²⁰ of the scale)? Written from the
/// definition with f64 and polygon clipping, not from the library's code. `None` for a pair
/// the tolerances decide (a shared-corner crossing or a coplanar overlap within a few
/// millionths of the scale): the library may answer either way there.
fn oracle_meets(mesh: &ValidMesh<'_>, i: u32, j: u32) -> Option<bool> {
    let (ti, tj) = (mesh.triangle(i).unwrap(), mesh.triangle(j).unwrap());
    let how = intersect_triangle_triangle(&ti, &tj);
    if how == TriangleTriangle::Disjoint {
        return Some(false);
    }
    let (ci, cj) = (mesh.triangles()[i as usize], mesh.triangles()[j as usize]);
    let corners = |t: &Triangle| [t.a, t.b, t.c];
    let scale = corners(&ti)
        .iter()
        .chain(corners(&tj).iter())
        .fold(0.0f32, |m, p| m.max(p.abs().max_element()));
    let same_place = |p: Vec3, q: Vec3| (p - q).abs().max_element() <= scale / 1_048_576.0;
    let shared: Vec<usize> = (0..3)
        .filter(|&k| {
            cj.contains(&ci[k]) || corners(&tj).iter().any(|&q| same_place(q, corners(&ti)[k]))
        })
        .collect();
    let decide = |value: f64, low: f64, high: f64| {
        if value > high {
            Some(true)
        } else if value < low {
            Some(false)
        } else {
            None
        }
    };
    match (shared.len(), how) {
        (0 | 3, _) => Some(true),
        (1, TriangleTriangle::Segment { a, b }) => {
            let v = corners(&ti)[shared[0]];
            let far = a.distance(v).max(b.distance(v)) as f64;
            decide(far, 1e-7 * scale as f64, 4e-6 * scale as f64)
        }
        (2, TriangleTriangle::Segment { .. }) => Some(false),
        (_, _) => {
            let smaller = (ti.area() as f64).min(tj.area() as f64);
            decide(overlap_area(&ti, &tj), 1e-9 * smaller, 1e-3 * smaller)
        }
    }
}

/// The area two coplanar triangles share: one clipped by the other's edges (Sutherland and
/// Hodgman), in f64, in the plane of the first.
fn overlap_area(t1: &Triangle, t2: &Triangle) -> f64 {
    let n = t1.normal().as_dvec3().normalize();
    let u = if n.x.abs() < 0.9 {
        n.cross(glam::DVec3::X)
    } else {
        n.cross(glam::DVec3::Y)
    }
    .normalize();
    let v = n.cross(u);
    let flat = |p: Vec3| {
        let p = p.as_dvec3();
        glam::DVec2::new(p.dot(u), p.dot(v))
    };
    let mut poly: Vec<glam::DVec2> = [t1.a, t1.b, t1.c].map(flat).to_vec();
    let mut clip = [t2.a, t2.b, t2.c].map(flat);
    let signed = |p: &[glam::DVec2]| {
        (0..p.len())
            .map(|k| p[k].perp_dot(p[(k + 1) % p.len()]))
            .sum::<f64>()
            / 2.0
    };
    if signed(&clip) < 0.0 {
        clip.reverse();
    }
    for k in 0..3 {
        let (e0, e1) = (clip[k], clip[(k + 1) % 3]);
        let inside = |p: glam::DVec2| (e1 - e0).perp_dot(p - e0) >= 0.0;
        let mut next = Vec::new();
        for m in 0..poly.len() {
            let (p, q) = (poly[m], poly[(m + 1) % poly.len()]);
            let (pin, qin) = (inside(p), inside(q));
            if pin {
                next.push(p);
            }
            if pin != qin {
                let dp = (e1 - e0).perp_dot(p - e0);
                let dq = (e1 - e0).perp_dot(q - e0);
                next.push(p + (q - p) * (dp / (dp - dq)));
            }
        }
        poly = next;
        if poly.len() < 3 {
            return 0.0;
        }
    }
    signed(&poly).abs()
}

/// Pairs of triangle indices, lower first.
type PairSet = BTreeSet<(u32, u32)>;

/// The oracle's answer over every pair: (pairs that meet, pairs it leaves undecided).
fn brute_self_pairs(mesh: &ValidMesh<'_>) -> (PairSet, PairSet) {
    let tris = triangles_of(mesh);
    let mut order: Vec<u32> = (0..tris.len() as u32).collect();
    order.sort_by(|&x, &y| {
        tris[x as usize]
            .bounds()
            .min
            .x
            .total_cmp(&tris[y as usize].bounds().min.x)
    });
    let (mut meet, mut undecided) = (BTreeSet::new(), BTreeSet::new());
    // Sweep along x: only triangles whose x ranges overlap can meet.
    for (k, &i) in order.iter().enumerate() {
        let bi = tris[i as usize].bounds();
        for &j in &order[k + 1..] {
            let bj = tris[j as usize].bounds();
            if bj.min.x > bi.max.x {
                break;
            }
            if !bi.overlaps(&bj) {
                continue;
            }
            let pair = (i.min(j), i.max(j));
            match oracle_meets(mesh, pair.0, pair.1) {
                Some(true) => {
                    meet.insert(pair);
                }
                Some(false) => {}
                None => {
                    undecided.insert(pair);
                }
            }
        }
    }
    (meet, undecided)
}

/// Checks the library's pairs against the oracle's on every pair it decides; returns the
/// library's pairs.
fn check_self(name: &str, mesh: &ValidMesh<'_>) -> BTreeSet<(u32, u32)> {
    let (got, any) = self_pairs(mesh, false);
    let (want, undecided) = brute_self_pairs(mesh);
    let decided: BTreeSet<(u32, u32)> = got.difference(&undecided).copied().collect();
    assert_eq!(decided, want, "{name}");
    assert_eq!(any, !got.is_empty(), "{name}");
    eprintln!(
        "{name}: {} self-intersecting pairs ({} left to the tolerances, {} of them reported)",
        got.len(),
        undecided.len(),
        got.intersection(&undecided).count()
    );
    got
}

fn self_pairs(mesh: &ValidMesh<'_>, unfiltered: bool) -> (BTreeSet<(u32, u32)>, bool) {
    let bvh = MeshBvh::build(mesh, &BuildConfig::default()).unwrap();
    let tree = bvh.bvh();
    let mut out = vec![TrianglePair::default(); 1 << 20];
    let n = mesh.triangle_count();
    let budget = PairBudget::for_triangles(n, n);
    let found = if unfiltered {
        touching_pairs_unfiltered(&tree, mesh, &mut out)
    } else {
        self_intersecting_pairs(&tree, mesh, budget, &mut out).unwrap()
    };
    assert!(!found.overflowed());
    let set: BTreeSet<(u32, u32)> = out[..found.written].iter().map(|p| (p.a, p.b)).collect();
    assert_eq!(set.len(), found.written, "a pair reported twice");
    assert!(out[..found.written].iter().all(|p| p.a < p.b));
    (set, self_intersects(&tree, mesh, budget).unwrap())
}

#[test]
fn clean_meshes_do_not_meet_themselves_and_agree_with_brute_force() {
    for name in ["spot", "fandisk", "uv-sphere", "stanford-bunny"] {
        let loaded = load_mesh(name);
        let got = check_self(name, &loaded.valid());
        assert!(got.is_empty(), "{name}: {got:?}");
    }
}

#[test]
fn the_neighbour_rule_is_what_keeps_clean_meshes_clean() {
    // Without the rule every pair sharing a corner counts: thousands on a clean mesh.
    let loaded = load_mesh("spot");
    let mesh = loaded.valid();
    let (with_rule, _) = self_pairs(&mesh, false);
    let (without, _) = self_pairs(&mesh, true);
    assert!(with_rule.is_empty(), "{with_rule:?}");
    assert!(without.len() > mesh.triangle_count(), "{}", without.len());
}

#[test]
fn displaced_vertices_make_intersections_that_match_brute_force() {
    let loaded = load_mesh("spot");
    let tris = triangles_of(&loaded.valid());
    let extent = bounds_of(&tris).extent().max_element();
    // Push every 211th vertex along its vertex normal by a fifth of the mesh: it pokes out
    // through its neighbours' far side, or in through the opposite wall.
    let mut positions = loaded.positions.clone();
    let mut normals = vec![Vec3::ZERO; positions.len()];
    for (t, corners) in loaded.triangles.iter().enumerate() {
        for &v in corners {
            normals[v as usize] += tris[t].normal();
        }
    }
    for (v, p) in positions.iter_mut().enumerate().step_by(211) {
        let n = normals[v].normalize_or_zero();
        *p = (Vec3::from_array(*p) - n * (0.2 * extent)).to_array();
    }
    let mesh = MeshRef::new(&positions, &loaded.triangles)
        .validate()
        .unwrap();
    let got = check_self("displaced spot", &mesh);
    assert!(!got.is_empty());
}

/// A soup of `n` random triangles in the unit cube, with every ninth one degenerate (a corner
/// repeated) and every seventh sharing corners with the one before, as indices into
/// positions.
fn soup(rng: &mut meshq_tests::SplitMix64, n: usize) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for k in 0..n {
        let base = positions.len() as u32;
        let centre = [rng.next_f32(), rng.next_f32(), rng.next_f32()];
        for _ in 0..3 {
            positions.push(centre.map(|c| c + rng.range(-0.2, 0.2)));
        }
        let mut t = [base, base + 1, base + 2];
        if k % 9 == 8 {
            t[2] = t[1];
        } else if k % 7 == 6 && base >= 3 {
            t[0] = base - 3;
            t[1] = base - 2;
        }
        triangles.push(t);
    }
    (positions, triangles)
}

#[test]
fn random_soups_under_any_affine_map_match_brute_force_and_never_panic() {
    let mut rng = meshq_tests::SplitMix64::new(0x5eed);
    let mut meeting = 0;
    for round in 0..40 {
        let (pa, ta) = soup(&mut rng, 60 + round);
        let (pb, tb) = soup(&mut rng, 50);
        let (ma, mb) = (
            MeshRef::new(&pa, &ta).validate().unwrap(),
            MeshRef::new(&pb, &tb).validate().unwrap(),
        );
        let (ba, bb) = (
            MeshBvh::build(&ma, &BuildConfig::default()).unwrap(),
            MeshBvh::build(&mb, &BuildConfig::default()).unwrap(),
        );
        // A map with scale and shear, or a wild one: huge, tiny, or flattening.
        let mut columns = [[0.0f32; 3]; 3];
        for c in &mut columns {
            *c = [
                rng.range(-1.5, 1.5),
                rng.range(-1.5, 1.5),
                rng.range(-1.5, 1.5),
            ];
        }
        match round % 8 {
            5 => columns[2] = [0.0; 3],
            6 => columns = columns.map(|c| c.map(|x| x * 1e30)),
            7 => columns = columns.map(|c| c.map(|x| x * 1e-30)),
            _ => {}
        }
        // Centred on the first soup's cube, so that the soups overlap.
        let linear = Affine {
            columns,
            translation: [0.0; 3],
        };
        let image = linear.apply(Vec3::splat(0.5));
        let place = Affine {
            columns,
            translation: (Vec3::splat(0.5) - image).to_array(),
        };
        let expected = brute_pairs(&triangles_of(&ma), &triangles_of(&mb), &place, None);
        check_two_meshes(&format!("soup {round}"), &ba, &bb, &place, &expected, None);
        meeting += expected.len();
        // One soup against itself: the library's self pairs against the oracle's.
        check_self(&format!("soup {round}"), &ma);
    }
    assert!(meeting > 100, "{meeting} meeting pairs in all");
}

//! Probe: would spatial splits (SBVH, Stich et al. 2009) make meshq's rays faster?
//!
//! Builds a binary tree with spatial splits here (allocating, unoptimised: a prototype, not the
//! product's builder) using the same SAH costs as `BuildConfig::balanced`, hands it to meshq
//! as a `Bvh` whose order repeats split triangles, collapses it to four and eight lanes, checks
//! every answer against the normal tree and times both, interleaved, best of 11 rounds.
//!
//! `cargo run --release -p meshq-bench --example sbvh_probe` (env `MESH`, `SUBDIVIDE`, `RAYS`,
//! `ALPHA` the overlap threshold, `BUDGET` the reference budget as a multiple of the triangle
//! count, `STICKS=n` a generated scene of `n` long thin boxes at random angles instead of a
//! mesh: the long, crossing triangles spatial splits are for).

use std::hint::black_box;
use std::time::{Duration, Instant};

use glam::Vec3;
use meshq::bvh::{BuildConfig, Bvh, BvhNode};
use meshq::math::{Aabb, PackedTriangle};
use meshq::query::PackedTriangles;
use meshq::wide::{WideBvh, WideBvh8, WideNode, WideNode8};
use meshq::{MeshBvh, MeshQuery, Traverse};
use meshq_tests::{load_mesh, workload};

const BINS: usize = 32;
const ROUNDS: usize = 11;

#[derive(Clone, Copy)]
struct Ref {
    tri: u32,
    lo: Vec3,
    hi: Vec3,
}

impl Ref {
    fn centre(&self) -> Vec3 {
        (self.lo + self.hi) * 0.5
    }
}

#[derive(Clone, Copy)]
struct Bx {
    lo: Vec3,
    hi: Vec3,
}

impl Bx {
    const EMPTY: Self = Self {
        lo: Vec3::splat(f32::INFINITY),
        hi: Vec3::splat(f32::NEG_INFINITY),
    };
    fn grow(&mut self, lo: Vec3, hi: Vec3) {
        self.lo = self.lo.min(lo);
        self.hi = self.hi.max(hi);
    }
    fn union(a: Self, b: Self) -> Self {
        Self {
            lo: a.lo.min(b.lo),
            hi: a.hi.max(b.hi),
        }
    }
    fn area(&self) -> f32 {
        let e = self.hi - self.lo;
        if e.min_element() < 0.0 {
            0.0
        } else {
            e.x * e.y + e.y * e.z + e.z * e.x
        }
    }
    fn intersect(a: Self, b: Self) -> Self {
        Self {
            lo: a.lo.max(b.lo),
            hi: a.hi.min(b.hi),
        }
    }
}

struct Builder<'m> {
    tris: &'m [[Vec3; 3]],
    nodes: Vec<BvhNode>,
    order: Vec<u32>,
    root_area: f32,
    alpha: f32,
    refs_made: usize,
    spatial_splits: usize,
    config: BuildConfig,
}

#[derive(Clone, Copy)]
enum Split {
    Object {
        axis: usize,
        bin: usize,
        lo: f32,
        scale: f32,
    },
    Spatial {
        axis: usize,
        plane: f32,
    },
}

/// The box of the part of triangle `t` whose coordinate `axis` lies in `[lo, hi]`.
fn clipped(t: &[Vec3; 3], axis: usize, lo: f32, hi: f32) -> Bx {
    let mut b = Bx::EMPTY;
    for i in 0..3 {
        let (p, q) = (t[i], t[(i + 1) % 3]);
        let (pa, qa) = (p[axis], q[axis]);
        if pa >= lo && pa <= hi {
            b.grow(p, p);
        }
        for plane in [lo, hi] {
            if (pa < plane && qa > plane) || (pa > plane && qa < plane) {
                let s = (plane - pa) / (qa - pa);
                let mut x = p + (q - p) * s;
                x[axis] = plane;
                b.grow(x, x);
            }
        }
    }
    b
}

impl Builder<'_> {
    fn bounds(refs: &[Ref]) -> (Bx, Bx) {
        let (mut b, mut c) = (Bx::EMPTY, Bx::EMPTY);
        for r in refs {
            b.grow(r.lo, r.hi);
            let m = r.centre();
            c.grow(m, m);
        }
        (b, c)
    }

    /// Best object split: (cost, split, overlap area of the two sides).
    fn object_split(&self, refs: &[Ref], bounds: &Bx, centres: &Bx) -> Option<(f32, Split, f32)> {
        let mut best: Option<(f32, Split, f32)> = None;
        let area = bounds.area();
        for axis in 0..3 {
            let extent = centres.hi[axis] - centres.lo[axis];
            if extent <= 0.0 {
                continue;
            }
            let scale = BINS as f32 / extent;
            let mut boxes = [Bx::EMPTY; BINS];
            let mut counts = [0usize; BINS];
            for r in refs {
                let b = (((r.centre()[axis] - centres.lo[axis]) * scale) as usize).min(BINS - 1);
                boxes[b].grow(r.lo, r.hi);
                counts[b] += 1;
            }
            if let Some((cost, b, overlap)) = self.sweep(&boxes, &counts, &counts, area)
                && best.as_ref().is_none_or(|(c, _, _)| cost < *c)
            {
                let split = Split::Object {
                    axis,
                    bin: b,
                    lo: centres.lo[axis],
                    scale,
                };
                best = Some((cost, split, overlap));
            }
        }
        best
    }

    /// The cheapest plane between bins by the SAH, for bins with boxes `boxes`, `enter[b]`
    /// references starting and `exit[b]` ending in bin `b`: its cost, the bin left of it and
    /// the overlap area of its two sides.
    fn sweep(
        &self,
        boxes: &[Bx; BINS],
        enter: &[usize; BINS],
        exit: &[usize; BINS],
        area: f32,
    ) -> Option<(f32, usize, f32)> {
        let mut right = [(Bx::EMPTY, 0usize); BINS];
        let mut acc = (Bx::EMPTY, 0);
        for b in (1..BINS).rev() {
            acc = (Bx::union(acc.0, boxes[b]), acc.1 + exit[b]);
            right[b] = acc;
        }
        let mut best: Option<(f32, usize, f32)> = None;
        let mut left = (Bx::EMPTY, 0);
        for b in 0..BINS - 1 {
            left = (Bx::union(left.0, boxes[b]), left.1 + enter[b]);
            let (rb, rn) = right[b + 1];
            if left.1 == 0 || rn == 0 {
                continue;
            }
            let cost = self.config.traversal_cost
                + (left.0.area() * left.1 as f32 + rb.area() * rn as f32) / area
                    * self.config.triangle_cost;
            if best.is_none_or(|(c, _, _)| cost < c) {
                best = Some((cost, b, Bx::intersect(left.0, rb).area()));
            }
        }
        best
    }

    fn spatial_split(&self, refs: &[Ref], bounds: &Bx) -> Option<(f32, Split)> {
        let mut best: Option<(f32, Split)> = None;
        let area = bounds.area();
        for axis in 0..3 {
            let (lo, hi) = (bounds.lo[axis], bounds.hi[axis]);
            let extent = hi - lo;
            if extent <= 0.0 {
                continue;
            }
            let width = extent / BINS as f32;
            let plane = |b: usize| lo + width * b as f32;
            let mut boxes = [Bx::EMPTY; BINS];
            let mut enter = [0usize; BINS];
            let mut exit = [0usize; BINS];
            for r in refs {
                let bin = |x: f32| (((x - lo) / width) as usize).min(BINS - 1);
                let (first, last) = (bin(r.lo[axis]), bin(r.hi[axis]));
                enter[first] += 1;
                exit[last] += 1;
                let t = &self.tris[r.tri as usize];
                let rb = Bx { lo: r.lo, hi: r.hi };
                for (b, bin_box) in boxes.iter_mut().enumerate().take(last + 1).skip(first) {
                    if first == last {
                        bin_box.grow(r.lo, r.hi);
                        continue;
                    }
                    let c = Bx::intersect(clipped(t, axis, plane(b), plane(b + 1)), rb);
                    if (c.hi - c.lo).min_element() >= 0.0 {
                        bin_box.grow(c.lo, c.hi);
                    }
                }
            }
            if let Some((cost, b, _)) = self.sweep(&boxes, &enter, &exit, area)
                && best.as_ref().is_none_or(|(c, _)| cost < *c)
            {
                let plane = plane(b + 1);
                best = Some((cost, Split::Spatial { axis, plane }));
            }
        }
        best
    }

    fn leaf(&mut self, index: usize, refs: &[Ref], bounds: &Bx) {
        let first = self.order.len() as u32;
        self.order.extend(refs.iter().map(|r| r.tri));
        let aabb = Aabb::new(bounds.lo, bounds.hi).padded();
        self.nodes[index] = BvhNode {
            min: aabb.min.to_array(),
            first,
            max: aabb.max.to_array(),
            count: refs.len() as u32,
        };
    }

    fn build(&mut self, index: usize, refs: Vec<Ref>, depth: u32, budget: usize) {
        let (bounds, centres) = Self::bounds(&refs);
        let n = refs.len();
        let leaf_cost = n as f32 * self.config.triangle_cost;
        if n == 1 || depth + 1 >= self.config.max_depth {
            return self.leaf(index, &refs, &bounds);
        }
        let object = self.object_split(&refs, &bounds, &centres);
        let mut best: Option<(f32, Split)> = object.as_ref().map(|&(c, s, _)| (c, s));
        let overlap = object.as_ref().map_or(f32::INFINITY, |o| o.2);
        if overlap / self.root_area > self.alpha
            && budget > 0
            && let Some((cost, split)) = self.spatial_split(&refs, &bounds)
            && best.as_ref().is_none_or(|(c, _)| cost < *c)
        {
            best = Some((cost, split));
        }
        let made_before = self.refs_made;
        let (left, right) = match best {
            Some((cost, _)) if n <= self.config.max_leaf_size as usize && leaf_cost <= cost => {
                return self.leaf(index, &refs, &bounds);
            }
            Some((
                _,
                Split::Object {
                    axis,
                    bin,
                    lo,
                    scale,
                },
            )) => refs
                .into_iter()
                .partition(|r| (((r.centre()[axis] - lo) * scale) as usize).min(BINS - 1) <= bin),
            Some((_, Split::Spatial { axis, plane })) => {
                let (mut l, mut r) = (Vec::new(), Vec::new());
                for x in refs {
                    if x.hi[axis] <= plane {
                        l.push(x);
                    } else if x.lo[axis] >= plane {
                        r.push(x);
                    } else {
                        let t = &self.tris[x.tri as usize];
                        let own = Bx { lo: x.lo, hi: x.hi };
                        let a = Bx::intersect(clipped(t, axis, f32::NEG_INFINITY, plane), own);
                        let b = Bx::intersect(clipped(t, axis, plane, f32::INFINITY), own);
                        l.push(Ref {
                            tri: x.tri,
                            lo: a.lo,
                            hi: a.hi,
                        });
                        r.push(Ref {
                            tri: x.tri,
                            lo: b.lo,
                            hi: b.hi,
                        });
                        self.refs_made += 1;
                    }
                }
                self.spatial_splits += 1;
                (l, r)
            }
            None => {
                let mut refs = refs;
                refs.sort_by(|a, b| a.centre().x.total_cmp(&b.centre().x));
                let r = refs.split_off(n / 2);
                (refs, r)
            }
        };
        let aabb = Aabb::new(bounds.lo, bounds.hi).padded();
        let first = self.nodes.len();
        self.nodes.push(BvhNode::EMPTY);
        self.nodes.push(BvhNode::EMPTY);
        self.nodes[index] = BvhNode {
            min: aabb.min.to_array(),
            first: first as u32,
            max: aabb.max.to_array(),
            count: 0,
        };
        // What is left of the budget goes to the children in proportion to their references.
        let left_budget = budget.saturating_sub(self.refs_made - made_before);
        let share = left_budget * left.len() / (left.len() + right.len()).max(1);
        self.build(first, left, depth + 1, share);
        self.build(first + 1, right, depth + 1, left_budget - share);
    }
}

fn env<T: std::str::FromStr>(name: &str, default: T) -> T {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// `count` boxes 1.2 long and 0.02 thick, centred in the cube `[-1, 1]³`, pointing anywhere
/// (a fixed pseudo-random sequence), twelve triangles each.
fn sticks(count: usize) -> meshq_tests::LoadedMesh {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0
    };
    let (mut positions, mut triangles) = (Vec::new(), Vec::new());
    for _ in 0..count {
        let centre = Vec3::new(next(), next(), next());
        let along = Vec3::new(next(), next(), next()).normalize_or(Vec3::X);
        let side = along.any_orthonormal_vector();
        let up = along.cross(side);
        let base = positions.len() as u32;
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
    meshq_tests::LoadedMesh {
        name: "sticks".into(),
        positions,
        triangles,
    }
}

fn main() {
    let mut loaded = match (std::env::var("STICKS").ok(), std::env::var("MESH")) {
        (Some(n), _) => sticks(n.parse().expect("STICKS: a count")),
        (None, Ok(path)) => meshq_tests::load_obj(std::path::Path::new(&path)),
        (None, Err(_)) => load_mesh("stanford-bunny"),
    };
    for _ in 0..env("SUBDIVIDE", 0) {
        loaded = meshq_tests::subdivided(&loaded);
    }
    let mesh = loaded.valid();
    let alpha: f32 = env("ALPHA", 1e-5);
    let budget: f32 = env("BUDGET", 1.3);
    let rays = workload::random_rays(&loaded.positions, env("RAYS", 200_000), 1);
    let camera = workload::camera_rays(&loaded.positions, 512, 512);

    let tris: Vec<[Vec3; 3]> = (0..mesh.triangle_count() as u32)
        .map(|t| {
            let t = mesh.triangle(t).expect("triangle");
            [t.a, t.b, t.c]
        })
        .collect();
    let start = Instant::now();
    let refs: Vec<Ref> = tris
        .iter()
        .enumerate()
        .map(|(i, t)| Ref {
            tri: i as u32,
            lo: t[0].min(t[1]).min(t[2]),
            hi: t[0].max(t[1]).max(t[2]),
        })
        .collect();
    let (root, _) = Builder::bounds(&refs);
    let n = refs.len();
    let mut b = Builder {
        tris: &tris,
        nodes: vec![BvhNode::EMPTY],
        order: Vec::new(),
        root_area: root.area(),
        alpha,
        refs_made: 0,
        spatial_splits: 0,
        config: BuildConfig::default(),
    };
    b.build(0, refs, 1, ((budget - 1.0) * n as f32) as usize);
    let sbvh_build = start.elapsed();
    let start = Instant::now();
    let owned = MeshBvh::build(&mesh, &BuildConfig::default()).expect("build");
    let normal_build = start.elapsed();
    let normal_nodes = meshq_tests::checked_bvh(&owned, &mesh)
        .expect("view")
        .nodes()
        .len();
    println!(
        "{n} triangles: {} references (+{:.1}%), {} spatial splits, {} nodes (normal {}); \
         prototype build {:.1} ms, meshq build {:.1} ms",
        b.order.len(),
        100.0 * (b.order.len() - n) as f64 / n as f64,
        b.spatial_splits,
        b.nodes.len(),
        normal_nodes,
        sbvh_build.as_secs_f64() * 1e3,
        normal_build.as_secs_f64() * 1e3,
    );
    let sbvh = Bvh::from_built_parts(&b.nodes, &b.order, &mesh).expect("valid topology");
    let mut packed_s = vec![PackedTriangle::default(); b.order.len()];
    let packed_s: PackedTriangles<'_> = sbvh.pack_triangles(&mesh, &mut packed_s).expect("pack");
    let mut w4 = vec![WideNode::EMPTY; b.nodes.len()];
    let wide_s = WideBvh::build(&sbvh, &mut w4).expect("wide");
    let mut w8 = vec![WideNode8::EMPTY; b.nodes.len()];
    let wide8_s = WideBvh8::build(&sbvh, &mut w8).expect("wide8");

    let bvh = meshq_tests::checked_bvh(&owned, &mesh).expect("view");
    let packed = owned.packed();
    let owned4 = owned.clone().with_four_wide_nodes().expect("four-wide");
    let wide = owned4.wide().expect("wide");
    let mut n8 = vec![WideNode8::EMPTY; bvh.nodes().len()];
    let wide8 = WideBvh8::build(&bvh, &mut n8).expect("wide8");

    // Every answer the same as the normal tree's, bit for bit.
    for r in rays.iter().chain(&camera) {
        let want = wide.with(&packed).raycast(r);
        assert_eq!(wide_s.with(&packed_s).raycast(r), want);
        assert_eq!(wide8_s.with(&packed_s).raycast(r), want);
    }
    println!("{} rays: the same hits", rays.len() + camera.len());

    // Each tree as a closest-hit test of one ray, timed on each workload.
    type Hits<'a> = &'a dyn Fn(&meshq::math::Ray) -> bool;
    let trees: [(&str, Hits<'_>); 4] = [
        ("4 normal", &|r| wide.with(&packed).raycast(r).is_some()),
        ("4 sbvh", &|r| wide_s.with(&packed_s).raycast(r).is_some()),
        ("8 normal", &|r| wide8.with(&packed).raycast(r).is_some()),
        ("8 sbvh", &|r| wide8_s.with(&packed_s).raycast(r).is_some()),
    ];
    let variants: Vec<(String, &[meshq::math::Ray], Hits<'_>)> =
        [("random", &rays), ("camera", &camera)]
            .into_iter()
            .flat_map(|(workload, rays)| {
                trees
                    .iter()
                    .map(move |&(tree, hits)| (format!("{workload} {tree}"), rays.as_slice(), hits))
            })
            .collect();
    let mut best = vec![Duration::MAX; variants.len()];
    for _ in 0..ROUNDS {
        for (i, (_, rays, hits)) in variants.iter().enumerate() {
            let start = Instant::now();
            black_box(rays.iter().filter(|r| hits(r)).count());
            best[i] = best[i].min(start.elapsed());
        }
    }
    for ((name, rays, _), t) in variants.iter().zip(&best) {
        println!(
            "{name:>18}: {:>8.2} ms  {:>6.2} M rays/s",
            t.as_secs_f64() * 1e3,
            rays.len() as f64 / t.as_secs_f64() / 1e6
        );
    }
}

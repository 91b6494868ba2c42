//! Meshes remeshing finds hard, made here: capsules with long thin side strips and
//! high-valence poles, a cone of needle-thin facets, an open tube of strips, boxes, stretched
//! spheres, a patch of slivers and a range scan.

use meshq::Vec3;

/// Positions and triangles.
pub type Mesh = (Vec<[f32; 3]>, Vec<[u32; 3]>);

/// A capsule as `trimesh.creation.capsule(height, radius, count=[n, n])` makes it: two
/// hemispheres of `n` longitudes and `n/2` bands each, one band of side triangles as long as
/// the capsule between them.
pub fn capsule(n: u32, radius: f32, height: f32) -> Mesh {
    let bands = n / 2;
    let mut positions = vec![[0.0, 0.0, height / 2.0 + radius]];
    let mut rings = Vec::new();
    let mut ring = |positions: &mut Vec<[f32; 3]>, z0: f32, j: u32, sign: f32| {
        let phi = std::f32::consts::FRAC_PI_2 * j as f32 / bands as f32;
        let (r, z) = (radius * phi.sin(), z0 + sign * radius * phi.cos());
        rings.push(positions.len() as u32);
        for i in 0..n {
            let a = std::f32::consts::TAU * i as f32 / n as f32;
            positions.push([r * a.cos(), r * a.sin(), z]);
        }
    };
    for j in 1..=bands {
        ring(&mut positions, height / 2.0, j, 1.0);
    }
    for j in (1..=bands).rev() {
        ring(&mut positions, -height / 2.0, j, -1.0);
    }
    let bottom = positions.len() as u32;
    positions.push([0.0, 0.0, -height / 2.0 - radius]);
    let mut triangles = Vec::new();
    for i in 0..n {
        triangles.push([0, rings[0] + i, rings[0] + (i + 1) % n]);
    }
    for k in 0..rings.len() - 1 {
        let (a, b) = (rings[k], rings[k + 1]);
        for i in 0..n {
            let i1 = (i + 1) % n;
            triangles.push([a + i, b + i, b + i1]);
            triangles.push([a + i, b + i1, a + i1]);
        }
    }
    let last = rings[rings.len() - 1];
    for i in 0..n {
        triangles.push([bottom, last + (i + 1) % n, last + i]);
    }
    (positions, triangles)
}

/// A closed cone of `n` sections: apex at `z = height`, base disc of `radius` at `z = 0`.
/// Every side facet is a needle from the apex (at 1,024 sections, under a third of a degree
/// there), and the apex and the base centre have valence `n`.
pub fn cone(n: u32, radius: f32, height: f32) -> Mesh {
    let mut positions = vec![[0.0, 0.0, height], [0.0, 0.0, 0.0]];
    for i in 0..n {
        let a = std::f32::consts::TAU * i as f32 / n as f32;
        positions.push([radius * a.cos(), radius * a.sin(), 0.0]);
    }
    let mut triangles = Vec::new();
    for i in 0..n {
        let (r0, r1) = (2 + i, 2 + (i + 1) % n);
        triangles.push([0, r0, r1]);
        triangles.push([1, r1, r0]);
    }
    (positions, triangles)
}

/// An open tube of `n` long strips (two boundary loops).
pub fn tube(n: u32, radius: f32, length: f32) -> Mesh {
    let mut positions = Vec::new();
    for z in [0.0, length] {
        for i in 0..n {
            let a = std::f32::consts::TAU * i as f32 / n as f32;
            positions.push([radius * a.cos(), radius * a.sin(), z]);
        }
    }
    let mut triangles = Vec::new();
    for i in 0..n {
        let i1 = (i + 1) % n;
        triangles.push([i, i1, n + i1]);
        triangles.push([i, n + i1, n + i]);
    }
    (positions, triangles)
}

/// A box of twelve triangles, `x` by `y` by `z`.
pub fn cuboid(x: f32, y: f32, z: f32) -> Mesh {
    let positions = (0..8)
        .map(|i| {
            let c = |bit: u32, s: f32| if i & bit != 0 { s } else { 0.0 };
            [c(1, x), c(2, y), c(4, z)]
        })
        .collect();
    let quads = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    let triangles = quads
        .iter()
        .flat_map(|&[a, b, c, d]| [[a, b, c], [a, c, d]])
        .collect();
    (positions, triangles)
}

/// An octahedron subdivided `levels` times onto the unit sphere, then scaled by `scale`.
pub fn sphere(levels: u32, scale: [f32; 3]) -> Mesh {
    let mut positions: Vec<Vec3> =
        [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z].to_vec();
    let mut triangles: Vec<[u32; 3]> = vec![
        [0, 2, 4],
        [2, 1, 4],
        [1, 3, 4],
        [3, 0, 4],
        [2, 0, 5],
        [1, 2, 5],
        [3, 1, 5],
        [0, 3, 5],
    ];
    for _ in 0..levels {
        let mut midpoints = std::collections::HashMap::new();
        let mut mid = |a: u32, b: u32, positions: &mut Vec<Vec3>| {
            *midpoints.entry((a.min(b), a.max(b))).or_insert_with(|| {
                let p = (positions[a as usize] + positions[b as usize]).normalize();
                positions.push(p);
                positions.len() as u32 - 1
            })
        };
        triangles = triangles
            .iter()
            .flat_map(|&[a, b, c]| {
                let (ab, bc, ca) = (
                    mid(a, b, &mut positions),
                    mid(b, c, &mut positions),
                    mid(c, a, &mut positions),
                );
                [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]
            })
            .collect();
    }
    let scale = Vec3::from(scale);
    (
        positions.iter().map(|p| (*p * scale).to_array()).collect(),
        triangles,
    )
}

/// A flat `side × side` grid whose rows are squeezed in turn, so half its triangles are
/// slivers (an open patch: one boundary loop).
pub fn slivers(side: u32) -> Mesh {
    let mut positions = Vec::new();
    let mut y = 0.0f32;
    for j in 0..=side {
        for i in 0..=side {
            positions.push([i as f32, y, 0.0]);
        }
        y += if j % 2 == 0 { 0.02 } else { 1.0 };
    }
    let row = side + 1;
    let mut triangles = Vec::new();
    for j in 0..side {
        for i in 0..side {
            let v = j * row + i;
            triangles.push([v, v + 1, v + row + 1]);
            triangles.push([v, v + row + 1, v + row]);
        }
    }
    (positions, triangles)
}

/// An open range scan of `side × side` samples, as a scanner sees a surface from above: a
/// height field over a grid of jittered samples (each moved up to 0.2 of the spacing, which
/// never folds a triangle over), cut into triangles along the grid. Hills give gentle and
/// steep slopes, and a step of 0.3 along a slanted line, a jump edge, is spanned by slivers
/// under a degree standing nearly upright, as scans of an object's silhouette have.
/// `2 · (side − 1)²` triangles, one boundary loop, every triangle facing up.
pub fn range_scan(side: u32) -> Mesh {
    let mut state = 0x2545_F491_u32;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        state as f32 / u32::MAX as f32 - 0.5
    };
    let step = 1.0 / side as f32;
    let mut positions = Vec::with_capacity((side * side) as usize);
    for j in 0..side {
        for i in 0..side {
            let x = (i as f32 + 0.4 * next()) * step;
            let y = (j as f32 + 0.4 * next()) * step;
            let hills = 0.15 * (6.0 * x).sin() * (4.0 * y).cos();
            let jump = if x + 0.3 * y > 0.7 { 0.3 } else { 0.0 };
            positions.push([x, y, hills + jump]);
        }
    }
    let mut triangles = Vec::with_capacity(2 * (side as usize - 1).pow(2));
    for j in 0..side - 1 {
        for i in 0..side - 1 {
            let v = j * side + i;
            triangles.push([v, v + 1, v + side + 1]);
            triangles.push([v, v + side + 1, v + side]);
        }
    }
    (positions, triangles)
}

/// `n` copies of one triangle.
pub fn same(n: u32) -> Mesh {
    let positions = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    (positions, vec![[0, 1, 2]; n as usize])
}

/// `n` long slivers through the centre, each turned `2π/n` about z from the last.
pub fn crossing(n: u32) -> Mesh {
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for i in 0..n {
        let a = std::f32::consts::TAU * i as f32 / n as f32;
        let (c, s) = (a.cos(), a.sin());
        let base = positions.len() as u32;
        positions.push([-c, -s, -0.001 * (i % 7) as f32]);
        positions.push([c, s, 0.001 * (i % 5) as f32]);
        positions.push([c + 1e-4, s, 0.0]);
        triangles.push([base, base + 1, base + 2]);
    }
    (positions, triangles)
}

/// `n` triangles of zero area, all at one point.
pub fn point(n: u32) -> Mesh {
    let positions = vec![[0.25, 0.5, 0.75]; 3 * n as usize];
    let triangles = (0..n).map(|i| [3 * i, 3 * i + 1, 3 * i + 2]).collect();
    (positions, triangles)
}

/// `n` triangles, each spanning the whole box `[-1, 1]³` (corners on its faces, turned a
/// little each time).
pub fn overlap(n: u32) -> Mesh {
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for i in 0..n {
        let t = i as f32 / n as f32;
        let base = positions.len() as u32;
        positions.push([-1.0, -1.0 + 2.0 * t, -1.0]);
        positions.push([1.0, 1.0 - 2.0 * t, -1.0]);
        positions.push([2.0 * t - 1.0, 0.0, 1.0]);
        triangles.push([base, base + 1, base + 2]);
    }
    (positions, triangles)
}

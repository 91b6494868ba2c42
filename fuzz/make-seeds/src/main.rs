//! Writes a seed corpus for `blob_parse`: small valid blobs of every mesh layout, each with
//! both mode bytes, into the directory given as the only argument; among them a scene of long
//! crossing triangles built with spatial splits (a format 4 blob with split references).

use meshq::MeshBvh;
use meshq::blob::MeshLayout;
use meshq::bvh::{BuildConfig, SpatialSplits};
use meshq::mesh::MeshRef;

/// Writes `scene`'s blob in both stored-mesh layouts, each with both mode bytes.
fn write_seeds(dir: &str, name: &str, scene: &MeshBvh) -> Result<(), Box<dyn std::error::Error>> {
    for layout in [MeshLayout::Indexed, MeshLayout::Packed] {
        let bytes = scene.to_blob(layout)?;
        for mode in [0u8, 1] {
            let mut seed = vec![mode];
            seed.extend_from_slice(&bytes);
            std::fs::write(format!("{dir}/{name}-{layout:?}-{mode}"), seed)?;
        }
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dir = std::env::args().nth(1).ok_or("usage: make_seeds DIR")?;
    std::fs::create_dir_all(&dir)?;
    // A grid of n×n quads on a bumpy surface, for a few sizes (1 to 50 triangles).
    for n in [0usize, 1, 2, 5] {
        let mut positions = Vec::new();
        for j in 0..=n {
            for i in 0..=n {
                let (x, y) = (i as f32, j as f32);
                positions.push([x, y, (x * 0.7).sin() * (y * 0.4).cos()]);
            }
        }
        let mut triangles = Vec::new();
        let w = n as u32 + 1;
        for j in 0..n as u32 {
            for i in 0..n as u32 {
                let a = j * w + i;
                triangles.push([a, a + 1, a + w + 1]);
                triangles.push([a, a + w + 1, a + w]);
            }
        }
        if n == 0 {
            positions.clear();
        }
        let mesh = MeshRef::new(&positions, &triangles).validate()?;
        let config = BuildConfig {
            max_leaf_size: 2,
            ..BuildConfig::default()
        };
        let scene = MeshBvh::build(&mesh, &config)?;
        write_seeds(&dir, &format!("grid{n}"), &scene)?;
    }
    // Long thin boxes at pseudo-random angles crossing each other, as few as give split
    // references.
    let mut scene = None;
    for sticks in 2..40 {
        let (positions, triangles) = crossing_sticks(sticks);
        let mesh = MeshRef::new(&positions, &triangles).validate()?;
        let built =
            MeshBvh::build_spatial(&mesh, &BuildConfig::default(), &SpatialSplits::DEFAULT)?;
        if !built.split_refs().is_empty() {
            scene = Some(built);
            break;
        }
    }
    let scene = scene.ok_or("no crossing scene was built with split references")?;
    write_seeds(&dir, "crossing-spatial", &scene)?;
    Ok(())
}

/// `count` boxes 1.2 long and 0.02 thick (twelve triangles each) at places and angles from a
/// fixed linear congruential sequence in `[-1, 1]³`.
fn crossing_sticks(count: u32) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let mut state = 0x2545_f491u32;
    let mut next = move || {
        state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        (state >> 8) as f32 / (1u32 << 24) as f32 * 2.0 - 1.0
    };
    let (mut positions, mut triangles) = (Vec::new(), Vec::new());
    for k in 0..count {
        let centre = [next(), next(), next()];
        let mut along = [next(), next(), next()];
        let len = along.iter().map(|x| x * x).sum::<f32>().sqrt().max(1e-3);
        along.iter_mut().for_each(|x| *x /= len);
        // Two directions across the stick: any vector not along it, made orthogonal.
        let pick = if along[0].abs() < 0.9 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        };
        let cross = |a: [f32; 3], b: [f32; 3]| {
            [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ]
        };
        let side = cross(along, pick);
        let up = cross(along, side);
        for corner in 0..8u32 {
            let sign = |bit: u32| if corner & bit == 0 { -1.0 } else { 1.0 };
            let p: [f32; 3] = core::array::from_fn(|i| {
                centre[i]
                    + along[i] * 0.6 * sign(4)
                    + side[i] * 0.01 * sign(2)
                    + up[i] * 0.01 * sign(1)
            });
            positions.push(p);
        }
        let base = 8 * k;
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
    (positions, triangles)
}

//! Writes a seed corpus for `blob_parse`: small valid blobs of every mesh layout, each with
//! both mode bytes, into the directory given as the only argument.

use meshq::MeshBvh;
use meshq::blob::MeshLayout;
use meshq::bvh::BuildConfig;
use meshq::mesh::MeshRef;

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
        for layout in [MeshLayout::Indexed, MeshLayout::Packed] {
            let bytes = scene.to_blob(layout)?;
            for mode in [0u8, 1] {
                let mut seed = vec![mode];
                seed.extend_from_slice(&bytes);
                std::fs::write(format!("{dir}/grid{n}-{layout:?}-{mode}"), seed)?;
            }
        }
    }
    Ok(())
}

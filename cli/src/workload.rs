//! `meshq workload`: writes the DESIGN.md query workloads for a mesh as raw files that
//! `raycast` and `closest` read.

use std::io::Write;
use std::path::PathBuf;

use anyhow::{Context, Result, bail};
use clap::{Args, ValueEnum};
use meshq::mesh::MeshRef;
use meshq_workload::{CameraRays, QueryPoints, RandomRays, centre_radius};

use crate::atomic::AtomicFile;
use crate::mesh_file::read_mesh;
use crate::output::say;

/// `--kind`: which workload.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Kind {
    /// Rays from a sphere of radius 1.5·r toward points in the box (6 float32 per ray).
    RandomRays,
    /// A pinhole camera's rays, row-major (6 float32 per ray).
    CameraRays,
    /// Points in the box grown by 10 % (3 float32 per point).
    Points,
}

#[derive(Args, Debug)]
#[command(after_help = "Examples:\n  \
    meshq workload assets/stanford-bunny.obj -o rays.bin\n  \
    meshq workload assets/spot.obj --kind camera-rays --image 640x480 -o camera.bin\n  \
    meshq workload assets/spot.obj --kind points --count 100000 -o points.bin")]
pub struct WorkloadArgs {
    /// The mesh whose bounding box places the workload.
    pub mesh: PathBuf,
    /// Which workload.
    #[arg(long, value_enum, default_value_t = Kind::RandomRays)]
    pub kind: Kind,
    /// How many rays or points (random rays and points).
    #[arg(long, default_value_t = 1_000_000)]
    pub count: usize,
    /// Image size `WIDTHxHEIGHT` (camera rays).
    #[arg(long, default_value = "1024x1024")]
    pub image: String,
    /// Generator seed.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Where to write the records.
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
}

pub fn run(args: &WorkloadArgs) -> Result<()> {
    crate::atomic::refuse_inputs(&args.output, &[&args.mesh])?;
    let data = read_mesh(&args.mesh)?;
    // The workloads are placed by the mesh's bounds: they need a valid, non-empty mesh.
    let mesh = MeshRef::new(&data.positions, &data.triangles)
        .validate()
        .with_context(|| format!("{}: invalid mesh", args.mesh.display()))?;
    if mesh.triangle_count() == 0 {
        bail!(
            "{}: the mesh has no triangles, so no bounds to place a workload in",
            args.mesh.display()
        );
    }
    let (_, _, bounds) = centre_radius(&data.positions);
    let mut out = AtomicFile::create(&args.output, &[&args.mesh])?;
    let mut floats = |values: &[f32]| -> Result<()> {
        for v in values {
            out.write_all(&v.to_le_bytes())?;
        }
        Ok(())
    };
    let written = match args.kind {
        Kind::RandomRays => {
            for r in RandomRays::new(bounds, args.seed).take(args.count) {
                floats(&[
                    r.origin.x, r.origin.y, r.origin.z, r.dir.x, r.dir.y, r.dir.z,
                ])?;
            }
            args.count
        }
        Kind::CameraRays => {
            let (w, h) = args
                .image
                .split_once('x')
                .and_then(|(w, h)| Some((w.parse().ok()?, h.parse().ok()?)))
                .with_context(|| format!("--image {}: expected WIDTHxHEIGHT", args.image))?;
            for r in CameraRays::new(bounds, w, h) {
                floats(&[
                    r.origin.x, r.origin.y, r.origin.z, r.dir.x, r.dir.y, r.dir.z,
                ])?;
            }
            w * h
        }
        Kind::Points => {
            for p in QueryPoints::new(bounds, args.seed).take(args.count) {
                floats(&p.to_array())?;
            }
            args.count
        }
    };
    out.commit()?;
    say!("wrote {written} records to {}", args.output.display());
    Ok(())
}

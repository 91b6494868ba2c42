//! `meshq sdf`: a signed-distance volume of a mesh, written as NRRD.

use std::io::Write;
use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Result, anyhow};
use clap::Args;
use meshq::inside::{SampleGrid, WindingAccuracy};
use serde::Serialize;

use crate::atomic::AtomicFile;
use crate::output::say;
use crate::structure::{PrepareTime, QueryInput, with_structure};
use crate::threads::Threads;
use crate::winding::{ACCURACY_HELP, accuracy_parser};
use crate::{output, winding};

/// A padding: a number ≥ 0.
fn padding(text: &str) -> Result<f32, String> {
    match text.parse::<f32>() {
        Ok(p) if p >= 0.0 && p.is_finite() => Ok(p),
        _ => Err(format!("expected a padding ≥ 0, got {text:?}")),
    }
}

/// A band: a distance > 0 (`inf` allowed).
fn band(text: &str) -> Result<f32, String> {
    match text.parse::<f32>() {
        Ok(d) if d > 0.0 => Ok(d),
        _ => Err(format!("expected a distance > 0, got {text:?}")),
    }
}

#[derive(Args, Debug)]
#[command(after_help = "Examples:\n  \
    meshq sdf assets/spot.obj -o spot.nrrd --resolution 128\n  \
    meshq sdf assets/stanford-bunny.obj -o bunny.nrrd --resolution 256 --band 0.01 --threads 0")]
pub struct SdfArgs {
    #[command(flatten)]
    pub input: QueryInput,
    /// The volume: NRRD (a text header, then little-endian float32 values, x fastest), signed
    /// distances in the mesh's units, negative inside.
    #[arg(short, long)]
    pub out: PathBuf,
    /// Samples along the box's longest axis (cubic cells; the other axes in proportion).
    #[arg(long, default_value_t = 128, value_parser = clap::value_parser!(u32).range(2..=2048))]
    pub resolution: u32,
    /// Room around the mesh's box on every side, as a fraction of its longest side.
    #[arg(long, default_value_t = 0.1, value_parser = padding)]
    pub padding: f32,
    /// A narrow band: samples farther than D from the surface hold ±D (faster); default none.
    #[arg(long, value_name = "D", value_parser = band)]
    pub band: Option<f32>,
    #[arg(long, value_name = "RATIO", default_value = "2", value_parser = accuracy_parser,
          help = ACCURACY_HELP)]
    pub accuracy: WindingAccuracy,
    /// Print the figures as one JSON object.
    #[arg(long)]
    pub json: bool,
}

#[derive(Serialize)]
struct Summary {
    samples: u64,
    counts: [u32; 3],
    spacing: [f32; 3],
    origin: [f32; 3],
    /// Samples inside (negative).
    inside: u64,
    #[serde(flatten)]
    prepare: PrepareTime,
    threads: usize,
    /// The volume alone, on those threads.
    query_seconds: f64,
}

pub fn run(args: &SdfArgs) -> Result<()> {
    let threads = Threads::new(args.input.threads)?;
    let mut file = AtomicFile::create(&args.out, &args.input.paths())?;
    let mut verb = "";
    let band = args.band.unwrap_or(f32::INFINITY);
    let (summary, values) = with_structure(&args.input, |mut s| {
        let built = winding::prepare(&mut s)?;
        let tree = winding::tree(&s, &built)?;
        verb = s.verb();
        let bounds = tree.mesh().bounds();
        let grid = SampleGrid::cubic(bounds, args.resolution, args.padding)
            .ok_or_else(|| anyhow!("the mesh has no extent to sample (empty, or not finite)"))?;
        let mut values = vec![0.0f32; grid.len()];
        let start = Instant::now();
        match threads.pool() {
            None => {
                tree.signed_distance_grid(&s.scene, &grid, band, args.accuracy, 0, &mut values)?
            }
            Some(pool) => pool.install(|| {
                meshq::parallel::signed_distance_grid(
                    &tree,
                    &s.scene,
                    &grid,
                    band,
                    args.accuracy,
                    &mut values,
                )
            })?,
        }
        let query_seconds = start.elapsed().as_secs_f64();
        let summary = Summary {
            samples: values.len() as u64,
            counts: grid.counts(),
            spacing: grid.spacing().to_array(),
            origin: grid.min().to_array(),
            inside: values.iter().filter(|v| **v < 0.0).count() as u64,
            prepare: s.time(),
            threads: threads.count(),
            query_seconds,
        };
        Ok((summary, values))
    })?;
    let [nx, ny, nz] = summary.counts;
    let [sx, sy, sz] = summary.spacing;
    let [ox, oy, oz] = summary.origin;
    // NRRD 4: the lattice placed in space by its origin and one direction per axis.
    write!(
        file,
        "NRRD0004\n# signed distance, negative inside (meshq sdf)\ntype: float\ndimension: 3\n\
         space dimension: 3\nsizes: {nx} {ny} {nz}\nspace origin: ({ox},{oy},{oz})\n\
         space directions: ({sx},0,0) (0,{sy},0) (0,0,{sz})\nkinds: space space space\n\
         endian: little\nencoding: raw\n\n"
    )?;
    for v in &values {
        file.write_all(&v.to_le_bytes())?;
    }
    file.commit()?;
    if args.json {
        output::json(&summary)
    } else {
        say!(
            "{nx}×{ny}×{nz} samples, {} inside, {verb} {:.3} s, volume {:.3} s on {} thread(s)",
            summary.inside,
            summary.prepare.seconds(),
            summary.query_seconds,
            summary.threads
        );
        Ok(())
    }
}

//! `meshq sweep`: shapes moved along segments from a file, the first contact of each.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Result, bail};
use clap::{Args, ValueEnum};
use meshq::math::{Obb, Vec3};
use meshq::query::{MeshQuery, SweepHit, SweepShape};
use rayon::prelude::*;
use serde::Serialize;

use crate::output::say;
use crate::raycast::per_second;
use crate::records::{RecordReader, ResultWriter};
use crate::structure::{PrepareTime, QueryInput, with_structure};
use crate::threads::Threads;
use crate::{output, progress};

/// Sweeps read and answered per chunk.
const CHUNK: usize = 1 << 16;

/// The shape every record of the file moves.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ShapeKind {
    /// 7 floats: centre x y z, radius, motion x y z.
    Sphere,
    /// 10 floats: end a x y z, end b x y z, radius, motion x y z.
    Capsule,
    /// 18 floats: centre x y z, three orthonormal axes (x y z each), half extents along them,
    /// motion x y z.
    Box,
}

impl ShapeKind {
    /// Floats per record.
    const fn floats(self) -> usize {
        match self {
            Self::Sphere => 7,
            Self::Capsule => 10,
            Self::Box => 18,
        }
    }

    /// The shape and motion of one record of [`floats`](Self::floats) numbers.
    fn read(self, r: &[f32]) -> Option<(SweepShape, Vec3)> {
        let v = |i: usize| Some(Vec3::new(*r.get(i)?, *r.get(i + 1)?, *r.get(i + 2)?));
        Some(match self {
            Self::Sphere => (
                SweepShape::Sphere {
                    center: v(0)?,
                    radius: *r.get(3)?,
                },
                v(4)?,
            ),
            Self::Capsule => (
                SweepShape::Capsule {
                    a: v(0)?,
                    b: v(3)?,
                    radius: *r.get(6)?,
                },
                v(7)?,
            ),
            Self::Box => (
                SweepShape::Box(Obb::new(v(0)?, [v(3)?, v(6)?, v(9)?], v(12)?)),
                v(15)?,
            ),
        })
    }
}

#[derive(Args, Debug)]
#[command(after_help = "Examples:\n  \
    meshq sweep assets/spot.obj --shape sphere --sweeps spheres.bin --out contacts.bin --json\n  \
    meshq sweep level.blob --shape capsule --sweeps moves.bin --out contacts.bin --threads 0")]
pub struct SweepArgs {
    #[command(flatten)]
    pub input: QueryInput,
    /// The shape every record moves (its record layout, raw little-endian float32, no header:
    /// sphere 7 floats, capsule 10, box 18; see `--help`).
    #[arg(long, value_enum)]
    pub shape: ShapeKind,
    /// The sweeps: one record per sweep, the shape where it starts, then the motion (the
    /// shape ends at start + motion).
    #[arg(long)]
    pub sweeps: PathBuf,
    /// Results, 32 bytes per sweep: float32 t (the fraction of the motion done at first
    /// contact, 0 to 1; +inf when the shape touches nothing), uint32 triangle (0xFFFFFFFF on
    /// a miss), float32 contact point x y z on the mesh, float32 unit normal x y z from the
    /// mesh toward the shape (NaN on a miss).
    #[arg(long)]
    pub out: PathBuf,
    /// Print the figures as one JSON object.
    #[arg(long)]
    pub json: bool,
}

#[derive(Serialize)]
struct Summary {
    sweeps: u64,
    /// Sweeps that touch the mesh.
    hits: u64,
    #[serde(flatten)]
    prepare: PrepareTime,
    threads: usize,
    /// The queries alone, on those threads.
    query_seconds: f64,
    sweeps_per_second: f64,
}

pub fn run(args: &SweepArgs) -> Result<()> {
    let threads = Threads::new(args.input.threads)?;
    let floats_per = args.shape.floats();
    let mut reader = RecordReader::open(&args.sweeps, floats_per, "sweep")?;
    let mut inputs = args.input.paths();
    inputs.push(&args.sweeps);
    let mut writer = ResultWriter::create(&args.out, &inputs)?;
    let mut verb = "";
    let summary = with_structure(&args.input, |s| {
        verb = s.verb();
        let bar = progress::bar(reader.expected, "sweeps");
        let mut floats = Vec::new();
        let (mut query_seconds, mut hits, mut done) = (0.0f64, 0u64, 0u64);
        while reader.next_chunk(CHUNK, &mut floats)? > 0 {
            let mut sweeps = Vec::with_capacity(floats.len() / floats_per);
            for (k, r) in floats.chunks_exact(floats_per).enumerate() {
                let Some(sweep) = args.shape.read(r) else {
                    bail!("sweep {}: a short record", done + k as u64);
                };
                sweeps.push(sweep);
            }
            let start = Instant::now();
            let one = |(shape, motion): &(SweepShape, Vec3)| s.scene.sweep(shape, *motion);
            let answers: Vec<_> = match threads.pool() {
                None => sweeps.iter().map(one).collect(),
                Some(pool) => pool.install(|| sweeps.par_iter().map(one).collect()),
            };
            query_seconds += start.elapsed().as_secs_f64();
            for (k, answer) in answers.into_iter().enumerate() {
                let hit = answer.map_err(|e| anyhow::anyhow!("sweep {}: {e}", done + k as u64))?;
                hits += u64::from(hit.is_some());
                write_hit(&mut writer, hit)?;
            }
            done += sweeps.len() as u64;
            bar.inc(sweeps.len() as u64);
        }
        bar.finish_and_clear();
        Ok(Summary {
            sweeps: reader.count,
            hits,
            prepare: s.time(),
            threads: threads.count(),
            query_seconds,
            sweeps_per_second: per_second(reader.count, query_seconds),
        })
    })?;
    writer.finish()?;
    if args.json {
        output::json(&summary)
    } else {
        say!(
            "{} sweeps, {} touch the mesh, {verb} {:.3} s, queries {:.3} s: {:.0} sweeps/s",
            summary.sweeps,
            summary.hits,
            summary.prepare.seconds(),
            summary.query_seconds,
            summary.sweeps_per_second
        );
        Ok(())
    }
}

/// One 32-byte result record.
fn write_hit(writer: &mut ResultWriter, hit: Option<SweepHit>) -> Result<()> {
    match hit {
        Some(h) => {
            writer.write(h.t, h.tri)?;
            writer.write_f32s(&h.point.to_array())?;
            writer.write_f32s(&h.normal.to_array())
        }
        None => {
            writer.write(f32::INFINITY, u32::MAX)?;
            writer.write_f32s(&[f32::NAN; 6])
        }
    }
}

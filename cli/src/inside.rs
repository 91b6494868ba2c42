//! `meshq inside`: points from a file, one winding-number record per point.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::Result;
use clap::Args;
use meshq::inside::WindingAccuracy;
use meshq::math::Vec3;
use serde::Serialize;

use crate::output::say;
use crate::raycast::per_second;
use crate::records::{RecordReader, ResultWriter};
use crate::structure::{PrepareTime, QueryInput, with_structure};
use crate::threads::Threads;
use crate::winding::{ACCURACY_HELP, accuracy_parser};
use crate::{output, progress, winding};

/// Points read and queried per chunk (12 MB of input).
const CHUNK: usize = 1 << 20;

#[derive(Args, Debug)]
#[command(after_help = "Examples:\n  \
    meshq workload assets/spot.obj --kind points -o points.bin\n  \
    meshq inside assets/spot.obj --points points.bin --out inside.bin --json\n  \
    meshq inside assets/stanford-bunny.obj --points points.bin --out inside.bin --accuracy exact")]
pub struct InsideArgs {
    #[command(flatten)]
    pub input: QueryInput,
    /// Points: raw little-endian float32, 3 per point (x y z), no header.
    #[arg(long)]
    pub points: PathBuf,
    /// Results: per point, float32 generalized winding number (1 inside a closed mesh facing
    /// outwards, 0 outside, fractions near holes; NaN for a point that is not finite) then
    /// uint32 1 when inside (|winding number| ≥ 1/2), else 0.
    #[arg(long)]
    pub out: PathBuf,
    #[arg(long, value_name = "RATIO", default_value = "2", value_parser = accuracy_parser,
          help = ACCURACY_HELP)]
    pub accuracy: WindingAccuracy,
    /// Print the figures as one JSON object.
    #[arg(long)]
    pub json: bool,
}

#[derive(Serialize)]
struct Summary {
    points: u64,
    /// Points inside.
    inside: u64,
    #[serde(flatten)]
    prepare: PrepareTime,
    threads: usize,
    /// The queries alone, on those threads.
    query_seconds: f64,
    points_per_second: f64,
}

pub fn run(args: &InsideArgs) -> Result<()> {
    let threads = Threads::new(args.input.threads)?;
    let mut reader = RecordReader::open(&args.points, 3, "point")?;
    let mut inputs = args.input.paths();
    inputs.push(&args.points);
    let mut writer = ResultWriter::create(&args.out, &inputs)?;
    let mut verb = "";
    let summary = with_structure(&args.input, |mut s| {
        let built = winding::prepare(&mut s)?;
        let tree = winding::tree(&s, &built)?;
        verb = s.verb();
        let bar = progress::bar(reader.expected, "points");
        let (mut floats, mut points, mut numbers) = (Vec::new(), Vec::new(), Vec::new());
        let mut keys = Vec::new();
        let (mut query_seconds, mut inside) = (0.0f64, 0u64);
        while reader.next_chunk(CHUNK, &mut floats)? > 0 {
            let (records, _) = floats.as_chunks::<3>();
            points.clear();
            points.extend(records.iter().map(|&p| Vec3::from_array(p)));
            numbers.resize(points.len(), 0.0f32);
            keys.resize(points.len(), 0u64);
            let start = Instant::now();
            match threads.pool() {
                None => tree.winding_numbers(&points, args.accuracy, &mut keys, &mut numbers)?,
                Some(pool) => pool.install(|| {
                    meshq::parallel::winding_numbers(&tree, &points, args.accuracy, &mut numbers)
                })?,
            }
            query_seconds += start.elapsed().as_secs_f64();
            for &w in &numbers[..points.len()] {
                let holds = w.abs() >= 0.5;
                inside += u64::from(holds);
                writer.write(w, u32::from(holds))?;
            }
            bar.inc(points.len() as u64);
        }
        bar.finish_and_clear();
        Ok(Summary {
            points: reader.count,
            inside,
            prepare: s.time(),
            threads: threads.count(),
            query_seconds,
            points_per_second: per_second(reader.count, query_seconds),
        })
    })?;
    writer.finish()?;
    if args.json {
        output::json(&summary)
    } else {
        say!(
            "{} points, {} inside, {verb} {:.3} s, queries {:.3} s: {:.2} M points/s",
            summary.points,
            summary.inside,
            summary.prepare.seconds(),
            summary.query_seconds,
            summary.points_per_second / 1e6
        );
        Ok(())
    }
}

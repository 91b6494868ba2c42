//! `meshq raycast`: rays from a file, one hit record per ray.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::Result;
use clap::Args;
use meshq::MeshQuery;
use meshq::math::{Ray, RayHit, Vec3};
use meshq::query::RayOptions;
use serde::Serialize;

use crate::output::say;
use crate::records::{RecordReader, ResultWriter};
use crate::structure::{QueryInput, with_structure};
use crate::{output, progress};

/// Rays read and queried per chunk (24 MB of input).
const CHUNK: usize = 1 << 20;

#[derive(Args, Debug)]
pub struct RaycastArgs {
    #[command(flatten)]
    pub input: QueryInput,
    /// Rays: raw little-endian float32, 6 per ray (ox oy oz dx dy dz), no header.
    #[arg(long)]
    pub rays: PathBuf,
    /// Hits: per ray, float32 t (+inf for a miss) then uint32 triangle (0xFFFFFFFF for a miss).
    #[arg(long)]
    pub out: PathBuf,
    /// Any-hit (occlusion) queries: a hit is recorded as t = 0 and triangle 0 (any-hit says
    /// only that something is hit, not what).
    #[arg(long, conflicts_with = "hits")]
    pub any: bool,
    /// Record the nearest N hits of each ray (every triangle the ray crosses, once, nearest
    /// first; on equal t the lower triangle first): N records per ray, those past its last
    /// hit written as misses.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=4096))]
    pub hits: Option<u32>,
    /// Print the figures as one JSON object.
    #[arg(long)]
    pub json: bool,
}

#[derive(Serialize)]
struct Summary {
    rays: u64,
    hits: u64,
    build_seconds: f64,
    query_seconds: f64,
    rays_per_second: f64,
}

pub fn run(args: &RaycastArgs) -> Result<()> {
    let mut reader = RecordReader::open(&args.rays, 6, "ray")?;
    let mut inputs = args.input.paths();
    inputs.push(&args.rays);
    let mut writer = ResultWriter::create(&args.out, &inputs)?;
    let summary = with_structure(&args.input, |s| {
        let bar = progress::bar(reader.expected, "rays");
        let (mut floats, mut rays) = (Vec::new(), Vec::with_capacity(CHUNK));
        let mut results: Vec<(f32, u32)> = Vec::with_capacity(CHUNK);
        let (mut hits, mut query_seconds) = (0u64, 0.0f64);
        let per_ray = args.hits.map_or(1, |n| n as usize);
        let miss = RayHit {
            t: f32::INFINITY,
            tri: u32::MAX,
            u: 0.0,
            v: 0.0,
        };
        let mut nearest = vec![miss; per_ray];
        while reader.next_chunk(CHUNK, &mut floats)? > 0 {
            rays.clear();
            let (records, _) = floats.as_chunks::<6>();
            rays.extend(records.iter().map(|&[ox, oy, oz, dx, dy, dz]| {
                Ray::new(Vec3::new(ox, oy, oz), Vec3::new(dx, dy, dz))
            }));
            results.clear();
            let start = Instant::now();
            if args.hits.is_some() {
                for r in &rays {
                    let found = s.scene.raycast_all(r, &RayOptions::default(), &mut nearest);
                    let (written, _) = nearest.split_at(found.written);
                    results.extend(written.iter().map(|h| (h.t, h.tri)));
                    results.extend((found.written..per_ray).map(|_| (miss.t, miss.tri)));
                }
            } else if args.any {
                results.extend(rays.iter().map(|r| {
                    if s.scene.raycast_any(r) {
                        (0.0, 0)
                    } else {
                        (f32::INFINITY, u32::MAX)
                    }
                }));
            } else {
                results.extend(rays.iter().map(|r| {
                    s.scene
                        .raycast(r)
                        .map_or((f32::INFINITY, u32::MAX), |h| (h.t, h.tri))
                }));
            }
            query_seconds += start.elapsed().as_secs_f64();
            for &(t, tri) in &results {
                hits += u64::from(t.is_finite());
                writer.write(t, tri)?;
            }
            bar.inc(rays.len() as u64);
        }
        bar.finish_and_clear();
        Ok(Summary {
            rays: reader.count,
            hits,
            build_seconds: s.prepare_seconds,
            query_seconds,
            rays_per_second: per_second(reader.count, query_seconds),
        })
    })?;
    writer.finish()?;
    if args.json {
        output::json(&summary)
    } else {
        say!(
            "{} rays, {} hits ({}), prepared in {:.3} s, queries {:.3} s: {:.2} M rays/s",
            summary.rays,
            summary.hits,
            match (args.any, args.hits) {
                (true, _) => "any-hit".to_owned(),
                (false, Some(n)) => format!("nearest {n} per ray"),
                (false, None) => "closest hit".to_owned(),
            },
            summary.build_seconds,
            summary.query_seconds,
            summary.rays_per_second / 1e6
        );
        Ok(())
    }
}

/// Items per second, 0 when nothing was timed.
pub fn per_second(count: u64, seconds: f64) -> f64 {
    if seconds > 0.0 {
        count as f64 / seconds
    } else {
        0.0
    }
}

//! `meshq raycast`: rays from a file, one hit record per ray.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Result, bail};
use clap::builder::{PossibleValuesParser, TypedValueParser};
use clap::{Args, ValueEnum};
use meshq::math::{Ray, RayHit, Vec3};
use meshq::owned::MeshIndex;
use meshq::parallel;
use meshq::query::{MeshQuery, RayOptions, TriangleTest, sorts_ray_batch};
use rayon::prelude::*;
use serde::Serialize;

use crate::output::say;
use crate::records::{RecordReader, ResultWriter};
use crate::structure::{PrepareTime, QueryInput, with_structure};
use crate::threads::Threads;
use crate::{output, progress};

/// Rays read and queried per chunk (24 MB of input).
const CHUNK: usize = 1 << 20;

/// The triangle an any-hit record names: any-hit says only that something is hit, not what.
pub const ANY_HIT: u32 = 0xFFFF_FFFE;

/// What each hit record holds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum HitFormat {
    /// float32 t, uint32 triangle: 8 bytes.
    #[default]
    #[value(name = "t-tri")]
    TTri,
    /// float32 t, uint32 triangle, float32 u, v (barycentric weights of the second and third
    /// corners): 16 bytes.
    #[value(name = "t-tri-uv")]
    TTriUv,
    /// t, triangle, u, v, then the hit point x, y, z (float32): 28 bytes.
    Full,
}

#[derive(Args, Debug)]
#[command(after_help = "Examples:\n  \
    meshq workload assets/stanford-bunny.obj -o rays.bin\n  \
    meshq raycast bunny.meshq --rays rays.bin --out hits.bin --json\n  \
    meshq raycast assets/spot.obj --rays rays.bin --out hits.bin --format full --hits 4\n  \
    meshq raycast bunny.meshq --rays rays.bin --out hits.bin --threads 0 --json")]
pub struct RaycastArgs {
    #[command(flatten)]
    pub input: QueryInput,
    /// Rays: raw little-endian float32, 6 per ray (ox oy oz dx dy dz), no header.
    #[arg(long)]
    pub rays: PathBuf,
    /// Hits: per ray, one record as --format says; a miss has t = +inf and triangle
    /// 0xFFFFFFFF (u, v and the point NaN).
    #[arg(long)]
    pub out: PathBuf,
    /// What each record holds (little-endian).
    #[arg(long, value_enum, default_value_t = HitFormat::TTri)]
    pub format: HitFormat,
    /// Any-hit (occlusion) queries: a hit is recorded as t = 0 and triangle 0xFFFFFFFE (any-hit
    /// says only that something is hit, not what); records are t-tri only.
    #[arg(long, conflicts_with = "hits")]
    pub any: bool,
    /// Record the nearest N hits of each ray (every triangle the ray crosses, once, nearest
    /// first; on equal t the lower triangle first): N records per ray, those past its last
    /// hit written as misses.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=4096))]
    pub hits: Option<u32>,
    /// The ray–triangle test: watertight (no ray slips through a closed mesh), Möller–Trumbore
    /// or two-step (the plane, then barycentric coordinates); they differ only at edges shared
    /// by two triangles.
    #[arg(long, value_name = "TEST", default_value = "watertight", value_parser = triangle_test())]
    pub triangle_test: TriangleTest,
    /// Answer one ray per call instead of in batches (Morton order of the origins, packets
    /// of rays sharing an origin): the same records; for comparing with one-ray-per-call APIs.
    #[arg(long)]
    pub per_ray: bool,
    /// Print the figures as one JSON object.
    #[arg(long)]
    pub json: bool,
}

impl RaycastArgs {
    /// The ray options the arguments ask for.
    fn options(&self) -> RayOptions {
        RayOptions {
            test: self.triangle_test,
            ..RayOptions::default()
        }
    }
}

#[derive(Serialize)]
struct Summary {
    rays: u64,
    /// Hit records written (rays that hit, or with --hits every hit recorded).
    hits: u64,
    #[serde(flatten)]
    prepare: PrepareTime,
    /// Threads that answered (`--threads`).
    threads: usize,
    /// The queries alone, on those threads.
    query_seconds: f64,
    rays_per_second: f64,
}

/// Parses a `--triangle-test` name, listing the names in the help.
fn triangle_test() -> impl TypedValueParser<Value = TriangleTest> {
    PossibleValuesParser::new(TriangleTest::ALL.map(TriangleTest::name))
        .try_map(|name: String| TriangleTest::from_name(&name).ok_or("an unknown triangle test"))
}

/// A miss, as records write it.
const MISS: RayHit = RayHit {
    t: f32::INFINITY,
    tri: u32::MAX,
    u: f32::NAN,
    v: f32::NAN,
};

/// Writes `hit` of `ray` as `format` says.
fn write_record(
    writer: &mut ResultWriter,
    format: HitFormat,
    ray: &Ray,
    hit: &RayHit,
) -> Result<()> {
    writer.write(hit.t, hit.tri)?;
    if format != HitFormat::TTri {
        writer.write_f32s(&[hit.u, hit.v])?;
    }
    if format == HitFormat::Full {
        let p = if hit.t.is_finite() {
            ray.at(hit.t)
        } else {
            Vec3::NAN
        };
        writer.write_f32s(&p.to_array())?;
    }
    Ok(())
}

/// The record of an any-hit answer.
fn any_record(hit: bool) -> RayHit {
    if hit {
        RayHit {
            t: 0.0,
            tri: ANY_HIT,
            ..MISS
        }
    } else {
        MISS
    }
}

/// Scratch of the batch calls on this thread.
#[derive(Default)]
struct Scratch {
    keys: Vec<u64>,
    answers: Vec<Option<RayHit>>,
    flags: Vec<bool>,
}

impl Scratch {
    /// Sizes every buffer for calls of `len` rays. Growing one writes its new elements, so
    /// that its pages are mapped here, not in the first batch call that writes them.
    fn prepare(&mut self, len: usize) {
        self.keys.resize(len, 0);
        self.answers.resize(len, None);
        self.flags.resize(len, false);
    }
}

/// Rays per batch call of [`query_here`]: batches of [`BATCH`] rays, whose scratch stays
/// small and in cache, or the whole chunk when the core sorts it.
fn rays_per_call(scene: &MeshIndex, rays: &[Ray]) -> usize {
    if sorts_ray_batch(scene, rays) {
        rays.len().max(1)
    } else {
        BATCH
    }
}

/// Answers `rays` on this thread — in batches, or one query per call with `--per-ray` (every
/// hit queries always go one per call) — appending each ray's records.
fn query_here(
    scene: &MeshIndex,
    rays: &[Ray],
    args: &RaycastArgs,
    nearest: &mut [RayHit],
    scratch: &mut Scratch,
    results: &mut Vec<RayHit>,
) -> Result<()> {
    let options = args.options();
    if args.hits.is_some() {
        for r in rays {
            let found = scene.raycast_all(r, &options, nearest);
            let (written, _) = nearest.split_at(found.written);
            results.extend_from_slice(written);
            results.extend((found.written..nearest.len()).map(|_| MISS));
        }
    } else if args.any && args.per_ray {
        results.extend(
            rays.iter()
                .map(|r| any_record(scene.raycast_any_with(r, &options))),
        );
    } else if args.per_ray {
        results.extend(
            rays.iter()
                .map(|r| scene.raycast_with(r, &options).unwrap_or(MISS)),
        );
    } else {
        let per_call = rays_per_call(scene, rays);
        scratch.prepare(per_call.min(rays.len()));
        for batch in rays.chunks(per_call) {
            let keys = &mut scratch.keys[..batch.len()];
            if args.any {
                let flags = &mut scratch.flags[..batch.len()];
                scene.raycast_any_batch(batch, &options, keys, flags)?;
                results.extend(flags.iter().map(|&f| any_record(f)));
            } else {
                let answers = &mut scratch.answers[..batch.len()];
                scene.raycast_batch(batch, &options, keys, answers)?;
                results.extend(answers.iter().map(|a| a.unwrap_or(MISS)));
            }
        }
    }
    Ok(())
}

/// Rays per batch call on one thread, unless the core sorts the chunk's rays
/// (`meshq::query::sorts_ray_batch`: many rays on a large mesh), which needs them in one call.
const BATCH: usize = 1 << 14;

/// Answers `rays` on the current rayon pool (`meshq::parallel` batches, or one every-hit
/// query per ray), appending the same records as [`query_here`].
fn query_on_threads(
    scene: &MeshIndex,
    rays: &[Ray],
    args: &RaycastArgs,
    per_ray: usize,
    answers: &mut Vec<Option<RayHit>>,
    results: &mut Vec<RayHit>,
) -> Result<()> {
    let options = args.options();
    if args.hits.is_some() {
        let records: Vec<RayHit> = rays
            .par_iter()
            .map_init(
                || vec![MISS; per_ray],
                |nearest, r| {
                    let found = scene.raycast_all(r, &options, nearest);
                    let mut out = nearest.clone();
                    out.iter_mut().skip(found.written).for_each(|h| *h = MISS);
                    out
                },
            )
            .flatten_iter()
            .collect();
        results.extend(records);
    } else if args.any {
        let mut flags = Vec::new();
        flags.par_extend(rayon::iter::repeat_n(false, rays.len()));
        parallel::raycast_any_batch(scene, rays, &options, &mut flags)?;
        results.par_extend(flags.par_iter().map(|&f| any_record(f)));
    } else {
        // Filled and converted on the pool as well: on a chunk's first pass this memory is
        // fresh, and one thread faulting it in held a 1M-ray chunk's two threads back by
        // about a tenth.
        answers.clear();
        answers.par_extend(rayon::iter::repeat_n(None, rays.len()));
        parallel::raycast_batch(scene, rays, &options, answers)?;
        results.par_extend(answers.par_iter().map(|a| a.unwrap_or(MISS)));
    }
    Ok(())
}

pub fn run(args: &RaycastArgs) -> Result<()> {
    if args.any && args.format != HitFormat::TTri {
        bail!("--any records only that something is hit: use --format t-tri");
    }
    let threads = Threads::new(args.input.threads)?;
    let mut reader = RecordReader::open(&args.rays, 6, "ray")?;
    let mut inputs = args.input.paths();
    inputs.push(&args.rays);
    let mut writer = ResultWriter::create(&args.out, &inputs)?;
    let mut verb = "";
    let summary = with_structure(&args.input, |s| {
        verb = s.verb();
        let bar = progress::bar(reader.expected, "rays");
        // Per ray, its records (one, or N with --hits); rays are read in chunks of at most
        // CHUNK records, so memory stays the same whatever N is.
        let per_ray = args.hits.map_or(1, |n| n as usize);
        let chunk = (CHUNK / per_ray).max(1);
        let (mut floats, mut rays) = (Vec::new(), Vec::with_capacity(chunk));
        let mut results: Vec<RayHit> = Vec::with_capacity(CHUNK);
        let (mut hits, mut query_seconds) = (0u64, 0.0f64);
        let mut nearest = vec![MISS; per_ray];
        let mut answers = Vec::new();
        let mut scratch = Scratch::default();
        while reader.next_chunk(chunk, &mut floats)? > 0 {
            rays.clear();
            let (records, _) = floats.as_chunks::<6>();
            rays.extend(records.iter().map(|&[ox, oy, oz, dx, dy, dz]| {
                Ray::new(Vec3::new(ox, oy, oz), Vec3::new(dx, dy, dz))
            }));
            // The buffers the queries write on this thread are sized, and so written, before
            // the clock starts: the first write to fresh memory faults its page in (a
            // 1M-ray chunk's records are 4,096 pages of 4 KiB), the kernel's work, not the
            // queries'. (Threads fill theirs on the pool: see `query_on_threads`.)
            results.clear();
            results.resize(rays.len() * per_ray, MISS);
            results.clear();
            if threads.pool().is_none() && !args.per_ray && args.hits.is_none() {
                scratch.prepare(rays_per_call(&s.scene, &rays).min(rays.len()));
            }
            let start = Instant::now();
            match threads.pool() {
                None => query_here(
                    &s.scene,
                    &rays,
                    args,
                    &mut nearest,
                    &mut scratch,
                    &mut results,
                )?,
                Some(pool) => pool.install(|| {
                    query_on_threads(&s.scene, &rays, args, per_ray, &mut answers, &mut results)
                })?,
            }
            query_seconds += start.elapsed().as_secs_f64();
            for (i, hit) in results.iter().enumerate() {
                hits += u64::from(hit.t.is_finite());
                if let Some(ray) = rays.get(i / per_ray) {
                    write_record(&mut writer, args.format, ray, hit)?;
                }
            }
            bar.inc(rays.len() as u64);
        }
        bar.finish_and_clear();
        Ok(Summary {
            rays: reader.count,
            hits,
            prepare: s.time(),
            threads: threads.count(),
            query_seconds,
            rays_per_second: per_second(reader.count, query_seconds),
        })
    })?;
    writer.finish()?;
    if args.json {
        output::json(&summary)
    } else {
        say!(
            "{} rays, {} hits ({}), {verb} {:.3} s, queries {:.3} s: {:.2} M rays/s",
            summary.rays,
            summary.hits,
            match (args.any, args.hits) {
                (true, _) => "any-hit".to_owned(),
                (false, Some(n)) => format!("nearest {n} per ray"),
                (false, None) => "closest hit".to_owned(),
            },
            summary.prepare.seconds(),
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

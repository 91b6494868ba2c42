//! `meshq closest`: points from a file, one closest-point record per point.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::Result;
use clap::Args;
use meshq::inside::WindingAccuracy;
use meshq::math::Vec3;
use meshq::owned::MeshPseudoNormals;
use meshq::query::MeshQuery;
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

/// What `--signed` takes the sign from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Sign {
    /// The generalized winding number: inside when |w| ≥ 1/2.
    Winding,
    /// The angle-weighted pseudo-normal at the closest point (Bærentzen and Aanæs).
    PseudoNormal,
}

/// A distance limit: a number ≥ 0 (`inf` allowed).
fn non_negative(text: &str) -> Result<f32, String> {
    match text.parse::<f32>() {
        Ok(d) if d >= 0.0 => Ok(d),
        _ => Err(format!("expected a distance ≥ 0, got {text:?}")),
    }
}

#[derive(Args, Debug)]
#[command(after_help = "Examples:\n  \
    meshq workload assets/spot.obj --kind points -o points.bin\n  \
    meshq closest assets/spot.obj --points points.bin --out closest.bin --max-distance 0.05 --json\n  \
    meshq closest assets/spot.obj --points points.bin --out closest.bin --threads 2")]
pub struct ClosestArgs {
    #[command(flatten)]
    pub input: QueryInput,
    /// Points: raw little-endian float32, 3 per point (x y z), no header.
    #[arg(long)]
    pub points: PathBuf,
    /// Results: per point, float32 distance then uint32 triangle (+inf and 0xFFFFFFFF when
    /// nothing lies within --max-distance, the mesh is empty or the point is not finite); with
    /// --signed the distance is negative inside.
    #[arg(long)]
    pub out: PathBuf,
    /// Only surface points within this distance (inclusive) count; default: no limit.
    #[arg(long, value_name = "D", value_parser = non_negative)]
    pub max_distance: Option<f32>,
    /// Signed distances: negative inside, told by the generalized winding number (so open,
    /// non-manifold and self-intersecting meshes have an inside too).
    #[arg(long)]
    pub signed: bool,
    #[arg(long, value_name = "RATIO", default_value = "2", value_parser = accuracy_parser,
          requires = "signed", help = ACCURACY_HELP)]
    pub accuracy: WindingAccuracy,
    /// How --signed tells inside: by the generalized winding number (any mesh), or by the
    /// angle-weighted pseudo-normal at the closest point (closed, manifold, consistently
    /// oriented meshes only, refused otherwise naming an edge; no winding numbers computed).
    #[arg(long, value_enum, default_value_t = Sign::Winding, requires = "signed")]
    pub sign: Sign,
    /// Print the figures as one JSON object.
    #[arg(long)]
    pub json: bool,
}

#[derive(Serialize)]
struct Summary {
    points: u64,
    /// Points with a surface point within the limit.
    found: u64,
    /// Of those, points inside (with --signed).
    #[serde(skip_serializing_if = "Option::is_none")]
    inside: Option<u64>,
    #[serde(flatten)]
    prepare: PrepareTime,
    /// Threads that answered (`--threads`).
    threads: usize,
    /// The queries alone, on those threads.
    query_seconds: f64,
    points_per_second: f64,
}

pub fn run(args: &ClosestArgs) -> Result<()> {
    let threads = Threads::new(args.input.threads)?;
    let mut reader = RecordReader::open(&args.points, 3, "point")?;
    let mut inputs = args.input.paths();
    inputs.push(&args.points);
    let mut writer = ResultWriter::create(&args.out, &inputs)?;
    let limit = args.max_distance.unwrap_or(f32::INFINITY);
    let mut verb = "";
    let summary = with_structure(&args.input, |mut s| {
        let by_winding = args.signed && args.sign == Sign::Winding;
        let built = if by_winding {
            winding::prepare(&mut s)?
        } else {
            None
        };
        let tree = if by_winding {
            Some(winding::tree(&s, &built)?)
        } else {
            None
        };
        let mesh = s.scene.mesh();
        let pseudo = if args.signed && args.sign == Sign::PseudoNormal {
            let normals = MeshPseudoNormals::of(&mesh).map_err(|e| {
                anyhow::anyhow!("{}: --sign pseudo-normal: {e}", args.input.input.display())
            })?;
            Some(normals)
        } else {
            None
        };
        verb = s.verb();
        let bar = progress::bar(reader.expected, "points");
        let mut floats = Vec::new();
        let (mut points, mut keys, mut results) = (Vec::new(), Vec::new(), Vec::new());
        let (mut near, mut numbers) = (Vec::new(), Vec::new());
        let (mut query_seconds, mut found_count, mut inside) = (0.0f64, 0u64, 0u64);
        while reader.next_chunk(CHUNK, &mut floats)? > 0 {
            let (records, _) = floats.as_chunks::<3>();
            points.clear();
            points.extend(records.iter().map(|&p| Vec3::from_array(p)));
            keys.resize(points.len(), 0u64);
            results.resize(points.len(), None);
            let start = Instant::now();
            // One batch per chunk: answered in Morton order with seeded searches, with the same
            // answers as one call per point (and the same on any number of threads).
            match threads.pool() {
                None => s
                    .scene
                    .closest_points(&points, limit, &mut keys, &mut results)?,
                Some(pool) => pool.install(|| {
                    meshq::parallel::closest_points(&s.scene, &points, limit, &mut results)
                })?,
            }
            if let Some(tree) = &tree {
                // The sign: the winding numbers of the points a surface point was found for.
                near.clear();
                near.extend(
                    results[..points.len()]
                        .iter()
                        .zip(&points)
                        .filter_map(|(c, &p)| c.map(|_| p)),
                );
                numbers.resize(near.len(), 0.0f32);
                keys.resize(near.len().max(points.len()), 0u64);
                match threads.pool() {
                    None => tree.winding_numbers(&near, args.accuracy, &mut keys, &mut numbers)?,
                    Some(pool) => pool.install(|| {
                        meshq::parallel::winding_numbers(tree, &near, args.accuracy, &mut numbers)
                    })?,
                }
            }
            query_seconds += start.elapsed().as_secs_f64();
            let mut signs = numbers[..near.len()].iter();
            for (found, &p) in results[..points.len()].iter().zip(&points) {
                found_count += u64::from(found.is_some());
                let (d, tri) =
                    found.map_or((f32::INFINITY, u32::MAX), |c| (c.distance_from(p), c.tri));
                // As WindingTree::signed_distance (inside when |w| ≥ 1/2) or
                // PseudoNormals::signed_distance.
                let is_inside = match (found, &pseudo) {
                    (Some(c), Some(normals)) => {
                        normals.view().inside_at(&mesh, p, c).unwrap_or(false)
                    }
                    (Some(_), None) if args.signed => signs.next().is_some_and(|w| w.abs() >= 0.5),
                    _ => false,
                };
                inside += u64::from(is_inside);
                writer.write(if is_inside { -d } else { d }, tri)?;
            }
            bar.inc(points.len() as u64);
        }
        bar.finish_and_clear();
        Ok(Summary {
            points: reader.count,
            found: found_count,
            inside: args.signed.then_some(inside),
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
            "{} points, {} found, {verb} {:.3} s, queries {:.3} s: {:.2} M points/s",
            summary.points,
            summary.found,
            summary.prepare.seconds(),
            summary.query_seconds,
            summary.points_per_second / 1e6
        );
        Ok(())
    }
}

//! `meshq distance`: how far apart two meshes are, and where.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Result, bail};
use clap::Args;
use meshq::Traverse;
use meshq::collide::{DistanceLimits, PairBudget, mesh_distance};
use serde::Serialize;

use crate::check::{bvh_of, load, parse_transform};
use crate::output;
use crate::output::say;

#[derive(Args, Debug)]
#[command(after_help = "Examples:\n  \
    meshq distance assets/spot.obj assets/spot.obj --transform 1,0,0,0,0,1,0,0,0,0,1,0,1.2,0,0,1\n  \
    meshq distance part.obj fixture.obj --max-distance 0.5 --json")]
pub struct DistanceArgs {
    /// The first mesh: OBJ, PLY or STL. Points and distances are in its frame.
    pub mesh: PathBuf,
    /// The second mesh.
    pub other: PathBuf,
    /// Where the second mesh sits in the first one's frame: a 4×4 matrix of 16 numbers in
    /// column-major order (three.js `Matrix4.elements`), separated by commas or spaces;
    /// bottom row 0 0 0 1. Default: the identity.
    #[arg(long)]
    pub transform: Option<String>,
    /// Look no farther than this (in the first mesh's units): when the meshes are farther
    /// apart, say so instead of finding the closest pair, which is much faster. Default: no
    /// limit.
    #[arg(long, value_name = "D")]
    pub max_distance: Option<f32>,
    /// Stop at the first pair found this close or closer, though a closer one may exist.
    /// Default: 0, stopping only where the meshes meet.
    #[arg(long, value_name = "D", default_value_t = 0.0)]
    pub stop_at: f32,
    /// The most triangle pairs the search may test before it stops with an error. Default:
    /// 2^20 + 256 per triangle of the two meshes, far above what well-shaped meshes need.
    #[arg(long, value_name = "N")]
    pub max_pair_tests: Option<usize>,
    /// Print the result as one JSON object.
    #[arg(long)]
    pub json: bool,
}

/// The closest pair, as printed.
#[derive(Serialize)]
struct Pair {
    /// The distance in the first mesh's units: 0 when the meshes meet.
    distance: f32,
    /// The first mesh's point and triangle.
    point_a: [f32; 3],
    triangle_a: u32,
    /// The second mesh's point (in the first mesh's frame) and triangle.
    point_b: [f32; 3],
    triangle_b: u32,
}

#[derive(Serialize)]
struct Report {
    mesh: String,
    triangles: usize,
    other: String,
    other_triangles: usize,
    /// Whether the meshes meet (touching counts).
    meets: bool,
    /// The closest pair; `null` when none is within `--max-distance`.
    closest: Option<Pair>,
    /// Building both BVHs (file reading excluded).
    build_seconds: f64,
    /// The search alone.
    query_seconds: f64,
}

pub fn run(args: &DistanceArgs) -> Result<()> {
    let limits = DistanceLimits {
        max_distance: args.max_distance.unwrap_or(f32::INFINITY),
        stop_at: args.stop_at,
    };
    if !(limits.max_distance >= 0.0) {
        bail!("--max-distance must be a number ≥ 0");
    }
    if !(limits.stop_at >= 0.0) {
        bail!("--stop-at must be a number ≥ 0");
    }
    let place = args.transform.as_deref().map(parse_transform).transpose()?;
    let (data, name) = load(&args.mesh)?;
    let (other_data, other_name) = load(&args.other)?;
    let start = Instant::now();
    let (a, b) = (bvh_of(&data, &name)?, bvh_of(&other_data, &other_name)?);
    let build_seconds = start.elapsed().as_secs_f64();
    let (na, nb) = (a.mesh().triangle_count(), b.mesh().triangle_count());
    for (count, mesh) in [(na, &name), (nb, &other_name)] {
        if count == 0 {
            bail!("{mesh} has no triangles: there is nothing to measure");
        }
    }
    let budget = args.max_pair_tests.map_or_else(
        || PairBudget::for_triangles(na, nb),
        |max_tests| PairBudget { max_tests },
    );
    let (ta, tb, pa, pb) = (a.bvh(), b.bvh(), a.packed(), b.packed());
    let start = Instant::now();
    let found = mesh_distance(ta.with(&pa), tb.with(&pb), place.as_ref(), limits, budget).map_err(
        |spent| anyhow::anyhow!("{name} against {other_name}: {spent} (--max-pair-tests)"),
    )?;
    let query_seconds = start.elapsed().as_secs_f64();
    let report = Report {
        mesh: name,
        triangles: na,
        other: other_name,
        other_triangles: nb,
        meets: found.is_some_and(|f| f.distance == 0.0),
        closest: found.map(|f| Pair {
            distance: f.distance,
            point_a: f.on_a.to_array(),
            triangle_a: f.triangle_a,
            point_b: f.on_b.to_array(),
            triangle_b: f.triangle_b,
        }),
        build_seconds,
        query_seconds,
    };
    if args.json {
        return output::json(&report);
    }
    let point = |p: [f32; 3]| format!("({}, {}, {})", p[0], p[1], p[2]);
    match &report.closest {
        None => say!(
            "{} and {}: farther apart than {}",
            report.mesh,
            report.other,
            limits.max_distance
        ),
        Some(c) if report.meets => say!(
            "{} and {} meet: triangle {} of the first and {} of the second at {}",
            report.mesh,
            report.other,
            c.triangle_a,
            c.triangle_b,
            point(c.point_a)
        ),
        Some(c) => say!(
            "{} and {}: distance {}, from {} on triangle {} to {} on triangle {}",
            report.mesh,
            report.other,
            c.distance,
            point(c.point_a),
            c.triangle_a,
            point(c.point_b),
            c.triangle_b
        ),
    }
    say!(
        "  built in {:.3} s, searched in {:.6} s",
        report.build_seconds,
        report.query_seconds
    );
    Ok(())
}

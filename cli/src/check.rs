//! `meshq check`: where a mesh meets itself, and where it meets another mesh.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result, bail};
use clap::Args;
use meshq::Traverse;
use meshq::bvh::BuildConfig;
use meshq::collide::{
    Affine, Found, PairBudget, TrianglePair, intersecting_pairs, intersection_segments,
    self_intersecting_pairs,
};
use meshq::error::PairBudgetSpent;
use meshq::mesh::MeshRef;
use meshq::owned::MeshBvh;
use serde::Serialize;

use crate::mesh_file::read_mesh;
use crate::output;
use crate::output::say;

#[derive(Args, Debug)]
#[command(after_help = "Examples:\n  \
    meshq check assets/spot.obj\n  \
    meshq check a.obj --against b.obj --transform 1,0,0,0,0,1,0,0,0,0,1,0,0.2,0,0,1 --json")]
pub struct CheckArgs {
    /// The mesh: OBJ, PLY or STL.
    pub mesh: PathBuf,
    /// A second mesh to test against the first.
    #[arg(long)]
    pub against: Option<PathBuf>,
    /// Where the second mesh sits in the first one's frame: a 4×4 matrix of 16 numbers in
    /// column-major order (three.js `Matrix4.elements`), separated by commas or spaces;
    /// bottom row 0 0 0 1. Default: the identity.
    #[arg(long, requires = "against")]
    pub transform: Option<String>,
    /// How many intersecting pairs to list.
    #[arg(long, default_value_t = 10)]
    pub first: usize,
    /// The most triangle pairs each check may test before it stops with an error. Default:
    /// 2^20 + 256 per triangle of the meshes checked, far above what well-shaped meshes need;
    /// meshes whose triangles pile up in one place (copies, zero-area triangles) need more.
    #[arg(long, value_name = "N")]
    pub max_pair_tests: Option<usize>,
    /// Print the result as one JSON object.
    #[arg(long)]
    pub json: bool,
}

/// What the command found, as printed.
#[derive(Serialize)]
struct Report {
    mesh: String,
    triangles: usize,
    /// Pairs of the mesh's triangles that meet beyond the corners or edge they share.
    self_intersecting_pairs: usize,
    /// The first of them, as triangle index pairs (lower index first).
    self_first_pairs: Vec<[u32; 2]>,
    /// Triangle pairs the self-check tested (the rest were ruled out by boxes).
    self_pairs_tested: usize,
    /// Triangles of zero area (corners in a line or at one point): they meet nothing, so
    /// the checks pass over them.
    degenerate_triangles: usize,
    #[serde(skip_serializing_if = "Option::is_none")]
    against: Option<Against>,
    /// Time of the checks, BVH builds included, file reading not.
    check_seconds: f64,
}

#[derive(Serialize)]
struct Against {
    mesh: String,
    triangles: usize,
    /// Pairs (triangle of the first mesh, triangle of the second) that meet.
    intersecting_pairs: usize,
    /// Of those, pairs whose planes cross (each has an intersection segment).
    crossing_pairs: usize,
    first_pairs: Vec<[u32; 2]>,
    /// Triangle pairs tested.
    pairs_tested: usize,
}

/// Reads `path` as a valid mesh and builds its BVH.
pub(crate) fn load(path: &Path) -> Result<(crate::mesh_file::MeshData, String)> {
    let data = read_mesh(path)?;
    MeshRef::new(&data.positions, &data.triangles)
        .validate()
        .with_context(|| format!("{}: invalid mesh", path.display()))?;
    Ok((data, path.display().to_string()))
}

pub(crate) fn bvh_of(data: &crate::mesh_file::MeshData, name: &str) -> Result<MeshBvh> {
    let mesh = MeshRef::new(&data.positions, &data.triangles)
        .validate()
        .with_context(|| format!("{name}: invalid mesh"))?;
    MeshBvh::build(&mesh, &BuildConfig::default())
        .with_context(|| format!("{name}: cannot build its BVH"))
}

/// Parses the `--transform` text: 16 finite numbers, an affine matrix.
pub(crate) fn parse_transform(text: &str) -> Result<Affine> {
    let numbers: Vec<f32> = text
        .split(|c: char| c == ',' || c.is_whitespace())
        .filter(|s| !s.is_empty())
        .map(|s| {
            s.parse::<f32>()
                .with_context(|| format!("--transform: `{s}` is not a number"))
        })
        .collect::<Result<_>>()?;
    let Ok(matrix) = <[f32; 16]>::try_from(numbers.as_slice()) else {
        bail!("--transform needs 16 numbers, got {}", numbers.len());
    };
    Affine::from_cols_4x4(&matrix).map_err(|e| anyhow::anyhow!("--transform: {e}"))
}

/// Runs `query` to count the pairs, then, when there are any, again into a buffer of the
/// first `wanted` of them (never larger than the count, so a huge `--first` allocates
/// nothing more). A spent budget is an error naming the check, the mesh and the flag.
fn first_pairs(
    wanted: usize,
    what: &str,
    query: impl Fn(&mut [TrianglePair]) -> Result<Found, PairBudgetSpent>,
) -> Result<(Found, Vec<TrianglePair>)> {
    let counted = within_budget(what, query(&mut []))?;
    if counted.total == 0 || wanted == 0 {
        return Ok((counted, Vec::new()));
    }
    let mut first = vec![TrianglePair::default(); wanted.min(counted.total)];
    let found = within_budget(what, query(&mut first))?;
    first.truncate(found.written);
    Ok((found, first))
}

/// The found pairs, or an error saying which check ran out and how to give it more.
fn within_budget(what: &str, found: Result<Found, PairBudgetSpent>) -> Result<Found> {
    found.map_err(|spent| anyhow::anyhow!("{what}: {spent} (--max-pair-tests)"))
}

/// The budget for a check over meshes of `a` and `b` triangles: `--max-pair-tests` or the
/// default that scales with them.
fn budget(args: &CheckArgs, a: usize, b: usize) -> PairBudget {
    args.max_pair_tests.map_or_else(
        || PairBudget::for_triangles(a, b),
        |max_tests| PairBudget { max_tests },
    )
}

fn as_pairs(pairs: &[TrianglePair]) -> Vec<[u32; 2]> {
    pairs.iter().map(|p| [p.a, p.b]).collect()
}

pub fn run(args: &CheckArgs) -> Result<()> {
    let place = args.transform.as_deref().map(parse_transform).transpose()?;
    let (data, name) = load(&args.mesh)?;
    let other = args.against.as_deref().map(load).transpose()?;
    let start = Instant::now();
    let bvh = bvh_of(&data, &name)?;
    let (mesh, tree) = (bvh.mesh(), bvh.bvh());
    let n = mesh.triangle_count();
    let degenerate_triangles = (0..n)
        .filter_map(|t| mesh.triangle(t as u32))
        .filter(|t| t.is_degenerate())
        .count();
    // Zero-area triangles are the usual reason for a spent budget: the error says how many.
    let described = if degenerate_triangles > 0 {
        format!("{name} ({degenerate_triangles} of {n} triangles have zero area)")
    } else {
        name.clone()
    };
    let self_budget = budget(args, n, n);
    let what = format!("{described}: self-intersection check");
    let (found, first) = first_pairs(args.first, &what, |out| {
        self_intersecting_pairs(&tree, &mesh, self_budget, out)
    })?;
    let self_first_pairs = as_pairs(&first);
    let against = match &other {
        None => None,
        Some((other_data, other_name)) => {
            let other_bvh = bvh_of(other_data, other_name)?;
            let (other_mesh, other_tree) = (other_bvh.mesh(), other_bvh.bvh());
            let (a, b) = (tree.with(&mesh), other_tree.with(&other_mesh));
            let pair_budget = budget(args, n, other_mesh.triangle_count());
            let what = format!("{described} against {other_name}");
            let (pairs, first) = first_pairs(args.first, &what, |out| {
                intersecting_pairs(a, b, place.as_ref(), pair_budget, out)
            })?;
            let crossing = within_budget(
                &what,
                intersection_segments(a, b, place.as_ref(), pair_budget, &mut []),
            )?;
            Some(Against {
                mesh: other_name.clone(),
                triangles: other_mesh.triangle_count(),
                intersecting_pairs: pairs.total,
                crossing_pairs: crossing.total,
                first_pairs: as_pairs(&first),
                pairs_tested: pairs.tested,
            })
        }
    };
    let report = Report {
        mesh: name,
        triangles: mesh.triangle_count(),
        self_intersecting_pairs: found.total,
        self_first_pairs,
        self_pairs_tested: found.tested,
        degenerate_triangles,
        against,
        check_seconds: start.elapsed().as_secs_f64(),
    };
    if args.json {
        return output::json(&report);
    }
    print_report(&report)
}

fn print_report(r: &Report) -> Result<()> {
    let list = |pairs: &[[u32; 2]], total: usize| {
        let shown: Vec<String> = pairs.iter().map(|[a, b]| format!("{a}–{b}")).collect();
        let more = total.saturating_sub(pairs.len());
        if more > 0 {
            format!("{} and {more} more", shown.join(", "))
        } else {
            shown.join(", ")
        }
    };
    say!("{}: {} triangles", r.mesh, r.triangles);
    if r.degenerate_triangles > 0 {
        say!(
            "  {} degenerate (zero-area) triangles, which meet nothing",
            r.degenerate_triangles
        );
    }
    if r.self_intersecting_pairs == 0 {
        say!("  no self-intersections");
    } else {
        say!(
            "  {} self-intersecting triangle pairs: {}",
            r.self_intersecting_pairs,
            list(&r.self_first_pairs, r.self_intersecting_pairs)
        );
    }
    if let Some(a) = &r.against {
        say!("against {}: {} triangles", a.mesh, a.triangles);
        if a.intersecting_pairs == 0 {
            say!("  the meshes do not meet");
        } else {
            say!(
                "  {} intersecting triangle pairs ({} crossing, {} coplanar): {}",
                a.intersecting_pairs,
                a.crossing_pairs,
                a.intersecting_pairs - a.crossing_pairs,
                list(&a.first_pairs, a.intersecting_pairs)
            );
        }
    }
    say!("  {:.3} s", r.check_seconds);
    Ok(())
}

//! `meshq remesh`: isotropic remeshing of a mesh file, with quality figures before and after.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Context, Result};
use clap::Args;
use meshq::collide::PairBudget;
use meshq::mesh::MeshRef;
use meshq::owned::Remeshed;
use meshq::remesh::{EdgeTarget, MeshQuality, RemeshConfig};
use serde::Serialize;

use crate::mesh_file::read_mesh;
use crate::mesh_write::write_mesh;
use crate::output::say;
use crate::{output, progress};

#[derive(Args, Debug)]
#[command(after_help = "Examples:\n  \
    meshq remesh assets/spot.obj -o spot-remeshed.ply\n  \
    meshq remesh assets/fandisk.obj -o fandisk.obj --target-ratio 0.8 --feature-angle 45 --json")]
pub struct RemeshArgs {
    /// The mesh: OBJ, PLY or STL; it must be manifold and consistently oriented.
    pub mesh: PathBuf,
    /// Where to write the result: `.obj` or `.ply`.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Target edge length, in the mesh's units (default: the input's mean edge length).
    #[arg(long, conflicts_with = "target_ratio")]
    pub target_length: Option<f32>,
    /// Target edge length as a multiple of the input's mean edge length.
    #[arg(long)]
    pub target_ratio: Option<f32>,
    /// Iterations of split, collapse, flip, smooth and project.
    #[arg(long, default_value_t = 10)]
    pub iterations: u32,
    /// Keep creases sharper than this dihedral angle, in degrees.
    #[arg(long)]
    pub feature_angle: Option<f32>,
    /// The most point–triangle tests the distance report may make (default: 2^20 + 256 per
    /// triangle of the input and the result). Past it, the distance is the largest of the
    /// samples measured so far; 0 skips the report (and the trees it builds).
    #[arg(long, value_name = "N")]
    pub max_distance_tests: Option<usize>,
    /// Print the figures as one JSON object.
    #[arg(long)]
    pub json: bool,
}

/// Quality figures of one mesh, as printed.
#[derive(Serialize)]
struct Figures {
    triangles: usize,
    vertices: usize,
    valence_6_percent: f32,
    min_angle_off_boundary_degrees: f32,
    triangles_under_30_degrees_percent: f32,
    mean_edge: f32,
    edge_length_cv: f32,
}

impl From<MeshQuality> for Figures {
    fn from(q: MeshQuality) -> Self {
        Self {
            triangles: q.triangles,
            vertices: q.vertices,
            valence_6_percent: q.valence_6_percent,
            min_angle_off_boundary_degrees: q.min_angle_off_boundary,
            triangles_under_30_degrees_percent: q.under_30_percent,
            mean_edge: q.mean_edge,
            edge_length_cv: q.edge_cv,
        }
    }
}

#[derive(Serialize)]
struct Summary {
    target_length: f32,
    iterations: u32,
    splits: usize,
    collapses: usize,
    flips: usize,
    creases: usize,
    /// Vertices moved after the iterations to widen small angles.
    relaxed: usize,
    /// The most vertices and triangles held at once: buffers this large repeat the run.
    peak_vertices: usize,
    peak_triangles: usize,
    before: Figures,
    after: Figures,
    /// Two-sided distance to the input, sampled at vertices and centroids, over the input's
    /// bounding-box diagonal: the largest over the samples measured.
    hausdorff_relative: f32,
    /// Samples of both meshes, and how many the test budget let the report measure.
    distance_samples: u64,
    distance_samples_measured: u64,
    /// Point–triangle tests the distance report made.
    distance_tests: u64,
    remesh_seconds: f64,
}

pub fn run(args: &RemeshArgs) -> Result<()> {
    crate::atomic::refuse_inputs(&args.output, &[&args.mesh])?;
    let data = read_mesh(&args.mesh)?;
    let mesh = MeshRef::new(&data.positions, &data.triangles)
        .validate()
        .with_context(|| format!("{}: invalid mesh", args.mesh.display()))?;
    let target = match (args.target_length, args.target_ratio) {
        (Some(length), _) => {
            anyhow::ensure!(
                length > 0.0 && length.is_finite(),
                "--target-length must be positive"
            );
            EdgeTarget::Length(length)
        }
        (None, Some(ratio)) => {
            anyhow::ensure!(
                ratio > 0.0 && ratio.is_finite(),
                "--target-ratio must be positive"
            );
            EdgeTarget::MeanEdgeTimes(ratio)
        }
        (None, None) => EdgeTarget::default(),
    };
    let config = RemeshConfig {
        target,
        iterations: args.iterations,
        feature_angle: args.feature_angle,
    };
    let bar = progress::bar(Some(u64::from(config.iterations)), "iterations");
    let start = Instant::now();
    let remeshed =
        Remeshed::with_progress(&mesh, &config, |r| bar.set_position(r.iterations.into()))
            .with_context(|| format!("cannot remesh {}", args.mesh.display()))?;
    let remesh_seconds = start.elapsed().as_secs_f64();
    bar.finish_and_clear();
    let budget = args.max_distance_tests.map_or_else(
        || PairBudget::for_triangles(mesh.triangle_count(), remeshed.triangles.len()),
        |max_tests| PairBudget { max_tests },
    );
    let distance = remeshed.distance_to(&mesh, budget)?;
    write_mesh(
        &args.output,
        &[&args.mesh],
        &remeshed.positions,
        &remeshed.triangles,
    )?;
    let r = remeshed.report;
    let summary = Summary {
        // The mean the run resolved its target from: the same figure, bit for bit.
        target_length: config.target.length(remeshed.before.mean_edge),
        iterations: r.iterations,
        splits: r.splits,
        collapses: r.collapses,
        flips: r.flips,
        creases: r.creases,
        relaxed: r.relaxed,
        peak_vertices: r.peak_vertices,
        peak_triangles: r.peak_triangles,
        before: remeshed.before.into(),
        after: remeshed.after.into(),
        hausdorff_relative: distance.relative,
        distance_samples: distance.samples,
        distance_samples_measured: distance.measured,
        distance_tests: distance.tested,
        remesh_seconds,
    };
    if args.json {
        return output::json(&summary);
    }
    say!(
        "remeshed {} -> {}",
        args.mesh.display(),
        args.output.display()
    );
    say!(
        "  target edge {:.6}, {} iterations: {} splits, {} collapses, {} flips, {} crease edges, {:.3} s",
        summary.target_length,
        r.iterations,
        r.splits,
        r.collapses,
        r.flips,
        r.creases,
        remesh_seconds
    );
    say!(
        "  {:<7} {:>10} {:>10} {:>12} {:>10} {:>8}",
        "",
        "triangles",
        "valence 6",
        "min angle",
        "< 30°",
        "edge CV"
    );
    for (name, f) in [("before", &summary.before), ("after", &summary.after)] {
        say!(
            "  {:<7} {:>10} {:>9.2}% {:>11.2}° {:>9.3}% {:>8.4}",
            name,
            f.triangles,
            f.valence_6_percent,
            f.min_angle_off_boundary_degrees,
            f.triangles_under_30_degrees_percent,
            f.edge_length_cv
        );
    }
    if distance.is_complete() {
        say!(
            "  distance to the input: {:.2e} of the bounding-box diagonal",
            distance.relative
        );
    } else {
        // Triangles no box separates make every sample cost as much as the mesh: say what
        // was measured rather than run for minutes.
        say!(
            "  distance to the input: at least {:.2e} of the bounding-box diagonal, from {} of {} samples \
             ({} point-triangle tests: raise --max-distance-tests for all)",
            distance.relative,
            distance.measured,
            distance.samples,
            distance.tested
        );
    }
    Ok(())
}

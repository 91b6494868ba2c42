//! `meshq`: bake acceleration-structure blobs offline, inspect them, run ray and
//! closest-point queries from files, and remesh meshes.

mod allocator;
mod atomic;
mod bake;
mod check;
mod closest;
mod distance;
mod inside;
mod inspect;
mod inspect_cells;
mod mesh_write;
mod output;
mod progress;
mod quality;
mod raycast;
mod records;
mod remesh;
mod sdf;
mod structure;
mod structure_arg;
mod sweep;
mod threads;
mod winding;
mod workload;

use meshq_cli::mesh_file;
use std::io::Write;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

#[derive(Parser, Debug)]
#[command(name = "meshq", version, about = "Bake, inspect and query meshq blobs")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Build an acceleration structure over a mesh and write it as a blob.
    Bake(bake::BakeArgs),
    /// Validate a blob and show its header, shape and size.
    Inspect(inspect::InspectArgs),
    /// Cast rays from a file at a mesh or blob.
    Raycast(raycast::RaycastArgs),
    /// Find the closest surface point for points from a file.
    Closest(closest::ClosestArgs),
    /// Tell which points are inside a mesh (generalized winding numbers: open and
    /// non-manifold meshes too).
    Inside(inside::InsideArgs),
    /// Write a signed-distance volume of a mesh (NRRD).
    Sdf(sdf::SdfArgs),
    /// Move spheres, capsules or boxes along segments from a file: where each first touches.
    Sweep(sweep::SweepArgs),
    /// Remesh a mesh toward uniform, near-equilateral triangles on its surface.
    Remesh(remesh::RemeshArgs),
    /// Find where a mesh meets itself, or another mesh.
    Check(check::CheckArgs),
    /// Find how far apart two meshes are: the closest pair of points.
    Distance(distance::DistanceArgs),
    /// Write a reproducible ray or point set for a mesh (the DESIGN.md workloads).
    Workload(workload::WorkloadArgs),
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return parse_failure(&e),
    };
    let result = match &cli.command {
        Command::Bake(args) => bake::run(args),
        Command::Inspect(args) => inspect::run(args),
        Command::Raycast(args) => raycast::run(args),
        Command::Closest(args) => closest::run(args),
        Command::Inside(args) => inside::run(args),
        Command::Sdf(args) => sdf::run(args),
        Command::Sweep(args) => sweep::run(args),
        Command::Remesh(args) => remesh::run(args),
        Command::Check(args) => check::run(args),
        Command::Distance(args) => distance::run(args),
        Command::Workload(args) => workload::run(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        // The reader went away (`meshq inspect blob | head -1`): stop quietly with the status
        // a shell gives a command killed by SIGPIPE, as other Unix tools do.
        Err(e) if closed_pipe(&e) => ExitCode::from(141),
        Err(e) => {
            // One line: the context chain joined with ": ", with any line breaks or tabs a
            // parser put in its message flattened. If even stderr fails, the status says it.
            let message = format!("{e:#}");
            let line: Vec<&str> = message.split_whitespace().collect();
            let _ = writeln!(std::io::stderr(), "meshq: error: {}", line.join(" "));
            ExitCode::FAILURE
        }
    }
}

/// `--help`, `--version` or a usage error: clap's text, written and checked here (clap's own
/// `exit` ignores a failed write, so `meshq --help > /dev/full` reported success). Help and
/// version go to stdout with status 0, usage errors to stderr with status 2; a closed pipe
/// gives 141 and any other failed write 1, with a line on stderr when stdout failed.
fn parse_failure(e: &clap::Error) -> ExitCode {
    use std::io::IsTerminal;
    // Colours only for a terminal, as clap decides for itself.
    let terminal = if e.use_stderr() {
        std::io::stderr().is_terminal()
    } else {
        std::io::stdout().is_terminal()
    };
    let rendered = e.render();
    let text = if terminal {
        rendered.ansi().to_string()
    } else {
        rendered.to_string()
    };
    if !e.use_stderr() {
        let written = std::io::stdout()
            .write_all(text.as_bytes())
            .and_then(|()| std::io::stdout().flush());
        return match written {
            Ok(()) => ExitCode::SUCCESS,
            Err(w) if w.kind() == std::io::ErrorKind::BrokenPipe => ExitCode::from(141),
            Err(w) => {
                let _ = writeln!(
                    std::io::stderr(),
                    "meshq: error: cannot write to stdout: {w}"
                );
                ExitCode::FAILURE
            }
        };
    }
    let _ = std::io::stderr().write_all(text.as_bytes());
    ExitCode::from(2)
}

/// Whether `e` is a write that failed because its reader closed the pipe: to standard output,
/// or to an output path that is a pipe (`--out /dev/stdout`, a named pipe).
fn closed_pipe(e: &anyhow::Error) -> bool {
    e.chain().any(|cause| {
        let io = cause
            .downcast_ref::<output::StdoutError>()
            .map(|s| &s.0)
            .or_else(|| cause.downcast_ref::<std::io::Error>());
        io.is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe)
    })
}

//! `meshq`: bake acceleration-structure blobs offline, inspect them, run ray and
//! closest-point queries from files, and remesh meshes.

mod bake;
mod check;
mod closest;
mod inspect;
mod inspect_cells;
mod mesh_file;
mod mesh_write;
mod output;
mod progress;
mod quality;
mod raycast;
mod records;
mod remesh;
mod structure;
mod structure_arg;
mod workload;

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
    /// Remesh a mesh toward uniform, near-equilateral triangles on its surface.
    Remesh(remesh::RemeshArgs),
    /// Find where a mesh meets itself, or another mesh.
    Check(check::CheckArgs),
    /// Write a reproducible ray or point set for a mesh (the DESIGN.md workloads).
    Workload(workload::WorkloadArgs),
}

fn main() -> ExitCode {
    // clap prints usage errors itself and exits with status 2.
    let cli = Cli::parse();
    let result = match &cli.command {
        Command::Bake(args) => bake::run(args),
        Command::Inspect(args) => inspect::run(args),
        Command::Raycast(args) => raycast::run(args),
        Command::Closest(args) => closest::run(args),
        Command::Remesh(args) => remesh::run(args),
        Command::Check(args) => check::run(args),
        Command::Workload(args) => workload::run(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            // One line: the context chain joined with ": ".
            eprintln!("meshq: error: {e:#}");
            ExitCode::FAILURE
        }
    }
}

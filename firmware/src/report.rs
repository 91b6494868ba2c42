//! What the firmware prints over semihosting. Integers and raw bit patterns only: float
//! formatting would cost flash and could print the same bits differently from other targets.
//! The panic-free build prints nothing (its exit status says it all), so formatting code does
//! not enter the proof.

use meshq::advanced::BlobHeader;
use meshq::error::BlobError;
#[cfg(feature = "remesh")]
use meshq::error::{MeshError, RemeshError};
#[cfg(not(feature = "remesh"))]
use meshq::math::RayHit;
#[cfg(feature = "remesh")]
use meshq::remesh::RemeshReport;
use meshq_workload::GoldenError;
#[cfg(feature = "remesh")]
use meshq_workload::MeshDigest;
#[cfg(not(feature = "remesh"))]
use meshq_workload::ParityReport;

#[cfg(not(feature = "panic-free"))]
use semihosting::println;

/// Type-checks its arguments but never runs, so no formatting code is linked into the
/// panic-free build.
#[cfg(feature = "panic-free")]
macro_rules! println {
    ($($arg:tt)*) => {
        if false {
            let _ = core::format_args!($($arg)*);
        }
    };
}

pub fn start(mesh: &str, blob_bytes: usize) {
    println!("meshq firmware: {mesh}, blob of {blob_bytes} bytes in flash");
}

pub fn blob_refused(error: &BlobError) {
    println!("blob refused: {error}");
}

pub fn golden_unusable(error: &GoldenError) {
    println!("golden file: {error}");
}

pub fn wrong_mesh(got: u32, expected: u32) {
    println!("the blob has {got} triangles; the golden line is for {expected}");
}

pub fn blob_loaded(header: &BlobHeader) {
    println!(
        "validated in place: {} over {} triangles, {} nodes or cells, {} references, depth {}",
        header.kind, header.triangle_count, header.node_count, header.reference_count, header.depth
    );
}

#[cfg(not(feature = "remesh"))]
pub fn sample(index: usize, hit: Option<RayHit>) {
    match hit {
        Some(h) => println!(
            "ray {index}: t=0x{:08x} tri={} u=0x{:08x} v=0x{:08x}",
            h.t.to_bits(),
            h.tri,
            h.u.to_bits(),
            h.v.to_bits()
        ),
        None => println!("ray {index}: miss"),
    }
}

#[cfg(not(feature = "remesh"))]
pub fn parity(got: &ParityReport, golden: &ParityReport) {
    println!(
        "hits {} any-hits {} closest points {} digest 0x{:016x}",
        got.hits, got.any_hits, got.points_found, got.digest
    );
    println!("golden digest 0x{:016x}", golden.digest);
    if got == golden {
        println!("PARITY OK");
    } else {
        println!("PARITY MISMATCH");
    }
}

#[cfg(not(feature = "remesh"))]
pub fn stack(validation: u32, queries: u32, printing: u32) {
    println!(
        "stack high-water marks (bytes): validation {validation}, queries {queries}, \
         sample queries with printing {printing}"
    );
}

#[cfg(feature = "remesh")]
pub fn remeshed(run: &RemeshReport, got: &MeshDigest, golden: &MeshDigest) {
    println!(
        "remeshed in {} iterations: {} splits, {} collapses, {} flips; peak {} vertices, {} \
         triangles",
        run.iterations, run.splits, run.collapses, run.flips, run.peak_vertices, run.peak_triangles
    );
    println!(
        "result: {} vertices, {} triangles, digest 0x{:016x}",
        got.vertices, got.triangles, got.digest
    );
    println!(
        "golden: {} vertices, {} triangles, digest 0x{:016x}",
        golden.vertices, golden.triangles, golden.digest
    );
    if got == golden {
        println!("REMESH PARITY OK");
    } else {
        println!("REMESH PARITY MISMATCH");
    }
}

#[cfg(feature = "remesh")]
pub fn remesh_memory(arrays: usize, stack: u32) {
    println!("stack high-water mark (bytes): remeshing {stack}, of which the mesh arrays {arrays}");
}

#[cfg(feature = "remesh")]
pub fn input_too_large(vertices: usize, triangles: usize) {
    println!("the input does not fit: at most {vertices} vertices and {triangles} triangles");
}

#[cfg(feature = "remesh")]
pub fn mesh_refused(error: &MeshError) {
    println!("mesh refused: {error}");
}

#[cfg(feature = "remesh")]
pub fn remesh_failed(error: &RemeshError) {
    println!("remeshing failed: {error}");
}

#[cfg(feature = "winding")]
pub fn winding(
    got: &meshq_workload::WindingDigest,
    golden: &meshq_workload::WindingDigest,
    stack: u32,
) {
    println!(
        "winding numbers of {} points from the blob's expansions: {} inside, digest 0x{:016x}, \
         signed distances 0x{:016x}",
        got.points, got.inside, got.digest, got.signed
    );
    println!(
        "golden: {} inside, digest 0x{:016x}, signed distances 0x{:016x}",
        golden.inside, golden.digest, golden.signed
    );
    println!("stack high-water mark (bytes): inside queries {stack}");
    if got == golden {
        println!("WINDING PARITY OK");
    } else {
        println!("WINDING PARITY MISMATCH");
    }
}

/// Reports why the winding check could not run; returns the exit status.
#[cfg(feature = "winding")]
pub fn winding_unusable(why: &crate::winding_run::Unusable) -> i32 {
    use crate::winding_run::Unusable;
    match why {
        Unusable::NoExpansions => {
            println!("the blob holds no winding-number expansions (bake with --winding)");
            2
        }
        Unusable::NotIndexed => {
            println!("the blob's mesh is not stored indexed");
            2
        }
        Unusable::Golden(error) => {
            println!("winding golden file: {error}");
            3
        }
    }
}

//! What the firmware prints over semihosting. Integers and raw bit patterns only: float
//! formatting would cost flash and could print the same bits differently from other targets.
//! The panic-free build prints nothing (its exit status says it all), so formatting code does
//! not enter the proof.

use meshq::blob::BlobHeader;
use meshq::error::BlobError;
use meshq::math::RayHit;
use meshq_workload::{GoldenError, ParityReport};

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

pub fn stack(validation: u32, queries: u32, printing: u32) {
    println!(
        "stack high-water marks (bytes): validation {validation}, queries {queries}, \
         sample queries with printing {printing}"
    );
}

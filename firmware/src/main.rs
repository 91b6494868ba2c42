//! meshq on a Cortex-M4F with no allocator: validates a blob that sits in flash, queries it in
//! place through [`BlobView`] (no node or triangle is copied to RAM), and checks every answer
//! bit against the golden digest the native test suite computed from brute force.
//!
//! With `--features remesh` it remeshes the small UV sphere from its blob instead (see
//! `remesh_run`).
//!
//! Exit status (through semihosting, so QEMU exits with it): 0 when the digest matches, 1 on a
//! digest mismatch, 2 when the blob is refused, 3 when the golden file has no usable line for
//! the mesh, 4 when the blob holds another mesh than the golden line describes.
//!
//! With `--features winding` it then answers containment and signed distance from the
//! winding-number expansions stored in the blob, against `tests/golden/winding.txt` (exit 1 on
//! a mismatch, 2 for a blob without expansions or an unindexed mesh, 3 without a golden line).

#![no_std]
#![no_main]

#[cfg(not(feature = "remesh"))]
mod in_place;
#[cfg(feature = "panic-free")]
mod panic_free;
#[cfg(feature = "remesh")]
mod remesh_run;
mod report;
mod stack;
#[cfg(feature = "winding")]
mod winding_run;

use cortex_m_rt::entry;
#[cfg(not(feature = "remesh"))]
use meshq::MeshQuery;
use meshq::blob::BlobView;
#[cfg(not(feature = "remesh"))]
use meshq_workload::{find_golden, run_parity};

#[cfg(not(feature = "remesh"))]
use crate::in_place::InPlace;

/// The blob, baked offline by `meshq bake` and linked into flash.
static BLOB: &[u8] = include_bytes!(env!("MESHQ_BLOB"));
/// The golden parity file shared with the native and WebAssembly tests.
#[cfg(not(feature = "remesh"))]
static GOLDEN: &str = include_str!("../../tests/golden/parity.txt");
/// The mesh the blob was baked from (its file stem in `assets/`).
const MESH: &str = env!("MESHQ_MESH");
/// How many closest-hit answers are printed in full, as a readable sample.
#[cfg(not(feature = "remesh"))]
const SAMPLES: usize = 3;

#[entry]
fn main() -> ! {
    semihosting::process::exit(run())
}

/// Checks the whole blob once (checksum, every count, index, range and the depth); after this
/// no query on the view can read out of bounds. Kept out of line so the validator's traversal
/// stack is not added to the frame that later runs the queries.
#[inline(never)]
fn validate(bytes: &'static [u8]) -> Result<BlobView<'static>, meshq::error::BlobError> {
    BlobView::parse(bytes)
}

/// `--features remesh`: remesh the blob's mesh instead of querying it.
#[cfg(feature = "remesh")]
fn run() -> i32 {
    remesh_run::run(core::hint::black_box(BLOB), MESH)
}

#[cfg(not(feature = "remesh"))]
fn run() -> i32 {
    // Opaque to the optimiser: the blob is a compile-time constant, and without this the
    // compiler could fold checks on its known bytes away, which would hollow out the
    // panic-free proof (it must hold for any blob, not just this one).
    let blob: &'static [u8] = core::hint::black_box(BLOB);
    report::start(MESH, blob.len());
    // The view is large: it is returned in place and then borrowed, never moved, because
    // moving it would link a general-purpose memcpy (most of a kilobyte of flash).
    stack::repaint();
    let parsed = validate(blob);
    let validation_stack = stack::high_water();
    let view = match &parsed {
        Ok(view) => view,
        Err(error) => {
            report::blob_refused(error);
            return 2;
        }
    };
    let golden = match find_golden(GOLDEN, MESH) {
        Ok(golden) => golden,
        Err(error) => {
            report::golden_unusable(&error);
            return 3;
        }
    };
    let header = view.header();
    if header.triangle_count != golden.triangles {
        report::wrong_mesh(header.triangle_count, golden.triangles);
        return 4;
    }
    report::blob_loaded(header);

    // The queries are placed around the golden line's box (the BVH root box it was written
    // from), whichever structure the blob holds.
    let bounds = golden.bounds();
    let ((), printing_stack) = stack::measured(|| {
        for (index, ray) in golden.spec.rays(bounds).take(SAMPLES).enumerate() {
            report::sample(index, view.raycast(&ray));
        }
    });
    let (got, query_stack) =
        stack::measured(|| run_parity(&golden.spec, bounds, &mut InPlace(view)));
    report::parity(&got, &golden.report);
    report::stack(validation_stack, query_stack, printing_stack);
    if got != golden.report {
        return 1;
    }
    #[cfg(feature = "winding")]
    {
        let (outcome, winding_stack) = stack::measured(|| winding_run::run(view, MESH));
        match outcome {
            Ok((got, golden)) => {
                report::winding(&got, &golden, winding_stack);
                if got != golden {
                    return 1;
                }
            }
            Err(unusable) => return report::winding_unusable(&unusable),
        }
    }
    0
}

//! meshq for JavaScript (wasm-bindgen): build a BVH from the arrays of a three.js
//! `BufferGeometry` or load a prebuilt blob, then cast rays and find closest points, one at a
//! time or a whole batch per call. The package also ships `three.js`, a drop-in for
//! `THREE.Mesh.prototype.raycast` (see the README). `remesh` remeshes a geometry's arrays; `intersectsMesh`,
//! `intersectingPairs`, `intersectionSegments` and `selfIntersections` find where meshes meet.
//!
//! The same core code runs here as natively and on microcontrollers, so answers are bit for bit
//! the same (the `parity` tests check this against the golden file).

mod all_hits;
mod args;
mod batch;
mod build;
mod collide;
mod fields;
mod geometry;
mod inside;
mod js_objects;
mod levels;
mod mesh_bvh;
mod options;
mod overlaps;
mod remesh;
mod storage;
mod sweeps;
mod typings;
mod workload;

pub use batch::{MISS_DISTANCE, MISS_T, MISS_TRIANGLE, RAY_CHUNK, SORTED_PASS};
pub use mesh_bvh::MeshBvh;
pub use remesh::remesh;
pub use workload::{camera_rays, query_points, random_rays};

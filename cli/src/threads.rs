//! `--threads`: how many threads build and answer. One (the default) works on the calling
//! thread; more spread the queries over a rayon pool of that many threads
//! through `meshq::parallel`, and build a BVH with `MeshBvh::build_parallel`: the same tree
//! and the same answers, bit for bit.

use anyhow::{Context, Result};
use meshq::MeshBvh;
use meshq::bvh::{BuildConfig, SpatialSplits};
use meshq::error::BuildError;
use meshq::mesh::ValidMesh;

/// The most threads `--threads` takes: more would only exhaust the system's threads (the
/// request is refused as a usage error rather than failing while the threads start).
pub const MAX_THREADS: i64 = 1024;

/// The pool for `--threads N`: `None` for 1; for 0, one thread per core.
pub struct Threads(Option<rayon::ThreadPool>);

impl Threads {
    pub fn new(threads: u16) -> Result<Self> {
        if threads == 1 {
            return Ok(Self(None));
        }
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(usize::from(threads))
            .build()
            .context("cannot start the threads")?;
        Ok(Self(Some(pool)))
    }

    /// The pool, when queries run on more than the calling thread.
    pub fn pool(&self) -> Option<&rayon::ThreadPool> {
        self.0.as_ref()
    }

    /// How many threads answer.
    pub fn count(&self) -> usize {
        self.0
            .as_ref()
            .map_or(1, rayon::ThreadPool::current_num_threads)
    }
}

impl Threads {
    /// A BVH of `mesh`: built on the pool when there is one (the same tree either way).
    pub fn build_bvh(
        &self,
        mesh: &ValidMesh<'_>,
        config: &BuildConfig,
        spatial: Option<&SpatialSplits>,
    ) -> Result<MeshBvh, BuildError> {
        match (spatial, self.pool()) {
            (Some(spatial), None) => MeshBvh::build_spatial(mesh, config, spatial),
            (Some(spatial), Some(pool)) => {
                pool.install(|| MeshBvh::build_spatial_parallel(mesh, config, spatial))
            }
            (None, None) => MeshBvh::build(mesh, config),
            (None, Some(pool)) => pool.install(|| MeshBvh::build_parallel(mesh, config)),
        }
    }
}

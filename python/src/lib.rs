//! meshq for Python: the extension module `meshq._meshq`, re-exported by the `meshq` package
//! (python/meshq). It binds the core's owned API ([`meshq::owned::MeshIndex`] and the
//! remesher) to numpy arrays; batches run on rayon's thread pool with the GIL released.

mod allocator;
mod arrays;
mod build;
mod closest;
mod mesh;
mod pairs;
mod pool;
mod rays;
mod remesh;
mod shapes;

use pyo3::prelude::*;

/// The extension module.
#[pymodule]
fn _meshq(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<mesh::Mesh>()?;
    m.add_function(wrap_pyfunction!(remesh::remesh, m)?)?;
    m.add_function(wrap_pyfunction!(pool::after_fork_in_child, m)?)?;
    Ok(())
}

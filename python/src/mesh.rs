//! The `Mesh` class: a triangle mesh with its structure (a BVH by default), built from numpy
//! arrays or loaded from a blob, shareable between threads and picklable as its blob.

use std::sync::{RwLock, RwLockReadGuard, RwLockWriteGuard};

use meshq::blob::MeshLayout;
use meshq::bvh::BuildConfig;
use meshq::inside::WindingTree;
use meshq::mesh::MeshRef;
use meshq::owned::{MeshBvh, MeshIndex, MeshPseudoNormals, StructureKind};
use numpy::{PyArray1, PyArray2};
use pyo3::PyTypeInfo;
use pyo3::exceptions::{PyRuntimeError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyByteArray, PyBytes, PyMemoryView, PyTuple};

use crate::arrays::{floats, indices, rows};
use crate::build::{Nodes, build_choice};

/// What a [`Mesh`] holds: the core's owned [`MeshIndex`] and what its first queries of a kind
/// prepare.
pub struct Storage {
    /// The mesh and every buffer its queries read.
    pub scene: MeshIndex,
    /// The blob this was loaded from, handed back as it is by `to_blob()`.
    pub blob: Option<Vec<u8>>,
    /// For a k-d tree, octree or grid: a BVH of the same mesh with its winding-number
    /// expansions, made by the first inside query (a BVH prepares its own).
    pub winding: Option<MeshBvh>,
    /// The angle-weighted pseudo-normals, made by the first query signed by them.
    pub pseudo: Option<MeshPseudoNormals>,
}

impl Storage {
    /// The winding-number tree, if prepared.
    pub fn winding_tree(&self) -> Option<WindingTree<'_>> {
        match (&self.scene, &self.winding) {
            (MeshIndex::Bvh(bvh), _) | (_, Some(bvh)) => bvh.winding(),
            _ => None,
        }
    }
}

/// A triangle mesh and its acceleration structure, ready for queries from numpy arrays.
///
/// Conventions: positions are `float32` (other dtypes are converted once); triangles are
/// counter-clockwise seen from their front. Every structure gives the same answers, bit for
/// bit; on equal distance the lower triangle index wins. Batch calls release the GIL and use
/// every core. A `Mesh` is safe to share between threads and pickles as its blob (so it goes to
/// Dask workers as bytes and is never rebuilt there).
#[pyclass(module = "meshq", name = "Mesh", frozen)]
pub struct Mesh {
    storage: RwLock<Storage>,
}

/// The bytes of a `bytes`, `bytearray` or `memoryview`, or a `TypeError` naming `blob`.
fn blob_bytes(blob: &Bound<'_, PyAny>) -> PyResult<Vec<u8>> {
    if let Ok(bytes) = blob.cast::<PyBytes>() {
        return Ok(bytes.as_bytes().to_vec());
    }
    if let Ok(array) = blob.cast::<PyByteArray>() {
        return Ok(array.to_vec());
    }
    if blob.is_instance_of::<PyMemoryView>() {
        let copied = PyBytes::type_object(blob.py()).call1((blob,))?;
        return Ok(copied.cast::<PyBytes>()?.as_bytes().to_vec());
    }
    Err(PyTypeError::new_err(format!(
        "blob must be bytes, bytearray or memoryview, got {}",
        blob.get_type().name()?
    )))
}

fn value_error(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(e.to_string())
}

impl Mesh {
    /// The storage, read-locked for queries.
    pub fn read(&self) -> PyResult<RwLockReadGuard<'_, Storage>> {
        self.storage
            .read()
            .map_err(|_| PyRuntimeError::new_err("the mesh was poisoned by a panic"))
    }

    fn write(&self) -> PyResult<RwLockWriteGuard<'_, Storage>> {
        self.storage
            .write()
            .map_err(|_| PyRuntimeError::new_err("the mesh was poisoned by a panic"))
    }

    /// The storage with its winding-number expansions made (once), read-locked.
    pub fn with_winding(&self) -> PyResult<RwLockReadGuard<'_, Storage>> {
        if self.read()?.winding_tree().is_none() {
            let mut storage = self.write()?;
            let storage = &mut *storage;
            match &mut storage.scene {
                MeshIndex::Bvh(bvh) => bvh.prepare_winding_numbers().map_err(value_error)?,
                other => {
                    if storage.winding.is_none() {
                        let bvh = MeshBvh::build(&other.mesh(), &BuildConfig::default())
                            .and_then(MeshBvh::with_winding_numbers)
                            .map_err(value_error)?;
                        storage.winding = Some(bvh);
                    }
                }
            }
        }
        self.read()
    }

    /// The storage with its pseudo-normals made (once), read-locked; a `ValueError` naming the
    /// edge of a mesh that is not closed, manifold and consistently oriented.
    pub fn with_pseudo_normals(&self) -> PyResult<RwLockReadGuard<'_, Storage>> {
        if self.read()?.pseudo.is_none() {
            let mut storage = self.write()?;
            if storage.pseudo.is_none() {
                let made = MeshPseudoNormals::of(&storage.scene.mesh()).map_err(value_error)?;
                storage.pseudo = Some(made);
            }
        }
        self.read()
    }

    fn from_storage(scene: MeshIndex, blob: Option<Vec<u8>>) -> Self {
        Self {
            storage: RwLock::new(Storage {
                scene,
                blob,
                winding: None,
                pseudo: None,
            }),
        }
    }
}

#[pymethods]
impl Mesh {
    /// Builds the structure of the mesh `vertices` (`(n, 3)` floats) / `faces` (`(m, 3)` vertex
    /// indices). `structure`: `"bvh"` (default), `"kdtree"`, `"octree"` or `"grid"`;
    /// `quality`: `"balanced"` (binned SAH, default), `"fast"` or `"high"`; `max_leaf_size`,
    /// `bins`, `max_depth` tune the BVH; `spatial_splits` (`True` or the extra room `0..=4`)
    /// builds a BVH with spatial splits; `sweep_sah` (`True` or the triangles between weighed
    /// cuts, `≥ 1`) splits the BVH's nodes by sweep SAH (exact split positions, many times the
    /// build time; not with `spatial_splits`); `nodes` picks the BVH's query nodes (`"eight-wide"`,
    /// the default on every x86-64 and AArch64, `"four-wide"`, or `"compact"`: 8-bit child
    /// boxes, half the memory), all giving the same answers. Raises `ValueError` naming a bad
    /// argument or what is wrong with the mesh (an index out of range, a non-finite position…).
    #[new]
    #[pyo3(signature = (vertices, faces, *, structure = "bvh", quality = "balanced", max_leaf_size = None, bins = None, max_depth = None, spatial_splits = None, sweep_sah = None, nodes = None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        vertices: &Bound<'_, PyAny>,
        faces: &Bound<'_, PyAny>,
        structure: &str,
        quality: &str,
        max_leaf_size: Option<&Bound<'_, PyAny>>,
        bins: Option<&Bound<'_, PyAny>>,
        max_depth: Option<&Bound<'_, PyAny>>,
        spatial_splits: Option<&Bound<'_, PyAny>>,
        sweep_sah: Option<&Bound<'_, PyAny>>,
        nodes: Option<&str>,
    ) -> PyResult<Self> {
        let choice = build_choice(
            structure,
            quality,
            max_leaf_size,
            bins,
            max_depth,
            spatial_splits,
            sweep_sah,
            nodes,
        )?;
        let positions = floats(vertices, "vertices", 3)?;
        let corners = indices(faces, "faces", 3)?;
        let scene = py.detach(|| -> Result<MeshIndex, String> {
            let mesh = MeshRef::from_flat(&positions, &corners)
                .and_then(MeshRef::validate)
                .map_err(|e| e.to_string())?;
            let built = match (choice.kind, &choice.spatial) {
                (StructureKind::Bvh, None) => {
                    MeshBvh::build(&mesh, &choice.config).map(MeshIndex::Bvh)
                }
                (StructureKind::Bvh, Some(spatial)) => {
                    MeshBvh::build_spatial(&mesh, &choice.config, spatial).map(MeshIndex::Bvh)
                }
                (other, _) => MeshIndex::build(&mesh, other),
            };
            let mut built = built.map_err(|e| e.to_string())?;
            if let MeshIndex::Bvh(bvh) = &mut built {
                match choice.nodes {
                    Nodes::Default => Ok(()),
                    Nodes::EightWide => bvh.eight_wide_nodes(),
                    Nodes::FourWide => bvh.four_wide_nodes(),
                    Nodes::Compact => bvh.compact_nodes(),
                }
                .map_err(|e| e.to_string())?;
            }
            Ok(built)
        });
        Ok(Self::from_storage(
            scene.map_err(PyValueError::new_err)?,
            None,
        ))
    }

    /// Loads a blob (`bytes`, `bytearray` or `memoryview`) baked by `meshq bake`, `to_blob()`
    /// or the JavaScript package, of any structure. It is validated once (checksum, every
    /// count, index and range) and decoded into the buffers a build makes: the same answers,
    /// bit for bit, as the mesh it was baked from. Raises `ValueError` naming what is wrong.
    #[staticmethod]
    fn from_blob(py: Python<'_>, blob: &Bound<'_, PyAny>) -> PyResult<Self> {
        let bytes = blob_bytes(blob)?;
        let scene = py.detach(|| MeshIndex::from_blob(&bytes).map(|s| (s, bytes)));
        let (scene, bytes) = scene.map_err(value_error)?;
        Ok(Self::from_storage(scene, Some(bytes)))
    }

    /// The blob of this mesh and structure as `bytes`. `layout`: `None` (a loaded blob as it
    /// was loaded, else `"indexed"`), `"indexed"` (positions and indices), `"packed"` (larger,
    /// fastest in place) or `"omitted"` (no mesh). `winding=True` stores the winding-number
    /// expansions too (a BVH only), so readers answer inside queries without making them.
    #[pyo3(signature = (layout = None, *, winding = false))]
    fn to_blob<'py>(
        &self,
        py: Python<'py>,
        layout: Option<&str>,
        winding: bool,
    ) -> PyResult<Bound<'py, PyBytes>> {
        let mesh_layout = match layout {
            None | Some("indexed") => MeshLayout::Indexed,
            Some("packed") => MeshLayout::Packed,
            Some("omitted") => MeshLayout::Omitted,
            Some(other) => {
                return Err(PyValueError::new_err(format!(
                    "layout must be 'indexed', 'packed' or 'omitted', got {other:?}"
                )));
            }
        };
        let mut afresh = layout.is_some();
        let storage = if winding {
            if !matches!(self.read()?.scene, MeshIndex::Bvh(_)) {
                return Err(PyValueError::new_err("winding=True applies to a BVH"));
            }
            let storage = self.with_winding()?;
            // Loaded bytes hold the expansions only from format version 6.
            let stored = storage.blob.as_deref().is_some_and(|bytes| {
                meshq::advanced::BlobHeader::read(bytes).is_ok_and(|h| h.version >= 6)
            });
            afresh |= !stored;
            storage
        } else {
            self.read()?
        };
        let bytes = match (&storage.blob, afresh) {
            (Some(bytes), false) => bytes.clone(),
            _ => py
                .detach(|| storage.scene.to_blob(mesh_layout))
                .map_err(value_error)?,
        };
        Ok(PyBytes::new(py, &bytes))
    }

    /// Pickles as `Mesh.from_blob(self.to_blob())`.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyTuple>> {
        let py = slf.py();
        let bytes = slf.get().to_blob(py, None, false)?;
        let load = slf.getattr("from_blob")?;
        PyTuple::new(py, [load.into_any(), PyTuple::new(py, [bytes])?.into_any()])
    }

    /// The structure's kind: `"bvh"`, `"kdtree"`, `"octree"` or `"grid"`.
    #[getter]
    fn structure(&self) -> PyResult<String> {
        let kind = match self.read()?.scene {
            MeshIndex::Bvh(_) => StructureKind::Bvh,
            MeshIndex::KdTree(_) => StructureKind::KdTree,
            MeshIndex::Octree(_) => StructureKind::Octree,
            MeshIndex::Grid(_) => StructureKind::Grid,
        };
        Ok(kind.to_string())
    }

    /// The number of triangles.
    #[getter]
    fn triangle_count(&self) -> PyResult<usize> {
        Ok(self.read()?.scene.mesh().triangle_count())
    }

    /// The number of vertices.
    #[getter]
    fn vertex_count(&self) -> PyResult<usize> {
        Ok(self.read()?.scene.mesh().vertex_count())
    }

    /// The vertex positions, `(n, 3)` `float32` (a copy).
    #[getter]
    fn vertices<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f32>>> {
        let flat: Vec<f32> = self
            .read()?
            .scene
            .mesh()
            .positions()
            .as_flattened()
            .to_vec();
        rows(py, flat, 3)
    }

    /// The triangles, `(m, 3)` `uint32` vertex indices (a copy).
    #[getter]
    fn faces<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<u32>>> {
        let flat: Vec<u32> = self
            .read()?
            .scene
            .mesh()
            .triangles()
            .as_flattened()
            .to_vec();
        rows(py, flat, 3)
    }

    /// The mesh's bounding box as a `(2, 3)` `float32` array: the minimum corner, then the
    /// maximum.
    #[getter]
    fn bounds<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f32>>> {
        let b = self.read()?.scene.mesh().bounds();
        let flat = [b.min.to_array(), b.max.to_array()].as_flattened().to_vec();
        rows(py, flat, 3)
    }

    fn __len__(&self) -> PyResult<usize> {
        self.triangle_count()
    }

    fn __repr__(&self) -> PyResult<String> {
        let storage = self.read()?;
        let mesh = storage.scene.mesh();
        Ok(format!(
            "meshq.Mesh({} triangles, {} vertices, structure={:?})",
            mesh.triangle_count(),
            mesh.vertex_count(),
            self.structure()?
        ))
    }
}

/// The 1-D array type the query methods return.
pub type Column<'py, T> = Bound<'py, PyArray1<T>>;

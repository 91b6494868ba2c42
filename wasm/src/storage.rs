//! The owned buffers of a [`crate::MeshBvh`] and the validated views that borrow them, kept
//! together (self_cell) so the views are checked once and then reused by every query.

use meshq::blob::BlobView;
use meshq::bvh::{
    Bvh, BvhNode, LeafTriangles, PackedTriangle, RayOptions, TreeArrays, WideBvh, WideNode,
};
use meshq::math::{ClosestPoint, Ray, RayHit, Triangle};
use meshq::mesh::ValidMesh;
use self_cell::self_cell;

/// What a [`crate::MeshBvh`] owns: a mesh and the BVH built from it, or a blob's bytes.
pub enum Owner {
    /// Built in this module from JavaScript arrays.
    Built {
        /// Vertex positions, `x y z` per vertex.
        positions: Vec<f32>,
        /// Triangle corner indices, three per triangle.
        indices: Vec<u32>,
        /// The used BVH nodes.
        nodes: Vec<BvhNode>,
        /// The BVH's triangle order.
        order: Vec<u32>,
        /// The triangles copied in leaf order (`Bvh::pack_triangles`), so a leaf reads one
        /// contiguous run: about 15–20 % faster rays for 36 bytes per triangle.
        packed: Vec<PackedTriangle>,
        /// The tree collapsed four-wide (`Bvh::widen`), which ray and closest-point queries
        /// walk: fewer, fuller nodes, so fewer dependent memory loads per query.
        wide: Vec<WideNode>,
    },
    /// A blob, loaded (and validated) as is.
    Blob(Vec<u8>),
}

/// The validated views over an [`Owner`].
pub enum Views<'a> {
    /// A BVH over a mesh, both in slices.
    Built {
        /// The mesh.
        mesh: ValidMesh<'a>,
        /// Its BVH.
        bvh: Bvh<'a>,
        /// The same tree, four-wide (same answers, bit for bit).
        wide: WideBvh<'a>,
        /// The mesh's triangles in the BVH's leaf order.
        packed: LeafOrder<'a>,
    },
    /// A blob queried in place.
    Blob(BlobView<'a>),
}

/// Triangles packed in a BVH's leaf order, read by order slot.
#[derive(Clone, Copy)]
pub struct LeafOrder<'a>(pub &'a [PackedTriangle]);

impl LeafTriangles for LeafOrder<'_> {
    #[inline(always)]
    fn corners(&self, slot: usize, _tri: u32) -> Option<Triangle> {
        self.0.get(slot).map(PackedTriangle::triangle)
    }

    #[inline(always)]
    fn run(&self, first: usize, count: usize) -> Option<&[PackedTriangle]> {
        self.0.get(first..first.checked_add(count)?)
    }
}

self_cell!(
    /// An [`Owner`] and its [`Views`].
    pub struct Storage {
        owner: Owner,
        #[covariant]
        dependent: Views,
    }
);

impl Views<'_> {
    pub fn raycast(&self, ray: &Ray, options: &RayOptions) -> Option<RayHit> {
        match self {
            Self::Built { wide, packed, .. } => wide.raycast_with(packed, ray, options),
            Self::Blob(view) => view.raycast_with(ray, options),
        }
    }

    pub fn raycast_any(&self, ray: &Ray, options: &RayOptions) -> bool {
        match self {
            Self::Built { wide, packed, .. } => wide.raycast_any_with(packed, ray, options),
            Self::Blob(view) => view.raycast_any_with(ray, options),
        }
    }

    pub fn closest_point(&self, point: glam::Vec3, max_distance: f32) -> Option<ClosestPoint> {
        match self {
            Self::Built { wide, packed, .. } => wide.closest_point(packed, point, max_distance),
            Self::Blob(view) => view.closest_point(point, max_distance),
        }
    }

    pub fn traverse<V: meshq::bvh::BvhVisitor>(&self, visitor: &mut V) {
        match self {
            Self::Built { bvh, .. } => bvh.traverse(visitor),
            Self::Blob(view) => view.traverse(visitor),
        }
    }

    pub fn triangle(&self, index: u32) -> Option<Triangle> {
        match self {
            Self::Built { mesh, .. } => mesh.triangle(index),
            Self::Blob(view) => view.mesh().triangle(index),
        }
    }

    pub fn triangle_count(&self) -> u32 {
        match self {
            Self::Built { mesh, .. } => u32::try_from(mesh.triangle_count()).unwrap_or(u32::MAX),
            Self::Blob(view) => view.header().triangle_count,
        }
    }

    pub fn node_count(&self) -> usize {
        match self {
            Self::Built { bvh, .. } => bvh.nodes().len(),
            Self::Blob(view) => view.tree().node_count(),
        }
    }

    pub fn node(&self, index: usize) -> Option<BvhNode> {
        match self {
            Self::Built { bvh, .. } => bvh.nodes().get(index).copied(),
            Self::Blob(view) => view.tree().node(index),
        }
    }

    pub fn depth(&self) -> u32 {
        match self {
            Self::Built { bvh, .. } => bvh.depth(),
            Self::Blob(view) => view.header().depth,
        }
    }

    pub fn bounds(&self) -> meshq::math::Aabb {
        match self {
            Self::Built { bvh, .. } => bvh.bounds(),
            Self::Blob(view) => view.bounds(),
        }
    }
}

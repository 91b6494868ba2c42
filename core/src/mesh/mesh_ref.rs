use crate::error::{FlatSlice, MeshError};

use super::{MAX_COORDINATE, ValidMesh};

/// A borrowed, unvalidated triangle mesh: vertex positions and triangles as vertex-index triples.
///
/// Triangles are counter-clockwise seen from their front (see
/// [`Triangle`](crate::math::Triangle)). Nothing is copied and nothing is ever written.
#[derive(Clone, Copy, Debug)]
pub struct MeshRef<'a> {
    positions: &'a [[f32; 3]],
    triangles: &'a [[u32; 3]],
}

impl<'a> MeshRef<'a> {
    /// A mesh over `positions` (`[x, y, z]`) and `triangles` (three vertex indices each).
    #[must_use]
    pub const fn new(positions: &'a [[f32; 3]], triangles: &'a [[u32; 3]]) -> Self {
        Self {
            positions,
            triangles,
        }
    }

    /// A mesh over flat buffers, `x0 y0 z0 x1 …` and `i0 j0 k0 i1 …` — the layout of a three.js
    /// `BufferGeometry`'s position attribute and index — viewed as triples without copying.
    ///
    /// # Errors
    /// [`MeshError::FlatLength`] when a length is not a multiple of 3.
    pub fn from_flat(positions: &'a [f32], indices: &'a [u32]) -> Result<Self, MeshError> {
        let (p, rest) = positions.as_chunks::<3>();
        if !rest.is_empty() {
            return Err(MeshError::FlatLength {
                what: FlatSlice::Positions,
                len: positions.len(),
            });
        }
        let (t, rest) = indices.as_chunks::<3>();
        if !rest.is_empty() {
            return Err(MeshError::FlatLength {
                what: FlatSlice::Indices,
                len: indices.len(),
            });
        }
        Ok(Self::new(p, t))
    }

    /// The positions as given.
    #[must_use]
    pub const fn positions(&self) -> &'a [[f32; 3]] {
        self.positions
    }

    /// The triangles as given.
    #[must_use]
    pub const fn triangles(&self) -> &'a [[u32; 3]] {
        self.triangles
    }

    /// Checks the mesh once: counts fit in `u32`, every coordinate is finite and within
    /// ±[`MAX_COORDINATE`], every index names an existing vertex. Zero-area triangles are
    /// allowed (they are kept and never reported by queries). An empty mesh is valid.
    ///
    /// Vertices are checked before triangles; the first problem found is reported.
    ///
    /// # Errors
    /// The [`MeshError`] naming the offending vertex or triangle.
    pub fn validate(self) -> Result<ValidMesh<'a>, MeshError> {
        let vertex_count =
            u32::try_from(self.positions.len()).map_err(|_| MeshError::TooManyVertices {
                count: self.positions.len(),
            })?;
        u32::try_from(self.triangles.len()).map_err(|_| MeshError::TooManyTriangles {
            count: self.triangles.len(),
        })?;
        // A fast pass decides; only a bad mesh takes the slow pass that names the culprit. One
        // comparison per coordinate covers both rules of `check_vertex` (NaN and ±∞ fail
        // `abs() <= MAX_COORDINATE` too), and both folds run without early exits, so they
        // vectorise.
        let coordinates_ok = self
            .positions
            .iter()
            .flatten()
            .fold(true, |ok, c| ok & (c.abs() <= MAX_COORDINATE));
        if !coordinates_ok {
            for (vertex, &p) in (0u32..).zip(self.positions) {
                check_vertex(vertex, p)?;
            }
        }
        let indices_ok = self
            .triangles
            .iter()
            .flatten()
            .fold(true, |ok, &i| ok & (i < vertex_count));
        if !indices_ok {
            for (triangle, &t) in (0u32..).zip(self.triangles) {
                check_triangle(triangle, t, vertex_count)?;
            }
        }
        Ok(ValidMesh::new_unchecked_by_validate(
            self.positions,
            self.triangles,
        ))
    }
}

/// The rule every stored vertex obeys: finite coordinates within ±[`MAX_COORDINATE`].
pub(crate) fn check_vertex(vertex: u32, p: [f32; 3]) -> Result<(), MeshError> {
    if p.iter().any(|c| !c.is_finite()) {
        return Err(MeshError::NonFiniteCoordinate { vertex });
    }
    if p.iter().any(|c| c.abs() > MAX_COORDINATE) {
        return Err(MeshError::CoordinateTooLarge { vertex });
    }
    Ok(())
}

/// The rule every stored triangle obeys: its three indices name existing vertices.
pub(crate) fn check_triangle(
    triangle: u32,
    t: [u32; 3],
    vertex_count: u32,
) -> Result<(), MeshError> {
    match t.into_iter().find(|&i| i >= vertex_count) {
        Some(index) => Err(MeshError::IndexOutOfRange {
            triangle,
            index,
            vertex_count,
        }),
        None => Ok(()),
    }
}

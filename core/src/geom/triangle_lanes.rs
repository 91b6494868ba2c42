//! Four triangles side by side, one per SIMD lane, for the leaf tests that take four at once
//! (closest point, watertight ray filter).

use glam::{BVec4A, Mat4, Vec3, Vec4};

use crate::math::{PackedTriangle, Triangle};

/// Four points, a lane each: the x, y and z rows.
#[derive(Clone, Copy)]
pub(crate) struct Lanes3 {
    pub(crate) rows: [Vec4; 3],
}

impl Lanes3 {
    #[inline(always)]
    pub(crate) fn splat(p: Vec3) -> Self {
        Self {
            rows: [Vec4::splat(p.x), Vec4::splat(p.y), Vec4::splat(p.z)],
        }
    }

    /// Coordinate `k` (0 = x, 1 = y, anything else z) of the four points, read where it is
    /// stored: the row is found by its offset (`k` clamped, so no bounds check), not by a
    /// branch per axis that a new ray's frame would mispredict.
    #[inline(always)]
    pub(crate) fn axis_ref(&self, k: usize) -> &Vec4 {
        let [.., z] = &self.rows;
        self.rows.get(k.min(2)).unwrap_or(z)
    }

    #[inline(always)]
    pub(crate) fn sub(self, o: Self) -> Self {
        let ([x, y, z], [ox, oy, oz]) = (self.rows, o.rows);
        Self {
            rows: [x - ox, y - oy, z - oz],
        }
    }

    /// `self + d·s`, per component, as the scalar `a + ab * s`.
    #[inline(always)]
    pub(crate) fn add_scaled(self, d: Self, s: Vec4) -> Self {
        let ([x, y, z], [dx, dy, dz]) = (self.rows, d.rows);
        Self {
            rows: [x + dx * s, y + dy * s, z + dz * s],
        }
    }

    /// `x·x' + y·y' + z·z'`, left to right, as [`dot`](crate::math::dot).
    #[inline(always)]
    pub(crate) fn dot(self, o: Self) -> Vec4 {
        let ([x, y, z], [ox, oy, oz]) = (self.rows, o.rows);
        x * ox + y * oy + z * oz
    }

    /// The cross product per lane, component by component as [`cross`](crate::math::cross).
    #[inline(always)]
    pub(crate) fn cross(self, o: Self) -> Self {
        let ([x, y, z], [ox, oy, oz]) = (self.rows, o.rows);
        Self {
            rows: [y * oz - z * oy, z * ox - x * oz, x * oy - y * ox],
        }
    }

    #[inline(always)]
    pub(crate) fn select(mask: BVec4A, yes: Self, no: Self) -> Self {
        let ([yx, yy, yz], [nx, ny, nz]) = (yes.rows, no.rows);
        Self {
            rows: [
                Vec4::select(mask, yx, nx),
                Vec4::select(mask, yy, ny),
                Vec4::select(mask, yz, nz),
            ],
        }
    }
}

/// Four triangles, corner coordinates spread over lanes.
#[derive(Clone, Copy)]
pub(crate) struct TriangleLanes {
    pub(crate) a: Lanes3,
    pub(crate) b: Lanes3,
    pub(crate) c: Lanes3,
}

impl TriangleLanes {
    /// Lane `i` holds `tris[i]`.
    #[inline(always)]
    pub(crate) fn new(tris: &[Triangle; 4]) -> Self {
        let [t0, t1, t2, t3] = tris;
        let axis = |f: fn(&Triangle) -> Vec3| {
            let (p0, p1, p2, p3) = (f(t0), f(t1), f(t2), f(t3));
            Lanes3 {
                rows: [
                    Vec4::new(p0.x, p1.x, p2.x, p3.x),
                    Vec4::new(p0.y, p1.y, p2.y, p3.y),
                    Vec4::new(p0.z, p1.z, p2.z, p3.z),
                ],
            }
        };
        Self {
            a: axis(|t| t.a),
            b: axis(|t| t.b),
            c: axis(|t| t.c),
        }
    }

    /// Lane `i` holds `tris[i]`, loaded as rows and transposed; lanes past the end repeat the
    /// first triangle. `None` for an empty slice; only the first four are read.
    #[inline(always)]
    pub(crate) fn from_packed(tris: &[PackedTriangle]) -> Option<Self> {
        let first = tris.first()?;
        let t = |i: usize| tris.get(i).unwrap_or(first);
        // A triangle's nine floats as two rows of four and one left over.
        let head = |t: &PackedTriangle| Vec4::new(t.a[0], t.a[1], t.a[2], t.b[0]);
        let mid = |t: &PackedTriangle| Vec4::new(t.b[1], t.b[2], t.c[0], t.c[1]);
        let (t0, t1, t2, t3) = (t(0), t(1), t(2), t(3));
        let h = Mat4::from_cols(head(t0), head(t1), head(t2), head(t3)).transpose();
        let m = Mat4::from_cols(mid(t0), mid(t1), mid(t2), mid(t3)).transpose();
        Some(Self {
            a: Lanes3 {
                rows: [h.x_axis, h.y_axis, h.z_axis],
            },
            b: Lanes3 {
                rows: [h.w_axis, m.x_axis, m.y_axis],
            },
            c: Lanes3 {
                rows: [
                    m.z_axis,
                    m.w_axis,
                    Vec4::new(t0.c[2], t1.c[2], t2.c[2], t3.c[2]),
                ],
            },
        })
    }
}

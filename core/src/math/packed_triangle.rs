//! A triangle's corners stored by value, the record packed triangle arrays and blobs hold.

use serde::{Deserialize, Serialize};

use super::Triangle;
use glam::Vec3;

/// A triangle's corners by value: 36 bytes, a plain `#[repr(C)]` record.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PackedTriangle {
    /// First corner.
    pub a: [f32; 3],
    /// Second corner.
    pub b: [f32; 3],
    /// Third corner.
    pub c: [f32; 3],
}

impl PackedTriangle {
    /// A placeholder for initializing buffers.
    pub const EMPTY: Self = Self {
        a: [0.0; 3],
        b: [0.0; 3],
        c: [0.0; 3],
    };

    /// The corners of `t`, stored.
    #[inline]
    #[must_use]
    pub fn new(t: &Triangle) -> Self {
        Self {
            a: t.a.to_array(),
            b: t.b.to_array(),
            c: t.c.to_array(),
        }
    }

    /// The corners as a [`Triangle`].
    #[inline(always)]
    #[must_use]
    pub fn triangle(&self) -> Triangle {
        Triangle::new(
            Vec3::from_array(self.a),
            Vec3::from_array(self.b),
            Vec3::from_array(self.c),
        )
    }
}

const _: () = assert!(core::mem::size_of::<PackedTriangle>() == 36);

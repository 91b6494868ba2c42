//! `geometry`: the core's primitive tests as plain functions, for JavaScript code that has no
//! mesh (or wants one triangle's answer): closest points on a triangle (by each method), a
//! segment and a plane; ray against triangle (by each test), plane and box; triangle against
//! box and triangle; the solid angle of a triangle.
//!
//! Exported as a class of static methods, `geometry.closestPointTriangle(…)`, so the package's
//! namespace stays small. Arguments are read as strictly as everywhere else (see
//! [`crate::args`]); every result is a fresh plain object or a primitive.

use js_sys::Object;
use meshq::geom::{
    closest_point_plane, closest_point_segment, closest_point_triangle,
    closest_point_triangle_projection, closest_point_triangle_rotation,
    closest_points_segment_segment, intersect_ray_aabb, intersect_ray_plane,
    intersect_ray_triangle, intersect_ray_triangle_two_step, intersect_ray_triangle_watertight,
    overlap_triangle_aabb, point_on_plane, point_on_segment, solid_angle_triangle, triangles_meet,
};
use meshq::math::{Aabb, ClosestPoint, Plane, Triangle, TriangleFeature, Vec3};
use meshq::query::TriangleTest;
use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;

use crate::args::{finite, range_error, side, vector};
use crate::fields::{omitted, optional_choice, optional_number};
use crate::js_objects::set;
use crate::mesh_bvh::{js_ray, or_undefined};

/// The primitive tests, as static methods (`geometry.intersectRayTriangle(…)`).
#[wasm_bindgen(js_name = geometry)]
pub struct Geometry;

/// The names of the closest-point methods, in `ClosestPointMethod` order.
const CLOSEST_METHODS: [&str; 3] = ["regions", "projection", "rotation"];

fn xyz(v: Vec3) -> Result<JsValue, JsValue> {
    let o = Object::new();
    set(&o, "x", v.x)?;
    set(&o, "y", v.y)?;
    set(&o, "z", v.z)?;
    Ok(o.into())
}

fn triangle(a: &JsValue, b: &JsValue, c: &JsValue) -> Result<Triangle, JsValue> {
    Ok(Triangle::new(
        vector(a, "a")?,
        vector(b, "b")?,
        vector(c, "c")?,
    ))
}

fn plane(normal: &JsValue, offset: &JsValue) -> Result<Plane, JsValue> {
    let normal = vector(normal, "normal")?;
    if normal == Vec3::ZERO {
        return Err(range_error("normal must not be zero"));
    }
    Ok(Plane {
        normal,
        offset: finite(offset, "offset")?,
    })
}

fn aabb(min: &JsValue, max: &JsValue) -> Result<Aabb, JsValue> {
    let (min, max) = (vector(min, "min")?, vector(max, "max")?);
    if !min.cmple(max).all() {
        return Err(range_error("min must not exceed max on any axis"));
    }
    Ok(Aabb::new(min, max))
}

/// The distance between two points, in `f64` (an `f32` square would overflow past 1.8e19).
fn distance(p: Vec3, q: Vec3) -> f64 {
    let dx = f64::from(p.x) - f64::from(q.x);
    let dy = f64::from(p.y) - f64::from(q.y);
    let dz = f64::from(p.z) - f64::from(q.z);
    (dx * dx + dy * dy + dz * dz).sqrt()
}

/// `{ point, distance, u, v, feature, featureIndex }` of the closest point `c` to `p` on a
/// triangle.
fn closest_object(p: Vec3, c: &ClosestPoint) -> Result<JsValue, JsValue> {
    let (feature, index) = match c.feature {
        TriangleFeature::Face => ("face", 0),
        TriangleFeature::Edge(i) => ("edge", i),
        TriangleFeature::Vertex(i) => ("vertex", i),
    };
    let o = Object::new();
    set(&o, "point", xyz(c.point)?)?;
    set(&o, "distance", distance(p, c.point))?;
    set(&o, "u", c.u)?;
    set(&o, "v", c.v)?;
    set(&o, "feature", feature)?;
    set(&o, "featureIndex", index)?;
    Ok(o.into())
}

#[wasm_bindgen(js_class = geometry)]
impl Geometry {
    /// The point of triangle `a, b, c` closest to `point` (all `Vec3Like`): `{ point,
    /// distance, u, v, feature, featureIndex }`, `u`, `v` the weights of `b` and `c`,
    /// `feature` `"face"` (strictly inside), `"edge"` (`featureIndex` 0 = ab, 1 = bc, 2 = ca)
    /// or `"vertex"` (0 = a, 1 = b, 2 = c). `method`: `"regions"` (the default, Ericson's
    /// Voronoi-region walk, which every mesh query uses), `"projection"` (onto the plane, then
    /// half-plane tests) or `"rotation"` (turned onto a plane, solved in 2D, turned back); the
    /// same answer up to rounding. A zero-area triangle is handled as its edges. `"regions"`
    /// takes triangles up to about 10¹⁸ across (beyond, its squared edges overflow and the
    /// result is NaN); the other two rescale and take any size.
    #[wasm_bindgen(js_name = closestPointTriangle, unchecked_return_type = "TriangleClosestPoint")]
    pub fn closest_point_triangle(
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] point: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] a: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] b: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] c: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "ClosestPointMethod | null")] method: Option<JsValue>,
    ) -> Result<JsValue, JsValue> {
        let p = vector(point, "point")?;
        let tri = triangle(a, b, c)?;
        let method = optional_choice(&or_undefined(method), "method", &CLOSEST_METHODS)?;
        let found = match method {
            Some("projection") => closest_point_triangle_projection(p, &tri),
            Some("rotation") => closest_point_triangle_rotation(p, &tri),
            _ => closest_point_triangle(p, &tri),
        };
        closest_object(p, &found)
    }

    /// The point of segment `a, b` closest to `point`: `{ point, t, distance }`, the point at
    /// `a + t·(b − a)`, `t` in `[0, 1]` (0 for a zero-length segment).
    #[wasm_bindgen(js_name = closestPointSegment, unchecked_return_type = "SegmentClosestPoint")]
    pub fn closest_point_segment(
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] point: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] a: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] b: &JsValue,
    ) -> Result<JsValue, JsValue> {
        let p = vector(point, "point")?;
        let (q, t) = closest_point_segment(p, vector(a, "a")?, vector(b, "b")?);
        let o = Object::new();
        set(&o, "point", xyz(q)?)?;
        set(&o, "t", t)?;
        set(&o, "distance", distance(p, q))?;
        Ok(o.into())
    }

    /// The closest points of segments `p1, q1` and `p2, q2`: `{ pointA, pointB, s, t,
    /// distance }`, `pointA = p1 + s·(q1 − p1)`, `pointB = p2 + t·(q2 − p2)`.
    #[wasm_bindgen(js_name = closestPointsSegmentSegment, unchecked_return_type = "SegmentPair")]
    pub fn closest_points_segment_segment(
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] p1: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] q1: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] p2: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] q2: &JsValue,
    ) -> Result<JsValue, JsValue> {
        let r = closest_points_segment_segment(
            vector(p1, "p1")?,
            vector(q1, "q1")?,
            vector(p2, "p2")?,
            vector(q2, "q2")?,
        );
        let o = Object::new();
        set(&o, "pointA", xyz(r.on_first)?)?;
        set(&o, "pointB", xyz(r.on_second)?)?;
        set(&o, "s", r.s)?;
        set(&o, "t", r.t)?;
        set(&o, "distance", distance(r.on_first, r.on_second))?;
        Ok(o.into())
    }

    /// The projection of `point` onto the plane `normal · x = offset` (`normal` not zero, any
    /// length).
    #[wasm_bindgen(js_name = closestPointPlane, unchecked_return_type = "XYZ")]
    pub fn closest_point_plane(
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] point: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] normal: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "number")] offset: &JsValue,
    ) -> Result<JsValue, JsValue> {
        let p = vector(point, "point")?;
        xyz(closest_point_plane(p, &plane(normal, offset)?))
    }

    /// Whether `point` lies on the plane `normal · x = offset` within `relative` (default 0, a
    /// number ≥ 0) times the larger of its largest coordinate and the plane's distance from
    /// the origin, plus the rounding of its coordinates to 32-bit floats.
    #[wasm_bindgen(js_name = pointOnPlane)]
    pub fn point_on_plane(
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] point: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] normal: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "number")] offset: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "number | null")] relative: Option<JsValue>,
    ) -> Result<bool, JsValue> {
        let p = vector(point, "point")?;
        let relative = optional_number(&or_undefined(relative), "relative")?.unwrap_or(0.0);
        if relative < 0.0 {
            return Err(range_error("relative must be a number ≥ 0"));
        }
        Ok(point_on_plane(p, &plane(normal, offset)?, relative as f32))
    }

    /// Whether `point` is within `tolerance` (a distance ≥ 0, inclusive) of segment `a, b`.
    #[wasm_bindgen(js_name = pointOnSegment)]
    pub fn point_on_segment(
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] point: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] a: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] b: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "number")] tolerance: &JsValue,
    ) -> Result<bool, JsValue> {
        let tolerance = finite(tolerance, "tolerance")?;
        if tolerance < 0.0 {
            return Err(range_error("tolerance must be a number ≥ 0"));
        }
        Ok(point_on_segment(
            vector(point, "point")?,
            vector(a, "a")?,
            vector(b, "b")?,
            tolerance,
        ))
    }

    /// Where the ray `origin + t·direction`, `t` in `[near, far]`, hits triangle `a, b, c`:
    /// `{ t, u, v }` (`u`, `v` the weights of `b` and `c`; edges and corners count) or `null`.
    /// `side`: a `Side` or `RayOptions` (`{ side, test }`, the test `"watertight"` by
    /// default, `"moller-trumbore"` or `"two-step"`), as for `MeshBvh.raycast`. A zero-area
    /// triangle is never hit.
    #[wasm_bindgen(js_name = intersectRayTriangle, unchecked_return_type = "TriangleHit | null")]
    #[allow(clippy::too_many_arguments)]
    pub fn intersect_ray_triangle(
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] origin: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] direction: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] a: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] b: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] c: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Side | RayOptions | null")] side_in: Option<JsValue>,
        #[wasm_bindgen(unchecked_param_type = "number | null")] near: Option<JsValue>,
        #[wasm_bindgen(unchecked_param_type = "number | null")] far: Option<JsValue>,
    ) -> Result<JsValue, JsValue> {
        let ray = js_ray(origin, direction, near, far)?;
        let tri = triangle(a, b, c)?;
        let options = side(&or_undefined(side_in))?;
        let hit = match options.test {
            TriangleTest::Watertight => intersect_ray_triangle_watertight(&ray, &tri, options.cull),
            TriangleTest::MollerTrumbore => intersect_ray_triangle(&ray, &tri, options.cull),
            TriangleTest::TwoStep => intersect_ray_triangle_two_step(&ray, &tri, options.cull),
        };
        let Some(hit) = hit else {
            return Ok(JsValue::NULL);
        };
        let o = Object::new();
        set(&o, "t", hit.t)?;
        set(&o, "u", hit.u)?;
        set(&o, "v", hit.v)?;
        Ok(o.into())
    }

    /// The `t` where the ray crosses the plane `normal · x = offset`, within `[near, far]`
    /// (either side of the plane), or `null` (parallel, or out of range).
    #[wasm_bindgen(js_name = intersectRayPlane)]
    pub fn intersect_ray_plane(
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] origin: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] direction: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] normal: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "number")] offset: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "number | null")] near: Option<JsValue>,
        #[wasm_bindgen(unchecked_param_type = "number | null")] far: Option<JsValue>,
    ) -> Result<Option<f32>, JsValue> {
        let ray = js_ray(origin, direction, near, far)?;
        Ok(intersect_ray_plane(&ray, &plane(normal, offset)?))
    }

    /// The ray's span inside the box `min, max` (`min ≤ max` on every axis; faces count):
    /// `{ near, far }`, the entry and exit `t` clipped to `[near, far]`, or `null`.
    #[wasm_bindgen(js_name = intersectRayAabb, unchecked_return_type = "RaySpan | null")]
    pub fn intersect_ray_aabb(
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] origin: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] direction: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] min: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] max: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "number | null")] near: Option<JsValue>,
        #[wasm_bindgen(unchecked_param_type = "number | null")] far: Option<JsValue>,
    ) -> Result<JsValue, JsValue> {
        let ray = js_ray(origin, direction, near, far)?;
        let Some((entry, exit)) = intersect_ray_aabb(&ray, &aabb(min, max)?) else {
            return Ok(JsValue::NULL);
        };
        let o = Object::new();
        set(&o, "near", entry)?;
        set(&o, "far", exit)?;
        Ok(o.into())
    }

    /// Whether triangle `a, b, c` and the box `min, max` share a point (touching counts).
    #[wasm_bindgen(js_name = overlapTriangleAabb)]
    pub fn overlap_triangle_aabb(
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] a: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] b: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] c: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] min: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] max: &JsValue,
    ) -> Result<bool, JsValue> {
        Ok(overlap_triangle_aabb(&triangle(a, b, c)?, &aabb(min, max)?))
    }

    /// Whether two triangles share a point, decided exactly on their coordinates (touching
    /// counts; a zero-area triangle meets nothing). `first` and `second`: three `Vec3Like`
    /// corners each.
    #[wasm_bindgen(js_name = trianglesMeet)]
    pub fn triangles_meet(
        #[wasm_bindgen(unchecked_param_type = "[Vec3Like, Vec3Like, Vec3Like]")] first: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "[Vec3Like, Vec3Like, Vec3Like]")] second: &JsValue,
    ) -> Result<bool, JsValue> {
        Ok(triangles_meet(
            &corners(first, "first")?,
            &corners(second, "second")?,
        ))
    }

    /// The signed solid angle (steradians, in `[−2π, 2π]`) triangle `a, b, c` subtends at
    /// `point`: positive when `point` lies behind it (the side its counter-clockwise normal
    /// points away from), 0 on its plane. Summed over a closed outward mesh and divided by
    /// 4π: the winding number.
    #[wasm_bindgen(js_name = solidAngleTriangle)]
    pub fn solid_angle_triangle(
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] point: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] a: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] b: &JsValue,
        #[wasm_bindgen(unchecked_param_type = "Vec3Like")] c: &JsValue,
    ) -> Result<f32, JsValue> {
        let p = vector(point, "point")?;
        Ok(solid_angle_triangle(&triangle(a, b, c)?, p))
    }
}

/// A triangle given as an array of three corners.
fn corners(value: &JsValue, what: &str) -> Result<Triangle, JsValue> {
    let array = value.dyn_ref::<js_sys::Array>().filter(|_| !omitted(value));
    let Some(array) = array.filter(|a| a.length() == 3) else {
        return Err(crate::args::type_error(&format!(
            "{what} must be an array of three corners, got {}",
            crate::args::value_kind(value)
        )));
    };
    Ok(Triangle::new(
        vector(&array.get(0), &format!("{what}[0]"))?,
        vector(&array.get(1), &format!("{what}[1]"))?,
        vector(&array.get(2), &format!("{what}[2]"))?,
    ))
}

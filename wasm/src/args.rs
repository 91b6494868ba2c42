//! Strict readers of JavaScript arguments: each value is checked before it is used, and a bad
//! one throws a `TypeError` (wrong kind of value) or a `RangeError` (right kind, bad value)
//! naming the argument. Nothing is coerced silently, and nothing is borrowed from the caller
//! across a call, so no misuse can leave the module in a bad state.

use glam::Vec3;
use js_sys::{
    Array, Float32Array, Float64Array, RangeError, Reflect, TypeError, Uint8Array, Uint32Array,
};
use meshq::geom::CullMode;
use meshq::query::{RayOptions, TriangleTest};
use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;

/// A `TypeError` naming `what`.
pub fn type_error(message: &str) -> JsValue {
    TypeError::new(message).into()
}

/// A `RangeError` naming `what`.
pub fn range_error(message: &str) -> JsValue {
    RangeError::new(message).into()
}

/// What kind of value `value` is, for messages.
pub fn value_kind(value: &JsValue) -> String {
    if value.is_undefined() {
        "undefined".into()
    } else if value.is_null() {
        "null".into()
    } else if let Some(name) = value
        .dyn_ref::<js_sys::Object>()
        .map(|o| o.constructor().name())
        .and_then(|n| n.as_string())
    {
        name
    } else {
        value
            .js_typeof()
            .as_string()
            .unwrap_or_else(|| "value".into())
    }
}

/// A number as JavaScript writes it, for error messages: `Infinity`, `-Infinity` and `NaN`
/// (Rust would write `inf` and `NaN`), and an exponent beyond JavaScript's fixed-point range.
pub struct JsNumber(pub f64);

impl core::fmt::Display for JsNumber {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        let x = self.0;
        if x.is_nan() {
            f.write_str("NaN")
        } else if x.is_infinite() {
            f.write_str(if x > 0.0 { "Infinity" } else { "-Infinity" })
        } else if x != 0.0 && !(1e-7..1e21).contains(&x.abs()) {
            // JavaScript switches to exponents outside that range, with an explicit sign.
            let text = format!("{x:e}");
            match text.split_once('e') {
                Some((mantissa, exp)) if !exp.starts_with('-') => write!(f, "{mantissa}e+{exp}"),
                _ => f.write_str(&text),
            }
        } else {
            write!(f, "{x}")
        }
    }
}

/// A number (`f64`) or a `TypeError`.
pub fn number(value: &JsValue, what: &str) -> Result<f64, JsValue> {
    value.as_f64().ok_or_else(|| {
        type_error(&format!(
            "{what} must be a number, got {}",
            value_kind(value)
        ))
    })
}

/// A finite number, as `f32` (values beyond its range are a `RangeError`, not infinity).
pub fn finite(value: &JsValue, what: &str) -> Result<f32, JsValue> {
    let x = number(value, what)?;
    let f = x as f32;
    if !f.is_finite() {
        return Err(range_error(&format!(
            "{what} must be a finite number, got {}",
            JsNumber(x)
        )));
    }
    Ok(f)
}

/// A point or direction: `[x, y, z]` (an array or a typed array of 3 numbers) or an object
/// with numeric `x`, `y`, `z` (a three.js `Vector3`). Every coordinate must be finite.
///
/// This runs on every single-ray call, so the common forms cost as few calls into JavaScript
/// as possible, and error messages are only formatted for an error.
pub fn vector(value: &JsValue, what: &str) -> Result<Vec3, JsValue> {
    const AXES: [&str; 3] = ["x", "y", "z"];
    let three = |length: u32| {
        if length == 3 {
            Ok(())
        } else {
            Err(range_error(&format!(
                "{what} must hold exactly 3 numbers, got {length}"
            )))
        }
    };
    let number = |v: JsValue, axis: usize| {
        v.as_f64().ok_or_else(|| {
            type_error(&format!(
                "{what}.{} must be a number, got {}",
                AXES[axis],
                value_kind(&v)
            ))
        })
    };
    let xyz: [f64; 3] = if let Some(f) = value.dyn_ref::<Float32Array>() {
        three(f.length())?;
        let mut xyz = [0.0f32; 3];
        f.copy_to(&mut xyz);
        xyz.map(f64::from)
    } else if let Some(a) = value.dyn_ref::<Array>() {
        three(a.length())?;
        [
            number(a.get(0), 0)?,
            number(a.get(1), 1)?,
            number(a.get(2), 2)?,
        ]
    } else if let Some(f) = value.dyn_ref::<Float64Array>() {
        three(f.length())?;
        [f.get_index(0), f.get_index(1), f.get_index(2)]
    } else if value.is_object() {
        let get = |axis: usize| {
            let v =
                Reflect::get(value, &JsValue::from_str(AXES[axis])).unwrap_or(JsValue::UNDEFINED);
            number(v, axis)
        };
        [get(0)?, get(1)?, get(2)?]
    } else {
        return Err(type_error(&format!(
            "{what} must be [x, y, z] or an object with x, y, z (a Vector3), got {}",
            value_kind(value)
        )));
    };
    let mut out = [0.0f32; 3];
    for (axis, (o, c)) in out.iter_mut().zip(xyz).enumerate() {
        *o = c as f32;
        if !o.is_finite() {
            return Err(range_error(&format!(
                "{what}.{} must be a finite number, got {}",
                AXES[axis],
                JsNumber(c)
            )));
        }
    }
    Ok(Vec3::from_array(out))
}

/// A number that arrived as a plain `f64` argument (JavaScript turns anything that is not a
/// number into NaN on the way): finite, as `f32`.
pub fn finite_number(x: f64, what: &str) -> Result<f32, JsValue> {
    let f = x as f32;
    if !f.is_finite() {
        return Err(range_error(&format!(
            "{what} must be a finite number, got {}",
            JsNumber(x)
        )));
    }
    Ok(f)
}

/// A ray's `[near, far]` from optional plain numbers: omitted means `0` and `Infinity`;
/// otherwise not NaN, with `near ≤ far`.
pub fn range_numbers(near: Option<f64>, far: Option<f64>) -> Result<(f32, f32), JsValue> {
    let read = |x: Option<f64>, what: &str, default: f32| -> Result<f32, JsValue> {
        match x {
            None => Ok(default),
            Some(x) if x.is_nan() => Err(range_error(&format!(
                "{what} must be a number (or omitted), got NaN"
            ))),
            Some(x) => Ok(x as f32),
        }
    };
    let (n, f) = (read(near, "near", 0.0)?, read(far, "far", f32::INFINITY)?);
    if n > f {
        return Err(range_error(&format!(
            "near ({n}) must not exceed far ({f})"
        )));
    }
    Ok((n, f))
}

/// [`side`] from an optional plain number.
pub fn side_number(value: Option<f64>) -> Result<RayOptions, JsValue> {
    side(&value.map_or(JsValue::UNDEFINED, JsValue::from_f64))
}

/// A ray's `[near, far]`: omitted (`undefined` or `null`) means `0` and `Infinity`; otherwise
/// numbers, not NaN, with `near ≤ far`.
pub fn range(near: &JsValue, far: &JsValue) -> Result<(f32, f32), JsValue> {
    let read = |value: &JsValue, what: &str, default: f32| -> Result<f32, JsValue> {
        if value.is_undefined() || value.is_null() {
            return Ok(default);
        }
        let x = number(value, what)?;
        if x.is_nan() {
            return Err(range_error(&format!("{what} must be a number, got NaN")));
        }
        Ok(x as f32)
    };
    let (n, f) = (read(near, "near", 0.0)?, read(far, "far", f32::INFINITY)?);
    if n > f {
        return Err(range_error(&format!(
            "near ({n}) must not exceed far ({f})"
        )));
    }
    Ok((n, f))
}

/// A distance limit: omitted means `Infinity` (no limit); otherwise a number ≥ 0.
pub fn max_distance(value: &JsValue) -> Result<f32, JsValue> {
    if value.is_undefined() || value.is_null() {
        return Ok(f32::INFINITY);
    }
    let x = number(value, "maxDistance")?;
    if !(x >= 0.0) {
        return Err(range_error(&format!(
            "maxDistance must be a number ≥ 0 (or omitted for no limit), got {}",
            JsNumber(x)
        )));
    }
    Ok(x as f32)
}

/// Ray options from a `side` argument: a three.js material side, or a `RayOptions` object
/// `{ side, test }` with both fields optional.
///
/// Sides: `0` (`THREE.FrontSide`) hits front faces only, `1` (`THREE.BackSide`) back faces
/// only, `2` (`THREE.DoubleSide`) or omitted both; counter-clockwise triangles face front, as
/// in three.js. Tests (`test`): `"watertight"` (the default), `"moller-trumbore"`,
/// `"two-step"` ([`TriangleTest::name`]).
pub fn side(value: &JsValue) -> Result<RayOptions, JsValue> {
    if !value.is_object() {
        return Ok(RayOptions {
            cull: cull(value)?,
            ..RayOptions::default()
        });
    }
    let options = crate::fields::options(
        value,
        "side (a number or { side, test })",
        &["side", "test"],
    )?;
    let options = options.as_ref();
    let names = TriangleTest::ALL.map(TriangleTest::name);
    let test =
        crate::fields::optional_choice(&crate::fields::field(options, "test")?, "test", &names)?
            .and_then(TriangleTest::from_name)
            .unwrap_or_default();
    Ok(RayOptions {
        cull: cull(&crate::fields::field(options, "side")?)?,
        test,
    })
}

/// The faces a `side` number lets a ray hit (see [`side`]).
fn cull(value: &JsValue) -> Result<CullMode, JsValue> {
    if value.is_undefined() || value.is_null() {
        return Ok(CullMode::None);
    }
    match number(value, "side")? {
        0.0 => Ok(CullMode::Back),
        1.0 => Ok(CullMode::Front),
        2.0 => Ok(CullMode::None),
        other => Err(range_error(&format!(
            "side must be 0 (front), 1 (back) or 2 (double), got {}",
            JsNumber(other)
        ))),
    }
}

/// An input `Float32Array`, copied.
pub fn floats(value: &JsValue, what: &str) -> Result<Vec<f32>, JsValue> {
    float_array(value, what).map(|a| a.to_vec())
}

/// Input numbers: a `Float32Array`, not copied (see [`floats`] for the error).
pub fn float_array(value: &JsValue, what: &str) -> Result<Float32Array, JsValue> {
    value.dyn_ref::<Float32Array>().cloned().ok_or_else(|| {
        type_error(&format!(
            "{what} must be a Float32Array, got {}",
            value_kind(value)
        ))
    })
}

/// Input numbers: a `Float32Array` copied, or an array (or other typed array) of numbers
/// converted to `f32` (a value that is not a number becomes NaN, which validation refuses).
pub fn floats_or_numbers(value: &JsValue, what: &str) -> Result<Vec<f32>, JsValue> {
    if let Some(f) = value.dyn_ref::<Float32Array>() {
        return Ok(f.to_vec());
    }
    if Array::is_array(value) || value.is_instance_of::<Float64Array>() {
        return Ok(Float32Array::new(value).to_vec());
    }
    Err(type_error(&format!(
        "{what} must be a Float32Array or an array of numbers, got {}",
        value_kind(value)
    )))
}

/// Checks an output array's length: exactly `needed`.
fn exact(got: u32, needed: usize, what: &str, per: &str) -> Result<(), JsValue> {
    if got as usize != needed {
        return Err(range_error(&format!(
            "{what} holds {got} numbers; it must hold exactly {needed}{per}"
        )));
    }
    Ok(())
}

macro_rules! output {
    ($name:ident, $array:ty, $label:literal) => {
        /// An output array of exactly this type and `needed` elements (`per` explains the
        /// count in the error).
        pub fn $name(
            value: &JsValue,
            what: &str,
            needed: usize,
            per: &str,
        ) -> Result<$array, JsValue> {
            let array = value.dyn_ref::<$array>().ok_or_else(|| {
                type_error(&format!(
                    concat!("{} must be a ", $label, ", got {}"),
                    what,
                    value_kind(value)
                ))
            })?;
            exact(array.length(), needed, what, per)?;
            Ok(array.clone())
        }
    };
}

output!(output_f32, Float32Array, "Float32Array");
output!(output_u32, Uint32Array, "Uint32Array");
output!(output_u8, Uint8Array, "Uint8Array");

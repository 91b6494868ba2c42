//! Structured arguments read as strictly as the plain ones in [`crate::args`]: option objects
//! (unknown keys refused by name), whole numbers, choices among strings, 4×4 matrices and
//! boxes. `undefined` and `null` always mean "omitted"; a value of the wrong kind is a
//! `TypeError`, a value of the right kind but out of range a `RangeError`, each naming the
//! argument. wasm-bindgen's own conversions (`u32`, `Vec<f32>`, `String` parameters) would
//! coerce silently (`"abc"` → 0), so the exported functions take `JsValue`s and read them here.

use js_sys::{Array, Float64Array, Object, Reflect};
use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;

use crate::args::{JsNumber, range_error, type_error, value_kind};

/// Whether `value` is `undefined` or `null`.
pub fn omitted(value: &JsValue) -> bool {
    value.is_undefined() || value.is_null()
}

/// An options object. Omitted: `None`. Otherwise a plain object (not an array, a function, a
/// `Map` or another keyed collection, whose entries are not properties) whose every own key
/// is one of `allowed` (a key whose value is `undefined` counts as omitted).
pub fn options(value: &JsValue, what: &str, allowed: &[&str]) -> Result<Option<Object>, JsValue> {
    if omitted(value) {
        return Ok(None);
    }
    let object = match value.dyn_ref::<Object>() {
        Some(o)
            if value.is_object()
                && !Array::is_array(value)
                && !value.is_function()
                && !value.is_instance_of::<js_sys::Map>()
                && !value.is_instance_of::<js_sys::Set>()
                && !value.is_instance_of::<js_sys::WeakMap>() =>
        {
            o
        }
        _ => {
            return Err(type_error(&format!(
                "{what} must be an object, got {}",
                value_kind(value)
            )));
        }
    };
    for key in Object::keys(object).iter() {
        let key = key.as_string().unwrap_or_default();
        if !allowed.contains(&key.as_str()) {
            return Err(range_error(&format!(
                "{what}: unknown option {key:?} (the options are {})",
                allowed.join(", ")
            )));
        }
    }
    Ok(Some(object.clone()))
}

/// `options[key]`, or `undefined` when there are no options. A getter that throws passes its
/// error on, untouched.
pub fn field(options: Option<&Object>, key: &str) -> Result<JsValue, JsValue> {
    options.map_or(Ok(JsValue::UNDEFINED), |o| {
        Reflect::get(o, &JsValue::from_str(key))
    })
}

/// An optional number: omitted → `None`; a number that is not NaN → `Some`.
pub fn optional_number(value: &JsValue, what: &str) -> Result<Option<f64>, JsValue> {
    if omitted(value) {
        return Ok(None);
    }
    let x = value.as_f64().ok_or_else(|| {
        type_error(&format!(
            "{what} must be a number, got {}",
            value_kind(value)
        ))
    })?;
    if x.is_nan() {
        return Err(range_error(&format!("{what} must be a number, got NaN")));
    }
    Ok(Some(x))
}

/// An optional whole number in `0..=max`: omitted → `None`.
pub fn optional_whole(value: &JsValue, what: &str, max: f64) -> Result<Option<u64>, JsValue> {
    let Some(x) = optional_number(value, what)? else {
        return Ok(None);
    };
    if x.fract() != 0.0 || !(0.0..=max).contains(&x) {
        return Err(range_error(&format!(
            "{what} must be a whole number in 0..={max}, got {}",
            JsNumber(x)
        )));
    }
    Ok(Some(x as u64))
}

/// [`optional_whole`] for a `u32`.
pub fn optional_u32(value: &JsValue, what: &str) -> Result<Option<u32>, JsValue> {
    Ok(optional_whole(value, what, f64::from(u32::MAX))?.map(|n| n as u32))
}

/// A whole number in `0..=u32::MAX` that must be given.
pub fn required_u32(value: &JsValue, what: &str) -> Result<u32, JsValue> {
    optional_u32(value, what)?.ok_or_else(|| {
        type_error(&format!(
            "{what} must be a whole number, got {}",
            value_kind(value)
        ))
    })
}

/// An optional string that must be one of `choices`: omitted → `None`.
pub fn optional_choice(
    value: &JsValue,
    what: &str,
    choices: &[&'static str],
) -> Result<Option<&'static str>, JsValue> {
    if omitted(value) {
        return Ok(None);
    }
    let name = value.as_string().ok_or_else(|| {
        type_error(&format!(
            "{what} must be a string, got {}",
            value_kind(value)
        ))
    })?;
    choices
        .iter()
        .find(|c| **c == name)
        .copied()
        .map(Some)
        .ok_or_else(|| {
            let listed: Vec<String> = choices.iter().map(|c| format!("{c:?}")).collect();
            range_error(&format!(
                "{what} must be one of {}, got {name:?}",
                listed.join(", ")
            ))
        })
}

/// Finite numbers from an array or a typed array, exactly `count` of them (`None`: any count),
/// as `f32` (a value beyond its range is a `RangeError`, not infinity).
pub fn finite_numbers(
    value: &JsValue,
    what: &str,
    count: Option<usize>,
) -> Result<Vec<f32>, JsValue> {
    let raw: Vec<JsValue> = if let Some(a) = value.dyn_ref::<Array>() {
        a.iter().collect()
    } else if js_sys::ArrayBuffer::is_view(value) && !value.is_instance_of::<js_sys::DataView>() {
        Float64Array::new(value)
            .to_vec()
            .into_iter()
            .map(JsValue::from_f64)
            .collect()
    } else {
        return Err(type_error(&format!(
            "{what} must be an array or typed array of numbers, got {}",
            value_kind(value)
        )));
    };
    if let Some(n) = count
        && raw.len() != n
    {
        return Err(range_error(&format!(
            "{what} must hold exactly {n} numbers, got {}",
            raw.len()
        )));
    }
    raw.iter()
        .enumerate()
        .map(|(i, v)| crate::args::finite(v, &format!("{what}[{i}]")))
        .collect()
}

/// An optional 4×4 matrix: 16 numbers in column-major order (three.js `Matrix4.elements`),
/// given as an array, a typed array or a `Matrix4` itself (anything with `elements`).
pub fn optional_matrix(value: &JsValue, what: &str) -> Result<Option<[f32; 16]>, JsValue> {
    if omitted(value) {
        return Ok(None);
    }
    let elements =
        if value.is_object() && !Array::is_array(value) && !js_sys::ArrayBuffer::is_view(value) {
            Reflect::get(value, &JsValue::from_str("elements")).unwrap_or(JsValue::UNDEFINED)
        } else {
            value.clone()
        };
    if omitted(&elements) {
        return Err(type_error(&format!(
            "{what} must be 16 numbers (column-major, like Matrix4.elements) or a Matrix4, got {}",
            value_kind(value)
        )));
    }
    let numbers = finite_numbers(&elements, what, Some(16))?;
    let mut m = [0.0f32; 16];
    m.copy_from_slice(&numbers);
    Ok(Some(m))
}

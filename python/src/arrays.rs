//! numpy arrays in and out: inputs read as C-contiguous `float32` / `uint32` (converted once by
//! numpy when they are anything else), outputs handed to numpy without a copy.

use glam::Vec3;
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// `obj` as a C-contiguous, aligned numpy array of `dtype` (the array itself when it is one;
/// arrays unpickled from a buffer may be misaligned), or a `TypeError` naming `name`.
fn contiguous<'py>(
    obj: &Bound<'py, PyAny>,
    dtype: &str,
    name: &str,
) -> PyResult<Bound<'py, PyAny>> {
    let py = obj.py();
    let numpy = py.import("numpy")?;
    let kwargs = PyDict::new(py);
    kwargs.set_item("dtype", dtype)?;
    kwargs.set_item("requirements", "CA")?;
    numpy
        .call_method("require", (obj,), Some(&kwargs))
        .map_err(|e| PyTypeError::new_err(format!("{name} must be an array of numbers: {e}")))
}

/// The rows of an `(n, 3)` array of floats (`float32`, or converted to it), each checked
/// finite. A single row of 3 numbers is taken as `n = 1`.
pub fn vec3s(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<Vec<Vec3>> {
    with_floats(obj, name, 3, |flat| {
        finite_rows(flat, name)?;
        Ok(flat
            .chunks_exact(3)
            .map(|p| Vec3::new(p[0], p[1], p[2]))
            .collect())
    })
}

/// A `ValueError` naming the first value of `flat` (rows of 3) that is not finite.
pub fn finite_rows(flat: &[f32], name: &str) -> PyResult<()> {
    match flat.iter().position(|x| !x.is_finite()) {
        None => Ok(()),
        Some(at) => Err(PyValueError::new_err(format!(
            "{name}[{}, {}] is not finite as float32: {}",
            at / 3,
            at % 3,
            flat.get(at).copied().unwrap_or(f32::NAN)
        ))),
    }
}

/// Runs `read` on the values of an `(n, width)` float array, as one flat `float32` slice
/// borrowed from the array itself when it is C-contiguous, aligned `float32` (else from the
/// one conversion numpy makes).
pub fn with_floats<R>(
    obj: &Bound<'_, PyAny>,
    name: &str,
    width: usize,
    read: impl FnOnce(&[f32]) -> PyResult<R>,
) -> PyResult<R> {
    let array = contiguous(obj, "float32", name)?;
    let array = shaped::<f32>(&array, name, width)?;
    let readonly = array.readonly();
    read(readonly.as_slice()?)
}

/// The values of an `(n, width)` float array as one flat `float32` vector (not checked finite).
pub fn floats(obj: &Bound<'_, PyAny>, name: &str, width: usize) -> PyResult<Vec<f32>> {
    with_floats(obj, name, width, |flat| Ok(flat.to_vec()))
}

/// The values of an `(n, width)` array of whole numbers in `0..2^32` as `uint32`.
pub fn indices(obj: &Bound<'_, PyAny>, name: &str, width: usize) -> PyResult<Vec<u32>> {
    let py = obj.py();
    let numpy = py.import("numpy")?;
    let array = numpy.call_method1("asarray", (obj,))?;
    let kind: String = array.getattr("dtype")?.getattr("kind")?.extract()?;
    if kind != "i" && kind != "u" {
        return Err(PyTypeError::new_err(format!(
            "{name} must hold integers, got dtype {}",
            array.getattr("dtype")?.str()?
        )));
    }
    let size: usize = array.getattr("size")?.extract()?;
    if size > 0 {
        let low: i128 = array.call_method0("min")?.extract()?;
        let high: i128 = array.call_method0("max")?.extract()?;
        if low < 0 || high > i128::from(u32::MAX) {
            return Err(PyValueError::new_err(format!(
                "{name} must lie in 0..2^32, got values from {low} to {high}"
            )));
        }
    }
    let array = contiguous(&array, "uint32", name)?;
    let array = shaped::<u32>(&array, name, width)?;
    let readonly = array.readonly();
    Ok(readonly.as_slice()?.to_vec())
}

/// `array` checked to be `(n, width)` (or `(width,)`, one row) and cast to a 2-D array.
fn shaped<'py, T: numpy::Element>(
    array: &Bound<'py, PyAny>,
    name: &str,
    width: usize,
) -> PyResult<Bound<'py, PyArray2<T>>> {
    let shape: Vec<usize> = array.getattr("shape")?.extract()?;
    let array = match shape.as_slice() {
        [n] if *n == width => array.call_method1("reshape", (1, width))?,
        [_, w] if *w == width => array.clone(),
        _ => {
            return Err(PyValueError::new_err(format!(
                "{name} must have shape (n, {width}), got {shape:?}"
            )));
        }
    };
    Ok(array.cast_into::<PyArray2<T>>()?)
}

/// A vector of `n × width` values as an `(n, width)` array, without a copy.
pub fn rows<'py, T: numpy::Element>(
    py: Python<'py>,
    values: Vec<T>,
    width: usize,
) -> PyResult<Bound<'py, PyArray2<T>>> {
    let n = values.len() / width.max(1);
    PyArray1::from_vec(py, values).reshape([n, width])
}

/// A vector as a 1-D array, without a copy.
pub fn column<T: numpy::Element>(py: Python<'_>, values: Vec<T>) -> Bound<'_, PyArray1<T>> {
    PyArray1::from_vec(py, values)
}

/// An optional whole-number argument (`None` when omitted or `None`): a Python or numpy
/// integer in `0..=max`, or a `TypeError` / `ValueError` naming `name`.
pub fn whole(value: Option<&Bound<'_, PyAny>>, name: &str, max: u64) -> PyResult<Option<u64>> {
    let Some(value) = value.filter(|v| !v.is_none()) else {
        return Ok(None);
    };
    let kind = || {
        value
            .get_type()
            .name()
            .map_or_else(|_| "?".to_owned(), |n| n.to_string())
    };
    if value.is_instance_of::<pyo3::types::PyBool>() {
        return Err(PyTypeError::new_err(format!(
            "{name} must be a whole number, got bool"
        )));
    }
    let n: i128 = value.extract().map_err(|_| {
        PyTypeError::new_err(format!("{name} must be a whole number, got {}", kind()))
    })?;
    if n < 0 || n > i128::from(max) {
        return Err(PyValueError::new_err(format!(
            "{name} must be in 0..={max}, got {n}"
        )));
    }
    Ok(u64::try_from(n).ok())
}

/// [`whole`] for a count of items held in memory.
pub fn count(value: Option<&Bound<'_, PyAny>>, name: &str) -> PyResult<Option<usize>> {
    Ok(whole(value, name, usize::MAX as u64)?.map(|n| usize::try_from(n).unwrap_or(usize::MAX)))
}

/// [`whole`] for a 32-bit setting.
pub fn setting(value: Option<&Bound<'_, PyAny>>, name: &str) -> PyResult<Option<u32>> {
    Ok(whole(value, name, u64::from(u32::MAX))?.map(|n| u32::try_from(n).unwrap_or(u32::MAX)))
}

/// A point from three numbers (a sequence or an array), each finite.
pub fn point(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<Vec3> {
    match vec3s(obj, name)?.as_slice() {
        [p] => Ok(*p),
        other => Err(PyValueError::new_err(format!(
            "{name} must be one point of 3 numbers, got {} rows",
            other.len()
        ))),
    }
}

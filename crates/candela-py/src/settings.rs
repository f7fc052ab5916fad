//! Keyword arguments into the one settings description.
//!
//! `Scene.render(**kwargs)` passes every keyword except the two that only a
//! Python caller splits work by (`sample_range`, `passes`) to
//! [`Settings::resolve`] as JSON, so the keywords are the settings' own names
//! and every setting the CLI has is a keyword here with no code of its own.

use candela_render::settings::{Settings, SettingsError};
use candela_scene::RenderHints;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use serde_json::{Map, Number, Value};
use std::ops::Range;

/// Everything one `Scene.render` call asks for, validated.
#[derive(Clone, Debug)]
pub struct RenderRequest {
    /// The render's settings (defaults < scene hints < keywords).
    pub settings: Settings,
    /// Sample indices to render in each pixel, split into `passes`.
    pub samples: Range<u32>,
    /// Number of consecutive sample ranges, merged in order.
    pub passes: u32,
}

/// A settings error as Python's `ValueError`.
pub fn value_error(e: SettingsError) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// A Python value as JSON: None, bools, ints, finite floats, strings,
/// paths, and lists, tuples and dicts of these. `key` names the keyword in
/// errors.
pub fn to_json(key: &str, v: &Bound<'_, PyAny>) -> PyResult<Value> {
    let bad = |what: &str| PyValueError::new_err(format!("{key}={v}: {what}"));
    if v.is_none() {
        return Ok(Value::Null);
    }
    if v.is_instance_of::<PyBool>() {
        return Ok(Value::Bool(v.extract()?));
    }
    if v.is_instance_of::<PyInt>() {
        return match v.extract::<i64>() {
            Ok(i) => Ok(i.into()),
            Err(_) => v
                .extract::<u64>()
                .map(Value::from)
                .map_err(|_| bad("integer out of range")),
        };
    }
    if v.is_instance_of::<PyFloat>() {
        let f: f64 = v.extract()?;
        return Number::from_f64(f)
            .map(Value::Number)
            .ok_or_else(|| bad("expected a finite number"));
    }
    if v.is_instance_of::<PyString>() {
        return Ok(Value::String(v.extract()?));
    }
    if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
        let items: PyResult<Vec<Value>> = v.try_iter()?.map(|item| to_json(key, &item?)).collect();
        return Ok(Value::Array(items?));
    }
    if let Ok(d) = v.cast::<PyDict>() {
        let mut m = Map::new();
        for (k, item) in d.iter() {
            m.insert(k.extract::<String>()?, to_json(key, &item)?);
        }
        return Ok(Value::Object(m));
    }
    if let Ok(path) = v.extract::<std::path::PathBuf>() {
        return Ok(Value::String(path.to_string_lossy().into_owned()));
    }
    Err(bad(
        "expected None, a bool, a number, a string, a path, or a list of these",
    ))
}

/// Keyword arguments as a JSON object of settings.
pub fn kwargs_json(kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<Map<String, Value>> {
    let mut m = Map::new();
    if let Some(kwargs) = kwargs {
        for (k, v) in kwargs.iter() {
            let key: String = k.extract()?;
            let value = to_json(&key, &v)?;
            m.insert(key, value);
        }
    }
    Ok(m)
}

/// Pulls `sample_range` and `passes` out of the keywords and resolves the
/// rest against the scene's hints.
pub fn request(hints: &RenderHints, mut kwargs: Map<String, Value>) -> PyResult<RenderRequest> {
    let sample_range = kwargs.remove("sample_range");
    let passes = kwargs.remove("passes");
    let settings = Settings::resolve(hints, &kwargs).map_err(value_error)?;
    if settings.integrator.bounce_layers.is_some() || settings.integrator.technique_layers {
        // Refused, not dropped: the Python film and its wire format carry
        // the film's fixed sums only.
        return Err(PyValueError::new_err(
            "bounce_layers / technique_layers: Python films do not carry extra layers yet; \
             render them with the candela command (they are EXR layers)",
        ));
    }
    let spp = settings.sampling.spp();
    let samples = match sample_range {
        None | Some(Value::Null) => 0..spp,
        Some(v) => match serde_json::from_value::<(u32, u32)>(v.clone()) {
            Ok((s0, s1)) if s0 < s1 && s1 <= spp => s0..s1,
            _ => {
                return Err(PyValueError::new_err(format!(
                    "sample_range={v}: expected (start, end) with start < end <= spp ({spp})"
                )))
            }
        },
    };
    let n = samples.end - samples.start;
    let passes = match passes {
        None | Some(Value::Null) => 1,
        Some(v) => match v.as_u64() {
            Some(p) if (1..=n as u64).contains(&p) => p as u32,
            _ => {
                return Err(PyValueError::new_err(format!(
                    "passes={v}: expected 1 to {n} (one sample per pass at least)"
                )))
            }
        },
    };
    Ok(RenderRequest {
        settings,
        samples,
        passes,
    })
}

/// `range` cut into `passes` consecutive parts whose lengths differ by at
/// most one. Local and distributed renders use this same split, so their
/// per-pixel sums are added in the same order.
pub fn split_samples(range: &Range<u32>, passes: u32) -> Vec<Range<u32>> {
    let n = range.end - range.start;
    (0..passes)
        .map(|k| {
            let at = |k: u32| range.start + (n as u64 * k as u64 / passes as u64) as u32;
            at(k)..at(k + 1)
        })
        .collect()
}

/// The help of every setting, by name: the same text as `candela --help`
/// (written once, in `candela_render::settings::help`).
pub fn settings_help() -> Vec<(String, String)> {
    candela_render::settings::help()
}

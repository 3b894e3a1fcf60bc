//! What the scan tests share: running the Python oracles of `tools/oracles/`, reading their
//! JSON dumps, the real samples' folder and f32 tolerances.
#![allow(dead_code)]

pub mod bags;

use fixtures::oracles;
use glam::{DAffine3, DQuat, DVec3, Vec3};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Runs `tools/oracles/<script>` with the oracle venv's Python; `false` (after saying why) when
/// the venv is missing and oracles are not required.
pub fn run_oracle(script: &str, args: &[&Path]) -> bool {
    let Some(python) = oracles::python() else {
        return false;
    };
    oracles::run_ok(Command::new(python).arg(oracles::script(script)).args(args));
    true
}

/// `tools/oracles/read_reference.py FILE`: what pye57 / laspy read from `file`.
pub fn reference(file: &Path) -> Option<Value> {
    let out = file.with_extension("reference.json");
    run_oracle("read_reference.py", &[file, &out]).then(|| read_json(&out))
}

/// A JSON file.
pub fn read_json(path: &Path) -> Value {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// An array of numbers (`null` for NaN) as `Option<f64>`s.
pub fn opt_f64s(v: &Value) -> Vec<Option<f64>> {
    v.as_array()
        .expect("an array")
        .iter()
        .map(Value::as_f64)
        .collect()
}

/// An array of numbers, none null.
pub fn f64s(v: &Value) -> Vec<f64> {
    opt_f64s(v)
        .into_iter()
        .map(|x| x.expect("a number"))
        .collect()
}

/// An array of integers.
pub fn i64s(v: &Value) -> Vec<i64> {
    v.as_array()
        .expect("an array")
        .iter()
        .map(|x| x.as_i64().expect("an integer"))
        .collect()
}

/// The real public samples (`tests/data/real/`, see the README there).
pub fn real(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/real")
        .join(name)
}

/// Half the spacing of f32 values at magnitude `max_abs`: the most that rounding an f64 of
/// that size to f32 can move it. The tightest tolerance an f32 coordinate can honour.
pub fn f32_rounding(max_abs: f64) -> f64 {
    let v = (max_abs as f32).abs().max(f32::MIN_POSITIVE);
    let spacing = f64::from(f32::from_bits(v.to_bits() + 1) - v);
    spacing / 2.0
}

/// Whether an error's message names the file (by its name).
pub fn names_file(message: &str, path: &Path) -> bool {
    let name = path.file_name().expect("a file name").to_string_lossy();
    message.contains(name.as_ref())
}

/// A pose from a JSON rotation (w x y z) and translation.
pub fn pose_from(rotation_wxyz: &Value, translation: &Value) -> DAffine3 {
    let q = f64s(rotation_wxyz);
    let t = f64s(translation);
    DAffine3::from_rotation_translation(
        DQuat::from_xyzw(q[1], q[2], q[3], q[0]).normalize(),
        DVec3::new(t[0], t[1], t[2]),
    )
}

/// Asserts two poses agree to 1e-12 in every matrix element.
pub fn assert_pose_eq(a: &DAffine3, b: &DAffine3, what: &str) {
    let d = (a.to_cols_array().iter().zip(b.to_cols_array()))
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    assert!(d < 1e-12, "{what}: poses differ by {d}: {a:?} vs {b:?}");
}

/// Asserts a point lies within `tol` metres (on every axis) of (x, y, z).
pub fn close(p: Vec3, x: f64, y: f64, z: f64, tol: f64, what: &str) {
    let d = (p.as_dvec3() - DVec3::new(x, y, z)).abs().max_element();
    assert!(
        d <= tol,
        "{what}: {p:?} vs ({x}, {y}, {z}): {d} m > {tol} m"
    );
}

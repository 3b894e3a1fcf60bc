//! What every fuzz target checks on what a reader returns, beyond "no panic, no abort, no
//! timeout, no allocation over the RSS limit" (libFuzzer's own checks):
//!
//! - an error names the file, is the input's fault (exit code 2) and holds no control
//!   character (a file's text is escaped wherever a message quotes it);
//! - notes name the file and hold no control character;
//! - a cloud is consistent ([`PointCloud::validate`]), finite where unorganised (missing
//!   returns only in organised clouds), with a unit sensor orientation;
//! - a pose is finite and rigid.
//!
//! Targets for other crates' readers add their own checks here, next to these.

use cloud::{BadInput, CloudError, PointCloud};
use glam::DAffine3;
use std::fmt::Display;

/// The path every target hands to the reader (messages must name it).
pub fn path(name: &str) -> &std::path::Path {
    std::path::Path::new(name)
}

/// Checks a reader's error: names `name`, is bad input, no control characters.
pub fn check_error(e: &CloudError, name: &str) {
    check_message(e, name);
    assert!(
        e.is_bad_input(),
        "an error reading bytes must be the input's fault (exit 2): {e}"
    );
}

/// Checks any message about the file `name`: names it, no control characters.
pub fn check_message(msg: &dyn Display, name: &str) {
    let text = msg.to_string();
    assert!(text.contains(name), "message does not name {name}: {text}");
    assert!(
        !text.chars().any(char::is_control),
        "control character in a message: {text:?}"
    );
}

/// Checks notes: each names `name`, no control characters.
pub fn check_notes(notes: &[String], name: &str) {
    for n in notes {
        check_message(n, name);
        assert!(n.starts_with(name), "a note starts with the file: {n}");
    }
}

/// Checks a cloud a reader returned.
pub fn check_cloud(c: &PointCloud) {
    c.validate()
        .expect("a cloud read from a file is consistent");
    if c.organized.is_none() {
        assert!(
            c.points.iter().all(|p| p.is_finite()),
            "unorganised clouds hold only finite points"
        );
    } else {
        assert!(
            c.points
                .iter()
                .all(|p| p.is_finite() || (p.x.is_nan() && p.y.is_nan() && p.z.is_nan())),
            "an organised cloud's points are finite or missing returns"
        );
    }
    let q = c.sensor_orientation;
    assert!(
        q.is_finite() && (q.length() - 1.0).abs() < 1e-3,
        "sensor orientation {q:?} is a unit quaternion"
    );
    assert!(c.sensor_origin.is_finite());
}

/// Checks a pose a reader returned: finite, rotation orthonormal.
pub fn check_pose(p: &DAffine3) {
    assert!(p.is_finite(), "pose {p:?} is finite");
    let r = p.matrix3;
    let err = (r.transpose() * r - glam::DMat3::IDENTITY)
        .to_cols_array()
        .iter()
        .fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(err <= 1e-3 + 1e-9, "pose rotation is orthonormal ({err})");
}

/// Runs a cloud reader and checks what it returns.
pub fn cloud_target(
    name: &str,
    read: impl FnOnce(&std::path::Path) -> cloud::Result<(PointCloud, Vec<String>)>,
) {
    match read(path(name)) {
        Ok((c, notes)) => {
            check_cloud(&c);
            check_notes(&notes, name);
        }
        Err(e) => check_error(&e, name),
    }
}

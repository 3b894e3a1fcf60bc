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

/// Runs a scan reader of the interop crate (E57, LAS/LAZ, MCAP) and checks what it returns:
/// every scan's cloud as [`check_cloud`] does, poses finite and rigid, one odometry pose per
/// scan, a finite local origin, notes naming the file; an error names the file, is bad input
/// (out-of-memory is not: a small input must never need that much) and holds no control
/// character.
pub fn scans_target(
    name: &str,
    read: impl FnOnce(&std::path::Path) -> interop::Result<interop::ScanSet>,
) {
    match read(path(name)) {
        Ok(set) => {
            for scan in &set.scans {
                check_cloud(&scan.cloud);
                check_message(&scan.name, "");
                if let Some(pose) = &scan.world_from_scan {
                    check_pose(pose);
                }
                if let Some(frame) = &scan.frame_id {
                    check_message(frame, "");
                }
            }
            if let Some(odometry) = &set.odometry {
                assert_eq!(
                    odometry.len(),
                    set.scans.len(),
                    "one odometry pose per scan"
                );
                odometry.iter().for_each(check_pose);
            }
            assert!(set.local_origin_m.is_finite());
            check_notes(&set.notes, name);
        }
        Err(e) => {
            check_message(&e, name);
            assert!(
                e.is_bad_input(),
                "an error reading bytes must be the input's fault (exit 2): {e}"
            );
        }
    }
}

/// E57 pages: 1,020 bytes of data and their CRC-32C, big endian.
const E57_PAGE: usize = 1024;

/// CRC-32C (Castagnoli, reflected polynomial 0x82F63B78), bit by bit.
fn crc32c(data: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &byte in data {
        crc ^= u32::from(byte);
        for _ in 0..8 {
            crc = if crc & 1 == 1 {
                (crc >> 1) ^ 0x82F6_3B78
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

/// `data` with the CRC of every whole E57 page recomputed, so that a mutation reaches the
/// parser behind the page checks (which would refuse almost every mutated input); `None` where
/// `data` holds no whole page.
pub fn e57_with_page_crcs(data: &[u8]) -> Option<Vec<u8>> {
    if data.len() < E57_PAGE {
        return None;
    }
    let mut fixed = data.to_vec();
    for page in fixed.chunks_exact_mut(E57_PAGE) {
        let crc = crc32c(&page[..E57_PAGE - 4]);
        page[E57_PAGE - 4..].copy_from_slice(&crc.to_be_bytes());
    }
    Some(fixed)
}

#[cfg(test)]
mod tests {
    #[test]
    fn crc32c_check_value() {
        assert_eq!(super::crc32c(b"123456789"), 0xE306_9283);
    }
}

/// Lets a panic inside the `laz` crate unwind instead of aborting the fuzzer, once per process.
///
/// interop's LAS/LAZ reader runs the `las`/`laz` crates under `catch_unwind` and turns a panic
/// into a format error: the `laz` arithmetic decoder checks its state with `debug_assert!`s
/// that corrupt compressed data trips in debug-assertion builds (as cargo-fuzz builds), and no
/// check can tell such data apart before decoding it. libFuzzer's panic hook would abort on
/// those before the reader could catch them, stopping the `las` and `laz` targets within
/// seconds. Panics anywhere else (our code, the `las` crate) still abort and are reported.
pub fn tolerate_laz_panics() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        let abort = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            let in_laz = info
                .location()
                .is_some_and(|l| l.file().contains("/laz-") && l.file().contains("/src/"));
            if !in_laz {
                abort(info);
            }
        }));
    });
}

//! The static HTML report of a run (`semsim report RUN_DIR --html OUT.html`): one
//! self-contained file that needs no server and no network. It holds the world as GLB
//! (base64), three.js and its loader and the console's shared modules (`web/scene.js`,
//! `web/minimap.js`, `web/cloud.js`; as `data:` module URLs in an import map, their relative
//! imports rewritten to bare names the map resolves), the run's trajectory, door angles,
//! events, verdict and rules (JSON), optionally a small downsampled point cloud (binary,
//! base64: [`REPORT_CLOUD_POINTS`] points at most, about 0.5 MB), and the page's own script and
//! style (`web/report.html`, `web/report.js`).

use crate::cloud_layer::{class_names_json, CloudLayer};
use crate::error::Result;
use crate::run::RecordedRun;
use crate::world::ConsoleWorld;
use sim::{RobotModel, StartPose};
use std::path::Path;

const TEMPLATE: &str = include_str!("../web/report.html");
const SCRIPT: &str = include_str!("../web/report.js");
const STYLE: &str = include_str!("../web/style.css");
const THREE_MODULE: &str = include_str!("../web/vendor/three/three.module.js");
const THREE_CORE: &str = include_str!("../web/vendor/three/three.core.js");
const GLTF_LOADER: &str = include_str!("../web/vendor/three/addons/loaders/GLTFLoader.js");
const BUFFER_UTILS: &str = include_str!("../web/vendor/three/addons/utils/BufferGeometryUtils.js");
const SKELETON_UTILS: &str = include_str!("../web/vendor/three/addons/utils/SkeletonUtils.js");
const ORBIT_CONTROLS: &str = include_str!("../web/vendor/three/addons/controls/OrbitControls.js");
const SCENE: &str = include_str!("../web/scene.js");
const MINIMAP: &str = include_str!("../web/minimap.js");
const CLOUD: &str = include_str!("../web/cloud.js");

/// The most cloud points a report embeds: 13 bytes each, base64 4/3 of that, so about 0.5 MB
/// (the file stays small enough to mail).
pub const REPORT_CLOUD_POINTS: usize = 30_000;

/// A relative import (`'./three.core.js'`) and the bare name it becomes.
type Rewrite = (&'static str, &'static str);

/// The modules of the import map: the bare name, the source, and its relative imports with
/// the bare names they become (a `data:` URL has no folder to resolve them against).
const MODULES: &[(&str, &str, &[Rewrite])] = &[
    (
        "three",
        THREE_MODULE,
        &[("'./three.core.js'", "'three/core'")],
    ),
    ("three/core", THREE_CORE, &[]),
    (
        "three/addons/loaders/GLTFLoader.js",
        GLTF_LOADER,
        &[
            (
                "'../utils/BufferGeometryUtils.js'",
                "'three/addons/utils/BufferGeometryUtils.js'",
            ),
            (
                "'../utils/SkeletonUtils.js'",
                "'three/addons/utils/SkeletonUtils.js'",
            ),
        ],
    ),
    (
        "three/addons/utils/BufferGeometryUtils.js",
        BUFFER_UTILS,
        &[],
    ),
    ("three/addons/utils/SkeletonUtils.js", SKELETON_UTILS, &[]),
    (
        "three/addons/controls/OrbitControls.js",
        ORBIT_CONTROLS,
        &[],
    ),
    ("semsim/scene.js", SCENE, &[]),
    ("semsim/minimap.js", MINIMAP, &[]),
    ("semsim/cloud.js", CLOUD, &[]),
];

/// The report of `run` in `world` (the robot drawn at `start`, then moved along the
/// trajectory by the page), with `cloud` as a layer if given (downsample it to
/// [`REPORT_CLOUD_POINTS`]), as one HTML document.
pub fn report_html(
    world: &ConsoleWorld,
    robot: &RobotModel,
    start: StartPose,
    run: &RecordedRun,
    cloud: Option<&CloudLayer>,
) -> Result<String> {
    let glb = world.glb(robot, start)?;
    let imports: serde_json::Map<String, serde_json::Value> = MODULES
        .iter()
        .map(|(name, source, rewrites)| {
            let mut text = source.to_string();
            for (from, to) in rewrites.iter() {
                text = text.replace(from, to);
            }
            let url = format!("data:text/javascript;base64,{}", base64(text.as_bytes()));
            (name.to_string(), serde_json::Value::String(url))
        })
        .collect();
    let import_map = serde_json::json!({ "imports": imports }).to_string();
    let (cloud_meta, cloud_bin) = match cloud {
        Some(c) => (
            format!(
                r#"{{"info":{},"class_codes":{}}}"#,
                c.info_json().replace('<', "\\u003c"),
                class_names_json()
            ),
            base64(&c.bytes),
        ),
        None => ("null".to_string(), String::new()),
    };
    // The run's JSON goes in last: nothing it holds is taken for a placeholder.
    Ok(TEMPLATE
        .replace("@@STYLE@@", STYLE)
        .replace("@@IMPORTMAP@@", &import_map)
        .replace("@@SCRIPT@@", SCRIPT)
        .replace("@@GLB@@", &base64(&glb))
        .replace("@@CLOUD_META@@", &cloud_meta)
        .replace("@@CLOUD@@", &cloud_bin)
        .replace("@@RUN@@", &run.to_json()))
}

/// Writes the report atomically (a temporary file beside `path`, renamed over it).
pub fn write_report(path: &Path, html: &str) -> Result<()> {
    Ok(cloud::write_bytes_atomically(path, html.as_bytes())?)
}

/// Standard base64 (RFC 4648, with padding).
pub fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            chunk.get(1).copied().unwrap_or(0),
            chunk.get(2).copied().unwrap_or(0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for i in 0..4 {
            if i <= chunk.len() {
                out.push(char::from(ALPHABET[((n >> (18 - 6 * i)) & 63) as usize]));
            } else {
                out.push('=');
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_rfc_4648() {
        for (plain, coded) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(plain.as_bytes()), coded);
        }
    }

    #[test]
    fn every_relative_import_is_rewritten() {
        for (name, source, rewrites) in MODULES {
            let mut text = source.to_string();
            for (from, to) in rewrites.iter() {
                assert!(text.contains(from), "{name} no longer imports {from}");
                text = text.replace(from, to);
            }
            assert!(!text.contains("from './"), "{name} has a relative import");
            assert!(!text.contains("from '../"), "{name} has a relative import");
        }
        for p in [
            "@@STYLE@@",
            "@@IMPORTMAP@@",
            "@@SCRIPT@@",
            "@@GLB@@",
            "@@CLOUD_META@@",
            "@@CLOUD@@",
            "@@RUN@@",
        ] {
            assert!(TEMPLATE.contains(p), "the template lacks {p}");
        }
    }
}

//! The page's static files, compiled into the binary: the page, its script and style, and
//! the vendored three.js (see `web/vendor/three/README.md`). They are served from this fixed
//! table only: no request names a file on disk.

/// A static file.
pub(crate) struct Asset {
    /// Its URL path.
    pub path: &'static str,
    /// Its media type.
    pub content_type: &'static str,
    /// Its bytes.
    pub bytes: &'static [u8],
}

const JS: &str = "text/javascript; charset=utf-8";

/// Every static file.
pub(crate) const ASSETS: &[Asset] = &[
    Asset {
        path: "/",
        content_type: "text/html; charset=utf-8",
        bytes: include_bytes!("../web/index.html"),
    },
    Asset {
        path: "/app.js",
        content_type: JS,
        bytes: include_bytes!("../web/app.js"),
    },
    Asset {
        path: "/replay.js",
        content_type: JS,
        bytes: include_bytes!("../web/replay.js"),
    },
    Asset {
        path: "/scene.js",
        content_type: JS,
        bytes: include_bytes!("../web/scene.js"),
    },
    Asset {
        path: "/cloud.js",
        content_type: JS,
        bytes: include_bytes!("../web/cloud.js"),
    },
    Asset {
        path: "/minimap.js",
        content_type: JS,
        bytes: include_bytes!("../web/minimap.js"),
    },
    Asset {
        path: "/style.css",
        content_type: "text/css; charset=utf-8",
        bytes: include_bytes!("../web/style.css"),
    },
    Asset {
        path: "/vendor/three/three.module.js",
        content_type: JS,
        bytes: include_bytes!("../web/vendor/three/three.module.js"),
    },
    Asset {
        path: "/vendor/three/three.core.js",
        content_type: JS,
        bytes: include_bytes!("../web/vendor/three/three.core.js"),
    },
    Asset {
        path: "/vendor/three/addons/loaders/GLTFLoader.js",
        content_type: JS,
        bytes: include_bytes!("../web/vendor/three/addons/loaders/GLTFLoader.js"),
    },
    Asset {
        path: "/vendor/three/addons/utils/BufferGeometryUtils.js",
        content_type: JS,
        bytes: include_bytes!("../web/vendor/three/addons/utils/BufferGeometryUtils.js"),
    },
    Asset {
        path: "/vendor/three/addons/utils/SkeletonUtils.js",
        content_type: JS,
        bytes: include_bytes!("../web/vendor/three/addons/utils/SkeletonUtils.js"),
    },
    Asset {
        path: "/vendor/three/addons/controls/OrbitControls.js",
        content_type: JS,
        bytes: include_bytes!("../web/vendor/three/addons/controls/OrbitControls.js"),
    },
    Asset {
        path: "/vendor/three/LICENSE",
        content_type: "text/plain; charset=utf-8",
        bytes: include_bytes!("../web/vendor/three/LICENSE"),
    },
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_module_the_page_imports_is_served() {
        let served = |p: &str| ASSETS.iter().any(|a| a.path == p);
        let page = std::str::from_utf8(ASSETS[0].bytes).expect("utf-8");
        for needed in [
            "/app.js",
            "/style.css",
            "/vendor/three/three.module.js",
            "/vendor/three/addons/",
        ] {
            assert!(page.contains(needed), "the page does not name {needed}");
        }
        for a in ASSETS {
            assert!(!a.bytes.is_empty(), "{} is empty", a.path);
        }
        // The addons import each other relatively and three by its bare name.
        assert!(served("/vendor/three/three.core.js"));
        // The page's own modules are imported as `semsim/NAME`, which the import map sends
        // to `/NAME`.
        assert!(page.contains(r#""semsim/": "/""#));
        let app = std::str::from_utf8(ASSETS[1].bytes).expect("utf-8");
        for module in ["replay.js", "scene.js", "cloud.js", "minimap.js"] {
            assert!(app.contains(&format!("'semsim/{module}'")), "{module}");
            assert!(served(&format!("/{module}")), "{module}");
        }
        assert!(served("/vendor/three/addons/utils/BufferGeometryUtils.js"));
        assert!(served("/vendor/three/addons/utils/SkeletonUtils.js"));
    }
}

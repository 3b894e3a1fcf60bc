//! What the live and the replaying server answer alike: the page's files, the world's routes
//! (`/world.glb`, `/api/world.json`, the cloud layer's `/api/cloud.json` and `/api/cloud.bin`)
//! with the same headers, the same-origin rule for WebSocket upgrades, and serving a router
//! on a listener (TCP_NODELAY on every connection: state frames are small and must not wait
//! for Nagle's algorithm).

use crate::assets::ASSETS;
use crate::cloud_layer::{class_names_json, CloudLayer};
use crate::error::{ConsoleError, Result};
use axum::http::header::{CACHE_CONTROL, CONTENT_TYPE, ORIGIN, X_CONTENT_TYPE_OPTIONS};
use axum::http::{HeaderMap, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::routing::get;
use axum::serve::ListenerExt as _;
use axum::Router;
use std::future::Future;
use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::sync::Arc;

/// A file served to the page: never cached (the console's world changes between runs) and
/// never type-sniffed.
pub(crate) fn file(content_type: &'static str, body: impl IntoResponse) -> Response {
    (
        [
            (CONTENT_TYPE, content_type),
            (CACHE_CONTROL, "no-cache"),
            (X_CONTENT_TYPE_OPTIONS, "nosniff"),
        ],
        body,
    )
        .into_response()
}

/// The refusal (403) of a WebSocket upgrade whose `Origin` is not one of `origins` (compared
/// without case); `None` where it is, or where there is no `Origin` (not a browser page).
pub(crate) fn refuse_foreign_origin(headers: &HeaderMap, origins: &[String]) -> Option<Response> {
    let origin = headers.get(ORIGIN)?;
    let allowed = origin
        .to_str()
        .is_ok_and(|o| origins.iter().any(|a| a.eq_ignore_ascii_case(o)));
    (!allowed).then(|| {
        (
            StatusCode::FORBIDDEN,
            "WebSocket refused: the page is not the console's own (Origin does not match)",
        )
            .into_response()
    })
}

/// The world as the page loads it.
pub(crate) struct WorldFiles {
    /// `/world.glb`.
    pub glb: Vec<u8>,
    /// `/api/world.json`.
    pub world_json: String,
    /// The cloud layer, if any.
    pub cloud: Option<CloudLayer>,
}

/// The page's static files and the world's routes.
pub(crate) fn world_routes(files: WorldFiles) -> Router {
    let files = Arc::new(files);
    let mut r = Router::new();
    for asset in ASSETS {
        r = r.route(
            asset.path,
            get(move || async move { file(asset.content_type, asset.bytes) }),
        );
    }
    let f = files.clone();
    r = r.route(
        "/world.glb",
        get(move || async move { file("model/gltf-binary", f.glb.clone()) }),
    );
    let f = files.clone();
    r = r.route(
        "/api/world.json",
        get(move || async move { file("application/json", f.world_json.clone()) }),
    );
    // `null` without a cloud: the page then hides the layer's controls.
    let f = files.clone();
    r = r.route(
        "/api/cloud.json",
        get(move || async move {
            let json = match &f.cloud {
                Some(c) => format!(
                    r#"{{"info":{},"class_codes":{}}}"#,
                    c.info_json(),
                    class_names_json()
                ),
                None => "null".into(),
            };
            file("application/json", json)
        }),
    );
    let f = files;
    r.route(
        "/api/cloud.bin",
        get(move || async move {
            match &f.cloud {
                Some(c) => file("application/octet-stream", c.bytes.clone()),
                None => (StatusCode::NOT_FOUND, "no cloud layer (--cloud)").into_response(),
            }
        }),
    )
}

/// Binds `listen`: the listener and the address it got.
pub(crate) async fn bind(listen: SocketAddr) -> Result<(tokio::net::TcpListener, SocketAddr)> {
    let listener = tokio::net::TcpListener::bind(listen)
        .await
        .map_err(|source| ConsoleError::Bind {
            addr: listen,
            source,
        })?;
    let addr = listener.local_addr().map_err(|source| ConsoleError::Bind {
        addr: listen,
        source,
    })?;
    Ok((listener, addr))
}

/// Serves `router` on `listener` until `shutdown` completes, with TCP_NODELAY on every
/// accepted connection.
pub(crate) async fn serve(
    listener: tokio::net::TcpListener,
    router: Router,
    shutdown: impl Future<Output = ()> + Send + 'static,
) -> Result<()> {
    let listener = listener.tap_io(|tcp| {
        // A socket that refuses the option still works, with Nagle's delays.
        let _ = tcp.set_nodelay(true);
    });
    axum::serve(listener, router)
        .with_graceful_shutdown(shutdown)
        .await
        .map_err(ConsoleError::Serve)
}

/// The page's URL for a listening address, `http://HOST:PORT/` (an unspecified address shows
/// as 127.0.0.1).
pub(crate) fn page_url(mut addr: SocketAddr) -> String {
    if addr.ip().is_unspecified() {
        addr.set_ip(IpAddr::V4(Ipv4Addr::LOCALHOST));
    }
    format!("http://{addr}/")
}

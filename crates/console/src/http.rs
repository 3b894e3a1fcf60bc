//! What the live and the replaying server answer alike: files with the same headers, and the
//! same-origin rule for WebSocket upgrades.

use axum::http::header::{CACHE_CONTROL, CONTENT_TYPE, ORIGIN, X_CONTENT_TYPE_OPTIONS};
use axum::http::{HeaderMap, StatusCode};
use axum::response::{IntoResponse, Response};

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

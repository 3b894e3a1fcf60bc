//! The console as an HTTP server: loopback by default, the page and the world served, nothing
//! else, and WebSocket upgrades only from the console's own page.

mod common;

use common::*;
use console::ConsoleConfig;
use tokio_tungstenite::tungstenite::client::IntoClientRequest;
use tokio_tungstenite::tungstenite::http::HeaderValue;

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn binds_loopback_by_default() {
    let config = ConsoleConfig::default();
    assert!(config.listen.ip().is_loopback());
    assert_eq!(config.listen.port(), 8080);
    // The default address with the port left to the system: still loopback.
    let out = tempfile::tempdir().expect("temp dir");
    let mut any = ConsoleConfig::default();
    any.listen.set_port(0);
    let console = start(any, setup(out.path().into(), 600.0)).await;
    assert_eq!(console.addr.ip().to_string(), "127.0.0.1");
    assert!(console.url.starts_with("http://127.0.0.1:"));
    console.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn serves_the_page_the_world_and_nothing_else() {
    let out = tempfile::tempdir().expect("temp dir");
    let console = start(any_port(), setup(out.path().into(), 600.0)).await;
    let (status, page) = get(console.addr, "/").await;
    assert_eq!(status, 200);
    let page = String::from_utf8(page).expect("utf-8");
    assert!(page.contains("<title>semsim console</title>"), "{page}");
    assert!(page.contains("\"three\": \"/vendor/three/three.module.js\""));
    let (status, js) = get(console.addr, "/vendor/three/three.module.js").await;
    assert_eq!(status, 200);
    assert!(String::from_utf8_lossy(&js).contains("three.core.js"));
    let (status, glb) = get(console.addr, "/world.glb").await;
    assert_eq!(status, 200);
    assert_eq!(&glb[..4], b"glTF", "the GLB magic");
    assert_eq!(
        u32::from_le_bytes([glb[8], glb[9], glb[10], glb[11]]) as usize,
        glb.len()
    );
    let (status, world) = get(console.addr, "/api/world.json").await;
    assert_eq!(status, 200);
    let world: serde_json::Value = serde_json::from_slice(&world).expect("JSON");
    let entities = world["entities"].as_array().expect("entities");
    let robot = world["robot"].as_u64().expect("robot id");
    assert!(entities.iter().any(|e| e["class"] == "wall"));
    assert!(entities.iter().any(|e| e["class"] == "floor"));
    assert!(entities
        .iter()
        .any(|e| e["id"] == robot && e["class"] == "robot"));
    assert!(entities.iter().all(|e| e["relations"].is_array()));
    // The GLB has the robot with that id too.
    assert!(String::from_utf8_lossy(&glb).contains(&format!("\"robot {robot}\"")));
    // No --cloud: the layer's description is null and there are no points.
    let (status, cloud) = get(console.addr, "/api/cloud.json").await;
    assert_eq!((status, cloud.as_slice()), (200, b"null".as_slice()));
    assert_eq!(get(console.addr, "/api/cloud.bin").await.0, 404);
    for path in [
        "/nope",
        "/../Cargo.toml",
        "/vendor/three/",
        "/web/index.html",
        "/src/lib.rs",
    ] {
        assert_eq!(get(console.addr, path).await.0, 404, "{path}");
    }
    console.stop().await;
}

async fn upgrade_with_origin(
    addr: std::net::SocketAddr,
    origin: &str,
) -> Result<u16, tokio_tungstenite::tungstenite::Error> {
    let mut request = format!("ws://{addr}/ws")
        .into_client_request()
        .expect("request");
    request
        .headers_mut()
        .insert("Origin", HeaderValue::from_str(origin).expect("header"));
    let connect = tokio_tungstenite::connect_async(request);
    let (_, response) = tokio::time::timeout(TIMEOUT, connect)
        .await
        .expect("in time")?;
    Ok(response.status().as_u16())
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn cross_origin_upgrades_are_refused() {
    let out = tempfile::tempdir().expect("temp dir");
    let console = start(any_port(), setup(out.path().into(), 600.0)).await;
    let port = console.addr.port();
    for evil in [
        "http://evil.example".to_string(),
        format!("http://evil.example:{port}"),
        format!("http://127.0.0.1:{}", port.wrapping_add(1)),
        "null".to_string(),
    ] {
        match upgrade_with_origin(console.addr, &evil).await {
            Err(tokio_tungstenite::tungstenite::Error::Http(response)) => {
                assert_eq!(response.status().as_u16(), 403, "{evil}")
            }
            other => panic!("{evil}: {other:?}"),
        }
    }
    for own in [
        format!("http://127.0.0.1:{port}"),
        format!("http://localhost:{port}"),
    ] {
        assert_eq!(
            upgrade_with_origin(console.addr, &own).await.expect(&own),
            101
        );
    }
    console.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_allowed_origin_may_connect() {
    let out = tempfile::tempdir().expect("temp dir");
    let config = ConsoleConfig {
        allowed_origins: vec!["http://console.lan:8080".into()],
        ..any_port()
    };
    let console = start(config, setup(out.path().into(), 600.0)).await;
    assert_eq!(
        upgrade_with_origin(console.addr, "http://console.lan:8080")
            .await
            .expect("allowed"),
        101
    );
    console.stop().await;
}

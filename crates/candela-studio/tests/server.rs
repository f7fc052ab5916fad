//! The server without a browser: the token on every route and on the
//! WebSocket upgrade, error replies to bad requests, the settings form's
//! round trip, and a small render streamed as frames.

use candela_render::settings::Settings;
use candela_studio::{serve, Studio, StudioOptions};
use futures_util::{SinkExt, StreamExt};
use serde_json::{json, Map, Value};
use std::net::SocketAddr;
use std::time::Duration;
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio_tungstenite::tungstenite::Message;

const TOKEN: &str = "0123456789abcdef0123456789abcdef";

async fn start() -> SocketAddr {
    let studio = Studio::new(
        candela_scene::demo_scene(),
        StudioOptions {
            scene_path: None,
            out_dir: std::env::temp_dir(),
            token: Some(TOKEN.into()),
            settings: Map::new(),
        },
    )
    .expect("the demo scene loads");
    let listener = tokio::net::TcpListener::bind("127.0.0.1:0").await.unwrap();
    let addr = listener.local_addr().unwrap();
    tokio::spawn(serve(listener, studio));
    addr
}

/// The status code and body of a GET.
async fn get(addr: SocketAddr, path: &str) -> (u16, String) {
    let mut stream = tokio::net::TcpStream::connect(addr).await.unwrap();
    let request = format!("GET {path} HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\n\r\n");
    stream.write_all(request.as_bytes()).await.unwrap();
    let mut response = String::new();
    stream.read_to_string(&mut response).await.unwrap();
    let status = response[9..12].parse().unwrap();
    let body = response.split_once("\r\n\r\n").map_or("", |(_, b)| b);
    (status, body.to_string())
}

#[tokio::test]
async fn every_route_needs_the_token() {
    let addr = start().await;
    for path in [
        "/",
        "/static/app.js",
        "/api/scene",
        "/api/mesh",
        "/api/settings",
        "/api/bvh",
        "/ws",
    ] {
        assert_eq!(get(addr, path).await.0, 403, "{path} without a token");
        let wrong = format!("{path}?token=0123456789abcdef0123456789abcdee");
        assert_eq!(get(addr, &wrong).await.0, 403, "{path} with a wrong token");
    }
    let (status, page) = get(addr, &format!("/?token={TOKEN}")).await;
    assert_eq!(status, 200);
    assert!(
        page.contains(&format!("app.js?token={TOKEN}")),
        "the page's scripts carry the token"
    );
    assert_eq!(
        get(addr, &format!("/static/app.js?token={TOKEN}")).await.0,
        200
    );
    assert_eq!(
        get(addr, &format!("/static/nope.js?token={TOKEN}")).await.0,
        404
    );
    // The WebSocket upgrade itself is refused without the token.
    let url = format!("ws://{addr}/ws");
    match tokio_tungstenite::connect_async(url).await {
        Err(tokio_tungstenite::tungstenite::Error::Http(r)) => assert_eq!(r.status(), 403),
        other => panic!("upgrade without a token: {:?}", other.map(|_| ())),
    }
}

#[tokio::test]
async fn bvh_requests_out_of_range_are_errors() {
    let addr = start().await;
    let (status, body) = get(addr, &format!("/api/bvh?node=0&token={TOKEN}")).await;
    assert_eq!(status, 200);
    let root: Value = serde_json::from_str(&body).unwrap();
    assert_eq!(root["children"].as_array().unwrap().len(), 2);
    for bad in ["99999", "-1", "x"] {
        let (status, body) = get(addr, &format!("/api/bvh?node={bad}&token={TOKEN}")).await;
        assert_eq!(status, 400, "node={bad}");
        assert!(body.contains("\"error\""), "{body}");
    }
}

#[tokio::test]
async fn the_settings_form_round_trips() {
    let addr = start().await;
    let (status, body) = get(addr, &format!("/api/settings?token={TOKEN}")).await;
    assert_eq!(status, 200);
    let form: Value = serde_json::from_str(&body).unwrap();
    let values: Map<String, Value> = form["fields"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| (f["name"].as_str().unwrap().to_string(), f["value"].clone()))
        .collect();
    let hints = candela_scene::demo_scene().hints;
    let scene_settings = Settings::resolve(&hints, &Map::new()).unwrap();
    // Every setting is in the form, and sending the form back unchanged
    // gives the same settings.
    assert_eq!(values.len(), scene_settings.to_json().len());
    assert_eq!(Settings::resolve(&hints, &values).unwrap(), scene_settings);
}

type Socket =
    tokio_tungstenite::WebSocketStream<tokio_tungstenite::MaybeTlsStream<tokio::net::TcpStream>>;

async fn connect(addr: SocketAddr) -> Socket {
    let url = format!("ws://{addr}/ws?token={TOKEN}");
    tokio_tungstenite::connect_async(url).await.unwrap().0
}

/// The next message, within a generous time.
async fn next(ws: &mut Socket) -> Message {
    let wait = tokio::time::timeout(Duration::from_secs(120), ws.next());
    wait.await.expect("a reply in time").expect("open").unwrap()
}

async fn error_reply(ws: &mut Socket, request: &str) -> String {
    ws.send(Message::Text(request.into())).await.unwrap();
    match next(ws).await {
        Message::Text(t) => {
            let v: Value = serde_json::from_str(&t).unwrap();
            assert_eq!(v["type"], "error", "{t}");
            v["message"].as_str().unwrap().to_string()
        }
        other => panic!("expected an error, got {other:?}"),
    }
}

#[tokio::test]
async fn bad_requests_get_error_replies_and_the_session_goes_on() {
    let addr = start().await;
    let mut ws = connect(addr).await;
    assert!(error_reply(&mut ws, "{").await.starts_with("bad request:"));
    assert!(error_reply(&mut ws, r#"{"type":"teleport"}"#)
        .await
        .starts_with("bad request:"));
    let render = |settings: Value| json!({"type": "render", "settings": settings}).to_string();
    let m = error_reply(&mut ws, &render(json!({"spp": 1e12}))).await;
    assert!(m.contains("spp"), "{m}");
    let m = error_reply(&mut ws, &render(json!({"spp": 0}))).await;
    assert!(m.contains("spp (-s) 0"), "{m}");
    let m = error_reply(&mut ws, &render(json!({"cell": [790, 590, 100, 100]}))).await;
    assert!(m.contains("cell (-p)"), "{m}");
    let m = error_reply(
        &mut ws,
        &render(json!({"width": 4000000, "height": 4000000})),
    )
    .await;
    assert!(m.contains("memory"), "{m}");
    let m = error_reply(
        &mut ws,
        &render(json!({"eye": [0, 0, 0], "look_at": [0, 0, 0]})),
    )
    .await;
    assert!(m.contains("eye"), "{m}");
    let m = error_reply(&mut ws, &render(json!({"warp": 9}))).await;
    assert!(m.contains("unknown setting `warp`"), "{m}");
    let m = error_reply(&mut ws, r#"{"type":"save","format":"png"}"#).await;
    assert!(m.contains("no image"), "{m}");
    // Still serving: a small render streams a coarse frame, then passes.
    let small = json!({"width": 40, "height": 30, "spp": 3});
    ws.send(Message::Text(render(small).into())).await.unwrap();
    let mut spp_seen = Vec::new();
    loop {
        let Message::Binary(bytes) = next(&mut ws).await else {
            panic!("expected a frame");
        };
        let n = u32::from_le_bytes(bytes[..4].try_into().unwrap()) as usize;
        let header: Value = serde_json::from_slice(&bytes[4..4 + n]).unwrap();
        let png = png::Decoder::new(std::io::Cursor::new(bytes[4 + n..].to_vec()));
        let info = png.read_info().unwrap().info().clone();
        assert_eq!(
            (info.width, info.height),
            (
                header["width"].as_u64().unwrap() as u32,
                header["height"].as_u64().unwrap() as u32
            )
        );
        if header["coarse"] == true {
            assert!(spp_seen.is_empty(), "the coarse frame comes first");
        } else {
            assert_eq!((info.width, info.height), (40, 30));
        }
        spp_seen.push(header["spp"].as_u64().unwrap());
        if header["done"] == true {
            break;
        }
    }
    // Refinement frames are paced by time, so how many come between the
    // coarse frame and the last one depends on the machine's speed.
    assert!(spp_seen.windows(2).all(|w| w[0] <= w[1]), "{spp_seen:?}");
    assert_eq!(spp_seen.last(), Some(&3), "{spp_seen:?}");
}

/// The JSON of a text message; `None` for a frame.
fn text_reply(message: &Message) -> Option<Value> {
    match message {
        Message::Text(t) => Some(serde_json::from_str(t).unwrap()),
        _ => None,
    }
}

#[tokio::test]
async fn inspect_and_save_are_answered_while_a_render_refines() {
    let addr = start().await;
    let mut ws = connect(addr).await;
    let endless = json!({"type": "render", "job": 7,
        "settings": {"width": 48, "height": 36, "spp": 1_000_000}});
    ws.send(Message::Text(endless.to_string().into()))
        .await
        .unwrap();
    // A refinement frame: the film to inspect and save.
    let mut header = frame_of(&mut ws, 7).await;
    while header["coarse"] == true {
        header = frame_of(&mut ws, 7).await;
    }
    let inspect = json!({"type": "inspect", "x": 10, "y": 20, "samples": 2});
    ws.send(Message::Text(inspect.to_string().into()))
        .await
        .unwrap();
    ws.send(Message::Text(r#"{"type":"save","format":"png"}"#.into()))
        .await
        .unwrap();
    // Both replies come while the render goes on: no frame says it is done
    // before them, and frames of more samples follow them.
    let (mut paths, mut saved) = (None, None);
    while paths.is_none() || saved.is_none() {
        let message = next(&mut ws).await;
        if let Some(h) = frame_header(&message) {
            assert_eq!(h["done"], false, "the render finished before the replies");
            continue;
        }
        let reply = text_reply(&message).unwrap();
        match reply["type"].as_str() {
            Some("paths") => paths = Some(reply),
            Some("saved") => saved = Some(reply),
            _ => panic!("{reply}"),
        }
    }
    let paths = paths.unwrap();
    assert_eq!(paths["paths"].as_array().map(Vec::len), Some(2), "{paths}");
    assert!(paths["film_samples"].as_u64() >= Some(1), "{paths}");
    let files = saved.unwrap()["files"].as_array().unwrap().clone();
    assert!(!files.is_empty());
    for f in &files {
        assert!(std::path::Path::new(f.as_str().unwrap()).is_file(), "{f}");
    }
    let spp = header["spp"].as_u64().unwrap();
    loop {
        let later = frame_of(&mut ws, 7).await;
        assert_eq!(later["done"], false);
        if later["spp"].as_u64().unwrap() > spp {
            break;
        }
    }
}

#[tokio::test]
async fn a_save_with_denoise_writes_the_denoised_image_beside_the_raw_one() {
    let addr = start().await;
    let mut ws = connect(addr).await;
    let render = json!({"type": "render", "job": 3,
        "settings": {"width": 24, "height": 18, "spp": 2, "denoise": true}});
    ws.send(Message::Text(render.to_string().into()))
        .await
        .unwrap();
    if let Err(e) = candela_image::denoise::Oidn::load() {
        // As the CLI: refused in one line before anything renders.
        let message = next(&mut ws).await;
        let reply = text_reply(&message).unwrap_or_else(|| panic!("{message:?}"));
        assert_eq!(reply["type"], "error");
        assert_eq!(reply["message"], format!("--denoise: {e}"));
        return;
    }
    while frame_of(&mut ws, 3).await["done"] != true {}
    ws.send(Message::Text(r#"{"type":"save","format":"png"}"#.into()))
        .await
        .unwrap();
    let reply = text_reply(&next(&mut ws).await).unwrap();
    let files: Vec<String> = serde_json::from_value(reply["files"].clone()).unwrap();
    let raw = files
        .iter()
        .find(|f| f.ends_with(".png") && !f.contains(".denoised."));
    let raw = raw.unwrap_or_else(|| panic!("{files:?}"));
    let denoised = raw.replace(".png", ".denoised.png");
    assert!(files.contains(&denoised), "{files:?}");
    let (a, b) = (
        std::fs::read(raw).unwrap(),
        std::fs::read(&denoised).unwrap(),
    );
    assert_ne!(a, b, "the denoised image differs from the raw one");
}

/// The header of a frame message; `None` for text.
fn frame_header(message: &Message) -> Option<Value> {
    let Message::Binary(bytes) = message else {
        return None;
    };
    let n = u32::from_le_bytes(bytes[..4].try_into().unwrap()) as usize;
    Some(serde_json::from_slice(&bytes[4..4 + n]).unwrap())
}

/// The next frame of request `job`, skipping frames of older requests.
async fn frame_of(ws: &mut Socket, job: u64) -> Value {
    loop {
        let message = next(ws).await;
        let header = frame_header(&message).unwrap_or_else(|| panic!("{message:?}"));
        let id = header["job"].as_u64().unwrap();
        assert!(id <= job, "frame of job {id} before job {job} was answered");
        if id == job {
            return header;
        }
    }
}

#[tokio::test]
async fn frames_echo_the_page_job_and_a_layer_change_restarts_a_running_render() {
    let addr = start().await;
    let mut ws = connect(addr).await;
    // A render far longer than the test's patience (a million samples per
    // pixel): anything that waited for it to finish would time out.
    let endless = json!({"type": "render", "job": 41,
        "settings": {"width": 48, "height": 36, "spp": 1_000_000}});
    ws.send(Message::Text(endless.to_string().into()))
        .await
        .unwrap();
    let coarse = frame_of(&mut ws, 41).await;
    assert_eq!(
        (coarse["coarse"].clone(), coarse["layer"].clone()),
        (json!(true), json!("beauty"))
    );
    // Another layer while it runs: the render starts again showing it.
    let layer = json!({"type": "layer", "job": 42, "layer": "depth"});
    ws.send(Message::Text(layer.to_string().into()))
        .await
        .unwrap();
    let again = frame_of(&mut ws, 42).await;
    assert_eq!(again["layer"], "depth");
    assert_eq!(
        again["coarse"], true,
        "a new render: its coarse frame first"
    );
    // New settings cancel it too (the session does not wait for the render).
    let small = json!({"type": "render", "job": 50,
        "settings": {"width": 48, "height": 36, "spp": 2}, "layer": "normal"});
    ws.send(Message::Text(small.to_string().into()))
        .await
        .unwrap();
    let mut header = frame_of(&mut ws, 50).await;
    while header["done"] != true {
        header = frame_of(&mut ws, 50).await;
    }
    assert_eq!(
        (header["spp"].clone(), header["layer"].clone()),
        (json!(2), json!("normal"))
    );
    // Once a render is finished, another layer is the same film again.
    let layer = json!({"type": "layer", "job": 51, "layer": "albedo"});
    ws.send(Message::Text(layer.to_string().into()))
        .await
        .unwrap();
    let shown = frame_of(&mut ws, 51).await;
    assert_eq!(
        (
            shown["coarse"].clone(),
            shown["done"].clone(),
            shown["spp"].clone(),
            shown["layer"].clone()
        ),
        (json!(false), json!(true), json!(2), json!("albedo"))
    );
}

#[tokio::test]
async fn the_bvh_view_follows_the_bvh_setting() {
    let addr = start().await;
    let root = |kind: &'static str| async move {
        let query = if kind.is_empty() {
            String::new()
        } else {
            format!("&bvh={kind}")
        };
        let (status, body) = get(addr, &format!("/api/bvh?node=0{query}&token={TOKEN}")).await;
        (status, serde_json::from_str::<Value>(&body).unwrap())
    };
    let (_, start_tree) = root("").await;
    let (_, sah) = root("sah").await;
    assert_eq!(start_tree, sah, "the demo starts with the SAH tree");
    let (status, median) = root("median").await;
    assert_eq!(status, 200);
    assert_eq!(median["node"]["primitives"], sah["node"]["primitives"]);
    assert_ne!(median, sah, "the median split makes another tree");
    let (status, none) = root("none").await;
    assert_eq!(status, 200);
    assert_eq!(
        none["children"].as_array().unwrap().len(),
        0,
        "no hierarchy: one leaf"
    );
    let (status, bad) = root("octree").await;
    assert_eq!(status, 400);
    assert!(
        bad["message"].as_str().unwrap().contains("bvh octree"),
        "{bad}"
    );
}

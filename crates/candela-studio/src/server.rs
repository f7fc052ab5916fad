//! The HTTP and WebSocket server: routes, the token check, and one render
//! worker per WebSocket connection.
//!
//! Routes (every one needs `?token=`; 403 otherwise):
//! - `/` the page, `/static/<file>` its scripts and style;
//! - `/api/scene` the starting camera, image size and primitive counts;
//! - `/api/mesh` the triangles (see [`crate::mesh`]);
//! - `/api/settings` the settings form ([`crate::settings_form`]);
//! - `/api/bvh?node=N&bvh=KIND` one node of the BVH the `bvh` setting
//!   builds (the starting setting if `bvh` is not given; [`crate::bvh_view`]);
//! - `/ws` the WebSocket of render requests and frames ([`crate::protocol`]).

use crate::bvh_view::BvhView;
use crate::protocol::{parse_request, Reply, Request};
use crate::scene_pool::{build_scene, BuildKey, ScenePool};
use crate::worker::{self, Job, Outgoing, RenderJob, Source};
use crate::{assets, mesh, settings_form, token};
use axum::extract::ws::{Message, WebSocket, WebSocketUpgrade};
use axum::extract::{Path, Query, Request as HttpRequest, State};
use axum::http::{header, StatusCode};
use axum::middleware::{self, Next};
use axum::response::{IntoResponse, Response};
use axum::routing::get;
use axum::{Json, Router};
use candela_render::camera::{Camera, CameraView};
use candela_render::scene::{Geometry, Scene};
use candela_render::settings::{Bvh, Settings};
use candela_scene::Loaded;
use glam::Vec3;
use serde::Deserialize;
use serde_json::{json, Map, Value};
use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use tokio::sync::mpsc;

/// How to start the studio.
#[derive(Clone, Debug)]
pub struct StudioOptions {
    /// The scene file (`None`: the demo), for the command line.
    pub scene_path: Option<PathBuf>,
    /// Where "save" writes.
    pub out_dir: PathBuf,
    /// The secret of the URL; `None` makes a fresh one.
    pub token: Option<String>,
    /// Settings given on the command line (JSON changes over the scene's
    /// hints); the page's changes go over them.
    pub settings: Map<String, Value>,
}

/// A loaded scene ready to serve: what every request reads.
#[derive(Clone)]
pub struct Studio {
    shared: Arc<Shared>,
}

struct Shared {
    token: String,
    source: Arc<Source>,
    scene_info: Value,
    mesh: Vec<u8>,
    geometry: Geometry,
    /// The `bvh` setting the studio started with.
    start_bvh: Bvh,
    /// The trees shown so far, by `bvh` setting (built when first asked).
    trees: Mutex<Vec<(Bvh, Arc<BvhView>)>>,
    form: Value,
}

impl Shared {
    /// The tree the `kind` setting builds, built on first use.
    fn tree(&self, kind: Bvh) -> Arc<BvhView> {
        let mut trees = self.trees.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((_, tree)) = trees.iter().find(|(k, _)| *k == kind) {
            return tree.clone();
        }
        let tree = Arc::new(BvhView::build(&self.geometry, kind.into()));
        trees.push((kind, tree.clone()));
        tree
    }
}

impl Studio {
    /// Prepares `loaded` for the viewer: the default settings for it (its
    /// hints applied), its starting camera, mesh and BVH.
    pub fn new(loaded: Loaded, opts: StudioOptions) -> Result<Studio, String> {
        let settings =
            Settings::resolve(&loaded.hints, &opts.settings).map_err(|e| e.to_string())?;
        let desc = &loaded.scene;
        let camera =
            Scene::camera_for(desc, &settings.camera_options()).map_err(|e| e.to_string())?;
        let geometry = Geometry::from_desc(desc).map_err(|e| e.to_string())?;
        let triangles = mesh::triangles(&geometry);
        let view = orbit_view(&camera, desc.bounds());
        let scene_info = json!({
            "source": desc.source.display().to_string(),
            "width": settings.image.width,
            "height": settings.image.height,
            "view": {
                "eye": view.eye.to_array(),
                "target": view.target.to_array(),
                "up": view.up.to_array(),
                "fov": view.vfov_deg,
            },
            "orthographic": camera.is_orthographic(),
            "triangles": geometry.triangles.triangles.len(),
            "spheres": geometry.spheres.len(),
            "sphere_triangles": mesh::SPHERE_TRIANGLES,
        });
        let source = Source {
            loaded,
            path: opts.scene_path,
            out_dir: opts.out_dir,
            base: opts.settings,
            scenes: ScenePool::default(),
        };
        // The first tab renders at once: its scene is built here.
        let first = build_scene(&source, &settings)?;
        source.scenes.give(first, BuildKey::of(&settings));
        let start_bvh = settings.run.bvh;
        let first_tree = Arc::new(BvhView::build(&geometry, start_bvh.into()));
        let form =
            serde_json::to_value(settings_form::describe(&settings)).map_err(|e| e.to_string())?;
        Ok(Studio {
            shared: Arc::new(Shared {
                token: match opts.token {
                    Some(token) => token,
                    None => token::new_token()?,
                },
                source: Arc::new(source),
                scene_info,
                mesh: mesh::to_bytes(&triangles),
                geometry,
                start_bvh,
                trees: Mutex::new(vec![(start_bvh, first_tree)]),
                form,
            }),
        })
    }

    /// The secret every request must carry.
    pub fn token(&self) -> &str {
        &self.shared.token
    }

    /// The page's URL on `addr`.
    pub fn url(&self, addr: SocketAddr) -> String {
        format!("http://{addr}/?token={}", self.token())
    }
}

/// The camera's view with the look-at point moved along the view direction
/// to the depth of the scene's centre: the page orbits about it (a file
/// camera's own look-at point is often one unit ahead of the eye). Only
/// the look-at distance changes, so the camera renders the same image
/// (pinhole: the distance sets only the plane in focus of a thin lens).
fn orbit_view(camera: &Camera, bounds: Option<(Vec3, Vec3)>) -> CameraView {
    let mut view = camera.view();
    if let Some((lo, hi)) = bounds {
        let depth = ((lo + hi) * 0.5 - camera.eye).dot(camera.forward);
        if depth > 0.0 && camera.lens_radius == 0.0 {
            view.target = camera.eye + camera.forward * depth;
        }
    }
    view
}

/// The routes, behind the token check.
pub fn router(studio: &Studio) -> Router {
    let shared = studio.shared.clone();
    Router::new()
        .route("/", get(index))
        .route("/static/{file}", get(static_file))
        .route("/api/scene", get(scene_info))
        .route("/api/mesh", get(mesh_bytes))
        .route("/api/settings", get(settings))
        .route("/api/bvh", get(bvh_node))
        .route("/ws", get(websocket))
        .layer(middleware::from_fn_with_state(
            shared.clone(),
            require_token,
        ))
        .with_state(shared)
}

/// Serves `studio` on `listener` until the process ends.
pub async fn serve(listener: tokio::net::TcpListener, studio: Studio) -> std::io::Result<()> {
    axum::serve(listener, router(&studio)).await
}

type Shared_ = Arc<Shared>;

async fn require_token(State(s): State<Shared_>, req: HttpRequest, next: Next) -> Response {
    if token::query_has_token(req.uri().query(), &s.token) {
        next.run(req).await
    } else {
        (
            StatusCode::FORBIDDEN,
            "forbidden: this URL needs the token that `candela view` printed\n",
        )
            .into_response()
    }
}

async fn index(State(s): State<Shared_>) -> Response {
    let page = assets::INDEX_HTML.replace("{{TOKEN}}", &s.token);
    (
        [
            (header::CONTENT_TYPE, "text/html; charset=utf-8"),
            (header::CACHE_CONTROL, "no-store"),
        ],
        page,
    )
        .into_response()
}

async fn static_file(Path(file): Path<String>) -> Response {
    match assets::find(&file) {
        Some(a) => ([(header::CONTENT_TYPE, a.content_type)], a.body).into_response(),
        None => (StatusCode::NOT_FOUND, "no such file\n").into_response(),
    }
}

async fn scene_info(State(s): State<Shared_>) -> Json<Value> {
    Json(s.scene_info.clone())
}

async fn mesh_bytes(State(s): State<Shared_>) -> Response {
    (
        [(header::CONTENT_TYPE, "application/octet-stream")],
        s.mesh.clone(),
    )
        .into_response()
}

async fn settings(State(s): State<Shared_>) -> Json<Value> {
    Json(json!({ "fields": s.form }))
}

#[derive(Deserialize)]
struct NodeQuery {
    node: Option<String>,
    bvh: Option<String>,
}

async fn bvh_node(State(s): State<Shared_>, Query(q): Query<NodeQuery>) -> Response {
    let bad = |msg: String| (StatusCode::BAD_REQUEST, Json(Reply::error(msg))).into_response();
    let text = q.node.unwrap_or_else(|| "0".into());
    let Ok(index) = text.parse::<u32>() else {
        return bad(format!("node {text}: expected a node index"));
    };
    let kind = match q.bvh.as_deref() {
        None | Some("") => s.start_bvh,
        Some(name) => match serde_json::from_value::<Bvh>(Value::String(name.into())) {
            Ok(kind) => kind,
            Err(_) => return bad(format!("bvh {name}: expected sah, median or none")),
        },
    };
    // A first build of another tree takes a while on a big mesh: off the
    // async threads.
    let shared = s.clone();
    let Ok(tree) = tokio::task::spawn_blocking(move || shared.tree(kind)).await else {
        let msg = "the BVH build failed".to_string();
        return (StatusCode::INTERNAL_SERVER_ERROR, Json(Reply::error(msg))).into_response();
    };
    match tree.node(index) {
        Some(view) => Json(view).into_response(),
        None => bad(format!("node {index}: the BVH has {} nodes", tree.len())),
    }
}

async fn websocket(State(s): State<Shared_>, ws: WebSocketUpgrade) -> Response {
    ws.on_upgrade(move |socket| session(socket, s))
}

/// One page's session: requests in, frames out, one render worker.
async fn session(mut socket: WebSocket, s: Shared_) {
    let (out_tx, mut out_rx) = mpsc::unbounded_channel::<Outgoing>();
    let jobs = match worker::spawn(s.source.clone(), move |m| {
        let _ = out_tx.send(m);
    }) {
        Ok(jobs) => jobs,
        Err(e) => {
            let text = Reply::error(format!("cannot start the renderer: {e}")).to_text();
            let _ = socket.send(Message::Text(text.into())).await;
            return;
        }
    };
    // The last render request: cancelled by newer ones, started again by
    // a layer change while it runs.
    let mut running: Option<RenderJob> = None;
    loop {
        tokio::select! {
            incoming = socket.recv() => {
                let text = match incoming {
                    Some(Ok(Message::Text(t))) => t.to_string(),
                    Some(Ok(Message::Binary(_))) => {
                        let text = Reply::error("bad request: expected JSON text").to_text();
                        if socket.send(Message::Text(text.into())).await.is_err() { break; }
                        continue;
                    }
                    Some(Ok(_)) => continue,
                    Some(Err(_)) | None => break,
                };
                let job = match parse_request(&text) {
                    Ok(Request::Render { job, settings, layer }) => {
                        start(&mut running, RenderJob::new(job, settings, layer))
                    }
                    Ok(Request::Cancel) => {
                        if let Some(r) = &running { r.cancel.cancel(); }
                        continue;
                    }
                    Ok(Request::Layer { job, layer }) => match &running {
                        // The worker is busy with this render: waiting for
                        // it would delay the layer by the whole render.
                        Some(r) if !r.is_finished() && !r.cancel.is_cancelled() => {
                            let again = r.again(job, layer);
                            start(&mut running, again)
                        }
                        _ => Job::Layer { id: job, layer },
                    },
                    Ok(Request::Save { format }) => Job::Save(format),
                    Ok(Request::Inspect { x, y, samples }) => Job::Inspect { pixel: (x, y), samples },
                    Err(message) => {
                        let text = Reply::error(message).to_text();
                        if socket.send(Message::Text(text.into())).await.is_err() { break; }
                        continue;
                    }
                };
                if jobs.send(job).is_err() { break; }
            }
            Some(out) = out_rx.recv() => {
                let msg = match out {
                    Outgoing::Text(t) => Message::Text(t.into()),
                    Outgoing::Binary(b) => Message::Binary(b.into()),
                };
                if socket.send(msg).await.is_err() { break; }
            }
        }
    }
    // Dropping the job sender ends the worker after its current job.
    if let Some(r) = &running {
        r.cancel.cancel();
    }
}

/// Cancels the render in `running` and makes `job` the running one.
fn start(running: &mut Option<RenderJob>, job: RenderJob) -> Job {
    if let Some(r) = running.as_ref() {
        r.cancel.cancel();
    }
    *running = Some(job.clone());
    Job::Render(job)
}

/// Binds `addr`, tells `ready` the address bound (the port, if 0 was
/// asked), and serves `studio` until the process ends, on a small tokio
/// runtime (the renders run on their own threads).
pub fn run(
    studio: Studio,
    addr: SocketAddr,
    ready: impl FnOnce(SocketAddr),
) -> std::io::Result<()> {
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()?;
    runtime.block_on(async move {
        let listener = tokio::net::TcpListener::bind(addr).await?;
        ready(listener.local_addr()?);
        serve(listener, studio).await
    })
}

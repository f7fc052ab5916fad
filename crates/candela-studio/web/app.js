// Candela Studio: wires the 3D view, the orbiting camera, the progressive
// image, the panel and the modes together. `window.studio` exposes the
// state the browser tests read.
"use strict";
const $ = (id) => document.getElementById(id);
const studio = (window.studio = { frames: 0, done: 0, lastHeader: null, errors: [], saved: [] });

async function main() {
  const scene = await Net.json("/api/scene");
  const positions = new Float32Array(await Net.bytes("/api/mesh"));
  const form = await Net.json("/api/settings");
  studio.scene = scene;
  const W = scene.width, H = scene.height;
  for (const id of ["gl", "image", "overlay"]) { $(id).width = W; $(id).height = H; }
  fitViewport(W, H);
  window.addEventListener("resize", () => fitViewport(W, H));
  View3D.init($("gl"));
  View3D.setMesh(positions);
  const radius = sceneRadius(positions);
  const up = Math.abs(scene.view.up[1]) > 0.1 ? [0, 1, 0] : scene.view.up;
  // layerSettings: the settings a layer needs (direct/indirect only, bounce k).
  // job: the id of the newest request that produces frames; the server
  // echoes it in each frame, and frames of older ids are dropped.
  let mode = "render", layer = "beauty", layerSettings = {}, cell = null, job = 0;
  const redraw = () => View3D.draw(Orbit.camera(), radius, { dim: mode === "bvh" });
  // The 3D view is hidden while the opaque image covers it: without a GPU
  // (SwiftShader), compositing one canvas fewer per frame saves a
  // measurable part of the browser's CPU during a refinement (BENCHMARKS.md).
  const showImage = (on) => {
    const shown = on && mode !== "bvh";
    $("image").style.visibility = shown ? "visible" : "hidden";
    $("image").style.opacity = mode === "inspect" ? 0.5 : 1;
    $("gl").style.visibility = shown && mode !== "inspect" ? "hidden" : "visible";
  };

  const render = () => {
    const settings = { ...Panel.changes, ...Orbit.settings(), ...layerSettings };
    if (cell) settings.cell = cell;
    studio.job = ++job;
    Net.send({ type: "render", job, settings, layer });
  };
  studio.render = render;
  Orbit.init($("overlay"), { ...scene.view, up }, {
    moveStart: () => {
      studio.job = ++job; // frames of the cancelled render are dropped
      Net.send({ type: "cancel" });
      cell = null; clearOverlay(); showImage(false);
    },
    moved: redraw,
    stopped: render,
  });
  studio.camera = () => Orbit.settings();
  Panel.build($("settings"), form.fields, () => {
    render();
    // Another `bvh` setting: show the root of its tree.
    if (mode === "bvh" && (Panel.changes.bvh ?? undefined) !== Bvh.kind) goNode(0);
  });

  const onText = (msg) => {
    if (msg.type === "error") {
      studio.errors.push(msg.message);
      $("message").className = "";
      $("message").textContent = msg.message;
      Panel.showError(msg.message);
    } else if (msg.type === "paths") {
      studio.paths = msg;
      View3D.setLines(Inspect.lines(msg.paths, radius));
      $("inspect-table").innerHTML = Inspect.table(msg);
      redraw();
    } else if (msg.type === "saved") {
      studio.saved.push(...msg.files);
      $("message").className = "ok";
      $("message").textContent = "wrote " + msg.files.join(", ");
    }
  };
  // Frames are drawn one after another in the order they arrived: their
  // PNGs decode concurrently, and a pass's frame must not be drawn (and
  // become studio.lastHeader) after the next pass's.
  let drawing = Promise.resolve();
  const onFrame = (header, blob) => {
    if (header.job !== job) return; // a frame of an older request
    drawing = drawing.then(() => drawFrame(header, blob)).catch((e) => studio.errors.push(String(e)));
  };
  const drawFrame = async (header, blob) => {
    const bitmap = await createImageBitmap(blob);
    if (header.job !== job) return; // superseded while it decoded
    const ctx = $("image").getContext("2d");
    ctx.imageSmoothingEnabled = header.coarse;
    ctx.drawImage(bitmap, 0, 0, W, H);
    studio.frames += 1;
    studio.lastHeader = header;
    studio.lastPng = blob;
    if (studio.headers) studio.headers.push(header); // kept when a script asks (benches/)
    if (header.done) studio.done += 1;
    if (header.coarse && studio.firstCoarseMs === undefined) studio.firstCoarseMs = header.elapsed_ms;
    showImage(true);
    $("message").textContent = "";
    Panel.showError(null);
    $("command").textContent = header.command;
    $("status").textContent = `${header.coarse ? "coarse " : ""}${header.spp}/${header.target_spp} spp` +
      ` · ${header.layer} · ${header.elapsed_ms.toFixed(0)} ms${header.done ? " · done" : ""}`;
  };
  await Net.connect(onText, onFrame, () => ($("status").textContent = "disconnected"));
  redraw();
  render();

  const setMode = async (m) => {
    mode = m;
    $("mode").value = m;
    $("bvh-panel").hidden = m !== "bvh";
    $("inspect-panel").hidden = m !== "inspect";
    Orbit.enabled = m !== "cell" && m !== "inspect";
    $("overlay").style.cursor = m === "cell" || m === "inspect" ? "crosshair" : "grab";
    View3D.setLines([]);
    View3D.setHighlight(null);
    if (m === "bvh") await Bvh.show(0, scene, positions);
    if (m !== "cell") { cell = null; clearOverlay(); }
    redraw();
    showImage(true);
  };
  studio.setMode = setMode;
  const goNode = async (i) => { if (i !== null && i !== undefined) { await Bvh.show(i, scene, positions); redraw(); } };
  studio.bvh = { node: () => Bvh.node, go: goNode, child: (k) => goNode(Bvh.child(k)), up: () => goNode(Bvh.parent()) };
  $("mode").addEventListener("change", (e) => setMode(e.target.value));
  $("bvh-left").onclick = () => goNode(Bvh.child(0));
  $("bvh-right").onclick = () => goNode(Bvh.child(1));
  $("bvh-up").onclick = () => goNode(Bvh.parent());
  const setLayer = () => {
    const v = $("layer").value;
    $("bounce-label").hidden = v !== "bounce";
    const needs = v === "direct" || v === "indirect" ? { integrator: v }
      : v === "bounce" ? { bounce: Number($("bounce-k").value) } : {};
    const image = Object.keys(needs).length ? "beauty" : v;
    const rerender = JSON.stringify(needs) !== JSON.stringify(layerSettings);
    layerSettings = needs;
    layer = image;
    if (rerender) render();
    else Net.send({ type: "layer", job: (studio.job = ++job), layer });
  };
  $("layer").addEventListener("change", setLayer);
  $("bounce-k").addEventListener("change", setLayer);
  studio.setLayer = (v, k) => { $("layer").value = v; if (k !== undefined) $("bounce-k").value = k; setLayer(); };
  const inspect = (x, y) => {
    const samples = Number($("inspect-n").value) || 4;
    Net.send({ type: "inspect", x, y, samples });
  };
  studio.inspect = inspect;
  $("overlay").addEventListener("click", (e) => {
    if (mode !== "inspect") return;
    const r = $("overlay").getBoundingClientRect();
    inspect(Math.floor(((e.clientX - r.left) / r.width) * W), Math.floor(((e.clientY - r.top) / r.height) * H));
  });
  document.addEventListener("keydown", (e) => {
    if (e.target.tagName === "INPUT") return;
    if (e.key === "b") setMode(mode === "bvh" ? "render" : "bvh");
    if (e.key === "c") setMode(mode === "cell" ? "render" : "cell");
    if (e.key === "i") setMode(mode === "inspect" ? "render" : "inspect");
    if (mode === "bvh" && e.key === "l") goNode(Bvh.child(0));
    if (mode === "bvh" && e.key === "r") goNode(Bvh.child(1));
    if (mode === "bvh" && e.key === "u") goNode(Bvh.parent());
  });
  $("save-png").onclick = () => Net.send({ type: "save", format: "png" });
  $("save-exr").onclick = () => Net.send({ type: "save", format: "exr" });
  $("copy-command").onclick = () => navigator.clipboard.writeText($("command").textContent).catch(() => {});
  cellTool($("overlay"), W, H, () => mode === "cell", (rect) => { cell = rect; render(); });
  studio.ready = true;
}

// Dragging a rectangle in cell mode renders only that cell (CS184's -p).
function cellTool(el, W, H, active, done) {
  let start = null;
  const px = (e) => {
    const r = el.getBoundingClientRect();
    return [Math.round(((e.clientX - r.left) / r.width) * W), Math.round(((e.clientY - r.top) / r.height) * H)];
  };
  const rectOf = (a, b) => {
    const x0 = Math.max(0, Math.min(a[0], b[0])), y0 = Math.max(0, Math.min(a[1], b[1]));
    const x1 = Math.min(W, Math.max(a[0], b[0])), y1 = Math.min(H, Math.max(a[1], b[1]));
    return [x0, y0, x1 - x0, y1 - y0];
  };
  el.addEventListener("pointerdown", (e) => { if (active()) { start = px(e); el.setPointerCapture(e.pointerId); } });
  el.addEventListener("pointermove", (e) => { if (start) drawRect(rectOf(start, px(e))); });
  el.addEventListener("pointerup", (e) => {
    if (!start) return;
    const r = rectOf(start, px(e));
    start = null;
    if (r[2] > 0 && r[3] > 0) done(r);
  });
}

function drawRect(r) {
  const ctx = clearOverlay();
  ctx.strokeStyle = "#ffcc33";
  ctx.lineWidth = 2;
  ctx.strokeRect(r[0], r[1], r[2], r[3]);
}

function clearOverlay() {
  const c = $("overlay"), ctx = c.getContext("2d");
  ctx.clearRect(0, 0, c.width, c.height);
  return ctx;
}

function fitViewport(W, H) {
  const stage = $("stage");
  const s = Math.min((stage.clientWidth - 16) / W, (stage.clientHeight - 40) / H, 4);
  $("viewport").style.width = `${Math.floor(W * s)}px`;
  $("viewport").style.height = `${Math.floor(H * s)}px`;
}

function sceneRadius(p) {
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < p.length; i += 3)
    for (let k = 0; k < 3; k++) { lo[k] = Math.min(lo[k], p[i + k]); hi[k] = Math.max(hi[k], p[i + k]); }
  return p.length ? 0.5 * V.len(V.sub(hi, lo)) : 1;
}

main().catch((e) => { $("status").textContent = "error: " + e.message; studio.fatal = e.message; });

// Talking to the server: every URL carries the session's token.
"use strict";
const Net = {
  token: new URLSearchParams(location.search).get("token") || "",
  url(path) {
    return path + (path.includes("?") ? "&" : "?") + "token=" + encodeURIComponent(this.token);
  },
  async json(path) {
    const r = await fetch(this.url(path));
    const body = await r.json();
    if (!r.ok) throw new Error(body.message || r.statusText);
    return body;
  },
  async bytes(path) {
    const r = await fetch(this.url(path));
    if (!r.ok) throw new Error(r.statusText);
    return r.arrayBuffer();
  },
  // Opens the WebSocket; `onText(obj)` for JSON replies, `onFrame(header, pngBlob)` for images.
  connect(onText, onFrame, onClose) {
    const proto = location.protocol === "https:" ? "wss:" : "ws:";
    const ws = new WebSocket(proto + "//" + location.host + this.url("/ws"));
    ws.binaryType = "arraybuffer";
    ws.onmessage = (ev) => {
      if (typeof ev.data === "string") return onText(JSON.parse(ev.data));
      const n = new DataView(ev.data).getUint32(0, true);
      const header = JSON.parse(new TextDecoder().decode(new Uint8Array(ev.data, 4, n)));
      onFrame(header, new Blob([new Uint8Array(ev.data, 4 + n)], { type: "image/png" }));
    };
    ws.onclose = onClose;
    this.ws = ws;
    return new Promise((resolve) => (ws.onopen = resolve));
  },
  send(obj) {
    if (this.ws && this.ws.readyState === 1) this.ws.send(JSON.stringify(obj));
  },
};

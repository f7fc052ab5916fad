// The orbiting camera: left drag orbits about the look-at point (around the
// starting up direction), right or shift drag pans, the wheel zooms. It
// reports a move's start (so the render in progress is cancelled) and its
// stop (so a new render starts).
"use strict";
function rotate(v, axis, angle) {
  // Rodrigues' rotation of v about the unit vector axis.
  const c = Math.cos(angle), s = Math.sin(angle);
  const k = axis, kv = V.dot(k, v), kxv = V.cross(k, v);
  return [0, 1, 2].map((i) => v[i] * c + kxv[i] * s + k[i] * kv * (1 - c));
}

const Orbit = {
  init(element, view, callbacks) {
    this.eye = view.eye.slice();
    this.target = view.target.slice();
    this.worldUp = V.norm(view.up);
    this.fov = view.fov;
    this.cb = callbacks;
    this.enabled = true;
    let drag = null;
    element.addEventListener("contextmenu", (e) => e.preventDefault());
    element.addEventListener("pointerdown", (e) => {
      if (!this.enabled) return;
      drag = { x: e.clientX, y: e.clientY, pan: e.button === 2 || e.shiftKey, moved: false };
      element.setPointerCapture(e.pointerId);
    });
    element.addEventListener("pointermove", (e) => {
      if (!drag) return;
      const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
      if (!drag.moved && Math.abs(dx) + Math.abs(dy) < 2) return;
      if (!drag.moved) { drag.moved = true; this.cb.moveStart(); }
      drag.x = e.clientX; drag.y = e.clientY;
      if (drag.pan) this.pan(dx, dy, element.clientHeight); else this.orbit(dx, dy);
      this.cb.moved();
    });
    const end = () => {
      if (drag && drag.moved) this.cb.stopped();
      drag = null;
    };
    element.addEventListener("pointerup", end);
    element.addEventListener("pointercancel", end);
    element.addEventListener("wheel", (e) => {
      if (!this.enabled) return;
      e.preventDefault();
      this.cb.moveStart();
      const off = V.sub(this.eye, this.target);
      this.eye = V.add(this.target, V.scale(off, Math.exp(e.deltaY * 0.001)));
      this.cb.moved();
      clearTimeout(this.wheelTimer);
      this.wheelTimer = setTimeout(() => this.cb.stopped(), 150);
    }, { passive: false });
  },
  // The image's up: the world up made orthogonal to the view direction.
  up() {
    const f = V.norm(V.sub(this.target, this.eye));
    const right = V.norm(V.cross(f, this.worldUp));
    return V.cross(right, f);
  },
  orbit(dx, dy) {
    let off = V.sub(this.eye, this.target);
    off = rotate(off, this.worldUp, -dx * 0.008);
    const right = V.norm(V.cross(V.norm(V.scale(off, -1)), this.worldUp));
    const turned = rotate(off, right, -dy * 0.008);
    // Stop short of the poles, where the up direction is lost.
    if (Math.abs(V.dot(V.norm(turned), this.worldUp)) < 0.995) off = turned;
    this.eye = V.add(this.target, off);
  },
  pan(dx, dy, heightPx) {
    const off = V.sub(this.eye, this.target);
    const perPixel = (2 * V.len(off) * Math.tan((this.fov * Math.PI) / 360)) / heightPx;
    const f = V.norm(V.scale(off, -1));
    const right = V.norm(V.cross(f, this.worldUp));
    const up = V.cross(right, f);
    const move = V.add(V.scale(right, -dx * perPixel), V.scale(up, dy * perPixel));
    this.eye = V.add(this.eye, move);
    this.target = V.add(this.target, move);
  },
  camera() {
    return { eye: this.eye, target: this.target, up: this.up(), fov: this.fov };
  },
  // The camera as settings: the same names as the CLI's --eye, --look-at, --up, --fov.
  settings() {
    return { eye: this.eye, look_at: this.target, up: this.up(), fov: this.fov };
  },
};

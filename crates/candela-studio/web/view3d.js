// The WebGL2 view: the scene's triangles with flat shading (the normal of
// each triangle from screen-space derivatives), highlighted primitives, and
// coloured line segments (BVH boxes, paths).
"use strict";
const View3D = {
  init(canvas) {
    const gl = canvas.getContext("webgl2", { preserveDrawingBuffer: true });
    if (!gl) throw new Error("this browser has no WebGL2");
    this.gl = gl;
    const vs = `#version 300 es
      in vec3 pos; uniform mat4 mvp; out vec3 world;
      void main() { world = pos; gl_Position = mvp * vec4(pos, 1.0); }`;
    const fs = `#version 300 es
      precision highp float; in vec3 world; uniform vec3 color; uniform int shaded; out vec4 outColor;
      void main() {
        if (shaded == 0) { outColor = vec4(color, 1.0); return; }
        vec3 n = normalize(cross(dFdx(world), dFdy(world)));
        float l = 0.25 + 0.75 * abs(n.y * 0.6 + n.z * 0.5 + n.x * 0.3);
        outColor = vec4(color * l, 1.0);
      }`;
    const prog = gl.createProgram();
    for (const [type, src] of [[gl.VERTEX_SHADER, vs], [gl.FRAGMENT_SHADER, fs]]) {
      const s = gl.createShader(type);
      gl.shaderSource(s, src);
      gl.compileShader(s);
      if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
      gl.attachShader(prog, s);
    }
    gl.linkProgram(prog);
    this.prog = prog;
    this.loc = {
      pos: gl.getAttribLocation(prog, "pos"),
      mvp: gl.getUniformLocation(prog, "mvp"),
      color: gl.getUniformLocation(prog, "color"),
      shaded: gl.getUniformLocation(prog, "shaded"),
    };
    this.mesh = null;
    this.highlight = null;
    this.lines = [];
  },
  buffer(data) {
    const gl = this.gl;
    const b = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, b);
    gl.bufferData(gl.ARRAY_BUFFER, data, gl.STATIC_DRAW);
    return { b, n: data.length / 3 };
  },
  setMesh(positions) { this.mesh = this.buffer(positions); },
  setHighlight(positions) { this.highlight = positions && positions.length ? this.buffer(positions) : null; },
  // lines: [{ points: Float32Array of segment end points, color: [r, g, b] }]
  setLines(lines) { this.lines = lines.filter((l) => l.points.length).map((l) => ({ ...this.buffer(l.points), color: l.color })); },
  drawBuffer(buf, mode, color, shaded) {
    const gl = this.gl;
    gl.bindBuffer(gl.ARRAY_BUFFER, buf.b);
    gl.enableVertexAttribArray(this.loc.pos);
    gl.vertexAttribPointer(this.loc.pos, 3, gl.FLOAT, false, 0, 0);
    gl.uniform3fv(this.loc.color, color);
    gl.uniform1i(this.loc.shaded, shaded ? 1 : 0);
    gl.drawArrays(mode, 0, buf.n);
  },
  // camera: { eye, target, up, fov }; radius: the scene's size, for the clip planes.
  draw(camera, radius, options) {
    const gl = this.gl;
    const c = gl.canvas;
    gl.viewport(0, 0, c.width, c.height);
    gl.clearColor(0.2, 0.2, 0.2, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    gl.useProgram(this.prog);
    const dist = V.len(V.sub(camera.eye, camera.target));
    const near = Math.max(1e-4 * (dist + radius), (dist - 2 * radius) * 0.5);
    const far = dist + 4 * radius;
    const mvp = M.mul(M.perspective(camera.fov, c.width / c.height, near, far), M.lookAt(camera.eye, camera.target, camera.up));
    gl.uniformMatrix4fv(this.loc.mvp, false, mvp);
    const dim = options.dim ? 0.45 : 0.8;
    if (this.mesh) this.drawBuffer(this.mesh, gl.TRIANGLES, [dim, dim, dim], true);
    if (this.highlight) {
      gl.enable(gl.POLYGON_OFFSET_FILL);
      gl.polygonOffset(-1, -1);
      this.drawBuffer(this.highlight, gl.TRIANGLES, [1.0, 0.85, 0.2], true);
      gl.disable(gl.POLYGON_OFFSET_FILL);
    }
    gl.disable(gl.DEPTH_TEST);
    for (const l of this.lines) this.drawBuffer(l, gl.LINES, l.color, false);
  },
};

// The twelve edges of a box as line segments.
function boxEdges(min, max) {
  const p = (i) => [i & 1 ? max[0] : min[0], i & 2 ? max[1] : min[1], i & 4 ? max[2] : min[2]];
  const out = [];
  for (let i = 0; i < 8; i++)
    for (const bit of [1, 2, 4]) if (!(i & bit)) out.push(...p(i), ...p(i | bit));
  return new Float32Array(out);
}

// The path inspector: the traced samples of one pixel drawn as lines in
// the 3D view (camera ray and bounces in cyan, unoccluded light samples in
// yellow, occluded ones in dark red, escaping rays in blue) and listed
// vertex by vertex.
"use strict";
const Inspect = {
  lines(paths, radius) {
    const path = [], lit = [], shadowed = [], escape = [];
    for (const p of paths) {
      let from = p.camera_ray.origin;
      for (const v of p.vertices) {
        path.push(...from, ...v.position);
        from = v.position;
        for (const l of v.light_samples) {
          const to = l.point || V.add(v.position, V.scale(l.direction, radius));
          (l.visible ? lit : shadowed).push(...v.position, ...to);
        }
      }
      if (p.escape) escape.push(...p.escape.ray.origin, ...V.add(p.escape.ray.origin, V.scale(p.escape.ray.direction, radius)));
    }
    return [
      { points: new Float32Array(path), color: [0.2, 0.9, 1.0] },
      { points: new Float32Array(lit), color: [1.0, 0.9, 0.2] },
      { points: new Float32Array(shadowed), color: [0.5, 0.1, 0.1] },
      { points: new Float32Array(escape), color: [0.3, 0.4, 1.0] },
    ];
  },
  table(reply) {
    const f = (x) => (x === null || x === undefined ? "–" : typeof x === "number" ? x.toPrecision(3) : x);
    const v3 = (a) => (a ? "(" + a.map(f).join(", ") + ")" : "–");
    let html = `<p>pixel (${reply.pixel.join(", ")}): film mean ${v3(reply.film_mean)} over ${reply.film_samples} samples</p>`;
    for (const p of reply.paths) {
      const sum = p.contributions.reduce((s, c) => V.add(s, c.value), [0, 0, 0]);
      html += `<h3>sample ${p.sample}: value ${v3(p.value)}, ${p.end}</h3>` +
        `<p>contributions sum ${v3(sum)}</p><table><tr><th>k</th><th>surface</th><th>light samples (MIS w, contribution)</th><th>BSDF sample</th><th>roulette</th></tr>`;
      for (const v of p.vertices) {
        const ls = v.light_samples.map((l) => `${l.light}${l.visible === false ? " (occluded)" : ""}: w ${f(l.mis_weight)}, ${v3(l.contribution)}`).join("<br>");
        const sc = v.scatter ? `${v.scatter.lobe}, pdf ${f(v.scatter.pdf)}` : "–";
        const rr = v.roulette ? `p ${f(v.roulette.survival_probability)} ${v.roulette.survived ? "survived" : "ended"}` : "–";
        const em = v.emission ? `<br>emits ${v3(v.emission.contribution)} (w ${f(v.emission.mis_weight)})` : "";
        html += `<tr><td>${v.depth}</td><td>${v.shape}<br>${v.material} (${v.surface})<br>β ${v3(v.throughput)}${em}</td><td>${ls || "–"}</td><td>${sc}</td><td>${rr}</td></tr>`;
      }
      html += "</table>";
    }
    return html;
  },
};

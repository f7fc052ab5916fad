// BVH mode (the CS184 visualiser): the current node's box in white, its
// left child in red and its right child in green, its primitives
// highlighted; descend with l / r, go up with u. The tree is the one the
// panel's current `bvh` setting builds.
"use strict";
const Bvh = {
  node: null,
  // The `bvh` setting of the tree shown (undefined: the starting one).
  kind: undefined,
  async show(index, scene, positions) {
    const kind = Panel.changes.bvh ?? undefined;
    const v = await Net.json("/api/bvh?node=" + index + (kind ? "&bvh=" + encodeURIComponent(kind) : ""));
    this.node = v;
    this.kind = kind;
    const lines = [{ points: boxEdges(v.node.min, v.node.max), color: [1, 1, 1] }];
    const colors = [[1, 0.3, 0.3], [0.3, 1, 0.3]];
    // Children are drawn shrunk a little, so that edges they share with
    // their parent (or a flat child lying on its parent's face) stay visible.
    const inset = 0.015 * V.len(V.sub(v.node.max, v.node.min));
    v.children.forEach((c, i) => {
      const lo = c.min.map((m, k) => Math.min(m + inset, (m + c.max[k]) / 2));
      const hi = c.max.map((m, k) => Math.max(m - inset, (m + c.min[k]) / 2));
      lines.push({ points: boxEdges(lo, hi), color: colors[i] });
    });
    View3D.setLines(lines);
    View3D.setHighlight(primTriangles(v.prims, scene, positions));
    const n = v.node;
    document.getElementById("bvh-info").innerHTML =
      `node ${n.index} of ${v.nodes}, depth ${n.depth}${n.leaf ? " (leaf)" : ""}<br>` +
      `primitives: ${n.primitives}<br>SAH cost: ${n.sah_cost.toFixed(2)}` +
      v.children.map((c, i) => `<br>${i ? "right (green)" : "left (red)"}: ${c.primitives} primitives, cost ${c.sah_cost.toFixed(2)}`).join("");
    return v;
  },
  child(k) { return this.node && this.node.children[k] ? this.node.children[k].index : null; },
  parent() { return this.node ? this.node.parent : null; },
};

// The triangles of primitives `ids` (triangles first, then spheres of a
// fixed number of triangles each: the server's mesh order).
function primTriangles(ids, scene, positions) {
  const out = [];
  const tri = (t) => out.push(...positions.subarray(t * 9, t * 9 + 9));
  for (const id of ids) {
    if (id < scene.triangles) tri(id);
    else {
      const first = scene.triangles + (id - scene.triangles) * scene.sphere_triangles;
      for (let t = first; t < first + scene.sphere_triangles; t++) tri(t);
    }
  }
  return new Float32Array(out);
}

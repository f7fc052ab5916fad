//! The BVH as the page's BVH mode walks it, node by node (the CS184
//! visualiser): each node's box, its two children, the primitives under it
//! and its SAH cost.
//!
//! The tree shown is the binary hierarchy the render's 4-wide tree is
//! collapsed from ([`candela_render::accel::binary_tree`] with the render's
//! own build options), over the render scene's primitives in id order
//! (triangles, then spheres: the order of [`crate::mesh`]).

use candela_bvh::{BuildOptions, BuildStrategy, Bvh};
use candela_render::accel::{binary_tree, Accel, Layout};
use candela_render::scene::Geometry;
use serde::Serialize;

/// The hierarchy with, per node, its parent, its slot range and its cost.
pub struct BvhView {
    bvh: Bvh,
    opts: BuildOptions,
    parent: Vec<Option<u32>>,
    /// First slot and slot count of each node's subtree (depth-first
    /// layout: a subtree's leaves cover consecutive slots).
    slots: Vec<(u32, u32)>,
    /// Expected cost of each subtree by the surface area heuristic.
    cost: Vec<f32>,
}

/// One node as the page shows it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NodeInfo {
    /// The node's index (0 is the root).
    pub index: u32,
    /// Lower corner of the box.
    pub min: [f32; 3],
    /// Upper corner of the box.
    pub max: [f32; 3],
    /// Primitives in the subtree.
    pub primitives: u32,
    /// Whether the node is a leaf.
    pub leaf: bool,
    /// The subtree's SAH cost: a leaf costs `ceil(n / block)` primitive
    /// tests, an interior node one traversal step plus its children's
    /// costs weighted by their box area relative to its own (MacDonald and
    /// Booth 1990), in units of one primitive test.
    pub sah_cost: f32,
    /// Depth below the root.
    pub depth: u32,
}

/// A node with its family and its primitives: the answer to `/api/bvh`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NodeView {
    /// The node.
    pub node: NodeInfo,
    /// Its parent, if it is not the root.
    pub parent: Option<u32>,
    /// Its two children, if it is not a leaf.
    pub children: Vec<NodeInfo>,
    /// The primitive ids under it (see [`crate::mesh`] for the numbering).
    pub prims: Vec<u32>,
    /// Nodes in the whole tree.
    pub nodes: u32,
}

impl BvhView {
    /// Builds the tree over the scene's primitives as the render does.
    pub fn build(geometry: &Geometry, strategy: BuildStrategy) -> Self {
        let tris = &geometry.triangles;
        let soup: Vec<_> = crate::mesh::triangles(geometry)
            .into_iter()
            .take(tris.triangles.len())
            .collect();
        let spheres: Vec<_> = geometry
            .spheres
            .iter()
            .map(|s| (s.center, s.radius))
            .collect();
        let opts = Accel::default_options(strategy, Layout::Wide4);
        let bvh = binary_tree(&soup, &spheres, opts);
        let n = bvh.nodes().len();
        let mut view = BvhView {
            bvh,
            opts,
            parent: vec![None; n],
            slots: vec![(0, 0); n],
            cost: vec![0.0; n],
        };
        if n > 0 {
            view.visit(0);
        }
        view
    }

    /// Children of interior node `i`: the next node and `offset`.
    fn children(&self, i: u32) -> Option<(u32, u32)> {
        let node = self.bvh.nodes().get(i as usize)?;
        (!node.is_leaf()).then_some((i + 1, node.offset))
    }

    /// Fills parent, slot range and cost below `root`, without recursion
    /// (a degenerate tree may be deep).
    fn visit(&mut self, root: u32) {
        let mut stack = vec![(root, false)];
        while let Some((i, children_done)) = stack.pop() {
            let node = self.bvh.nodes()[i as usize];
            match self.children(i) {
                None => {
                    self.slots[i as usize] = (node.offset, node.count);
                    let block = self.opts.leaf_block.max(1) as u32;
                    self.cost[i as usize] =
                        self.opts.intersection_cost * node.count.div_ceil(block) as f32;
                }
                Some((l, r)) if children_done => {
                    let (ls, lc) = self.slots[l as usize];
                    let (_, rc) = self.slots[r as usize];
                    self.slots[i as usize] = (ls, lc + rc);
                    let area = node.bounds().half_area();
                    let part = |c: u32| {
                        let child = self.bvh.nodes()[c as usize].bounds().half_area();
                        let ratio = if area > 0.0 { child / area } else { 1.0 };
                        ratio * self.cost[c as usize]
                    };
                    self.cost[i as usize] = self.opts.traversal_cost + part(l) + part(r);
                }
                Some((l, r)) => {
                    self.parent[l as usize] = Some(i);
                    self.parent[r as usize] = Some(i);
                    stack.push((i, true));
                    stack.push((r, false));
                    stack.push((l, false));
                }
            }
        }
    }

    /// Nodes in the tree.
    pub fn len(&self) -> usize {
        self.bvh.nodes().len()
    }

    /// Whether the tree is empty (a scene with no primitives).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    fn depth(&self, mut i: u32) -> u32 {
        let mut d = 0;
        while let Some(p) = self.parent[i as usize] {
            (i, d) = (p, d + 1);
        }
        d
    }

    fn info(&self, i: u32) -> NodeInfo {
        let node = self.bvh.nodes()[i as usize];
        NodeInfo {
            index: i,
            min: node.min,
            max: node.max,
            primitives: self.slots[i as usize].1,
            leaf: node.is_leaf(),
            sah_cost: self.cost[i as usize],
            depth: self.depth(i),
        }
    }

    /// Node `i` with its family and primitives, or `None` if there is no
    /// such node.
    pub fn node(&self, i: u32) -> Option<NodeView> {
        if i as usize >= self.len() {
            return None;
        }
        let (first, count) = self.slots[i as usize];
        let order = self.bvh.primitive_order();
        let prims = order
            .get(first as usize..(first + count) as usize)
            .unwrap_or(&[])
            .to_vec();
        let children = self
            .children(i)
            .map(|(l, r)| vec![self.info(l), self.info(r)])
            .unwrap_or_default();
        Some(NodeView {
            node: self.info(i),
            parent: self.parent[i as usize],
            children,
            prims,
            nodes: self.len() as u32,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use candela_render::scene::{Scene, SceneOptions};

    #[test]
    fn the_root_covers_every_primitive_and_children_split_it() {
        let loaded = candela_scene::demo_scene();
        let opts = SceneOptions {
            width: 8,
            height: 6,
            ..Default::default()
        };
        let scene = Scene::build(&loaded.scene, &opts).unwrap();
        let view = BvhView::build(&scene.geometry, BuildStrategy::Sah);
        let root = view.node(0).unwrap();
        let n = scene.geometry.len() as u32;
        assert_eq!(root.node.primitives, n);
        let mut ids = root.prims.clone();
        ids.sort_unstable();
        assert_eq!(ids, (0..n).collect::<Vec<_>>());
        assert_eq!(root.children.len(), 2);
        let [l, r] = [&root.children[0], &root.children[1]];
        assert_eq!(l.primitives + r.primitives, n);
        // A child's box lies inside its parent's.
        for c in [l, r] {
            for k in 0..3 {
                assert!(c.min[k] >= root.node.min[k] && c.max[k] <= root.node.max[k]);
            }
            assert_eq!(view.node(c.index).unwrap().parent, Some(0));
        }
        // The root's cost is one step plus the area-weighted children.
        assert!(root.node.sah_cost > 1.0);
        assert!(view.node(view.len() as u32).is_none());
    }
}

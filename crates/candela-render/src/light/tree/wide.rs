//! The 4-wide tree the walk reads: the binary tree of `build.rs` with every
//! other level folded away, so that each node holds the bounds of up to
//! four children side by side ([`Bounds4`]) and one pass of 4-lane
//! arithmetic weighs them all. The walk is half as deep and costs one
//! importance evaluation per level instead of two (the layout of wide
//! BVHs for rays; Conty Estevez and Kulla's importance is unchanged).

use super::importance::Bounds4;
use super::{LightBounds, Node};

/// Marks a child that is a light (its index in the low bits), not a node.
pub(super) const LEAF: u32 = 1 << 31;

/// A node: its children's bounds in lanes, and per lane a child node's
/// index or `LEAF | light`. Unused lanes have zero power (importance 0,
/// never taken).
#[derive(Clone, Copy, Debug)]
pub(super) struct WideNode {
    pub bounds: Bounds4,
    pub child: [u32; 4],
}

/// The collapsed tree, each light's trail (two bits per level: the lane
/// taken), and the number of levels down to the deepest light.
pub(super) struct Wide {
    pub nodes: Vec<WideNode>,
    pub trails: Vec<Option<u64>>,
    pub depth: u32,
}

/// Collapses the binary tree `binary` (at least one node) over lights
/// indexed below `light_count`.
pub(super) fn collapse(binary: &[Node], light_count: usize) -> Wide {
    let mut wide = Wide {
        nodes: Vec::with_capacity(binary.len() / 3 + 1),
        trails: vec![None; light_count],
        depth: 0,
    };
    if binary[0].leaf {
        // A single light: a root with one lane.
        let light = binary[0].second_or_light;
        wide.nodes.push(WideNode {
            bounds: Bounds4::new(&[binary[0].bounds]),
            child: [LEAF | light, 0, 0, 0],
        });
        wide.trails[light as usize] = Some(0);
        wide.depth = 1;
    } else {
        node(binary, 0, 0, 0, &mut wide);
    }
    wide
}

/// Appends the wide node for binary interior node `at` (and its subtree),
/// reached at `level` by `trail`; returns its index.
fn node(binary: &[Node], at: usize, level: u32, trail: u64, out: &mut Wide) -> u32 {
    // The children of `at`, each interior one replaced by its own two.
    let mut kids = Vec::with_capacity(4);
    for c in [at + 1, binary[at].second_or_light as usize] {
        if binary[c].leaf {
            kids.push(c);
        } else {
            kids.push(c + 1);
            kids.push(binary[c].second_or_light as usize);
        }
    }
    let index = out.nodes.len();
    let bounds: Vec<LightBounds> = kids.iter().map(|&k| binary[k].bounds).collect();
    out.nodes.push(WideNode {
        bounds: Bounds4::new(&bounds),
        child: [0; 4],
    });
    let mut child = [0; 4];
    for (lane, &k) in kids.iter().enumerate() {
        let trail = trail | (lane as u64) << (2 * level);
        child[lane] = if binary[k].leaf {
            let light = binary[k].second_or_light;
            out.trails[light as usize] = Some(trail);
            out.depth = out.depth.max(level + 1);
            LEAF | light
        } else {
            node(binary, k, level + 1, trail, out)
        };
    }
    out.nodes[index].child = child;
    index as u32
}

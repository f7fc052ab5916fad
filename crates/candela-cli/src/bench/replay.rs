//! `candela bench rays`: replay a fixed ray set, check it, time it.

use super::files::{read_hits, read_rays, read_tri};
use super::{report_line, throughput, RaysArgs};
use anyhow::{bail, Result};
use candela_bvh::{BuildOptions, Bvh4, Bvh8};
use candela_render::accel::{
    binary_tree, primitive_boxes, triangle_soup, Accel, Layout, TraversalStats,
};
use candela_render::geometry::Ray;
use glam::Vec3;

/// Reads, builds, checks, then times closest and any hit on 1 and N threads.
pub fn run(args: &RaysArgs) -> Result<()> {
    let mesh = read_tri(&args.mesh)?;
    let set = read_rays(&args.rays)?;
    let hits = args.hits.as_deref().map(read_hits).transpose()?;
    let n_tri = mesh.indices.len();
    println!(
        "{}: {n_tri} triangles; {}: {} {} rays",
        args.mesh.display(),
        args.rays.display(),
        set.rays.len(),
        if set.kind == 0 { "primary" } else { "diffuse" }
    );
    let soup = triangle_soup(&mesh.positions, &mesh.indices)?;
    let mut opts = Accel::default_options(args.bvh.into(), args.layout.into());
    opts.intersection_cost = args.isect_cost.unwrap_or(opts.intersection_cost);
    opts.max_leaf_size = args.max_leaf.unwrap_or(opts.max_leaf_size);
    opts.leaf_block = args.leaf_block.unwrap_or(opts.leaf_block);
    opts.collapse = args.collapse.map_or(opts.collapse, Into::into);
    opts.wide_node_cost = args.node_cost.unwrap_or(opts.wide_node_cost);
    opts.wide_leaf_cost = args.leaf_cost.unwrap_or(opts.wide_leaf_cost);
    let accel = Accel::build_with_options(&soup, &[], opts, args.layout.into());
    print_sah_cost(&soup, opts, args.layout.into());
    drop(soup);
    let info = accel.info();
    println!(
        "build ({:?}, {:?}): {:.1} ms, {} nodes, depth {}, BVH {:.1} bytes/triangle, with triangle data {:.1} bytes/triangle",
        args.bvh,
        candela_render::accel::Layout::from(args.layout),
        info.build_seconds * 1e3,
        info.nodes,
        info.depth,
        info.bvh_bytes as f64 / n_tri.max(1) as f64,
        info.total_bytes as f64 / n_tri.max(1) as f64
    );
    let rays: Vec<Ray> = set
        .rays
        .iter()
        .take(args.limit.unwrap_or(usize::MAX))
        .map(|&(o, d)| Ray {
            origin: o,
            dir: d,
            t_max: set.t_far,
        })
        .collect();
    if let Some(hits) = &hits {
        check_hits(&accel, &rays, hits, &mesh.positions, &mesh.indices)?;
    }
    let mut stats = TraversalStats::default();
    for r in &rays {
        accel.intersect_counted(r, &mut stats);
    }
    let mut any_stats = TraversalStats::default();
    for r in &rays {
        accel.occluded_counted(r, &mut any_stats);
    }
    let n = rays.len().max(1) as f64;
    for (query, s) in [("closest", &stats), ("any", &any_stats)] {
        println!(
            "{query} hit: {:.1} nodes, {:.1} triangle tests per ray",
            s.nodes_visited as f64 / n,
            s.prims_tested as f64 / n
        );
    }
    let modes: &[bool] = if args.any_hit {
        &[true]
    } else {
        &[false, true]
    };
    for &any in modes {
        for threads in [1, args.threads] {
            let (m, h) = throughput(&accel, &rays, threads, any, args.seconds)?;
            report_line(
                if any { "any" } else { "closest" },
                threads,
                &m,
                h,
                rays.len(),
            );
            if args.threads == 1 {
                break;
            }
        }
    }
    Ok(())
}

/// Prints the wide tree's SAH cost (node tests and leaf visits at the
/// build's costs, leaf blocks of 4), from a second build of the same tree.
fn print_sah_cost(soup: &[[Vec3; 3]], opts: BuildOptions, layout: Layout) {
    let boxes = primitive_boxes(soup, &[]);
    let bvh = binary_tree(soup, &[], opts);
    let (node, leaf) = (opts.wide_node_cost, opts.wide_leaf_cost);
    let cost = match layout {
        Layout::Binary => return,
        Layout::Wide4 => Bvh4::from_binary_filled(bvh, &boxes, 4).sah_cost(node, leaf, 4),
        Layout::Wide8 => Bvh8::from_binary_filled(bvh, &boxes, 4).sah_cost(node, leaf, 4),
    };
    println!(
        "SAH cost: {cost:.2} (collapse {:?}, node cost {node}, leaf cost {leaf})",
        opts.collapse
    );
}

/// Compares closest hits with the reference. Ids must match and `t` agree
/// to 1e-5 relative; a different id at the same `t` is an exact tie (an edge
/// or vertex shared by two triangles) and is only reported. For very short
/// rays, 1e-5 of `t` is below what f32 can resolve (`t` comes from
/// coordinates of the size of the origin and of the triangle's vertices
/// relative to it, each rounded to an ulp), so a `t` within two ulps of the
/// largest such coordinate is accepted and counted separately.
fn check_hits(
    accel: &Accel,
    rays: &[Ray],
    hits: &[(f32, u32)],
    pos: &[Vec3],
    idx: &[[u32; 3]],
) -> Result<()> {
    // With --limit, only the replayed rays are checked.
    let hits = &hits[..hits.len().min(rays.len())];
    let (mut ties, mut bad, mut ulp_close) = (Vec::new(), Vec::new(), 0);
    for (i, (&(t_ref, id_ref), ray)) in hits.iter().zip(rays).enumerate() {
        let got = accel.intersect(ray);
        // Replayed scenes are triangle soups: the hit is triangle `id`.
        let (t, id) = got.map_or((f32::INFINITY, u32::MAX), |h| (h.t, h.prim.index()));
        let t_ok = t == t_ref || ((t - t_ref) / t_ref).abs() <= 1e-5;
        if id == id_ref && t_ok {
            continue;
        }
        let scale = idx.get(id as usize).map_or(0.0, |t| {
            t.iter()
                .map(|&v| (pos[v as usize] - ray.origin).abs().max_element())
                .fold(0.0, f32::max)
        });
        let ulp = 2.0 * ray.origin.abs().max_element().max(scale) * f32::EPSILON;
        if id == id_ref && (t - t_ref).abs() <= ulp {
            ulp_close += 1;
            continue;
        }
        if t_ok && id != u32::MAX && id_ref != u32::MAX && shares_vertex(idx, id, id_ref, pos) {
            ties.push(i);
        } else {
            bad.push(format!(
                "ray {i}: got t={t} id={id}, reference t={t_ref} id={id_ref}"
            ));
        }
    }
    println!(
        "check: {} of {} rays match the reference ({ulp_close} of them only to within 2 ulp of the coordinates); {} exact-edge ties {:?}",
        hits.len() - ties.len() - bad.len(),
        hits.len(),
        ties.len(),
        &ties[..ties.len().min(10)]
    );
    if !bad.is_empty() {
        bail!(
            "{} rays disagree with the reference:\n{}",
            bad.len(),
            bad[..bad.len().min(20)].join("\n")
        );
    }
    Ok(())
}

/// True if the two triangles share a vertex position (a tie on an edge or
/// vertex between them is then a legitimate alternative answer).
fn shares_vertex(idx: &[[u32; 3]], a: u32, b: u32, pos: &[Vec3]) -> bool {
    let (Some(ta), Some(tb)) = (idx.get(a as usize), idx.get(b as usize)) else {
        return false;
    };
    ta.iter().any(|&i| {
        tb.iter()
            .any(|&j| i == j || pos[i as usize] == pos[j as usize])
    })
}

//! Loads scene files and prints a summary and the load time of each
//! (`cargo run --release -p candela-scene --example load_timing -- FILES...`).

use candela_scene::{load, LoadOptions};
use std::path::Path;
use std::time::Instant;

fn main() {
    for arg in std::env::args().skip(1) {
        let path = Path::new(&arg);
        let mut best = f64::INFINITY;
        let mut last = None;
        for _ in 0..5 {
            let t = Instant::now();
            let r = load(path, &LoadOptions::default());
            best = best.min(t.elapsed().as_secs_f64() * 1e3);
            last = Some(r);
        }
        match last {
            Some(Ok(l)) => {
                let s = &l.scene;
                println!(
                    "{arg}: {:.2} ms, {} meshes, {} triangles, {} spheres, {} lights, {} cameras, {} materials, bounds {:?}",
                    best,
                    s.meshes.len(),
                    s.triangle_count(),
                    s.spheres.len(),
                    s.lights.len(),
                    s.cameras.len(),
                    s.materials.len(),
                    s.bounds()
                );
                print!("{}", l.report);
            }
            Some(Err(e)) => println!("{e}"),
            None => {}
        }
    }
}

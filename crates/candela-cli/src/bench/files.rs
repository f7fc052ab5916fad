//! Readers for the shared ray-replay formats (`.tri`, `.rays`, `.hits`;
//! described in the benchmark data's README). All little-endian.

use anyhow::{bail, ensure, Context, Result};
use glam::Vec3;
use std::path::Path;

/// A triangle mesh from a `.tri` file.
pub struct TriFile {
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Three vertex indices per triangle; the row is the primitive id.
    pub indices: Vec<[u32; 3]>,
}

/// Rays from a `.rays` file, with `t` in `(tnear, tfar)` from its header.
pub struct RaysFile {
    /// Origin and unit direction of each ray.
    pub rays: Vec<(Vec3, Vec3)>,
    /// 0 primary, 1 diffuse.
    pub kind: u32,
    /// Upper end of every ray's interval.
    pub t_far: f32,
}

/// Reference closest hits from a `.hits` file: `(t, id)`, a miss is `(inf, u32::MAX)`.
pub type Hits = Vec<(f32, u32)>;

fn u32_at(b: &[u8], at: usize) -> u32 {
    u32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]])
}
fn f32_at(b: &[u8], at: usize) -> f32 {
    f32::from_bits(u32_at(b, at))
}
fn vec_at(b: &[u8], at: usize) -> Vec3 {
    Vec3::new(f32_at(b, at), f32_at(b, at + 4), f32_at(b, at + 8))
}

/// Reads the file and checks its magic, version and exact length.
fn read_checked(path: &Path, magic: &[u8; 4], header: usize) -> Result<Vec<u8>> {
    let b = std::fs::read(path).with_context(|| format!("reading {}", path.display()))?;
    ensure!(
        b.len() >= header,
        "{}: {} bytes, shorter than the {header}-byte header",
        path.display(),
        b.len()
    );
    if &b[..4] != magic {
        bail!(
            "{}: not a {} file (magic {:?})",
            path.display(),
            String::from_utf8_lossy(magic),
            &b[..4]
        );
    }
    let version = u32_at(&b, 4);
    ensure!(
        version == 1,
        "{}: unsupported version {version}",
        path.display()
    );
    Ok(b)
}

fn check_len(path: &Path, b: &[u8], want: u64) -> Result<()> {
    ensure!(
        b.len() as u64 == want,
        "{}: {} bytes, but the header implies {want}",
        path.display(),
        b.len()
    );
    Ok(())
}

/// Reads a `.tri` mesh; fails on a bad header, a wrong length or an index out of range.
pub fn read_tri(path: &Path) -> Result<TriFile> {
    let b = read_checked(path, b"TRIM", 64)?;
    let (nv, nt) = (u32_at(&b, 8) as u64, u32_at(&b, 12) as u64);
    check_len(path, &b, 64 + nv * 12 + nt * 12)?;
    let positions: Vec<Vec3> = (0..nv as usize).map(|i| vec_at(&b, 64 + 12 * i)).collect();
    let base = 64 + 12 * nv as usize;
    let mut indices = Vec::with_capacity(nt as usize);
    for t in 0..nt as usize {
        let at = base + 12 * t;
        let idx = [u32_at(&b, at), u32_at(&b, at + 4), u32_at(&b, at + 8)];
        if let Some(bad) = idx.iter().find(|&&i| i as u64 >= nv) {
            bail!(
                "{}: triangle {t} uses vertex {bad}, but there are {nv}",
                path.display()
            );
        }
        indices.push(idx);
    }
    Ok(TriFile { positions, indices })
}

/// Reads a `.rays` set.
pub fn read_rays(path: &Path) -> Result<RaysFile> {
    let b = read_checked(path, b"RAYS", 64)?;
    let n = u64::from_le_bytes(b[8..16].try_into()?);
    check_len(path, &b, 64 + n.saturating_mul(24))?;
    let (kind, t_near, t_far) = (u32_at(&b, 16), f32_at(&b, 32), f32_at(&b, 36));
    ensure!(
        t_near == 0.0,
        "{}: tnear {t_near} unsupported (rays start at 0)",
        path.display()
    );
    let rays = (0..n as usize)
        .map(|i| (vec_at(&b, 64 + 24 * i), vec_at(&b, 64 + 24 * i + 12)))
        .collect();
    Ok(RaysFile { rays, kind, t_far })
}

/// Reads a `.hits` file.
pub fn read_hits(path: &Path) -> Result<Hits> {
    let b = read_checked(path, b"HITS", 32)?;
    let n = u32_at(&b, 8) as u64;
    check_len(path, &b, 32 + n * 8)?;
    Ok((0..n as usize)
        .map(|i| (f32_at(&b, 32 + 8 * i), u32_at(&b, 36 + 8 * i)))
        .collect())
}

//! The readable report of `candela compare`: one column per comparison.

use candela_image::metrics::comparison::{Comparison, Entry};
use std::fmt::Write;
use std::path::Path;

/// A row: its label and how to print one entry's cell.
type Row = (&'static str, Box<dyn Fn(&Entry) -> String>);

/// The report as an aligned table.
pub fn render(c: &Comparison) -> String {
    let name = |p: &Path| {
        p.file_name().map_or_else(
            || p.display().to_string(),
            |n| n.to_string_lossy().into_owned(),
        )
    };
    let headers: Vec<String> = c
        .entries
        .iter()
        .map(|e| format!("{} vs {}", name(&e.test), name(&e.against)))
        .collect();
    let mut rows: Vec<Row> = vec![
        (
            "relMSE (pbrt, eps 0.01)",
            Box::new(|e| sci(e.report.rel_mse)),
        ),
        ("MSE", Box::new(|e| sci(e.report.mse))),
        (
            "PSNR (peak 1)",
            Box::new(|e| format!("{:.2} dB", e.report.psnr)),
        ),
        ("z-test", Box::new(|e| verdict(e).to_string())),
        ("  max block |z|", Box::new(worst)),
        (
            "  global |z|",
            Box::new(|e| format!("{:.2}", e.report.z.global_abs_z)),
        ),
        (
            "  threshold |z|",
            Box::new(|e| format!("{:.2}", e.report.z.threshold)),
        ),
        (
            "  tests over",
            Box::new(|e| format!("{} of {}", e.report.z.count_over, 3 * e.report.z.blocks)),
        ),
        (
            "  variance from",
            Box::new(|e| e.report.variance_source.name().to_string()),
        ),
        ("spp (min/mean/max)", Box::new(spp)),
        (
            "render time",
            Box::new(|e| {
                e.info
                    .time_seconds
                    .map_or("-".into(), |t| format!("{t:.3} s"))
            }),
        ),
    ];
    if c.reference.is_some() {
        rows.push((
            "efficiency 1/(relMSE*s)",
            Box::new(|e| e.efficiency.map_or("-".into(), sci)),
        ));
    }
    let label_width = rows.iter().map(|(l, _)| l.len()).max().unwrap_or(0);
    let cells: Vec<Vec<String>> = rows
        .iter()
        .map(|(_, f)| c.entries.iter().map(f).collect())
        .collect();
    let widths: Vec<usize> = (0..c.entries.len())
        .map(|i| {
            cells
                .iter()
                .map(|r| r[i].len())
                .chain([headers[i].len()])
                .max()
                .unwrap_or(0)
        })
        .collect();
    let mut out = String::new();
    let line = |out: &mut String, label: &str, values: &[String]| {
        let _ = write!(out, "{label:<label_width$}");
        for (v, w) in values.iter().zip(&widths) {
            let _ = write!(out, "  {v:>w$}");
        }
        out.push('\n');
    };
    line(&mut out, "", &headers);
    for ((label, _), values) in rows.iter().zip(&cells) {
        line(&mut out, label, values);
    }
    let blocks = c.options.block_size;
    let _ = writeln!(
        out,
        "(z-test: {blocks}x{blocks} blocks, {}% family-wise false alarms)",
        c.options.false_alarm_rate * 100.0
    );
    if let Some(ratio) = c.efficiency_ratio {
        let (a, b) = (name(&c.entries[0].test), name(&c.entries[1].test));
        let _ = writeln!(
            out,
            "efficiency ratio {a} / {b}: {ratio:.3} ({a} reaches equal relMSE {ratio:.3}x as fast)"
        );
    } else if c.reference.is_some() {
        out.push_str("efficiency ratio: - (needs render time and samples in both headers)\n");
    }
    out
}

fn sci(x: f64) -> String {
    format!("{x:.4e}")
}

fn verdict(e: &Entry) -> &'static str {
    if e.report.z.passed() {
        "pass"
    } else {
        "FAIL"
    }
}

fn worst(e: &Entry) -> String {
    let z = &e.report.z;
    let channel = ["R", "G", "B"][z.worst.2.min(2)];
    format!(
        "{:.2} at block ({}, {}) {channel}",
        z.max_abs_z, z.worst.0, z.worst.1
    )
}

fn spp(e: &Entry) -> String {
    match e.info.spp {
        Some(s) if s.min == s.max => s.min.to_string(),
        Some(s) => format!("{}/{:.1}/{}", s.min, s.mean, s.max),
        None => "-".into(),
    }
}

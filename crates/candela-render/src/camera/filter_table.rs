//! The tabulated filter the camera samples from and the splats weigh by
//! (see `filter.rs` for the estimator).

use super::filter::PixelFilter;
use crate::sampling::piecewise::Distribution1D;
use glam::Vec2;
use std::sync::Arc;

/// Table cells per pixel of the filter's support.
const CELLS_PER_PIXEL: f32 = 32.0;

/// A filter ready to use: its description and, unless it is the
/// one-pixel box (which keeps the old path), its 1-D table.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FilmFilter {
    spec: PixelFilter,
    table: Option<Arc<FilterTable>>,
}

/// `f₁` at the centres of `n` equal cells over `[−r, r)`, its `|f₁|` as a
/// distribution, and the constants of the weights.
#[derive(Debug, PartialEq)]
struct FilterTable {
    radius: f32,
    values: Vec<f32>,
    abs: Distribution1D,
    /// `1 / ∫f₁`: turns a table value into the normalised `f_n`.
    inv_integral: f32,
    /// `∫|f₁| / ∫f₁`: the magnitude of a sample's weight per axis.
    weight: f32,
}

impl FilterTable {
    fn new(spec: &PixelFilter) -> Self {
        let radius = spec.radius();
        let n = (2.0 * radius * CELLS_PER_PIXEL).ceil().max(1.0) as usize;
        let cell = 2.0 * radius / n as f32;
        let values: Vec<f32> = (0..n)
            .map(|i| spec.eval_1d(-radius + (i as f32 + 0.5) * cell))
            .collect();
        let abs_values: Vec<f32> = values.iter().map(|v| v.abs()).collect();
        let integral: f64 = values.iter().map(|&v| f64::from(v)).sum::<f64>() * f64::from(cell);
        let abs_integral: f64 =
            abs_values.iter().map(|&v| f64::from(v)).sum::<f64>() * f64::from(cell);
        Self {
            radius,
            abs: Distribution1D::new(&abs_values),
            values,
            inv_integral: (1.0 / integral) as f32,
            weight: (abs_integral / integral) as f32,
        }
    }

    /// An offset in `[−r, r)` from `u` and its weight `f₁/(p ∫f₁)`.
    fn sample(&self, u: f32) -> (f32, f32) {
        let (x, _, i) = self.abs.sample(u);
        let offset = (2.0 * x - 1.0) * self.radius;
        let w = if self.values[i] < 0.0 {
            -self.weight
        } else {
            self.weight
        };
        (offset, w)
    }

    /// The cell of `offset`, if inside the support.
    fn cell(&self, offset: f32) -> Option<usize> {
        let t = (offset + self.radius) / (2.0 * self.radius);
        (0.0..1.0).contains(&t).then(|| self.abs.cell_of(t))
    }

    /// The normalised `f_n` at `offset` (0 outside the support).
    fn eval(&self, offset: f32) -> f32 {
        self.cell(offset)
            .map_or(0.0, |i| self.values[i] * self.inv_integral)
    }

    /// The density of [`FilterTable::sample`]'s offsets at `offset`.
    fn pdf(&self, offset: f32) -> f32 {
        self.cell(offset).map_or(0.0, |i| {
            self.abs.pdf((i as f32 + 0.5) / self.abs.len() as f32) / (2.0 * self.radius)
        })
    }
}

impl FilmFilter {
    /// The filter `spec` (validated by the settings), tabulated unless it
    /// is the one-pixel box.
    pub fn new(spec: PixelFilter) -> Self {
        let table = (!spec.is_pixel_box()).then(|| Arc::new(FilterTable::new(&spec)));
        Self { spec, table }
    }

    /// The filter's description.
    pub fn spec(&self) -> PixelFilter {
        self.spec
    }

    /// Whether samples take the old path: a uniform point in the pixel,
    /// weight 1, splats to the pixel they land in.
    pub fn is_pixel_box(&self) -> bool {
        self.table.is_none()
    }

    /// How far outside the frame (pixels) a film point may lie and still
    /// count for an edge pixel: `radius − 0.5`, 0 for the one-pixel box.
    pub fn margin(&self) -> f32 {
        self.table
            .as_ref()
            .map_or(0.0, |t| (t.radius - 0.5).max(0.0))
    }

    /// The film point offset from the pixel centre drawn from `u` (the
    /// sampler's 2-D number), and the sample's weight `f/p` over `∫f`
    /// (1 for non-negative filters). The one-pixel box answers
    /// `(u − 0.5, 1)`; the camera takes its own path for it.
    pub fn sample(&self, u: Vec2) -> (Vec2, f32) {
        match &self.table {
            None => (u - Vec2::splat(0.5), 1.0),
            Some(t) => {
                let (x, wx) = t.sample(u.x);
                let (y, wy) = t.sample(u.y);
                (Vec2::new(x, y), wx * wy)
            }
        }
    }

    /// The normalised filter `f_n(offset)` (integral 1 over the plane).
    pub fn eval(&self, offset: Vec2) -> f32 {
        match &self.table {
            None => {
                let inside = |d: f32| (-0.5..0.5).contains(&d);
                if inside(offset.x) && inside(offset.y) {
                    1.0
                } else {
                    0.0
                }
            }
            Some(t) => t.eval(offset.x) * t.eval(offset.y),
        }
    }

    /// The density of [`FilmFilter::sample`]'s offsets, per unit area.
    pub fn pdf(&self, offset: Vec2) -> f32 {
        match &self.table {
            None => self.eval(offset),
            Some(t) => t.pdf(offset.x) * t.pdf(offset.y),
        }
    }

    /// The pixels whose filter covers film point `film` on a `width` ×
    /// `height` frame, each with the weight `f_n(film − centre)` (zero
    /// weights left out): where a splat at `film` goes.
    pub fn pixels_covering(
        &self,
        film: Vec2,
        width: u32,
        height: u32,
    ) -> impl Iterator<Item = (u32, u32, f32)> + '_ {
        let r = self.spec.radius();
        let span = |c: f32, n: u32| {
            let lo = (c - 0.5 - r).floor().max(0.0) as i64;
            let hi = ((c - 0.5 + r).ceil() as i64).min(n as i64 - 1);
            lo..=hi
        };
        let (xs, ys) = (span(film.x, width), span(film.y, height));
        ys.flat_map(move |py| xs.clone().map(move |px| (px, py)))
            .filter_map(move |(px, py)| {
                let centre = Vec2::new(px as f32 + 0.5, py as f32 + 0.5);
                let w = self.eval(film - centre);
                (w != 0.0).then_some((px as u32, py as u32, w))
            })
    }
}

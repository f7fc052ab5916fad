//! Rectangles of pixels: the CS184 cell (`-p X Y DX DY`) and render tiles.

/// A rectangle of pixels `[x, x + width) × [y, y + height)`, y = 0 at the top.
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize,
)]
pub struct PixelRect {
    /// Left column.
    pub x: u32,
    /// Top row.
    pub y: u32,
    /// Columns.
    pub width: u32,
    /// Rows.
    pub height: u32,
}

impl PixelRect {
    /// A rectangle from its corner and size.
    pub fn new(x: u32, y: u32, width: u32, height: u32) -> Self {
        Self {
            x,
            y,
            width,
            height,
        }
    }

    /// The whole `width` × `height` frame.
    pub fn full(width: u32, height: u32) -> Self {
        Self::new(0, 0, width, height)
    }

    /// Number of pixels.
    pub fn area(&self) -> u64 {
        self.width as u64 * self.height as u64
    }

    /// One past the right column and the bottom row.
    pub fn end(&self) -> (u32, u32) {
        (
            self.x.saturating_add(self.width),
            self.y.saturating_add(self.height),
        )
    }

    /// The part of this rectangle inside a `width` × `height` frame.
    pub fn clamped(&self, width: u32, height: u32) -> Self {
        let (x0, y0) = (self.x.min(width), self.y.min(height));
        let (x1, y1) = self.end();
        Self::new(x0, y0, x1.min(width) - x0, y1.min(height) - y0)
    }

    /// Whether the rectangle lies entirely inside a `width` × `height` frame
    /// (an empty rectangle never does, so that a cell always renders something).
    pub fn fits_in(&self, width: u32, height: u32) -> bool {
        let (x1, y1) = self.end();
        self.area() > 0 && x1 <= width && y1 <= height
    }

    /// The pixels, row by row.
    pub fn pixels(self) -> impl Iterator<Item = (u32, u32)> {
        let (x1, y1) = self.end();
        (self.y..y1).flat_map(move |y| (self.x..x1).map(move |x| (x, y)))
    }

    /// Cuts the rectangle into `tile` × `tile` squares (smaller at the right
    /// and bottom edges), row by row. A `tile` of 0 is taken as 1.
    pub fn tiles(self, tile: u32) -> Vec<PixelRect> {
        let tile = tile.max(1);
        let (x1, y1) = self.end();
        let mut out = Vec::new();
        for y in (self.y..y1).step_by(tile as usize) {
            for x in (self.x..x1).step_by(tile as usize) {
                out.push(Self::new(x, y, tile.min(x1 - x), tile.min(y1 - y)));
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tiles_cover_the_rectangle_exactly_once() {
        let rect = PixelRect::new(3, 5, 37, 20);
        for tile in [1, 7, 16, 64] {
            let mut seen = std::collections::HashSet::new();
            for t in rect.tiles(tile) {
                assert!(t.width <= tile && t.height <= tile);
                for p in t.pixels() {
                    assert!(seen.insert(p), "pixel {p:?} twice with tile {tile}");
                }
            }
            assert_eq!(seen.len() as u64, rect.area());
            assert!(seen
                .iter()
                .all(|&(x, y)| (3..40).contains(&x) && (5..25).contains(&y)));
        }
    }

    #[test]
    fn clamping_and_fitting() {
        assert_eq!(
            PixelRect::new(90, 10, 20, 5).clamped(100, 12),
            PixelRect::new(90, 10, 10, 2)
        );
        assert_eq!(PixelRect::new(200, 0, 5, 5).clamped(100, 100).area(), 0);
        assert!(PixelRect::new(0, 0, 100, 100).fits_in(100, 100));
        assert!(!PixelRect::new(1, 0, 100, 100).fits_in(100, 100));
        assert!(!PixelRect::new(0, 0, 0, 10).fits_in(100, 100));
        assert!(!PixelRect::new(u32::MAX, 0, 10, 10).fits_in(100, 100));
    }
}

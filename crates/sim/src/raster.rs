//! The surface raster: the material of the top-most surface at each cell
//! centre, built once at load time by scan-line filling the surfaces in
//! document order. Cells are stored in 8×8 tiles of one byte each, so a tile
//! is one 64-byte cache line and a robot's sensors touch few lines per step.

use glam::DVec2;

use crate::geometry::{FillRule, Shape};

/// Tile side in cells (8×8 one-byte cells = one cache line).
const TILE: usize = 8;

/// Zero bytes after the last tile, so that a 4-byte gather at any cell's
/// index stays inside the allocation (the sensors' vector look-up).
pub(crate) const PAD: usize = 3;

/// Grid of material ids (0 = background, `m` = `Scenario::materials[m]`).
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceRaster {
    /// Number of columns.
    pub cols: usize,
    /// Number of rows.
    pub rows: usize,
    /// Cell side in px.
    pub cell: f64,
    tiles_x: usize,
    ids: Vec<u8>,
}

impl SurfaceRaster {
    /// A raster with no cells (everything reads as outside).
    pub fn empty() -> SurfaceRaster {
        SurfaceRaster {
            cols: 0,
            rows: 0,
            cell: 1.0,
            tiles_x: 0,
            ids: Vec::new(),
        }
    }

    /// Storage index of cell (`c`, `r`); callers keep `c < cols`, `r < rows`.
    #[inline(always)]
    pub fn index(&self, c: usize, r: usize) -> usize {
        ((r / TILE) * self.tiles_x + c / TILE) * (TILE * TILE) + (r % TILE) * TILE + c % TILE
    }

    /// Material id of cell (`c`, `r`) known to be inside the arena (0 if not).
    #[inline(always)]
    pub fn get_in_arena(&self, c: usize, r: usize) -> u8 {
        let idx = ((r >> 3) * self.tiles_x + (c >> 3)) * (TILE * TILE) + ((r & 7) << 3) + (c & 7);
        self.ids.get(idx).copied().unwrap_or(0)
    }

    /// The tiled ids (then `PAD` zero bytes) and the number of tiles per row
    /// (for the sensors' own look-up).
    #[inline(always)]
    pub(crate) fn tiles(&self) -> (&[u8], usize) {
        (&self.ids, self.tiles_x)
    }

    /// Material id of cell (`c`, `r`) (0 when out of range).
    #[inline(always)]
    pub fn get(&self, c: usize, r: usize) -> u8 {
        if c < self.cols && r < self.rows {
            self.ids.get(self.index(c, r)).copied().unwrap_or(0)
        } else {
            0
        }
    }

    /// Rasterises `(shape, material id)` pairs (later ones cover earlier ones)
    /// on a `width`×`height` arena.
    pub fn build<'a>(
        width: f64,
        height: f64,
        cell: f64,
        shapes: impl IntoIterator<Item = (&'a Shape, u8)>,
    ) -> SurfaceRaster {
        let cols = (width / cell).ceil().max(1.0) as usize;
        let rows = (height / cell).ceil().max(1.0) as usize;
        let tiles_x = cols.div_ceil(TILE);
        let tiles_y = rows.div_ceil(TILE);
        let mut ras = SurfaceRaster {
            cols,
            rows,
            cell,
            tiles_x,
            ids: vec![0u8; tiles_x * tiles_y * TILE * TILE + PAD],
        };
        let mut xs: Vec<(f64, i32)> = Vec::new();
        for (shape, m) in shapes {
            let b = shape.bbox;
            let r0 = (b.min.y / cell - 0.5).ceil().max(0.0) as usize;
            let r1 = (b.max.y / cell - 0.5).floor().min(rows as f64 - 1.0) as isize;
            if r1 < 0 {
                continue;
            }
            for r in r0..=(r1 as usize) {
                let y = (r as f64 + 0.5) * cell;
                xs.clear();
                for ring in &shape.rings {
                    let n = ring.len();
                    let mut a = ring[n - 1];
                    for &p in ring {
                        // Half-open rule, the same as `Shape::winding`.
                        let dir = if a.y <= y && p.y > y {
                            1
                        } else if p.y <= y && a.y > y {
                            -1
                        } else {
                            0
                        };
                        if dir != 0 {
                            let x = a.x + (y - a.y) * (p.x - a.x) / (p.y - a.y);
                            xs.push((x, dir));
                        }
                        a = p;
                    }
                }
                xs.sort_by(|p, q| p.0.total_cmp(&q.0));
                let mut w = 0;
                for k in 0..xs.len().saturating_sub(1) {
                    w += xs[k].1;
                    let inside = match shape.fill_rule {
                        FillRule::NonZero => w != 0,
                        FillRule::EvenOdd => w % 2 != 0,
                    };
                    if !inside {
                        continue;
                    }
                    let c0 = (xs[k].0 / cell - 0.5).ceil().max(0.0) as usize;
                    let c1 = ((xs[k + 1].0 / cell - 0.5).ceil().min(cols as f64)).max(0.0) as usize;
                    for c in c0..c1 {
                        let i = ras.index(c, r);
                        ras.ids[i] = m;
                    }
                }
            }
        }
        ras
    }

    /// Material id at `p`: `None` outside the grid, `Some(0)` background.
    #[inline]
    pub fn id_at(&self, p: DVec2) -> Option<u8> {
        self.id_at_cell(p.x / self.cell, p.y / self.cell)
    }

    /// Material id at cell coordinates (`cx`, `cy`) = position / cell side:
    /// `None` outside the grid.
    #[inline(always)]
    pub(crate) fn id_at_cell(&self, cx: f64, cy: f64) -> Option<u8> {
        // For cx >= 0, `(cx as usize) < cols` holds exactly when `cx < cols` (cols
        // is an integer); testing in f64 first lets the conversion be the cheap
        // signed one instead of the branchy float-to-unsigned one.
        if cx >= 0.0 && cy >= 0.0 && cx < self.cols as f64 && cy < self.rows as f64 {
            let (c, r) = (cx as i64 as usize, cy as i64 as usize);
            Some(self.ids.get(self.index(c, r)).copied().unwrap_or(0))
        } else {
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tile_index_is_a_bijection() {
        let ras = SurfaceRaster {
            cols: 21,
            rows: 10,
            cell: 1.0,
            tiles_x: 3,
            ids: vec![0; 3 * 2 * 64],
        };
        let mut seen = vec![false; ras.ids.len()];
        for r in 0..10 {
            for c in 0..21 {
                let i = ras.index(c, r);
                assert!(!seen[i]);
                seen[i] = true;
            }
        }
    }
}

//! The surface raster: the id of the top-most surface at each cell centre,
//! built once at load time by scan-line filling the surfaces in document order.

use glam::DVec2;

use crate::geometry::FillRule;
use crate::scenario::Surface;

/// Grid of surface ids (0 = background, `i + 1` = `surfaces[i]`).
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceRaster {
    /// Number of columns.
    pub cols: usize,
    /// Number of rows.
    pub rows: usize,
    /// Cell side in px.
    pub cell: f64,
    inv_cell: f64,
    ids: Vec<u16>,
}

impl SurfaceRaster {
    /// A raster with no cells (everything reads as outside).
    pub fn empty() -> SurfaceRaster {
        SurfaceRaster {
            cols: 0,
            rows: 0,
            cell: 1.0,
            inv_cell: 1.0,
            ids: Vec::new(),
        }
    }

    /// Rasterises `surfaces` (later ones cover earlier ones) on a `width`×`height` arena.
    pub fn build(width: f64, height: f64, cell: f64, surfaces: &[Surface]) -> SurfaceRaster {
        let cols = (width / cell).ceil().max(1.0) as usize;
        let rows = (height / cell).ceil().max(1.0) as usize;
        let mut ids = vec![0u16; cols * rows];
        let mut xs: Vec<(f64, i32)> = Vec::new();
        // Ids beyond u16 are clamped: more than 65 534 surfaces is not a real scenario.
        for (si, s) in surfaces.iter().enumerate() {
            let sid = (si + 1).min(u16::MAX as usize) as u16;
            let b = s.shape.bbox;
            let r0 = ((b.min.y / cell - 0.5).ceil().max(0.0)) as usize;
            let r1 = ((b.max.y / cell - 0.5).floor().min(rows as f64 - 1.0)) as isize;
            if r1 < 0 {
                continue;
            }
            for r in r0..=(r1 as usize) {
                let y = (r as f64 + 0.5) * cell;
                xs.clear();
                for ring in &s.shape.rings {
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
                    let inside = match s.shape.fill_rule {
                        FillRule::NonZero => w != 0,
                        FillRule::EvenOdd => w % 2 != 0,
                    };
                    if !inside {
                        continue;
                    }
                    let c0 = (xs[k].0 / cell - 0.5).ceil().max(0.0) as usize;
                    let c1 = ((xs[k + 1].0 / cell - 0.5).ceil().min(cols as f64)).max(0.0) as usize;
                    if c0 < c1 {
                        ids[r * cols + c0..r * cols + c1].fill(sid);
                    }
                }
            }
        }
        SurfaceRaster {
            cols,
            rows,
            cell,
            inv_cell: 1.0 / cell,
            ids,
        }
    }

    /// Surface id at `p`: `None` outside the grid, `Some(0)` background.
    #[inline]
    pub fn id_at(&self, p: DVec2) -> Option<u16> {
        let cx = p.x * self.inv_cell;
        let cy = p.y * self.inv_cell;
        if cx >= 0.0 && cy >= 0.0 {
            let (c, r) = (cx as usize, cy as usize);
            if c < self.cols && r < self.rows {
                return Some(self.ids[r * self.cols + c]);
            }
        }
        None
    }
}

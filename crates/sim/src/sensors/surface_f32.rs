//! The surface sensors in single precision (the fast precision's read):
//! every sensor's cell computed in f32, 16 sensors per AVX-512 vector and 8
//! per AVX2 one (the f64 read has 8 and 4), the readings rounded to f32.
//!
//! Each path performs the same f32 operations in the same order as
//! [`Query32::one`] (separately rounded multiplies and adds, no FMA, ordered
//! compares, truncation to i32), so every level gives the same bits. They
//! are not always the f64 read's bits rounded: a sensor within an f32
//! rounding (about 6e-5 cells at 1,000 cells from the origin) of a cell
//! border may land in the neighbouring cell.

use std::ops::Range;

use super::surface::{Query, SurfaceGrid};
use crate::simd::SimdLevel;
use crate::world::World;

/// One robot's read in f32 and raster cells: as the f64 `Query`, rounded.
struct Query32<'a> {
    bx: f32,
    by: f32,
    axx: f32,
    axy: f32,
    rxx: f32,
    rxy: f32,
    limx: f32,
    limy: f32,
    tiles_x: usize,
    ids: &'a [u8],
    readings: &'a [f32; 256],
    /// At most 16 materials: one AVX-512 register holds every reading.
    few: bool,
}

impl<'w> Query32<'w> {
    /// Robot `i`'s read in `world`: the f64 read's frame in cells, rounded
    /// (built by the lane paths themselves, as [`Query::at`] says why).
    #[inline(always)]
    fn at(world: &'w World, i: usize) -> Self {
        let q = Query::at(world, i);
        Query32 {
            bx: q.base.x as f32,
            by: q.base.y as f32,
            axx: q.ax.x as f32,
            axy: q.ax.y as f32,
            rxx: q.rx.x as f32,
            rxy: q.rx.y as f32,
            limx: q.lim.x as f32,
            limy: q.lim.y as f32,
            tiles_x: q.tiles_x,
            ids: q.ids,
            readings: &world.statics.readings_f32,
            few: q.few,
        }
    }

    /// The reading at robot-frame offset (`x`, `y`): the formula every path follows.
    #[inline(always)]
    fn one(&self, x: f32, y: f32) -> f32 {
        let cx = self.bx + self.axx * x + self.rxx * y;
        let cy = self.by + self.axy * x + self.rxy * y;
        // Non-short-circuit tests compile to one branch; NaN is outside.
        if (cx >= 0.0) & (cy >= 0.0) & (cx < self.limx) & (cy < self.limy) {
            // In range, so the i32 truncation is exact; `limx` ≤ the raster's
            // columns (they are an integer below 2^24 and rounding is monotone).
            let (c, r) = (cx as i32 as usize, cy as i32 as usize);
            let idx = ((r >> 3) * self.tiles_x + (c >> 3)) * 64 + ((r & 7) << 3) + (c & 7);
            self.readings[self.ids.get(idx).copied().unwrap_or(0) as usize]
        } else {
            0.0
        }
    }

    /// Scalar read of every sensor.
    #[inline(always)]
    fn scalar(&self, ox: &[f32], oy: &[f32], out: &mut [f32]) {
        for ((v, &x), &y) in out.iter_mut().zip(ox).zip(oy) {
            *v = self.one(x, y);
        }
    }
}

/// Lane-wise reads: [`Query32::one`]'s arithmetic one sensor per lane, then
/// the two look-ups: as gathers (or one permute for few materials) with
/// AVX-512, one sensor at a time with AVX2. Only called when
/// `Statics::lanes` holds, so the u32 lane index equals `one`'s usize one
/// for every in-arena sensor.
#[cfg(target_arch = "x86_64")]
mod lanes {
    use std::arch::x86_64::*;

    use super::Query32;
    use crate::World;
    use crate::sensors::surface::SurfaceGrid;
    use crate::sensors::surface::each_robot;

    /// Largest index whose 4-byte gather stays inside `ids` (the raster pads
    /// `ids` with `raster::PAD` zero bytes so that this is the last cell).
    #[inline(always)]
    fn last_gather(q: &Query32) -> u32 {
        (q.ids.len() - crate::raster::PAD) as u32 - 1
    }

    each_robot!(avx2, avx2_robot, "avx2", f32);

    /// AVX2: eight sensors' cells per iteration, the last batch partial;
    /// the look-ups one sensor at a time.
    ///
    /// Scalar look-ups, not AVX2 gathers: on AMD Zen 4 the two dependent
    /// gathers took as long as the rest of the read, and the tail of a
    /// 15-sensor grid ran through `one` with a branch per sensor.
    ///
    /// # Safety
    /// The CPU must support AVX2; `q.ids.len()` must be in `PAD + 1 ..= u32::MAX`.
    #[target_feature(enable = "avx2")]
    #[inline]
    unsafe fn avx2_robot(g: &SurfaceGrid, world: &World, i: usize, out: &mut [f32]) {
        let (q, ox, oy) = (&Query32::at(world, i), &g.ox32[..], &g.oy32[..]);
        let n = out.len().min(ox.len()).min(oy.len());
        let (bx, by) = (_mm256_set1_ps(q.bx), _mm256_set1_ps(q.by));
        let (axx, axy) = (_mm256_set1_ps(q.axx), _mm256_set1_ps(q.axy));
        let (rxx, rxy) = (_mm256_set1_ps(q.rxx), _mm256_set1_ps(q.rxy));
        let (lx, ly) = (_mm256_set1_ps(q.limx), _mm256_set1_ps(q.limy));
        let zero = _mm256_setzero_ps();
        let tx = _mm256_set1_epi32(q.tiles_x as i32);
        let seven = _mm256_set1_epi32(7);
        let last = _mm256_set1_epi32(last_gather(q) as i32);
        let lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
        let mut idx = [0u32; 8];
        let mut j = 0;
        while j < n {
            let m = (n - j).min(8);
            // Lanes past the last sensor are neither loaded nor stored.
            let todo = _mm256_cmpgt_epi32(_mm256_set1_epi32(m as i32), lane);
            // SAFETY: the lanes of `todo` are j..j + m, inside ox and oy;
            // masked-off lanes are not accessed (and cannot fault).
            let (x, y) = unsafe {
                (
                    _mm256_maskload_ps(ox.as_ptr().add(j), todo),
                    _mm256_maskload_ps(oy.as_ptr().add(j), todo),
                )
            };
            let cx = _mm256_add_ps(
                _mm256_add_ps(bx, _mm256_mul_ps(axx, x)),
                _mm256_mul_ps(rxx, y),
            );
            let cy = _mm256_add_ps(
                _mm256_add_ps(by, _mm256_mul_ps(axy, x)),
                _mm256_mul_ps(rxy, y),
            );
            // Ordered compares: NaN is outside, as in `one`.
            let ins = _mm256_and_ps(
                _mm256_and_ps(
                    _mm256_cmp_ps::<_CMP_GE_OQ>(cx, zero),
                    _mm256_cmp_ps::<_CMP_GE_OQ>(cy, zero),
                ),
                _mm256_and_ps(
                    _mm256_cmp_ps::<_CMP_LT_OQ>(cx, lx),
                    _mm256_cmp_ps::<_CMP_LT_OQ>(cy, ly),
                ),
            );
            // Outside lanes become +0.0, so cell 0; their reading is not used.
            let c = _mm256_cvttps_epi32(_mm256_and_ps(cx, ins));
            let r = _mm256_cvttps_epi32(_mm256_and_ps(cy, ins));
            let tile = _mm256_add_epi32(
                _mm256_mullo_epi32(_mm256_srli_epi32::<3>(r), tx),
                _mm256_srli_epi32::<3>(c),
            );
            let within = _mm256_add_epi32(
                _mm256_slli_epi32::<3>(_mm256_and_si256(r, seven)),
                _mm256_and_si256(c, seven),
            );
            let cell = _mm256_add_epi32(_mm256_slli_epi32::<6>(tile), within);
            // Unsigned min: a no-op for the indices `one` computes, a bound for the look-up.
            let cell = _mm256_min_epu32(cell, last);
            // SAFETY: idx has room for the 8 lanes.
            unsafe { _mm256_storeu_si256(idx.as_mut_ptr().cast(), cell) };
            let inside = _mm256_movemask_ps(ins) as u32;
            for (l, (v, &k)) in out[j..j + m].iter_mut().zip(&idx).enumerate() {
                // SAFETY: k <= last < ids.len() (the min above).
                let id = unsafe { *q.ids.get_unchecked(k as usize) };
                let reading = q.readings[id as usize];
                *v = if inside >> l & 1 == 1 { reading } else { 0.0 };
            }
            j += 8;
        }
    }

    each_robot!(avx512, avx512_robot, "avx512f", f32);

    /// AVX-512F: sixteen sensors per iteration, the last batch masked.
    ///
    /// # Safety
    /// The CPU must support AVX-512F; `q.ids.len()` must be in `PAD + 1 ..= u32::MAX`.
    // avx512f implies FMA in LLVM, but Rust never fuses a separate mul and add
    // (no contraction), so the bits stay those of `one`.
    #[target_feature(enable = "avx512f")]
    #[inline]
    unsafe fn avx512_robot(g: &SurfaceGrid, world: &World, i: usize, out: &mut [f32]) {
        let (q, ox, oy) = (&Query32::at(world, i), &g.ox32[..], &g.oy32[..]);
        let n = out.len().min(ox.len()).min(oy.len());
        let (bx, by) = (_mm512_set1_ps(q.bx), _mm512_set1_ps(q.by));
        let (axx, axy) = (_mm512_set1_ps(q.axx), _mm512_set1_ps(q.axy));
        let (rxx, rxy) = (_mm512_set1_ps(q.rxx), _mm512_set1_ps(q.rxy));
        let (lx, ly) = (_mm512_set1_ps(q.limx), _mm512_set1_ps(q.limy));
        let zero = _mm512_setzero_ps();
        let tx = _mm512_set1_epi32(q.tiles_x as i32);
        let (seven, byte) = (_mm512_set1_epi32(7), _mm512_set1_epi32(0xff));
        let last = _mm512_set1_epi32(last_gather(q) as i32);
        // SAFETY: readings has 256 entries, so 0..16 are in bounds.
        let table = unsafe { _mm512_loadu_ps(q.readings.as_ptr()) };
        let mut j = 0;
        while j < n {
            // The last batch may be partial: its missing lanes are neither loaded nor stored.
            let todo: __mmask16 = if n - j >= 16 {
                0xffff
            } else {
                (1u16 << (n - j)) - 1
            };
            // SAFETY: the lanes of `todo` are j..min(j + 16, n), inside ox, oy and out;
            // masked-off lanes are not accessed (and cannot fault).
            let (x, y) = unsafe {
                (
                    _mm512_maskz_loadu_ps(todo, ox.as_ptr().add(j)),
                    _mm512_maskz_loadu_ps(todo, oy.as_ptr().add(j)),
                )
            };
            let cx = _mm512_add_ps(
                _mm512_add_ps(bx, _mm512_mul_ps(axx, x)),
                _mm512_mul_ps(rxx, y),
            );
            let cy = _mm512_add_ps(
                _mm512_add_ps(by, _mm512_mul_ps(axy, x)),
                _mm512_mul_ps(rxy, y),
            );
            // Ordered compares, each masked by the previous ones: NaN is outside.
            let ins = _mm512_cmp_ps_mask::<_CMP_GE_OQ>(cx, zero);
            let ins = _mm512_mask_cmp_ps_mask::<_CMP_GE_OQ>(ins, cy, zero);
            let ins = _mm512_mask_cmp_ps_mask::<_CMP_LT_OQ>(ins, cx, lx);
            let ins = _mm512_mask_cmp_ps_mask::<_CMP_LT_OQ>(ins, cy, ly);
            // Outside lanes become 0, so cell 0; their reading is discarded below.
            let c = _mm512_maskz_cvttps_epi32(ins, cx);
            let r = _mm512_maskz_cvttps_epi32(ins, cy);
            let tile = _mm512_add_epi32(
                _mm512_mullo_epi32(_mm512_srli_epi32::<3>(r), tx),
                _mm512_srli_epi32::<3>(c),
            );
            let within = _mm512_add_epi32(
                _mm512_slli_epi32::<3>(_mm512_and_si512(r, seven)),
                _mm512_and_si512(c, seven),
            );
            let idx = _mm512_add_epi32(_mm512_slli_epi32::<6>(tile), within);
            // Unsigned min: a no-op for the indices `one` computes, a bound for the gather.
            let idx = _mm512_min_epu32(idx, last);
            // SAFETY: every lane of idx is <= last, so the 4 bytes read at ids + idx lie
            // inside ids.
            let ids = unsafe { _mm512_i32gather_epi32::<1>(idx, q.ids.as_ptr().cast()) };
            let ids = _mm512_and_si512(ids, byte);
            let v = if q.few {
                // All ids are below 16: one register holds every reading.
                _mm512_permutexvar_ps(ids, table)
            } else {
                // SAFETY: each id is masked to 0..=255, inside the 256 readings.
                unsafe { _mm512_i32gather_ps::<4>(ids, q.readings.as_ptr().cast()) }
            };
            // SAFETY: as for the loads.
            unsafe {
                _mm512_mask_storeu_ps(out.as_mut_ptr().add(j), todo, _mm512_maskz_mov_ps(ins, v))
            };
            j += 16;
        }
    }
}

impl SurfaceGrid {
    /// Robot `i`'s readings computed in f32 ([`crate::Sensor::read_f32`] of the
    /// surface sensors; the module doc says how it differs from `read`).
    #[inline]
    pub fn read_single(&self, world: &World, i: usize, out: &mut [f32]) {
        let n = self.ox32.len().min(out.len());
        self.read_single_robots(world, i..i + 1, &mut out[..n], n, crate::simd::level());
    }

    /// `read_single` of `robots`, robot `robots.start + k`'s to
    /// `out[k · stride..]` (at most `stride` readings, `out` long enough),
    /// with the instruction set `level` (which must not exceed
    /// `simd::detected()`; every level gives the same bits).
    #[inline]
    pub(super) fn read_single_robots(
        &self,
        world: &World,
        robots: Range<usize>,
        out: &mut [f32],
        stride: usize,
        level: SimdLevel,
    ) {
        let st = &*world.statics;
        if self.ox32.is_empty() || stride == 0 {
            return;
        }
        let scalar = |out: &mut [f32]| {
            for (k, i) in robots.clone().enumerate() {
                let n = self.ox32.len().min(stride);
                Query32::at(world, i).scalar(&self.ox32, &self.oy32, &mut out[k * stride..][..n]);
            }
        };
        if !st.lanes {
            return scalar(out);
        }
        debug_assert!(level <= crate::simd::detected());
        match level {
            #[cfg(target_arch = "x86_64")]
            // SAFETY: callers pass a level up to `detected()`, which saw AVX-512F on
            // this CPU; `lanes` holds, so ids.len() is in PAD + 1 ..= u32::MAX.
            SimdLevel::Avx512 => unsafe { lanes::avx512(self, world, robots, out, stride) },
            #[cfg(target_arch = "x86_64")]
            // SAFETY: as above, with AVX2.
            SimdLevel::Avx2 => unsafe { lanes::avx2(self, world, robots, out, stride) },
            _ => scalar(out),
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec2;
    use proptest::prelude::*;

    use super::*;
    use crate::sensors::frame;
    use crate::sensors::surface::fixtures::{levels, posed_roads, worlds};
    use crate::{Sensor, SurfaceSensors};

    /// The f32 formula written out plainly: the reference every level must match.
    fn reference(g: &SurfaceGrid, world: &World, i: usize, out: &mut [f32]) {
        let (p, ahead, right) = frame(world, i);
        let st = &*world.statics;
        let ras = st.scenario.raster();
        let inv = st.inv_cell;
        let (base, ax, rx) = (p * inv, ahead * inv, right * inv);
        let (lx, ly) = (st.limit.x as f32, st.limit.y as f32);
        for (o, v) in g.offsets.iter().zip(out.iter_mut()) {
            let (x, y) = (o.x as f32, o.y as f32);
            let cx = base.x as f32 + ax.x as f32 * x + rx.x as f32 * y;
            let cy = base.y as f32 + ax.y as f32 * x + rx.y as f32 * y;
            *v = if cx >= 0.0 && cy >= 0.0 && cx < lx && cy < ly {
                st.readings[ras.get_in_arena(cx as usize, cy as usize) as usize] as f32
            } else {
                0.0
            };
        }
    }

    fn same_bits(a: &[f32], b: &[f32]) -> bool {
        a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
    }

    /// Reads robot 0 at `pos`/`heading` with every level and the reference.
    fn check(world: &mut World, g: &SurfaceGrid, pos: DVec2, heading: f64) {
        world.set_pose(0, pos, heading);
        let mut want = vec![7.0; g.len() + 3];
        reference(g, world, 0, &mut want);
        for l in levels() {
            let mut got = vec![7.0; g.len() + 3];
            g.read_single_robots(world, 0..1, &mut got, g.len(), l);
            assert!(
                same_bits(&got, &want),
                "{l:?} differs at {pos:?} heading {heading}: {got:?} vs {want:?}"
            );
        }
        // The trait's read uses the process-wide level: same bits too.
        let mut got = vec![7.0; g.len() + 3];
        g.read_f32(world, 0, &mut got, &mut []);
        assert!(same_bits(&got, &want));
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(400))]

        /// Random poses, inside and outside the arena, with grids of every tail length.
        #[test]
        fn every_level_reads_the_single_precision_reference_bits(
            rings in 1usize..24, angles in 1usize..70, fov in 0.0f64..360.0,
            d_max in 0.0f64..300.0, x in -150.0f64..950.0, y in -150.0f64..750.0,
            heading in -4.0f64..4.0, w in 0usize..2,
        ) {
            let mut worlds = worlds();
            let g = SurfaceSensors { rings, angles, fov, d_min: 0.0, d_max }.grid();
            check(&mut worlds[w], &g, DVec2::new(x, y), heading);
        }

        /// Integer positions facing a grid axis: sensors on cell borders and the arena's edges.
        #[test]
        fn every_level_agrees_in_single_precision_on_cell_borders(
            x in -60i32..860, y in -60i32..660, quarter in -1i32..3, w in 0usize..2,
        ) {
            let mut worlds = worlds();
            let g = SurfaceSensors { rings: 11, angles: 9, fov: 180.0, d_min: 0.0, d_max: 50.0 }.grid();
            let heading = quarter as f64 * std::f64::consts::FRAC_PI_2;
            check(&mut worlds[w], &g, DVec2::new(x as f64, y as f64), heading);
        }

        /// Away from cell borders the single-precision read is the f64 read rounded.
        #[test]
        fn single_precision_reads_the_f64_cells_off_the_borders(
            x in 0.0f64..800.0, y in 0.0f64..600.0, heading in -4.0f64..4.0,
        ) {
            let mut worlds = worlds();
            let world = &mut worlds[0];
            let g = SurfaceSensors { rings: 7, angles: 13, ..Default::default() }.grid();
            world.set_pose(0, DVec2::new(x, y), heading);
            let mut wide = vec![0.0; g.len()];
            g.read(world, 0, &mut wide);
            let mut single = vec![0.0f32; g.len()];
            g.read_single(world, 0, &mut single);
            let positions = g.positions(world, 0);
            let inv = world.statics.inv_cell;
            for ((w, s), p) in wide.iter().zip(&single).zip(positions) {
                let c = p * inv;
                // Farther than 1e-3 cells from every cell border and the arena's edge.
                let clear = |v: f64| (v - v.round()).abs() > 1e-3;
                if clear(c.x) && clear(c.y) {
                    prop_assert_eq!(*w as f32, *s, "at {:?}", c);
                }
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]

        /// Every robot read in one call gets its own f32 read's bits, at every
        /// level and through the trait, and the values between robots stay.
        #[test]
        fn batched_single_precision_reads_give_each_robot_its_own_bits(
            poses in prop::collection::vec((-150.0f64..950.0, -150.0f64..750.0, -4.0f64..4.0), 8),
            rings in 1usize..12, angles in 1usize..40, gap in 0usize..5,
        ) {
            let (world, n) = posed_roads(&poses);
            let world = &world;
            let g = SurfaceSensors { rings, angles, ..Default::default() }.grid();
            let stride = g.len() + gap;
            let mut want = vec![7.0; n * stride];
            for i in 0..n {
                reference(&g, world, i, &mut want[i * stride..][..g.len()]);
            }
            for l in levels() {
                let mut got = vec![7.0; n * stride];
                g.read_single_robots(world, 0..n, &mut got, stride, l);
                prop_assert!(same_bits(&got, &want), "{:?}", l);
            }
            let mut got = vec![7.0; n * stride];
            g.read_robots_f32(world, n, &mut got, stride, &mut []);
            prop_assert!(same_bits(&got, &want));
        }
    }

    #[test]
    fn every_level_reads_exact_borders_and_odd_values_in_single_precision() {
        let mut worlds = worlds();
        let g = SurfaceSensors {
            rings: 7,
            angles: 13,
            ..Default::default()
        }
        .grid();
        for world in &mut worlds {
            let (w, h) = (world.scenario().width(), world.scenario().height());
            for pos in [
                DVec2::new(0.0, 0.0),
                DVec2::new(w, h),
                DVec2::new(w - 1e-9, h - 1e-9),
                DVec2::new(-0.0, 30.0),
                DVec2::new(f64::NAN, 30.0),
                DVec2::new(f64::INFINITY, 30.0),
                DVec2::new(1e300, -1e300),
                DVec2::new(w / 2.0, h / 2.0),
            ] {
                for heading in [0.0, 1.0, -2.5, std::f64::consts::PI] {
                    check(world, &g, pos, heading);
                }
            }
        }
    }
}

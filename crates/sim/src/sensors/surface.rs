//! Surface sensors: the paper's polar grid of friction readings in front of
//! the robot (road 1 … grass 0, 0 outside the arena).

use std::ops::Range;

use glam::DVec2;
use serde::{Deserialize, Serialize};

use super::{Sensor, SensorPlace, check_fov, frame, local, spread};
use crate::physics::{ParamError, check};
use crate::simd::SimdLevel;
use crate::world::World;

/// Surface sensors on a polar grid in front of the robot.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct SurfaceSensors {
    /// Rings (distances) of surface sensors: the rows of the input sheet.
    ///
    /// Paper: 3, re-sampled to 3.
    pub rings: usize,
    /// Surface sensors per ring, spread evenly over the field of view.
    ///
    /// Paper: 5, re-sampled to 6.
    pub angles: usize,
    /// Field of view of the surface sensors, centred ahead (180 = 90° to each side).
    ///
    /// Unit: degrees. Paper: 180.
    pub fov: f64,
    /// Distance of the nearest ring from the robot's centre.
    ///
    /// Unit: px.
    pub d_min: f64,
    /// Distance of the farthest ring from the robot's centre.
    ///
    /// Unit: px.
    pub d_max: f64,
}

impl Default for SurfaceSensors {
    fn default() -> Self {
        SurfaceSensors {
            rings: 3,
            angles: 5,
            fov: 180.0,
            d_min: 10.0,
            d_max: 50.0,
        }
    }
}

impl SurfaceSensors {
    /// Checks the layout; the error names the first bad field.
    pub fn validate(&self) -> Result<(), ParamError> {
        check(
            "rings",
            self.rings as f64,
            (1..=10_000).contains(&self.rings),
            "must be in 1..=10000",
        )?;
        check(
            "angles",
            self.angles as f64,
            (1..=10_000).contains(&self.angles),
            "must be in 1..=10000",
        )?;
        check_fov(self.fov)?;
        check("d_min", self.d_min, self.d_min >= 0.0, "must be >= 0")?;
        check(
            "d_max",
            self.d_max,
            self.d_max >= self.d_min,
            "must be >= d_min",
        )?;
        Ok(())
    }

    /// Number of sensors (`rings × angles`).
    pub fn len(&self) -> usize {
        self.rings * self.angles
    }

    /// Whether the layout has no sensor.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Every sensor's place, ring-major (index = ring·angles + angle_index).
    /// One ring sits midway between `d_min` and `d_max`.
    pub fn places(&self) -> Vec<SensorPlace> {
        let mut out = Vec::with_capacity(self.len());
        for ring in 0..self.rings {
            let distance = if self.rings == 1 {
                (self.d_min + self.d_max) / 2.0
            } else {
                self.d_min + (self.d_max - self.d_min) * ring as f64 / (self.rings - 1) as f64
            };
            for (angle_index, angle) in spread(self.angles, self.fov).enumerate() {
                out.push(SensorPlace {
                    ring,
                    angle_index,
                    distance,
                    angle,
                });
            }
        }
        out
    }

    /// The compiled sensor the world reads.
    pub fn grid(&self) -> SurfaceGrid {
        let places = self.places();
        let offsets: Vec<DVec2> = places.iter().map(|p| local(p.distance, p.angle)).collect();
        SurfaceGrid {
            ox: offsets.iter().map(|o| o.x).collect(),
            oy: offsets.iter().map(|o| o.y).collect(),
            ox32: offsets.iter().map(|o| o.x as f32).collect(),
            oy32: offsets.iter().map(|o| o.y as f32).collect(),
            offsets,
            places,
            rings: self.rings,
        }
    }
}

/// Compiled surface-sensor layout: robot-frame offsets (x ahead, y right).
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceGrid {
    /// Offsets in sensor order.
    pub offsets: Vec<DVec2>,
    /// The offsets' x and y apart, so that one vector instruction serves several sensors.
    ox: Vec<f64>,
    oy: Vec<f64>,
    /// The offsets rounded to f32, for the single-precision read (`surface_f32`).
    pub(super) ox32: Vec<f32>,
    pub(super) oy32: Vec<f32>,
    places: Vec<SensorPlace>,
    rings: usize,
}

impl SurfaceGrid {
    /// World positions of robot `i`'s sensors (for drawing).
    pub fn positions(&self, world: &World, i: usize) -> Vec<DVec2> {
        let (p, ahead, right) = frame(world, i);
        self.offsets
            .iter()
            .map(|o| p + ahead * o.x + right * o.y)
            .collect()
    }
}

/// One robot's read, everything in raster cells: the robot's centre and axes,
/// the arena size, and the raster the readings come from.
pub(super) struct Query<'a> {
    pub(super) base: DVec2,
    pub(super) ax: DVec2,
    pub(super) rx: DVec2,
    pub(super) lim: DVec2,
    pub(super) tiles_x: usize,
    pub(super) ids: &'a [u8],
    readings: &'a [f64; 256],
    /// Whether the scenario has at most 16 materials (so every id is below 16
    /// and two AVX-512 registers hold every reading).
    pub(super) few: bool,
}

impl<'w> Query<'w> {
    /// Robot `i`'s read in `world`. The lane paths build it themselves: built
    /// by their caller and passed by reference, it was stored field by field
    /// and reloaded with wider loads, which the CPU cannot forward from those
    /// stores, and every read stalled on it.
    #[inline(always)]
    pub(super) fn at(world: &'w World, i: usize) -> Self {
        let st = &*world.statics;
        let (p, ahead, right) = frame(world, i);
        let inv = st.inv_cell;
        let (ids, tiles_x) = st.scenario.raster().tiles();
        Query {
            base: p * inv,
            ax: ahead * inv,
            rx: right * inv,
            lim: st.limit,
            tiles_x,
            ids,
            readings: &st.readings,
            few: st.few_materials,
        }
    }

    /// The reading at robot-frame offset (`x`, `y`): the formula every path follows.
    #[inline(always)]
    fn one(&self, x: f64, y: f64) -> f64 {
        // Same operations in the same order as `base + ax * x + rx * y` on DVec2s.
        let cx = self.base.x + self.ax.x * x + self.rx.x * y;
        let cy = self.base.y + self.ax.y * x + self.rx.y * y;
        // Non-short-circuit tests compile to one branch.
        if (cx >= 0.0) & (cy >= 0.0) & (cx < self.lim.x) & (cy < self.lim.y) {
            // i32 conversions are cheaper than usize ones; the range test keeps them exact.
            let (c, r) = (cx as i32 as usize, cy as i32 as usize);
            let idx = ((r >> 3) * self.tiles_x + (c >> 3)) * 64 + ((r & 7) << 3) + (c & 7);
            self.readings[self.ids.get(idx).copied().unwrap_or(0) as usize]
        } else {
            0.0
        }
    }

    /// Scalar read of every sensor.
    #[inline(always)]
    fn scalar(&self, ox: &[f64], oy: &[f64], out: &mut [f64]) {
        for ((v, &x), &y) in out.iter_mut().zip(ox).zip(oy) {
            *v = self.one(x, y);
        }
    }
}

/// Defines `$name`, the lane read `$robot` of one robot at a time done for
/// a range of robots in one call compiled with `$feature` (so that the CPU
/// overlaps one robot's look-ups with the next's): robot `robots.start + k`'s
/// readings go to `all[k · stride..]`, at most `stride` of them. One
/// definition for the f64 and f32 reads at every level.
macro_rules! each_robot {
    ($name:ident, $robot:ident, $feature:literal, $t:ty) => {
        #[doc = concat!("[`", stringify!($robot), "`] of each of `robots`, robot `robots.start + k`'s readings to `all[k · stride..]`.")]
        ///
        /// # Safety
        #[doc = concat!("As for [`", stringify!($robot), "`].")]
        #[target_feature(enable = $feature)]
        pub(super) unsafe fn $name(
            g: &SurfaceGrid,
            world: &World,
            robots: std::ops::Range<usize>,
            all: &mut [$t],
            stride: usize,
        ) {
            for (k, i) in robots.enumerate() {
                let out = &mut all[k * stride..];
                let n = out.len().min(stride);
                // SAFETY: the caller's guarantees are this function's.
                unsafe { $robot(g, world, i, &mut out[..n]) };
            }
        }
    };
}
pub(super) use each_robot;

/// Lane-wise reads: the same per-sensor arithmetic as [`Query::one`] (IEEE mul
/// and add in the same order, no FMA, truncation to i32), one sensor per lane,
/// then the two look-ups: as gathers with AVX-512, one sensor at a time with
/// AVX2. Only called when `Statics::lanes` holds, so the u32 lane index
/// equals `one`'s usize one for every in-arena sensor.
#[cfg(target_arch = "x86_64")]
mod lanes {
    use std::arch::x86_64::*;

    use super::Query;
    use crate::World;
    use crate::sensors::surface::SurfaceGrid;

    /// Largest index whose 4-byte gather stays inside `ids` (the raster pads
    /// `ids` with `raster::PAD` zero bytes so that this is the last cell).
    #[inline(always)]
    fn last_gather(q: &Query) -> u32 {
        (q.ids.len() - crate::raster::PAD) as u32 - 1
    }

    each_robot!(avx2, avx2_robot, "avx2", f64);

    /// AVX2: four sensors' cells per iteration, the last batch partial; the
    /// look-ups one sensor at a time.
    ///
    /// Scalar look-ups, not AVX2 gathers, as in the f32 read (see there).
    ///
    /// # Safety
    /// The CPU must support AVX2; `q.ids.len()` must be in `PAD + 1 ..= u32::MAX`.
    #[target_feature(enable = "avx2")]
    #[inline]
    unsafe fn avx2_robot(g: &SurfaceGrid, world: &World, i: usize, out: &mut [f64]) {
        let (q, ox, oy) = (&Query::at(world, i), &g.ox[..], &g.oy[..]);
        let n = out.len().min(ox.len()).min(oy.len());
        let (bx, by) = (_mm256_set1_pd(q.base.x), _mm256_set1_pd(q.base.y));
        let (axx, axy) = (_mm256_set1_pd(q.ax.x), _mm256_set1_pd(q.ax.y));
        let (rxx, rxy) = (_mm256_set1_pd(q.rx.x), _mm256_set1_pd(q.rx.y));
        let (lx, ly) = (_mm256_set1_pd(q.lim.x), _mm256_set1_pd(q.lim.y));
        let zero = _mm256_setzero_pd();
        let tx = _mm_set1_epi32(q.tiles_x as i32);
        let seven = _mm_set1_epi32(7);
        let last = _mm_set1_epi32(last_gather(q) as i32);
        let lane = _mm256_setr_epi64x(0, 1, 2, 3);
        let mut cells = [0u32; 4];
        let mut j = 0;
        while j < n {
            let m = (n - j).min(4);
            // Lanes past the last sensor are neither loaded nor stored.
            let todo = _mm256_cmpgt_epi64(_mm256_set1_epi64x(m as i64), lane);
            // SAFETY: the lanes of `todo` are j..j + m, inside ox and oy;
            // masked-off lanes are not accessed (and cannot fault).
            let (x, y) = unsafe {
                (
                    _mm256_maskload_pd(ox.as_ptr().add(j), todo),
                    _mm256_maskload_pd(oy.as_ptr().add(j), todo),
                )
            };
            let cx = _mm256_add_pd(
                _mm256_add_pd(bx, _mm256_mul_pd(axx, x)),
                _mm256_mul_pd(rxx, y),
            );
            let cy = _mm256_add_pd(
                _mm256_add_pd(by, _mm256_mul_pd(axy, x)),
                _mm256_mul_pd(rxy, y),
            );
            // Ordered compares: NaN is outside, as in `one`.
            let ins = _mm256_and_pd(
                _mm256_and_pd(
                    _mm256_cmp_pd::<_CMP_GE_OQ>(cx, zero),
                    _mm256_cmp_pd::<_CMP_GE_OQ>(cy, zero),
                ),
                _mm256_and_pd(
                    _mm256_cmp_pd::<_CMP_LT_OQ>(cx, lx),
                    _mm256_cmp_pd::<_CMP_LT_OQ>(cy, ly),
                ),
            );
            // Outside lanes become +0.0, so cell 0; their reading is not used.
            let c = _mm256_cvttpd_epi32(_mm256_and_pd(cx, ins));
            let r = _mm256_cvttpd_epi32(_mm256_and_pd(cy, ins));
            let tile = _mm_add_epi32(
                _mm_mullo_epi32(_mm_srli_epi32::<3>(r), tx),
                _mm_srli_epi32::<3>(c),
            );
            let within = _mm_add_epi32(
                _mm_slli_epi32::<3>(_mm_and_si128(r, seven)),
                _mm_and_si128(c, seven),
            );
            let cell = _mm_add_epi32(_mm_slli_epi32::<6>(tile), within);
            // Unsigned min: a no-op for the indices `one` computes, a bound for the look-up.
            let cell = _mm_min_epu32(cell, last);
            // SAFETY: cells has room for the 4 lanes.
            unsafe { _mm_storeu_si128(cells.as_mut_ptr().cast(), cell) };
            let inside = _mm256_movemask_pd(ins) as u32;
            for (l, (v, &k)) in out[j..j + m].iter_mut().zip(&cells).enumerate() {
                // SAFETY: k <= last < ids.len() (the min above).
                let id = unsafe { *q.ids.get_unchecked(k as usize) };
                let reading = q.readings[id as usize];
                *v = if inside >> l & 1 == 1 { reading } else { 0.0 };
            }
            j += 4;
        }
    }

    each_robot!(avx512, avx512_robot, "avx512f", f64);

    /// AVX-512F: eight sensors per iteration, the last batch masked.
    ///
    /// # Safety
    /// The CPU must support AVX-512F; `q.ids.len()` must be in `PAD + 1 ..= u32::MAX`.
    // avx512f implies FMA in LLVM, but Rust never fuses a separate mul and add
    // (no contraction), so the bits stay those of `one`.
    #[target_feature(enable = "avx512f")]
    #[inline]
    unsafe fn avx512_robot(g: &SurfaceGrid, world: &World, i: usize, out: &mut [f64]) {
        let (q, ox, oy) = (&Query::at(world, i), &g.ox[..], &g.oy[..]);
        let n = out.len().min(ox.len()).min(oy.len());
        let (bx, by) = (_mm512_set1_pd(q.base.x), _mm512_set1_pd(q.base.y));
        let (axx, axy) = (_mm512_set1_pd(q.ax.x), _mm512_set1_pd(q.ax.y));
        let (rxx, rxy) = (_mm512_set1_pd(q.rx.x), _mm512_set1_pd(q.rx.y));
        let (lx, ly) = (_mm512_set1_pd(q.lim.x), _mm512_set1_pd(q.lim.y));
        let zero = _mm512_setzero_pd();
        let tx = _mm256_set1_epi32(q.tiles_x as i32);
        let (seven, byte) = (_mm256_set1_epi32(7), _mm256_set1_epi32(0xff));
        let last = _mm256_set1_epi32(last_gather(q) as i32);
        // SAFETY: readings has 256 entries, so 0..16 are in bounds.
        let (lo, hi) = unsafe {
            let r = q.readings.as_ptr();
            (_mm512_loadu_pd(r), _mm512_loadu_pd(r.add(8)))
        };
        let mut j = 0;
        while j < n {
            // The last batch may be partial: its missing lanes are neither loaded nor stored.
            let todo: __mmask8 = if n - j >= 8 {
                0xff
            } else {
                (1u8 << (n - j)) - 1
            };
            // SAFETY: the lanes of `todo` are j..min(j + 8, n), inside ox, oy and out;
            // masked-off lanes are not accessed (and cannot fault).
            let (x, y) = unsafe {
                (
                    _mm512_maskz_loadu_pd(todo, ox.as_ptr().add(j)),
                    _mm512_maskz_loadu_pd(todo, oy.as_ptr().add(j)),
                )
            };
            let cx = _mm512_add_pd(
                _mm512_add_pd(bx, _mm512_mul_pd(axx, x)),
                _mm512_mul_pd(rxx, y),
            );
            let cy = _mm512_add_pd(
                _mm512_add_pd(by, _mm512_mul_pd(axy, x)),
                _mm512_mul_pd(rxy, y),
            );
            // Ordered compares: NaN is outside, as in `one`.
            // Each compare is masked by the previous ones: the AND costs no extra op.
            let ins = _mm512_cmp_pd_mask::<_CMP_GE_OQ>(cx, zero);
            let ins = _mm512_mask_cmp_pd_mask::<_CMP_GE_OQ>(ins, cy, zero);
            let ins = _mm512_mask_cmp_pd_mask::<_CMP_LT_OQ>(ins, cx, lx);
            let ins = _mm512_mask_cmp_pd_mask::<_CMP_LT_OQ>(ins, cy, ly);
            // Outside lanes become 0, so cell 0; their reading is discarded below.
            let c = _mm512_maskz_cvttpd_epi32(ins, cx);
            let r = _mm512_maskz_cvttpd_epi32(ins, cy);
            let tile = _mm256_add_epi32(
                _mm256_mullo_epi32(_mm256_srli_epi32::<3>(r), tx),
                _mm256_srli_epi32::<3>(c),
            );
            let within = _mm256_add_epi32(
                _mm256_slli_epi32::<3>(_mm256_and_si256(r, seven)),
                _mm256_and_si256(c, seven),
            );
            let idx = _mm256_add_epi32(_mm256_slli_epi32::<6>(tile), within);
            // Unsigned min: a no-op for the indices `one` computes, a bound for the gather.
            let idx = _mm256_min_epu32(idx, last);
            // SAFETY: every lane of idx is <= last, so the 4 bytes read at ids + idx lie
            // inside ids.
            let ids = unsafe { _mm256_i32gather_epi32::<1>(q.ids.as_ptr().cast(), idx) };
            let ids = _mm256_and_si256(ids, byte);
            let v = if q.few {
                // All ids are below 16: two registers hold every reading.
                _mm512_permutex2var_pd(lo, _mm512_cvtepu32_epi64(ids), hi)
            } else {
                // SAFETY: each id is masked to 0..=255, inside the 256 readings.
                unsafe { _mm512_i32gather_pd::<8>(ids, q.readings.as_ptr().cast()) }
            };
            // SAFETY: as for the loads.
            unsafe {
                _mm512_mask_storeu_pd(out.as_mut_ptr().add(j), todo, _mm512_maskz_mov_pd(ins, v))
            };
            j += 8;
        }
    }
}

impl Sensor for SurfaceGrid {
    fn name(&self) -> &'static str {
        "surface"
    }

    fn rings(&self) -> usize {
        self.rings
    }

    fn places(&self) -> &[SensorPlace] {
        &self.places
    }

    #[inline]
    fn read(&self, world: &World, i: usize, out: &mut [f64]) {
        let n = self.ox.len().min(out.len());
        self.read_at_level(world, i..i + 1, &mut out[..n], n, crate::simd::level());
    }

    #[inline]
    fn read_f32(&self, world: &World, i: usize, out: &mut [f32], _scratch: &mut [f64]) {
        self.read_single(world, i, out);
    }

    fn read_robots(&self, world: &World, robots: usize, out: &mut [f64], stride: usize) {
        super::check_batch(self.len(), robots, out.len(), stride);
        self.read_at_level(world, 0..robots, out, stride, crate::simd::level());
    }

    fn read_robots_f32(
        &self,
        world: &World,
        robots: usize,
        out: &mut [f32],
        stride: usize,
        _scratch: &mut [f64],
    ) {
        super::check_batch(self.len(), robots, out.len(), stride);
        self.read_single_robots(world, 0..robots, out, stride, crate::simd::level());
    }
}

impl SurfaceGrid {
    /// The reads of `robots`, robot `robots.start + k`'s to
    /// `out[k · stride..]` (at most `stride` readings, `out` long enough),
    /// with the instruction set `level` (which must not exceed
    /// `simd::detected()`; every level gives the same bits).
    #[inline]
    fn read_at_level(
        &self,
        world: &World,
        robots: Range<usize>,
        out: &mut [f64],
        stride: usize,
        level: SimdLevel,
    ) {
        let st = &*world.statics;
        if self.ox.is_empty() || stride == 0 {
            return;
        }
        let scalar = |out: &mut [f64]| {
            for (k, i) in robots.clone().enumerate() {
                let n = self.ox.len().min(stride);
                Query::at(world, i).scalar(&self.ox, &self.oy, &mut out[k * stride..][..n]);
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

/// The worlds and levels the surface reads are tested on, f64 and f32 alike.
#[cfg(test)]
pub(super) mod fixtures {
    use crate::simd::{SimdLevel, detected};
    use crate::{LoadOptions, PhysicsParams, Scenario, World};

    /// Every level this CPU runs.
    pub(in crate::sensors) fn levels() -> Vec<SimdLevel> {
        [SimdLevel::Scalar, SimdLevel::Avx2, SimdLevel::Avx512]
            .into_iter()
            .filter(|&l| l <= detected())
            .collect()
    }

    /// roads.svg, and an arena of 20 sand strips of different friction (more than
    /// 16 materials: the look-up that gathers readings) on a 0.75 px raster.
    pub(in crate::sensors) fn worlds() -> Vec<World> {
        let roads =
            Scenario::from_svg(crate::ROADS_SVG, "roads.svg", &LoadOptions::default()).unwrap();
        let mut strips = String::from(
            r#"<svg xmlns="http://www.w3.org/2000/svg" xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" width="203" height="101">"#,
        );
        for k in 0..20 {
            strips += &format!(
                r#"<rect id="s{k}" inkscape:label="Sand" data-friction="{}" x="{}" y="{}" width="9.5" height="80"/>"#,
                1.0 + k as f64 * 0.4,
                k * 10,
                k % 3
            );
        }
        strips +=
            r#"<rect id="r" inkscape:label="Robot" x="94" y="44" width="12" height="12"/></svg>"#;
        let opts = LoadOptions {
            cell_size: 0.75,
            ..Default::default()
        };
        let strips = Scenario::from_svg(&strips, "strips.svg", &opts).unwrap();
        assert!(strips.materials().len() > 16);
        [roads, strips]
            .iter()
            .map(|sc| World::new(sc, &PhysicsParams::default()).unwrap())
            .collect()
    }

    /// roads.svg with its robots at `poses` (x, y, heading; one per robot,
    /// extra poses ignored), and its robot count (at least 2).
    pub(in crate::sensors) fn posed_roads(poses: &[(f64, f64, f64)]) -> (World, usize) {
        let mut world = worlds().swap_remove(0);
        let n = world.robots().len();
        assert!(n >= 2 && poses.len() >= n);
        for (i, &(x, y, heading)) in poses.iter().take(n).enumerate() {
            world.set_pose(i, glam::DVec2::new(x, y), heading);
        }
        (world, n)
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::fixtures::{levels, posed_roads, worlds};
    use super::*;

    /// The read as it was before the vector paths: the reference every level must match.
    fn reference(g: &SurfaceGrid, world: &World, i: usize, out: &mut [f64]) {
        let (p, ahead, right) = frame(world, i);
        let st = &*world.statics;
        let (ras, readings) = (st.scenario.raster(), &*st.readings);
        let (inv, lim) = (st.inv_cell, st.limit);
        let (base, ax, rx) = (p * inv, ahead * inv, right * inv);
        for (o, v) in g.offsets.iter().zip(out.iter_mut()) {
            let c = base + ax * o.x + rx * o.y;
            *v = if (c.x >= 0.0) & (c.y >= 0.0) & (c.x < lim.x) & (c.y < lim.y) {
                readings[ras.get_in_arena(c.x as i32 as usize, c.y as i32 as usize) as usize]
            } else {
                0.0
            };
        }
    }

    fn same_bits(a: &[f64], b: &[f64]) -> bool {
        a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
    }

    /// Reads robot 0 at `pos`/`heading` with every level and the reference.
    fn check(world: &mut World, g: &SurfaceGrid, pos: DVec2, heading: f64) {
        world.set_pose(0, pos, heading);
        let mut want = vec![7.0; g.len() + 3];
        reference(g, world, 0, &mut want);
        for l in levels() {
            let mut got = vec![7.0; g.len() + 3];
            g.read_at_level(world, 0..1, &mut got, g.len(), l);
            assert!(
                same_bits(&got, &want),
                "{l:?} differs at {pos:?} heading {heading}: {got:?} vs {want:?}"
            );
        }
        // The public read uses the process-wide level: same bits too.
        let mut got = vec![7.0; g.len() + 3];
        g.read(world, 0, &mut got);
        assert!(same_bits(&got, &want));
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(400))]

        /// Random poses, inside and outside the arena, with grids of every tail length.
        #[test]
        fn every_level_reads_the_reference_bits(
            rings in 1usize..24, angles in 1usize..70, fov in 0.0f64..360.0,
            d_max in 0.0f64..300.0, x in -150.0f64..950.0, y in -150.0f64..750.0,
            heading in -4.0f64..4.0, w in 0usize..2,
        ) {
            let mut worlds = worlds();
            let g = SurfaceSensors { rings, angles, fov, d_min: 0.0, d_max }.grid();
            check(&mut worlds[w], &g, DVec2::new(x, y), heading);
        }

        /// Integer positions facing a grid axis: straight-ahead sensors land exactly
        /// on cell borders, and the arena's edges are hit exactly.
        #[test]
        fn every_level_agrees_on_cell_borders(
            x in -60i32..860, y in -60i32..660, quarter in -1i32..3, w in 0usize..2,
        ) {
            let mut worlds = worlds();
            let g = SurfaceSensors { rings: 11, angles: 9, fov: 180.0, d_min: 0.0, d_max: 50.0 }.grid();
            let heading = quarter as f64 * std::f64::consts::FRAC_PI_2;
            check(&mut worlds[w], &g, DVec2::new(x as f64, y as f64), heading);
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]

        /// Every robot read in one call gets its own read's bits, at every
        /// level and through the trait, and the values between robots stay.
        #[test]
        fn batched_reads_give_each_robot_its_own_bits(
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
                g.read_at_level(world, 0..n, &mut got, stride, l);
                prop_assert!(same_bits(&got, &want), "{:?}", l);
            }
            let mut got = vec![7.0; n * stride];
            g.read_robots(world, n, &mut got, stride);
            prop_assert!(same_bits(&got, &want));
            // The shortest buffer that holds them: the last robot's gap is not needed.
            got.truncate(n * stride - gap);
            g.read_robots(world, n, &mut got, stride);
            prop_assert!(same_bits(&got, &want[..n * stride - gap]));
        }
    }

    #[test]
    #[should_panic(expected = "needs a longer buffer")]
    fn a_batched_read_into_too_short_a_buffer_panics() {
        let worlds = worlds();
        let g = SurfaceSensors::default().grid();
        let mut out = vec![0.0; 2 * g.len() - 1];
        g.read_robots(&worlds[0], 2, &mut out, g.len());
    }

    #[test]
    fn every_level_reads_exact_borders_and_odd_values() {
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

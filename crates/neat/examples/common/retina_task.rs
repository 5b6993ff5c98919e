//! The left & right retina task's images and input positions: 256 images of
//! a 4×2 retina, each pixel given as 0/1 (ours) or −3/+3 (AHNI's
//! `RetinaProblemFitnessFunction`, `inputMinValue = -3, inputMaxValue = 3`),
//! and the retina laid on a line or as a 4×2 grid in the substrate's plane.

/// Left-half objects (pixels as bits 3..0: top-left, top-right, bottom-left, bottom-right).
pub const LEFT_OBJECTS: [u8; 8] = [
    0b1000, 0b0100, 0b1100, 0b1111, 0b1011, 0b0111, 0b1110, 0b1101,
];
/// Right-half objects, same bit order.
pub const RIGHT_OBJECTS: [u8; 8] = [
    0b1011, 0b0111, 0b1110, 0b1101, 0b0010, 0b0001, 0b0011, 0b1111,
];

/// The values an off and an on pixel take as inputs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Pixels {
    /// Off 0, on 1 (our default).
    ZeroOne,
    /// Off −3, on +3 (AHNI's reproduction).
    PlusMinusThree,
}

impl Pixels {
    /// Parses `01` or `pm3`; the error is one line naming the value.
    pub fn parse(s: &str) -> Result<Pixels, String> {
        match s {
            "01" => Ok(Pixels::ZeroOne),
            "pm3" => Ok(Pixels::PlusMinusThree),
            other => Err(format!("--pixels {other}: expected 01 or pm3")),
        }
    }

    /// The input value of a pixel that is on (`true`) or off.
    pub fn value(self, on: bool) -> f64 {
        match self {
            Pixels::ZeroOne => f64::from(u8::from(on)),
            Pixels::PlusMinusThree => {
                if on {
                    3.0
                } else {
                    -3.0
                }
            }
        }
    }
}

/// The 256 images as inputs (left half first: top-left, top-right,
/// bottom-left, bottom-right of each half) and their labels (left half an
/// object, right half an object).
pub fn images(pixels: Pixels) -> Vec<([f64; 8], [bool; 2])> {
    (0..=255u8)
        .map(|image| {
            let (left, right) = (image >> 4, image & 0xf);
            let mut x = [0.0; 8];
            for bit in 0..4 {
                x[3 - bit] = pixels.value((left >> bit) & 1 == 1);
                x[7 - bit] = pixels.value((right >> bit) & 1 == 1);
            }
            (
                x,
                [LEFT_OBJECTS.contains(&left), RIGHT_OBJECTS.contains(&right)],
            )
        })
        .collect()
}

/// How the retina's eight pixels are placed in the substrate's plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Placement {
    /// All eight along y = −1 at x = −1 + 2i/7, in input order.
    Line,
    /// A 4×2 grid: columns at x = −1, −⅓, ⅓, 1 (the left half in the two
    /// left columns), the bottom row at y = −1, the top row at y = −⅔.
    Grid,
}

impl Placement {
    /// Parses `line` or `grid`; the error is one line naming the value.
    pub fn parse(s: &str) -> Result<Placement, String> {
        match s {
            "line" => Ok(Placement::Line),
            "grid" => Ok(Placement::Grid),
            other => Err(format!("--retina {other}: expected line or grid")),
        }
    }

    /// The positions of the eight inputs, in the order of [`images`].
    pub fn inputs(self) -> Vec<[f64; 2]> {
        match self {
            Placement::Line => (0..8)
                .map(|i| [-1.0 + 2.0 * f64::from(i) / 7.0, -1.0])
                .collect(),
            Placement::Grid => (0..8)
                .map(|i: u32| {
                    let (half, pixel) = (i / 4, i % 4);
                    let column = 2 * half + pixel % 2;
                    let y = if pixel < 2 { -2.0 / 3.0 } else { -1.0 };
                    [-1.0 + 2.0 * f64::from(column) / 3.0, y]
                })
                .collect(),
        }
    }
}

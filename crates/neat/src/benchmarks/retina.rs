//! The left & right retina problem (Verbancsics & Stanley 2011; Risi &
//! Stanley 2012), a benchmark for modular networks; the task of `cargo run
//! -p vivae-neat --example retina` and `vivae reproduce retina`
//! (docs/hyperneat-benchmarks.md).
//!
//! A 4×2 retina: the left 2×2 half and the right 2×2 half each show one of
//! 16 patterns, 8 of which are "objects" (the sets below, as in the
//! `gymnasium-retinatask` package). Output 0 says whether the left half shows
//! an object, output 1 the right half, on all 256 images. Fitness
//! `1000/(1 + E²)`, E the summed |output − label| over both outputs and all
//! images (outputs mapped from (−1, 1) to (0, 1)); solved when every output
//! is on the right side of 0.5. Evaluations are counted up to and including
//! the first solving genome.
//!
//! Our substrate is two-dimensional (the CPPN sees `(x1, y1, x2, y2)`), so the
//! retina is laid out along a line (the left half's four pixels at x < 0,
//! the right half's at x > 0, all at y = −1; outputs at (∓0.5, 1)) or, closer
//! to the public reproduction AHNI, as a 4×2 grid with AHNI's layer shapes
//! 4×2 → 4×2 → 4×1 → 2; pixels are 0/1 or AHNI's −3/+3 ([`Pixels`]).

use crate::hyperneat::es::{EsLayout, EsParams, decode_es_genome};
use crate::hyperneat::{
    HyperParams, LayeredLayout, SparseNetwork, decode_layered, leo_seeded_genomes,
};
use crate::{FeedForwardNetwork, Genome, GenomeSpec, NeatError, NeatParams, Network, Population};

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

/// How a genome becomes the network that sees the retina.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Mode {
    /// Plain HyperNEAT, layers 8 → 8 → 4 → 2, weight threshold 0.2.
    HyperNeat,
    /// The same with a link expression output (LEO), no seed.
    Leo,
    /// LEO with the Gaussian locality seed along x.
    LeoSeed,
    /// ES-HyperNEAT (paper defaults) from the 8 inputs to the 2 outputs.
    Es,
    /// ES-HyperNEAT with LEO and the locality seed.
    EsLeo,
    /// No substrate: a plain NEAT network on the 8 pixels and a bias.
    Neat,
}

impl Mode {
    /// `hyperneat`, `leo`, `leo-seed`, `es`, `es-leo` or `neat`; the error
    /// is one line naming the value.
    pub fn parse(s: &str) -> Result<Mode, String> {
        match s {
            "hyperneat" => Ok(Mode::HyperNeat),
            "leo" => Ok(Mode::Leo),
            "leo-seed" => Ok(Mode::LeoSeed),
            "es" => Ok(Mode::Es),
            "es-leo" => Ok(Mode::EsLeo),
            "neat" => Ok(Mode::Neat),
            other => Err(format!(
                "--mode {other}: expected hyperneat, leo, leo-seed, es, es-leo or neat"
            )),
        }
    }
    /// The summary's name, `retina-MODE`.
    pub fn name(self) -> &'static str {
        match self {
            Mode::HyperNeat => "retina-hyperneat",
            Mode::Leo => "retina-leo",
            Mode::LeoSeed => "retina-leo-seed",
            Mode::Es => "retina-es",
            Mode::EsLeo => "retina-es-leo",
            Mode::Neat => "retina-neat",
        }
    }
    fn leo(self) -> bool {
        matches!(self, Mode::Leo | Mode::LeoSeed | Mode::EsLeo)
    }
    fn seeded(self) -> bool {
        matches!(self, Mode::LeoSeed | Mode::EsLeo)
    }
}

const OUTPUTS: [[f64; 2]; 2] = [[-0.5, 1.0], [0.5, 1.0]];

/// The substrate: where the retina lies and the substrate's weight expression.
#[derive(Clone, Copy, Debug)]
pub struct Substrate {
    /// Where the retina's pixels lie.
    pub placement: Placement,
    /// The layered substrate's weight expression.
    pub hyper: HyperParams,
    /// ES-HyperNEAT's settings.
    pub es: EsParams,
}

impl Default for Substrate {
    /// The retina on a line, threshold 0.2, amplitude 3; ES's defaults.
    fn default() -> Self {
        let hyper = HyperParams::default();
        Substrate {
            placement: Placement::Line,
            hyper,
            es: EsParams {
                expression: hyper,
                ..EsParams::default()
            },
        }
    }
}

/// Builds the substrate network of `g` for `mode`.
fn network(g: &Genome, mode: Mode, sub: &Substrate) -> SparseNetwork {
    let leo_output = mode.leo().then_some(2);
    if matches!(mode, Mode::Es | Mode::EsLeo) {
        let layout = EsLayout {
            inputs: sub.placement.inputs(),
            outputs: OUTPUTS.to_vec(),
            weight_output: 0,
            bias_output: Some(1),
            leo_output,
        };
        return decode_es_genome(g, &layout, &sub.es).expect("valid ES layout");
    }
    let row = |n: usize, y: f64| -> Vec<[f64; 2]> {
        (0..n)
            .map(|i| [-1.0 + 2.0 * i as f64 / (n - 1) as f64, y])
            .collect()
    };
    let hidden = match sub.placement {
        Placement::Line => vec![row(8, -1.0 / 3.0), row(4, 1.0 / 3.0)],
        Placement::Grid => vec![
            [row(4, 0.0), row(4, -1.0 / 3.0)].concat(),
            row(4, 1.0 / 3.0),
        ],
    };
    let layout = LayeredLayout {
        layers: [vec![sub.placement.inputs()], hidden, vec![OUTPUTS.to_vec()]].concat(),
        weight_output: 0,
        bias_output: Some(1),
        leo_output,
    };
    let mut cppn = FeedForwardNetwork::from_genome(g);
    decode_layered(&mut cppn, &layout, &sub.hyper).expect("valid layered layout")
}

/// Fitness `1000/(1 + E²)` and how many of the 512 answers are right; a
/// substrate's outputs in (−1, 1) are mapped to (0, 1).
fn evaluate_substrate(net: &mut SparseNetwork, images: &[([f64; 8], [bool; 2])]) -> (f64, usize) {
    evaluate(net, images, |x| *x, |y| (y + 1.0) / 2.0)
}

/// The same for a plain NEAT network: the pixels and a bias of 1 in, its
/// sigmoid outputs in (0, 1) as they are.
fn evaluate_direct(net: &mut FeedForwardNetwork, images: &[([f64; 8], [bool; 2])]) -> (f64, usize) {
    evaluate(
        net,
        images,
        |x| [x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], 1.0],
        |y| y,
    )
}

/// Fitness `1000/(1 + E²)` and how many of the 512 answers are right, with
/// `input` building the network's inputs and `to_unit` mapping an output to (0, 1).
fn evaluate<N: Network, const I: usize>(
    net: &mut N,
    images: &[([f64; 8], [bool; 2])],
    input: impl Fn(&[f64; 8]) -> [f64; I],
    to_unit: impl Fn(f64) -> f64,
) -> (f64, usize) {
    let mut error = 0.0;
    let mut right = 0;
    let mut out = [0.0; 2];
    for (x, labels) in images {
        net.reset();
        net.activate(&input(x), &mut out);
        for (&y, &label) in out.iter().zip(labels) {
            let a = to_unit(y);
            error += (a - f64::from(u8::from(label))).abs();
            right += usize::from((a > 0.5) == label);
        }
    }
    (1000.0 / (1.0 + error * error), right)
}

/// The generation-0 population: minimal CPPNs, or LEO-seeded ones.
fn initial_population(params: &NeatParams, mode: Mode, seed: u64) -> Result<Population, NeatError> {
    if mode == Mode::Neat {
        return Population::new(params.clone(), GenomeSpec::plain(9, 2), seed);
    }
    let spec = GenomeSpec {
        outputs: if mode.leo() { 3 } else { 2 },
        ..GenomeSpec::cppn()
    };
    if !mode.seeded() {
        return Population::new(params.clone(), spec, seed);
    }
    let genomes = leo_seeded_genomes(&spec, params, params.population_size, seed ^ 0x5eed, 2);
    Population::from_genomes(params.clone(), spec, genomes, seed)
}

/// One run's outcome.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RetinaRun {
    /// Evaluations up to and including the first genome right on all 512
    /// answers, `None` when unsolved.
    pub evals: Option<usize>,
    /// Hidden nodes of the solving genome (its CPPN's, or the network's with
    /// [`Mode::Neat`]); 0 when unsolved.
    pub hidden: usize,
    /// The most right answers (of 512) any genome gave.
    pub best_right: usize,
    /// Hidden nodes of the substrate (or network) that first gave them.
    pub substrate_hidden: usize,
}

/// One run of at most `gens` generations.
pub fn run(
    params: &NeatParams,
    mode: Mode,
    sub: &Substrate,
    pixels: Pixels,
    seed: u64,
    gens: u32,
) -> Result<RetinaRun, NeatError> {
    let images = images(pixels);
    let mut pop = initial_population(params, mode, seed)?;
    let (mut best_right, mut best_hidden) = (0, 0);
    for _ in 0..gens {
        let mut fitness = Vec::with_capacity(pop.genomes().len());
        let mut first = None;
        for (i, g) in pop.genomes().iter().enumerate() {
            let (f, right, hidden) = if mode == Mode::Neat {
                let mut net = FeedForwardNetwork::from_genome(g);
                let (f, right) = evaluate_direct(&mut net, &images);
                (f, right, g.num_hidden())
            } else {
                let mut net = network(g, mode, sub);
                let (f, right) = evaluate_substrate(&mut net, &images);
                (f, right, net.num_hidden())
            };
            fitness.push(f);
            if right > best_right {
                (best_right, best_hidden) = (right, hidden);
            }
            if right == 512 && first.is_none() {
                first = Some(i);
            }
        }
        pop.set_fitnesses(fitness)?;
        if let Some(i) = first {
            return Ok(RetinaRun {
                evals: Some(pop.generation() as usize * pop.params().population_size + i + 1),
                hidden: pop.genomes()[i].num_hidden(),
                best_right,
                substrate_hidden: best_hidden,
            });
        }
        pop.next_generation();
    }
    Ok(RetinaRun {
        evals: None,
        hidden: 0,
        best_right,
        substrate_hidden: best_hidden,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_retina_run_counts_the_right_answers_of_each_mode() {
        let sub = Substrate::default();
        for mode in [Mode::HyperNeat, Mode::LeoSeed, Mode::Neat] {
            let params = if mode == Mode::Neat {
                NeatParams::plain_neat()
            } else {
                NeatParams::paper_cppn()
            };
            let r = run(&params, mode, &sub, Pixels::ZeroOne, 1, 2).unwrap();
            assert!(r.best_right >= 256 && r.best_right <= 512, "{mode:?} {r:?}");
            assert_eq!(r.evals.is_some(), r.best_right == 512);
            let again = run(&params, mode, &sub, Pixels::ZeroOne, 1, 2).unwrap();
            assert_eq!(again, r, "deterministic");
        }
        assert!(Mode::parse("leo-seed").is_ok() && Mode::parse("x").is_err());
    }
}

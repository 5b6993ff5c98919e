//! Weight perturbation and replacement, clamped to the weight amplitude.

use rand::{Rng, RngExt};

use crate::genome::{Genome, random_weight};
use crate::params::NeatParams;

/// A standard normal sample (Box–Muller; portable and deterministic).
pub fn gaussian<R: Rng + ?Sized>(rng: &mut R) -> f64 {
    // 1 - u keeps the logarithm's argument in (0, 1].
    let u1 = 1.0 - rng.random::<f64>();
    let u2 = rng.random::<f64>();
    (-2.0 * crate::math::ln(u1)).sqrt() * crate::math::cos(std::f64::consts::TAU * u2)
}

/// Changes each link's weight with `weight_link_probability`: replaced by a fresh
/// random weight with `weight_replace_probability`, else perturbed by
/// `N(0, weight_perturb_power²)`; the result is clamped to ±`weight_amplitude`.
pub fn mutate_weights<R: Rng + ?Sized>(genome: &mut Genome, params: &NeatParams, rng: &mut R) {
    let amp = params.weight_amplitude;
    for link in &mut genome.links {
        if !rng.random_bool(params.weight_link_probability) {
            continue;
        }
        let w = if rng.random_bool(params.weight_replace_probability) {
            random_weight(params, rng)
        } else {
            link.weight + gaussian(rng) * params.weight_perturb_power
        };
        link.weight = w.clamp(-amp, amp);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::genome::GenomeSpec;
    use crate::innovation::InnovationTracker;
    use rand::SeedableRng;
    use rand_pcg::Pcg64;

    #[test]
    fn weights_stay_within_amplitude() {
        let spec = GenomeSpec::cppn();
        let params = NeatParams {
            weight_perturb_power: 10.0,
            weight_link_probability: 1.0,
            ..NeatParams::default()
        };
        let mut rng = Pcg64::seed_from_u64(3);
        let mut t = InnovationTracker::new(8);
        let mut g = Genome::minimal(&spec, &params, &mut t, &mut rng);
        let before = g.clone();
        for _ in 0..50 {
            mutate_weights(&mut g, &params, &mut rng);
        }
        assert_ne!(g, before);
        assert!(g.links().iter().all(|l| l.weight.abs() <= 3.0));
    }

    #[test]
    fn gaussian_has_unit_variance() {
        let mut rng = Pcg64::seed_from_u64(1);
        let n = 20_000;
        let xs: Vec<f64> = (0..n).map(|_| gaussian(&mut rng)).collect();
        let mean = xs.iter().sum::<f64>() / n as f64;
        let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / n as f64;
        assert!(mean.abs() < 0.03, "{mean}");
        assert!((var - 1.0).abs() < 0.05, "{var}");
    }
}

//! NEAT hyper-parameters: the paper's Table II defaults, Stanley's for the rest.

use serde::{Deserialize, Serialize};

use crate::error::NeatError;

/// Every NEAT hyper-parameter, validated by [`NeatParams::validate`].
///
/// Defaults are the paper's Table II (population 100, weight amplitude 3.0,
/// threshold 15.0, C1 = C2 = 2.0, C3 = 0.5, C_ACT = 1.0, mating 0.75,
/// add-link 0.3, add-node 0.1, elitism 5 %) and Stanley's NEAT values elsewhere.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct NeatParams {
    // Each field's doc comment is also its entry in `vivae config reference`:
    // a closing paragraph may give `Unit:`, `Paper:` (the paper's value) and,
    // for an `Option`, `Example:`.
    /// Genomes per generation.
    ///
    /// Paper: 100.
    pub population_size: usize,
    /// CPPN link weights are clamped to `[-weight_amplitude, weight_amplitude]`.
    ///
    /// Paper: 3.0.
    pub weight_amplitude: f64,
    /// Initial and replacement weights are uniform in `[-r, r]` (clamped to the amplitude).
    pub initial_weight_range: f64,
    /// Compatibility distance below which a genome joins a species.
    ///
    /// Paper: 15.0.
    pub compatibility_threshold: f64,
    /// C1: coefficient of excess genes.
    ///
    /// Paper: 2.0.
    pub c_excess: f64,
    /// C2: coefficient of disjoint genes.
    ///
    /// Paper: 2.0.
    pub c_disjoint: f64,
    /// C3: coefficient of the mean absolute weight difference of matching genes.
    ///
    /// Paper: 0.5.
    pub c_weight: f64,
    /// C_ACT: coefficient of matching links whose target nodes' activation functions differ.
    ///
    /// Paper: 1.0.
    pub c_activation: f64,
    /// Divide the excess, disjoint and activation terms by the larger genome's link count.
    pub normalize_distance: bool,
    /// Genomes with fewer links than this are not normalised (N = 1), as in Stanley's NEAT.
    ///
    /// Unit: links.
    pub normalize_min_genes: usize,
    /// When set, the threshold moves each generation towards this many species.
    ///
    /// Unit: species. Example: 10.
    pub target_species: Option<usize>,
    /// Step by which the dynamic compatibility threshold moves each generation.
    pub threshold_step: f64,
    /// Lower bound of the dynamic compatibility threshold.
    pub threshold_min: f64,
    /// Probability that an offspring is produced by crossover (else cloned and mutated).
    ///
    /// Paper: 0.75.
    pub mating_probability: f64,
    /// Probability that a crossover takes its second parent from another species.
    pub interspecies_mating_probability: f64,
    /// Probability that a crossover child is not mutated afterwards.
    pub mate_only_probability: f64,
    /// Probability of the add-link mutation (tried when add-node did not happen).
    ///
    /// Paper: 0.3.
    pub add_link_probability: f64,
    /// Probability of the add-node mutation.
    ///
    /// Paper: 0.1.
    pub add_node_probability: f64,
    /// Probability that a non-structural mutation (neither add-node nor add-link) changes weights.
    pub weight_mutation_probability: f64,
    /// Per-link probability of changing its weight during a weight mutation.
    pub weight_link_probability: f64,
    /// Per-changed-link probability of replacing the weight instead of perturbing it.
    pub weight_replace_probability: f64,
    /// Standard deviation of the Gaussian weight perturbation.
    pub weight_perturb_power: f64,
    /// Probability that a non-structural mutation toggles one link's enabled flag.
    pub toggle_enable_probability: f64,
    /// Probability that a non-structural mutation changes one hidden node's activation function.
    pub activation_mutation_probability: f64,
    /// A gene disabled in either parent stays disabled in the child with this probability.
    ///
    /// Paper: 0.75 (Stanley).
    pub disabled_inherit_probability: f64,
    /// Attempts the add-link mutation makes to find an unconnected node pair.
    pub add_link_attempts: usize,
    /// Fraction of each species (best first) allowed to reproduce.
    pub survival_threshold: f64,
    /// Fraction of each species copied unchanged into the next generation (rounded up).
    ///
    /// Paper: 0.05.
    pub elitism_fraction: f64,
    /// Species smaller than this keep no elites (the champion's species always keeps one).
    ///
    /// Unit: genomes.
    pub elitism_min_species_size: usize,
    /// A species that has not improved for this many generations gets no offspring.
    ///
    /// Unit: generations. Paper: 15 (Stanley).
    pub stagnation_limit: u32,
    /// When set and the population's best fitness has not risen for this many
    /// generations, only the two best species reproduce, half the population
    /// each, as mutated copies of their champions (Stanley's "delta coding";
    /// his code uses `dropoff_age` + 5).
    ///
    /// Unit: generations. Example: 20.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub population_stagnation_limit: Option<u32>,
    /// Hidden nodes of the start genome, every input linked to each and each
    /// to every output; 0 links the inputs straight to the outputs (NEAT's
    /// minimal start). Lehman's maze code starts from 1 (`mazestartgenes`).
    #[serde(skip_serializing_if = "is_zero")]
    pub start_hidden: usize,
}

/// Whether a count is 0, which a serialised config leaves out (so configs
/// written before the key existed keep their checksums).
fn is_zero(n: &usize) -> bool {
    *n == 0
}

impl Default for NeatParams {
    fn default() -> Self {
        NeatParams {
            population_size: 100,
            weight_amplitude: 3.0,
            initial_weight_range: 1.0,
            compatibility_threshold: 15.0,
            c_excess: 2.0,
            c_disjoint: 2.0,
            c_weight: 0.5,
            c_activation: 1.0,
            normalize_distance: false,
            normalize_min_genes: 20,
            target_species: None,
            threshold_step: 0.3,
            threshold_min: 0.3,
            mating_probability: 0.75,
            interspecies_mating_probability: 0.001,
            mate_only_probability: 0.2,
            add_link_probability: 0.3,
            add_node_probability: 0.1,
            weight_mutation_probability: 0.8,
            weight_link_probability: 0.9,
            weight_replace_probability: 0.1,
            weight_perturb_power: 0.5,
            toggle_enable_probability: 0.01,
            activation_mutation_probability: 0.1,
            disabled_inherit_probability: 0.75,
            add_link_attempts: 20,
            survival_threshold: 0.2,
            elitism_fraction: 0.05,
            elitism_min_species_size: 5,
            stagnation_limit: 15,
            population_stagnation_limit: None,
            start_hidden: 0,
        }
    }
}

/// Largest accepted `population_size`.
pub const MAX_POPULATION: usize = 100_000;
/// Largest accepted `start_hidden`.
pub const MAX_START_HIDDEN: usize = 1_000;
/// Largest accepted `add_link_attempts`.
pub const MAX_ADD_LINK_ATTEMPTS: usize = 10_000;

fn invalid(field: &'static str, value: impl ToString, reason: &'static str) -> NeatError {
    NeatError::InvalidParam {
        field,
        value: value.to_string(),
        reason,
    }
}

fn probability(field: &'static str, p: f64) -> Result<(), NeatError> {
    if (0.0..=1.0).contains(&p) {
        Ok(())
    } else {
        Err(invalid(field, p, "must be a probability in [0, 1]"))
    }
}

fn positive(field: &'static str, x: f64) -> Result<(), NeatError> {
    if x.is_finite() && x > 0.0 {
        Ok(())
    } else {
        Err(invalid(field, x, "must be finite and > 0"))
    }
}

fn non_negative(field: &'static str, x: f64) -> Result<(), NeatError> {
    if x.is_finite() && x >= 0.0 {
        Ok(())
    } else {
        Err(invalid(field, x, "must be finite and >= 0"))
    }
}

impl NeatParams {
    /// The paper's Table II (the default): for evolving CPPNs for HyperNEAT.
    ///
    /// Tuned for few, smooth CPPNs with several activation functions: a high
    /// compatibility threshold (15) with activation differences counted, small
    /// weight perturbations. Use [`NeatParams::plain_neat`] for ordinary NEAT
    /// tasks (XOR, parity, pole balancing): with this preset they stall.
    pub fn paper_cppn() -> NeatParams {
        NeatParams::default()
    }

    /// Plain NEAT for direct encodings (XOR, parity, pole balancing).
    ///
    /// Stanley's XOR settings where our operators match his: population 150,
    /// compatibility 3.0 with C1 = C2 = 1.0, C3 = 0.4, add-node 0.03, weights
    /// capped at ±8, survival 20 %, stagnation 15; add-link 0.3 and a Gaussian
    /// weight perturbation of σ = 2.5 with 20 % replacement (tuned on seeds
    /// 1000–1039). Solves XOR in about 4,100 evaluations on average
    /// (`cargo run --release -p vivae-neat --example xor`). Pair it with
    /// [`GenomeSpec::plain`](crate::GenomeSpec::plain).
    pub fn plain_neat() -> NeatParams {
        NeatParams {
            population_size: 150,
            weight_amplitude: 8.0,
            initial_weight_range: 2.5,
            compatibility_threshold: 3.0,
            c_excess: 1.0,
            c_disjoint: 1.0,
            c_weight: 0.4,
            c_activation: 0.0,
            add_node_probability: 0.03,
            add_link_probability: 0.3,
            weight_mutation_probability: 0.9,
            weight_link_probability: 0.9,
            weight_replace_probability: 0.2,
            weight_perturb_power: 2.5,
            toggle_enable_probability: 0.0,
            activation_mutation_probability: 0.0,
            mating_probability: 0.75,
            interspecies_mating_probability: 0.001,
            mate_only_probability: 0.2,
            survival_threshold: 0.2,
            stagnation_limit: 15,
            ..NeatParams::default()
        }
    }

    /// Checks every field; the error names the first bad field and its value.
    pub fn validate(&self) -> Result<(), NeatError> {
        if self.population_size == 0 {
            return Err(invalid("population_size", 0, "must be at least 1"));
        }
        if self.population_size > MAX_POPULATION {
            return Err(invalid(
                "population_size",
                self.population_size,
                "must be at most 100000",
            ));
        }
        if self.add_link_attempts > MAX_ADD_LINK_ATTEMPTS {
            return Err(invalid(
                "add_link_attempts",
                self.add_link_attempts,
                "must be at most 10000",
            ));
        }
        positive("weight_amplitude", self.weight_amplitude)?;
        positive("initial_weight_range", self.initial_weight_range)?;
        non_negative("compatibility_threshold", self.compatibility_threshold)?;
        non_negative("c_excess", self.c_excess)?;
        non_negative("c_disjoint", self.c_disjoint)?;
        non_negative("c_weight", self.c_weight)?;
        non_negative("c_activation", self.c_activation)?;
        if self.target_species == Some(0) {
            return Err(invalid("target_species", 0, "must be at least 1 when set"));
        }
        non_negative("threshold_step", self.threshold_step)?;
        non_negative("threshold_min", self.threshold_min)?;
        probability("mating_probability", self.mating_probability)?;
        probability(
            "interspecies_mating_probability",
            self.interspecies_mating_probability,
        )?;
        probability("mate_only_probability", self.mate_only_probability)?;
        probability("add_link_probability", self.add_link_probability)?;
        probability("add_node_probability", self.add_node_probability)?;
        probability(
            "weight_mutation_probability",
            self.weight_mutation_probability,
        )?;
        probability("weight_link_probability", self.weight_link_probability)?;
        probability(
            "weight_replace_probability",
            self.weight_replace_probability,
        )?;
        non_negative("weight_perturb_power", self.weight_perturb_power)?;
        probability("toggle_enable_probability", self.toggle_enable_probability)?;
        probability(
            "activation_mutation_probability",
            self.activation_mutation_probability,
        )?;
        probability(
            "disabled_inherit_probability",
            self.disabled_inherit_probability,
        )?;
        if self.survival_threshold <= 0.0 || self.survival_threshold > 1.0 {
            return Err(invalid(
                "survival_threshold",
                self.survival_threshold,
                "must be in (0, 1]",
            ));
        }
        probability("elitism_fraction", self.elitism_fraction)?;
        if self.stagnation_limit == 0 {
            return Err(invalid("stagnation_limit", 0, "must be at least 1"));
        }
        self.validate_counts()
    }

    /// The counts `validate` leaves: the start's hidden nodes and the population's stagnation.
    fn validate_counts(&self) -> Result<(), NeatError> {
        if self.start_hidden > MAX_START_HIDDEN {
            let reason = "must be at most 1000";
            return Err(invalid("start_hidden", self.start_hidden, reason));
        }
        if self.population_stagnation_limit == Some(0) {
            let reason = "must be at least 1 when set";
            return Err(invalid("population_stagnation_limit", 0, reason));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid_and_table_two() {
        let p = NeatParams::default();
        p.validate().unwrap();
        assert_eq!(p.population_size, 100);
        assert_eq!(p.weight_amplitude, 3.0);
        assert_eq!(p.compatibility_threshold, 15.0);
        assert_eq!((p.c_excess, p.c_disjoint, p.c_weight), (2.0, 2.0, 0.5));
        assert_eq!(p.c_activation, 1.0);
        assert_eq!(p.mating_probability, 0.75);
        assert_eq!((p.add_link_probability, p.add_node_probability), (0.3, 0.1));
        assert_eq!(p.elitism_fraction, 0.05);
    }

    #[test]
    fn invalid_values_name_field_and_value() {
        let p = NeatParams {
            population_size: 0,
            ..NeatParams::default()
        };
        let e = p.validate().unwrap_err().to_string();
        assert!(e.contains("population_size") && e.contains('0'), "{e}");

        let p = NeatParams {
            add_node_probability: 1.5,
            ..NeatParams::default()
        };
        let e = p.validate().unwrap_err().to_string();
        assert!(
            e.contains("add_node_probability") && e.contains("1.5"),
            "{e}"
        );

        let p = NeatParams {
            compatibility_threshold: -1.0,
            ..NeatParams::default()
        };
        let e = p.validate().unwrap_err().to_string();
        assert!(
            e.contains("compatibility_threshold") && e.contains("-1"),
            "{e}"
        );

        let p = NeatParams {
            weight_perturb_power: f64::NAN,
            ..NeatParams::default()
        };
        assert!(p.validate().is_err());

        let p = NeatParams {
            population_stagnation_limit: Some(0),
            ..NeatParams::default()
        };
        let e = p.validate().unwrap_err().to_string();
        assert!(e.contains("population_stagnation_limit"), "{e}");
    }

    #[test]
    fn unset_population_stagnation_limit_is_not_written() {
        // Configs and checkpoints written before the option existed keep their bytes.
        let json = serde_json::to_string(&NeatParams::default()).unwrap();
        assert!(!json.contains("population_stagnation_limit"), "{json}");
        let p = NeatParams {
            population_stagnation_limit: Some(20),
            ..NeatParams::default()
        };
        let back: NeatParams = serde_json::from_str(&serde_json::to_string(&p).unwrap()).unwrap();
        assert_eq!(back, p);
    }

    #[test]
    fn serde_rejects_unknown_fields_and_fills_defaults() {
        let p: NeatParams = serde_json::from_str(r#"{"population_size": 150}"#).unwrap();
        assert_eq!(p.population_size, 150);
        assert_eq!(p.c_excess, 2.0);
        assert!(serde_json::from_str::<NeatParams>(r#"{"populaton_size": 150}"#).is_err());
    }
}

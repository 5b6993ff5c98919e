//! Typed errors of the NEAT library.

use std::fmt;

use thiserror::Error;

/// Everything that can go wrong when configuring or restoring NEAT.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum NeatError {
    /// A parameter has a value outside its valid range.
    #[error("invalid NEAT parameter `{field}` = {value}: {reason}")]
    InvalidParam {
        /// Name of the offending field.
        field: &'static str,
        /// The offending value, formatted.
        value: String,
        /// What the value must satisfy.
        reason: &'static str,
    },
    /// A genome specification is unusable (e.g. no inputs).
    #[error("invalid genome spec: {0}")]
    InvalidSpec(String),
    /// A genome violates a structural invariant.
    #[error("invalid genome: {0}")]
    InvalidGenome(#[from] GenomeError),
    /// A population (restored, or assembled from genomes) is inconsistent.
    #[error("invalid population: {0}")]
    InvalidPopulation(#[from] PopulationError),
    /// Fitness values given for a generation do not match its genomes.
    #[error("{given} fitness values for {genomes} genomes")]
    FitnessCount {
        /// Number of values given.
        given: usize,
        /// Number of genomes.
        genomes: usize,
    },
    /// A checkpoint could not be written or read (e.g. malformed JSON).
    #[error("checkpoint: {0}")]
    Checkpoint(String),
}

/// What is wrong with a genome's genes.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum GenomeError {
    /// Two node genes share an id.
    #[error("node id {0} appears twice")]
    DuplicateNode(u32),
    /// Node genes are not sorted by id.
    #[error("node ids not increasing at {0}")]
    NodeOrder(u32),
    /// Two link genes share an innovation number.
    #[error("innovation number {0} appears twice")]
    DuplicateInnovation(u32),
    /// Link genes are not sorted by innovation number.
    #[error("innovation numbers not increasing at {0}")]
    InnovationOrder(u32),
    /// Two link genes connect the same pair of nodes.
    #[error("duplicate link {from} -> {to}")]
    DuplicateLink {
        /// Source node id.
        from: u32,
        /// Target node id.
        to: u32,
    },
    /// A link gene's endpoint is not a node of the genome.
    #[error("link {innovation} ({from} -> {to}) refers to a missing node")]
    MissingNode {
        /// The link's innovation number.
        innovation: u32,
        /// Source node id.
        from: u32,
        /// Target node id.
        to: u32,
    },
    /// A link gene ends at an input node.
    #[error("link {innovation} targets input node {to}")]
    LinkIntoInput {
        /// The link's innovation number.
        innovation: u32,
        /// The input node's id.
        to: u32,
    },
    /// A link weight is NaN or infinite.
    #[error("link {innovation} has non-finite weight")]
    NonFiniteWeight {
        /// The link's innovation number.
        innovation: u32,
    },
}

/// Which genome of a population an error is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GenomeAt {
    /// Genome `i` of the current generation.
    Member(usize),
    /// The representative of the species with this id.
    Representative(u32),
    /// The best genome of the run so far.
    BestEver,
}

impl fmt::Display for GenomeAt {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            GenomeAt::Member(i) => write!(f, "genome {i}"),
            GenomeAt::Representative(id) => write!(f, "the representative of species {id}"),
            GenomeAt::BestEver => f.write_str("the best-ever genome"),
        }
    }
}

/// What is wrong with a population's state as a whole.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum PopulationError {
    /// The population has no genomes.
    #[error("no genomes")]
    Empty,
    /// A genome violates a structural invariant.
    #[error("{at}: {error}")]
    Genome {
        /// Which genome.
        at: GenomeAt,
        /// What is wrong with it.
        error: GenomeError,
    },
    /// A genome's inputs or outputs differ from the genome spec.
    #[error(
        "{at} has {inputs} inputs and {outputs} outputs; the spec says {spec_inputs} and {spec_outputs}"
    )]
    Shape {
        /// Which genome.
        at: GenomeAt,
        /// Its number of input nodes.
        inputs: usize,
        /// Its number of output nodes.
        outputs: usize,
        /// Inputs the spec asks for.
        spec_inputs: usize,
        /// Outputs the spec asks for.
        spec_outputs: usize,
    },
    /// The fitness list does not have one value per genome.
    #[error("{given} fitness values for {genomes} genomes")]
    FitnessCount {
        /// Number of values stored.
        given: usize,
        /// Number of genomes.
        genomes: usize,
    },
    /// A stored fitness (of a genome, a species or the best ever) is NaN or infinite.
    #[error("the fitness of {0} is not finite")]
    NonFiniteFitness(String),
    /// Two species share an id.
    #[error("species id {0} appears twice")]
    DuplicateSpecies(u32),
    /// A species has no members.
    #[error("species {0} has no members")]
    EmptySpecies(u32),
    /// A species lists a genome the population does not have.
    #[error("species {species} lists genome {member}, but there are {genomes} genomes")]
    MissingMember {
        /// The species id.
        species: u32,
        /// The listed member index.
        member: usize,
        /// Number of genomes.
        genomes: usize,
    },
    /// A genome is listed by no species or by more than one.
    #[error("genome {member} belongs to {count} species (must be exactly 1)")]
    Membership {
        /// The genome index.
        member: usize,
        /// How many species list it.
        count: usize,
    },
    /// A counter is not above every id it has handed out.
    #[error("{counter} is {value}, but {what} {used} is already in use")]
    Counter {
        /// Which counter.
        counter: &'static str,
        /// Its stored value.
        value: u32,
        /// What it numbers.
        what: &'static str,
        /// The largest id in use.
        used: u32,
    },
    /// A node's kind does not match its id (inputs are `0..inputs`, outputs
    /// follow, hidden nodes come after).
    #[error("{at}: node {id} is an {kind} node, but by its id it must be an {expected} node")]
    NodeKind {
        /// Which genome.
        at: GenomeAt,
        /// The node id.
        id: u32,
        /// Its kind in the genome (`input`, `hidden`, `output`).
        kind: &'static str,
        /// The kind its id implies.
        expected: &'static str,
    },
    /// A genome's link is numbered differently from the run's innovation history.
    #[error("{at}: link {from} -> {to} has innovation {innovation}, but the innovation history gives it {}", recorded.map_or("none".to_string(), |r| r.to_string()))]
    InnovationMismatch {
        /// Which genome.
        at: GenomeAt,
        /// Source node id.
        from: u32,
        /// Target node id.
        to: u32,
        /// The genome's innovation number for it.
        innovation: u32,
        /// The history's number for it, if it has one.
        recorded: Option<u32>,
    },
    /// The innovation history gives one number to two different links.
    #[error("innovation {0} is recorded for two different links")]
    SharedInnovation(u32),
    /// The innovation history records a split node that is not a hidden id, or records it twice.
    #[error("split node id {0} is not a hidden node id or is recorded twice")]
    SplitNode(u32),
    /// A record refers to a generation after the current one.
    #[error("{what} refers to generation {generation}, after the current generation {current}")]
    FutureGeneration {
        /// Which record.
        what: &'static str,
        /// The generation it names.
        generation: u32,
        /// The population's generation.
        current: u32,
    },
    /// The compatibility threshold is negative or not finite.
    #[error("compatibility threshold {0} is not finite and >= 0")]
    Threshold(f64),
}

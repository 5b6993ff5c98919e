//! NSGA-II (Deb et al. 2002) over fitness and the task's metrics: it adds the
//! Pareto front's size to `generations.csv` and writes the front
//! (`front.csv`, `front.jsonl`) with each checkpoint.

use std::fmt::Write as _;
use std::path::Path;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use vivae_neat::driver::Strategy;
use vivae_neat::strategies::{Measure, Nsga2, Nsga2Params, Objective};
use vivae_neat::{Genome, NeatError};

use crate::search::StrategyConfig;
use crate::config::Config;
use crate::error::Result;
use crate::io::{bad_input, write_atomic};
use crate::search::files;
use crate::search::files::{FrontLine, jsonl};
use crate::search::{
    BehaviourSpace, FrontFigure, Needs, RunStrategy, Search, Start, StrategyEntry, StrategyFigure, StrategyReport,
    TaskFacts, bad_setting, state_of,
};

/// NSGA-II's settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Nsga2Config {
    /// Objectives: fitness or a metric (contacts, on_road), maximised, or
    /// minimised when written with a leading minus (-contacts).
    pub objectives: Vec<String>,
    /// Probability that a child is the crossover of two tournament winners rather than a mutant.
    pub crossover_probability: f64,
}

impl Default for Nsga2Config {
    fn default() -> Self {
        Nsga2Config {
            objectives: vec!["fitness".into(), "-contacts".into()],
            crossover_probability: 0.5,
        }
    }
}

/// The objective `name`: `fitness` or one of a task's `metrics`, optionally
/// with a leading `-` (minimised).
pub fn objective_among(name: &str, metrics: &[&str]) -> Option<Objective> {
    let (maximise, what) = match name.strip_prefix('-') {
        Some(rest) => (false, rest),
        None => (true, name),
    };
    let measure = match what {
        "fitness" => Measure::Fitness,
        other => Measure::Metric(metrics.iter().position(|m| *m == other)?),
    };
    Some(Objective { measure, maximise })
}

/// Checks `[strategy.nsga2]` for a task measuring `metrics`; the error
/// names the key.
pub(super) fn validate(n: &Nsga2Config, metrics: &[&str]) -> std::result::Result<(), String> {
    if n.objectives.is_empty() {
        return Err(bad_setting(
            "nsga2.objectives",
            &n.objectives,
            "at least one objective",
        ));
    }
    if let Some(o) = (n.objectives.iter()).find(|o| objective_among(o, metrics).is_none()) {
        return Err(format!(
            "strategy.nsga2.objectives = {o:?}: expected fitness or {}, each optionally with a leading -",
            metrics.join(" or ")
        ));
    }
    if !(0.0..=1.0).contains(&n.crossover_probability) {
        return Err(bad_setting(
            "nsga2.crossover_probability",
            &n.crossover_probability,
            "must be in [0, 1]",
        ));
    }
    Ok(())
}

/// Keeps the objectives the task measures (the default minimises contacts,
/// which not every task counts).
pub(super) fn fit_to(n: &mut Nsga2Config, task: &TaskFacts<'_>) {
    if let Some(metrics) = task.metrics {
        n.objectives
            .retain(|o| objective_among(o, metrics).is_some());
    }
}

/// NSGA-II's registration.
pub static STRATEGY: StrategyEntry = StrategyEntry {
    kind: "nsga2",
    needs: Needs {
        behaviour: false,
        metrics: true,
    },
    takes_population: false,
    variant: "Nsga2",
    from_state: state_of::<Nsga2>,
    extra_columns: ",front_size",
    build,
    header_line: |c| {
        format!(
            "\n  strategy: nsga2, objectives {}",
            StrategyConfig::of(c).nsga2.objectives.join(", ")
        )
    },
    report,
    files: &[files::FRONT, files::FRONT_GENOMES],
    settings: None,
};

/// The Pareto front as saved with the last checkpoint, and its objectives.
fn report(dir: &Path, config: &Config, _space: &BehaviourSpace) -> Result<Option<StrategyReport>> {
    let front = crate::search::files::read_front(dir)?.unwrap_or_default();
    Ok(Some(StrategyReport {
        kind: STRATEGY.kind,
        objectives: StrategyConfig::of(config).nsga2.objectives,
        front: (front.into_iter())
            .map(|f| (f.member, f.fitness, f.objectives))
            .collect(),
        ..StrategyReport::default()
    }))
}

fn build(
    Start {
        config,
        spec,
        metrics,
        ..
    }: Start<'_>,
) -> Result<Search> {
    let neat = config.neat.clone();
    let s = &StrategyConfig::of(config).nsga2;
    let nsga = Nsga2Params {
        population_size: neat.population_size,
        objectives: (s.objectives.iter())
            .filter_map(|o| objective_among(o, metrics))
            .collect(),
        crossover_probability: s.crossover_probability,
    };
    let refused = |e: NeatError| bad_input(format!("strategy.nsga2: {e}"));
    let seed = config.experiment.seed;
    Ok(Search::of(
        Nsga2::new(neat, spec, nsga, seed).map_err(refused)?,
    ))
}

impl RunStrategy for Nsga2 {
    fn entry(&self) -> &'static StrategyEntry {
        &STRATEGY
    }

    fn batch(&self) -> Vec<Genome> {
        self.clone().ask().genomes.to_vec()
    }

    fn extra_fields(&self) -> String {
        format!(",{}", self.pareto_front().len())
    }

    fn summary_fields(&self) -> String {
        format!(" front_size={}", self.pareto_front().len())
    }

    /// Over two objectives: the last generation's objectives and its front
    /// (with more, no 2-D picture shows the front: `front.csv` has them all).
    fn figure(
        &self,
        config: &Config,
        _space: &BehaviourSpace,
        generation: u32,
    ) -> Option<StrategyFigure> {
        let objectives = StrategyConfig::of(config).nsga2.objectives;
        let [a, b] = &objectives[..] else {
            return None;
        };
        let two = |o: &[f64]| [o[0], o[1]];
        let mut members = self.pareto_front();
        members.sort_by(|a, b| b.2.total_cmp(&a.2));
        let front: Vec<[f64; 2]> = members.iter().map(|m| two(&m.1)).collect();
        Some(StrategyFigure::Front(FrontFigure {
            title: format!(
                "NSGA-II, generation {generation}: Pareto front of {} members (numbered as in front.csv)",
                front.len()
            ),
            objectives: [a.clone(), b.clone()],
            population: self.scored_objectives().iter().map(|o| two(o)).collect(),
            front,
        }))
    }

    /// The Pareto front, fittest first: `front.csv` (objectives) and
    /// `front.jsonl` (with genomes).
    fn write_outputs(&self, dir: &Path, config: &Config, _space: &BehaviourSpace) -> Result<()> {
        let mut front = self.pareto_front();
        front.sort_by(|a, b| b.2.total_cmp(&a.2));
        let lines: Vec<FrontLine> = (front.into_iter().enumerate())
            .map(|(member, (g, objectives, fitness))| FrontLine {
                member,
                fitness,
                objectives,
                genome: g.clone(),
            })
            .collect();
        let objectives = StrategyConfig::of(config).nsga2.objectives;
        let names = (objectives.iter()).map(|o| match o.strip_prefix('-') {
            Some(min) => format!("min_{min}"),
            None => format!("max_{o}"),
        });
        let mut csv = format!("member,fitness,{}\n", names.collect::<Vec<_>>().join(","));
        for l in &lines {
            let o: Vec<String> = l.objectives.iter().map(f64::to_string).collect();
            let _ = writeln!(csv, "{},{},{}", l.member, l.fitness, o.join(","));
        }
        write_atomic(&dir.join(files::FRONT), csv.as_bytes())?;
        write_atomic(&dir.join(files::FRONT_GENOMES), jsonl(&lines)?.as_bytes())
    }
}

/// Names of the objectives a run's Pareto front is over (a minimised one
/// without its `-`), for labelling its members.
pub fn front_objective_names(config: &Config) -> Vec<String> {
    (StrategyConfig::of(config).nsga2.objectives.iter())
        .map(|o| o.trim_start_matches('-').to_string())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A task's metrics (the driving task's).
    const METRICS: [&str; 2] = ["contacts", "on_road"];

    #[test]
    fn objectives_parse_with_their_direction() {
        let o = objective_among("-contacts", &METRICS).unwrap();
        assert_eq!((o.measure, o.maximise), (Measure::Metric(0), false));
        assert_eq!(objective_among("fitness", &METRICS).unwrap().measure, Measure::Fitness);
        assert_eq!(objective_among("on_road", &METRICS).unwrap().measure, Measure::Metric(1));
        assert!(objective_among("speed", &METRICS).is_none() && objective_among("--fitness", &METRICS).is_none());
    }
}

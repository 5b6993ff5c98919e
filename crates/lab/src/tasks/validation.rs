//! A finished run's champion validated on fresh episodes by its task
//! ([`RunTask::validation`]) and written as the run's `validation.json`, in
//! the shape the Python package's `vivae.gym.validate` writes for a
//! `gymnasium` run, so that a report and a reader take both alike.

use std::path::Path;

use serde::{Deserialize, Serialize};
use vivae_neat::Genome;

use crate::error::{Error, Result};
use crate::io::{read_text, write_atomic};
use crate::rundir::files;
use crate::tasks::RunTask;

/// A champion's validation as `validation.json` holds it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ValidationRecord {
    /// The environment (a Gymnasium id) or the task (its `--task` name) played.
    pub env: String,
    /// Episodes played.
    pub episodes: u32,
    /// The first and last episode's seed: Gymnasium's `reset` seeds, or the
    /// numbers of the episodes drawn from [`ValidationRecord::validation_seed`].
    pub seeds: [u64; 2],
    /// For a task played by vivae: the seed episode `k`'s start is drawn
    /// from with `k` (as a training evaluation's episodes from its seed).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub validation_seed: Option<u64>,
    /// The mean return.
    pub mean: f64,
    /// The returns' standard deviation.
    pub std: f64,
    /// The worst return.
    pub min: f64,
    /// The best return.
    pub max: f64,
    /// The mean return that solves the task, if it has one.
    pub reward_threshold: Option<f64>,
    /// Whether the mean reaches it (none without a threshold).
    pub solved: Option<bool>,
    /// The champion's generation.
    pub generation: u32,
    /// The champion's fitness in training.
    pub fitness: f64,
}

impl ValidationRecord {
    /// One line for a person: the mean, its range and the verdict.
    pub fn sentence(&self) -> String {
        let verdict = match (self.reward_threshold, self.solved) {
            (Some(t), Some(true)) => format!(", threshold {t}: solved"),
            (Some(t), _) => format!(", threshold {t}: not solved"),
            _ => String::new(),
        };
        format!(
            "the champion (generation {}) validated on {} fresh episodes of {}: mean return {:.2} (std {:.2}, {:.2} to {:.2}){verdict}",
            self.generation, self.episodes, self.env, self.mean, self.std, self.min, self.max
        )
    }
}

/// Validates `genome` (the champion of `generation`, of training fitness
/// `fitness`) by `task` and writes `validation.json` in the run directory
/// `dir` atomically; `None` (nothing written) for a task without validation.
pub fn write(
    dir: &Path,
    task: &dyn RunTask,
    genome: &Genome,
    generation: u32,
    fitness: f64,
) -> Result<Option<ValidationRecord>> {
    let Some((v, solved)) = task.validation(genome) else {
        return Ok(None);
    };
    let threshold = task.entry().reward_threshold.map(|t| t.value);
    let record = ValidationRecord {
        env: task.entry().name.to_string(),
        episodes: v.episodes,
        seeds: [0, u64::from(v.episodes.saturating_sub(1))],
        validation_seed: Some(v.seed),
        mean: v.mean,
        std: v.std,
        min: v.worst,
        max: v.best,
        reward_threshold: threshold,
        solved: threshold.map(|_| solved),
        generation,
        fitness,
    };
    let mut text =
        serde_json::to_string_pretty(&record).map_err(|e| Error::Invalid(e.to_string()))?;
    text.push('\n');
    write_atomic(&dir.join(files::VALIDATION), text.as_bytes())?;
    Ok(Some(record))
}

/// The run in `dir`'s `validation.json`, if it has one; the error names the
/// file and what is wrong with it.
pub fn read(dir: &Path) -> Result<Option<ValidationRecord>> {
    let path = dir.join(files::VALIDATION);
    if !path.is_file() {
        return Ok(None);
    }
    let text = read_text(&path)?;
    serde_json::from_str(&text)
        .map(Some)
        .map_err(|e| Error::RunFile {
            path,
            reason: e.to_string(),
        })
}

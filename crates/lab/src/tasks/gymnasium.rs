//! The classic-control tasks by their names, each with its episode stepped
//! from a given state under given actions ([`episode`]): what the
//! Python package exposes to compare every step with Gymnasium's own.

use super::classic::{Step, episode};
use super::{acrobot, cartpole, mountain_car, mountain_car_continuous, pendulum};

/// An episode of one task, as [`episode`] steps it.
pub type EpisodeFn = fn(&[f64], &[f64]) -> Result<Vec<Step>, String>;

/// The classic-control tasks by name, each with its episode.
pub static EPISODES: [(&str, EpisodeFn); 5] = [
    ("cartpole", episode::<cartpole::CartPole>),
    ("acrobot", episode::<acrobot::Acrobot>),
    ("mountain-car", episode::<mountain_car::MountainCar>),
    (
        "mountain-car-continuous",
        episode::<mountain_car_continuous::MountainCarContinuous>,
    ),
    ("pendulum", episode::<pendulum::Pendulum>),
];

/// The episode of the classic-control task named `task` (see [`episode`]).
pub fn episode_of(task: &str, state: &[f64], actions: &[f64]) -> Result<Vec<Step>, String> {
    let names = || EPISODES.map(|(n, _)| n).join(", ");
    let (_, run) = (EPISODES.iter().find(|(n, _)| *n == task)).ok_or_else(|| {
        format!(
            "task {task:?} is not a classic-control task (one of {})",
            names()
        )
    })?;
    run(state, actions)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_bad_state_or_action_or_task_is_refused_by_name() {
        let e = episode_of("acrobot", &[0.0; 3], &[0.0]).unwrap_err();
        assert!(e.contains("acrobot state"), "{e}");
        let e = episode_of("acrobot", &[0.0; 4], &[3.0]).unwrap_err();
        assert!(e.contains("action 3"), "{e}");
        let e = episode_of("driving", &[0.0; 4], &[0.0]).unwrap_err();
        assert!(e.contains("not a classic-control task"), "{e}");
    }
}

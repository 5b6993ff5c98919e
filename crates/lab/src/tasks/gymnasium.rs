//! The tasks whose episodes step from a given state under given actions
//! (the classic-control tasks, by their [`super::TaskEntry::stepped`]), by
//! name: what the Python package exposes to compare every step with
//! Gymnasium's own.

use super::{Step, entries, names_with};

/// The episode of the task named `task` from `state` under `actions` (see
/// [`super::Stepped`]); refused for a task that has none.
pub fn episode_of(task: &str, state: &[f64], actions: &[f64]) -> Result<Vec<Step>, String> {
    let stepped = entries()
        .into_iter()
        .find(|t| t.name == task)
        .and_then(|t| t.stepped);
    let run = stepped.ok_or_else(|| {
        format!(
            "task {task:?} is not a classic-control task (one of {})",
            names_with(|t| t.stepped.is_some())
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

    /// Gymnasium 1.4.0's steps with vivae's sin and cos (its module's `sin`
    /// and `cos` replaced by `portable_math`, `env.unwrapped.state` set to
    /// the start, each step's state and reward printed as bits): task, start,
    /// actions, then each step's state and reward.
    #[allow(clippy::type_complexity)]
    const GYMNASIUM: [(&str, &[f64], &[f64], &[(&[u64], u64)]); 4] = [
        (
            "acrobot",
            &[0.05, -0.08, 0.02, 0.07],
            &[2.0, 0.0, 1.0, 2.0],
            &[
                (
                    &[
                        0x3fa0f62f5eefb686,
                        0xbf93baa00ed43f48,
                        0xbfc7728dd2deda3c,
                        0x3fe0c371a8d53d38,
                    ],
                    0xbff0000000000000,
                ),
                (
                    &[
                        0x3f7efb3454395650,
                        0x3faa5249593e0372,
                        0xbfb0b6c3f64dd7dc,
                        0x3fc56673420eacbe,
                    ],
                    0xbff0000000000000,
                ),
                (
                    &[
                        0xbf734ece1f78ed78,
                        0x3fb4232a2631443a,
                        0xbfabbf773e70154c,
                        0x3fb94daee2530da2,
                    ],
                    0xbff0000000000000,
                ),
                (
                    &[
                        0xbf9ad45073a82fa5,
                        0x3fbf832926305e8e,
                        0xbfc3ce760de2bbc6,
                        0x3fd5627e4750f561,
                    ],
                    0xbff0000000000000,
                ),
            ],
        ),
        (
            "mountain-car",
            &[-0.5, 0.0],
            &[2.0, 0.0, 1.0, 2.0],
            &[
                (
                    &[0xbfdff2836de7e655, 0x3f4af92430335600],
                    0xbff0000000000000,
                ),
                (
                    &[0xbfdff868b91c294e, 0xbf37952cd10be2e8],
                    0xbff0000000000000,
                ),
                (
                    &[0xbfe000a124cd648e, 0xbf41b320fd3f9ba0],
                    0xbff0000000000000,
                ),
                (
                    &[0xbfdffc9cdec21461, 0x3f3295ab62d2ed88],
                    0xbff0000000000000,
                ),
            ],
        ),
        (
            "mountain-car-continuous",
            &[-0.5, 0.0],
            &[0.75, -1.5, 0.3, 1.0],
            &[
                (
                    &[0xbfdff07720000000, 0x3f4f11b780000000],
                    0xbfaccccccccccccd,
                ),
                (
                    &[0xbfdffc8540000000, 0xbf481c28c0000000],
                    0xbfcccccccccccccd,
                ),
                (
                    &[0xbfe0021020000000, 0xbf3e6c2800000000],
                    0xbf826e97a5e35400,
                ),
                (
                    &[0xbfdff605a0000000, 0x3f4c352c40000000],
                    0xbfb999999999999a,
                ),
            ],
        ),
        (
            "pendulum",
            &[2.5, -0.4],
            &[1.2, -3.0, 0.6, 2.0],
            &[
                (
                    &[0x4004176f45f83024, 0x3fcd4b17763c2cdc],
                    0xc01911dbca98f1aa,
                ),
                (
                    &[0x40043d67aa78b905, 0x3fd7bb3ed0558c66],
                    0xc019442e0aac5c6a,
                ),
                (
                    &[0x400498b0505ac326, 0x3fec86b3d6a32a36],
                    0xc019a8e18d9ae51c,
                ),
                (
                    &[0x40053bf1cc634c69, 0x3ff9823b6155727f],
                    0xc01ad8e24c47a052,
                ),
            ],
        ),
    ];

    #[test]
    fn steps_are_gymnasiums_to_the_bit() {
        for (task, start, actions, want) in GYMNASIUM {
            let got = episode_of(task, start, actions).unwrap();
            assert_eq!(got.len(), want.len(), "{task}");
            for (n, (step, (state, reward))) in got.iter().zip(want).enumerate() {
                let bits: Vec<u64> = step.state.iter().map(|v| v.to_bits()).collect();
                assert_eq!(bits, *state, "{task} step {n}");
                assert_eq!(step.reward.to_bits(), *reward, "{task} step {n}");
                assert!(!step.terminated && !step.truncated, "{task} step {n}");
            }
        }
    }
}

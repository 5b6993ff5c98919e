//! The rollout an episode steps, against the same step by hand in either
//! precision: a test of `rollout` that needs an [`Episode`], which that
//! module does not import.

use vivae_neat::{Population, Precision};

use super::Episode;
use crate::config::Config;
use crate::controller::sensors::{read_sheets, read_sheets_single};
use crate::tasks::driving::rollout::Drive;
use crate::tasks::scenarios::load_scenario;

/// A fast controller's rollout reads the sensors in f32 and steps on them
/// as they are; an exact one reads and steps in f64. (Where the two reads
/// differ — a sensor within an f32 rounding of a cell border — the fast
/// pinned hash tells them apart.)
#[test]
fn fast_rollout_steps_on_the_single_precision_read() {
    let scenario = load_scenario(None).unwrap().scenario;
    for precision in [Precision::Exact, Precision::Fast] {
        let mut config = Config::default();
        config.experiment.precision = precision;
        let exp = Episode::new(&config, &scenario).unwrap();
        let pop = Population::new(config.neat.clone(), exp.cppn_spec(), 5).unwrap();
        let c = exp.controller(&pop.genomes()[0]).unwrap();
        assert_eq!(c.single_inputs(), precision == Precision::Fast);
        let mut world = exp.world().clone();
        let mut rollout = exp.rollout(&c);
        // The same step by hand.
        let robots = exp.robots();
        let ni = Drive::num_inputs(&c);
        let mut states = c.batch_state(robots);
        let mut wide = vec![0.0; robots * ni];
        let mut single = vec![0.0f32; robots * ni];
        let mut outputs = vec![0.0; robots * Drive::num_outputs(&c)];
        for step in 0..60 {
            let by_hand = &world;
            for r in 0..robots {
                let w = &mut wide[r * ni..][..ni];
                read_sheets(exp.sensors(), by_hand, r, w);
                let s = &mut single[r * ni..][..ni];
                read_sheets_single(exp.sensors(), by_hand, r, s, &mut [0.0; 0]);
            }
            match precision {
                Precision::Fast => c.activate_batch_single(&mut states, &single, &mut outputs),
                Precision::Exact => c.activate_batch(&mut states, &wide, &mut outputs),
            }
            rollout.step(&mut world, &c, None);
            for r in 0..robots {
                let want: Vec<u64> = outputs[r * c.num_neurons()..][..c.num_neurons()]
                    .iter()
                    .map(|v| v.to_bits())
                    .collect();
                let got: Vec<u64> = rollout.outputs(r).iter().map(|v| v.to_bits()).collect();
                assert_eq!(got, want, "{precision:?} robot {r} step {step}");
            }
        }
    }
}

//! One episode of the predator–prey task stepped from outside, a step per
//! call: what [`Arena::play`] does in its loop, for callers that cannot hand
//! it closures (Python's PettingZoo environment steps it once per `step`).
//! The test below holds it to `play`'s outcome bit for bit.

use vivae_sim::World;

use crate::tasks::predator_prey::{Arena, Outcome};
use crate::tasks::robot::wheels;

/// An episode under way: the world, the steps played, the distance summed, the catch.
#[derive(Debug, Clone)]
pub struct Meeting {
    world: World,
    controls: [[f64; 2]; 2],
    steps: u32,
    sum: f64,
    caught: bool,
}

impl Meeting {
    /// The world now.
    pub fn world(&self) -> &World {
        &self.world
    }

    /// Steps played.
    pub fn steps(&self) -> u32 {
        self.steps
    }

    /// Whether the hunter has caught the prey.
    pub fn caught(&self) -> bool {
        self.caught
    }
}

impl Arena {
    /// A new episode at the scenario's start.
    pub fn start(&self) -> Meeting {
        Meeting {
            world: self.world.clone(),
            controls: [[0.0; 2]; 2],
            steps: 0,
            sum: 0.0,
            caught: false,
        }
    }

    /// Whether the episode is over: the catch, or all its steps played.
    pub fn over(&self, m: &Meeting) -> bool {
        m.caught || m.steps >= self.steps
    }

    /// One step: each side's outputs (turn, forward, as its network gives
    /// them) drive its robot. A step after the end does nothing.
    pub fn advance(&self, m: &mut Meeting, hunter: [f64; 2], prey: [f64; 2]) {
        if self.over(m) {
            return;
        }
        m.controls[self.hunter] = wheels(hunter[0], hunter[1]);
        m.controls[self.prey] = wheels(prey[0], prey[1]);
        m.world.step(&m.controls);
        m.steps += 1;
        m.caught = self.caught(&m.world);
        m.sum += self.gap(&m.world);
    }

    /// The hunter–prey centre distance in `world`, px.
    fn gap(&self, world: &World) -> f64 {
        let r = world.robots();
        r[self.hunter].pos.distance(r[self.prey].pos)
    }

    /// The hunter–prey centre distance now, as a share of the arena's diagonal.
    pub fn distance(&self, m: &Meeting) -> f64 {
        self.gap(&m.world) / self.diagonal
    }

    /// The outcome so far (the episode's, once [`Arena::over`]).
    pub fn outcome(&self, m: &Meeting) -> Outcome {
        Outcome {
            caught: m.caught,
            steps: m.steps,
            max_steps: self.steps,
            mean_distance: if m.steps == 0 {
                0.0
            } else {
                m.sum / f64::from(m.steps) / self.diagonal
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tasks::predator_prey::{INPUTS, OUTPUTS, STEPS, Side};
    use vivae_neat::{Network, Population, RecurrentNetwork};

    use crate::tasks::predator_prey::shipped_arena as arena;

    /// Steps `hunter` and `prey` through a meeting as a caller from outside would.
    fn stepped(a: &Arena, h: &vivae_neat::Genome, p: &vivae_neat::Genome) -> (Outcome, World) {
        let mut hn = RecurrentNetwork::from_genome(h);
        let mut pn = RecurrentNetwork::from_genome(p);
        let mut m = a.start();
        let (mut hi, mut pi) = ([0.0; INPUTS], [0.0; INPUTS]);
        let (mut ho, mut po) = ([0.0; OUTPUTS], [0.0; OUTPUTS]);
        while !a.over(&m) {
            a.inputs(m.world(), Side::Hunter, &mut hi);
            a.inputs(m.world(), Side::Prey, &mut pi);
            hn.activate(&hi, &mut ho);
            pn.activate(&pi, &mut po);
            a.advance(&mut m, ho, po);
        }
        (a.outcome(&m), m.world)
    }

    #[test]
    fn a_stepped_meeting_ends_as_play_does_bit_for_bit() {
        let spec = Arena::spec();
        let params = vivae_neat::NeatParams {
            population_size: 30,
            ..vivae_neat::NeatParams::plain_neat()
        };
        let mut pop = Population::new(params, spec, 7).unwrap();
        // Genomes of a few generations (bred on a made-up fitness), so that
        // some have hidden nodes and recurrent links.
        for _ in 0..4 {
            let n = pop.genomes().len();
            pop.set_fitnesses((0..n).map(|i| (i % 7) as f64).collect())
                .unwrap();
            pop.next_generation();
        }
        let g = pop.genomes();
        let mut catches = 0;
        for name in ["predator-prey", "predator-prey-obstacles"] {
            let a = arena(name);
            for k in 0..12 {
                let (h, p) = (&g[k], &g[(k * 5 + 3) % g.len()]);
                let mut last = None;
                let want = a.play_genomes(h, p);
                let mut hn = RecurrentNetwork::from_genome(h);
                let mut pn = RecurrentNetwork::from_genome(p);
                a.play(
                    |i, o| hn.activate(i, o),
                    |i, o| pn.activate(i, o),
                    |w| last = Some(w.robots().to_vec()),
                );
                let (got, world) = stepped(&a, h, p);
                assert_eq!(got, want, "{name} pair {k}");
                assert_eq!(Some(world.robots().to_vec()), last, "{name} pair {k}");
                catches += usize::from(got.caught);
            }
        }
        // A scripted chase catches a standing prey: the catch path is covered too.
        let a = arena("predator-prey");
        let mut m = a.start();
        let mut i = [0.0; INPUTS];
        while !a.over(&m) {
            a.inputs(m.world(), Side::Hunter, &mut i);
            let turn = if i[1] > 0.0 {
                0.5
            } else if i[2] > 0.0 {
                1.0
            } else {
                0.0
            };
            let forward = if i[1] > 0.0 { 1.0 } else { 0.3 };
            a.advance(&mut m, [turn, forward], [0.5, 0.5]);
        }
        let out = a.outcome(&m);
        assert!(
            out.caught && out.steps < STEPS,
            "{out:?} ({catches} catches by genomes)"
        );
        // Steps after the end change nothing.
        let before = m.world.robots().to_vec();
        a.advance(&mut m, [1.0, 1.0], [1.0, 1.0]);
        assert_eq!((a.outcome(&m), m.world.robots().to_vec()), (out, before));
    }
}

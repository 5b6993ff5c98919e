//! A contact cost: any fitness minus `cost` per contact begun per 1,000
//! robot-steps (robot–robot, robot–scripted robot, robot–obstacle), so that
//! avoiding pays even when a contact costs a robot little speed.
//! `fitness.contact_cost`.

use std::sync::Arc;

use vivae_sim::World;

use crate::tasks::driving::contacts::ContactCounter;
use crate::tasks::driving::fitness::{Fitness, FitnessMeter};

/// `inner`'s score minus `cost` × contacts per 1,000 robot-steps.
#[derive(Debug, Clone)]
pub struct ContactCost {
    /// The score before the cost.
    pub inner: Arc<dyn Fitness>,
    /// Cost per contact per 1,000 robot-steps.
    pub cost: f64,
    name: String,
}

impl ContactCost {
    /// `inner` with a cost of `cost` per contact per 1,000 robot-steps.
    pub fn new(inner: Arc<dyn Fitness>, cost: f64) -> ContactCost {
        let name = format!("{}-contacts", inner.name());
        ContactCost { inner, cost, name }
    }
}

struct Meter {
    inner: Box<dyn FitnessMeter>,
    observe_inner: bool,
    contacts: ContactCounter,
    cost: f64,
}

impl FitnessMeter for Meter {
    fn observe(&mut self, world: &World) {
        if self.observe_inner {
            self.inner.observe(world);
        }
        self.contacts.observe(world);
    }

    fn score(&self, world: &World, robot_steps: f64) -> f64 {
        let per_1000 = 1000.0 * self.contacts.counts().collisions() as f64 / robot_steps;
        self.inner.score(world, robot_steps) - self.cost * per_1000
    }
}

impl Fitness for ContactCost {
    fn name(&self) -> &str {
        &self.name
    }

    fn meter(&self, world: &World) -> Box<dyn FitnessMeter> {
        Box::new(Meter {
            inner: self.inner.meter(world),
            observe_inner: self.inner.observes_steps(),
            contacts: ContactCounter::new(world),
            cost: self.cost,
        })
    }
}

/// The fitness `config` names: the registry of the driving task's fitnesses.
pub fn of_config(config: &crate::tasks::driving::section::FitnessConfig) -> Arc<dyn Fitness> {
    use crate::tasks::driving::fitness::AverageSpeed;
    use crate::tasks::driving::fitness_progress::Progress;
    use crate::tasks::driving::section::FitnessKind;
    let base: Arc<dyn Fitness> = match config.kind {
        FitnessKind::AverageSpeed => Arc::new(AverageSpeed),
        FitnessKind::Progress => Arc::new(Progress),
    };
    if config.contact_cost > 0.0 {
        Arc::new(ContactCost::new(base, config.contact_cost))
    } else {
        base
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tasks::driving::fitness::AverageSpeed;
    use vivae_sim::{LoadOptions, PhysicsParams, Scenario};

    #[test]
    fn each_contact_costs_its_price_and_nothing_else_changes() {
        let s = crate::tasks::scenarios::find("traffic").unwrap();
        let sc = Scenario::from_svg(s.svg, "traffic", &LoadOptions::default()).unwrap();
        let start = World::new(&sc, &PhysicsParams::default()).unwrap();
        let costly = ContactCost::new(Arc::new(AverageSpeed), 0.5);
        let (mut plain, mut priced) = (AverageSpeed.meter(&start), costly.meter(&start));
        let mut counter = ContactCounter::new(&start);
        let mut w = start.clone();
        let steps = 400;
        for _ in 0..steps {
            // Full throttle, turning: the robots meet blocks, crates and each other.
            w.step(&vec![[1.0, 0.6]; w.robots().len()]);
            plain.observe(&w);
            priced.observe(&w);
            counter.observe(&w);
        }
        let rs = (w.robots().len() * steps) as f64;
        let contacts = counter.counts().collisions();
        assert!(contacts > 0, "no contact to price");
        let want = plain.score(&w, rs) - 0.5 * 1000.0 * contacts as f64 / rs;
        assert_eq!(priced.score(&w, rs), want);
    }
}

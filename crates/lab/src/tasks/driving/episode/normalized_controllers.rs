//! How an episode scales and cuts its controller's links
//! (`substrate.normalize_by`, `normalize_self_loops`, `recurrence`): tests
//! of `controller::normalize` that need an [`Episode`], which that module
//! does not import.

use vivae_neat::Population;

use super::Episode;
use crate::config::{Config, NormalizeBy, Recurrence, SubstrateConfig};
use crate::controller::normalize::SourceScale;
use crate::controller::substrate::PolarGrid;
use crate::tasks::scenarios::load_scenario;

fn experiment(neurons: usize, by: NormalizeBy, self_loops: bool) -> Episode {
    let mut c = Config::default();
    c.substrate.neurons = PolarGrid::new(neurons, neurons).unwrap();
    c.substrate.normalize_by = by;
    c.substrate.normalize_self_loops = self_loops;
    Episode::new(&c, &load_scenario(None).unwrap().scenario).unwrap()
}

fn scale_of(e: &Episode, c: &SubstrateConfig) -> SourceScale {
    SourceScale::new(c, e.sensors(), &e.substrate_spec().neuron_nodes())
}

#[test]
fn count_is_one_at_the_papers_resolution_and_area_follows_the_radius() {
    let e = experiment(3, NormalizeBy::Count, true);
    let mut c = Config::default().substrate;
    assert!(scale_of(&e, &c).factors().iter().all(|&f| f == 1.0));
    c.normalize_by = NormalizeBy::Area;
    let area = scale_of(&e, &c);
    // 15 sensors on 3 rings (ρ = 1/3, 2/3, 1), then 9 neurons on 3 rings.
    let (sensors, neurons) = area.factors().split_at(15);
    for (f, ring) in sensors.iter().zip((0..3).flat_map(|r| [r; 5])) {
        let want = 15.0 * (ring + 1) as f64 / 3.0 / 10.0; // Σρ = 5·(1/3 + 2/3 + 1) = 10
        assert!((f - want).abs() < 1e-12, "{f} vs {want}");
    }
    assert!((sensors.iter().sum::<f64>() - 15.0).abs() < 1e-9);
    assert!((neurons.iter().sum::<f64>() - 9.0).abs() < 1e-9);
    c.normalize = false;
    assert!(scale_of(&e, &c).factors().iter().all(|&f| f == 1.0));
}

#[test]
fn unscaled_self_loops_keep_the_cppns_weight() {
    let plain = {
        let mut c = Config::default();
        c.substrate.neurons = PolarGrid::new(9, 9).unwrap();
        c.substrate.normalize = false;
        Episode::new(&c, &load_scenario(None).unwrap().scenario).unwrap()
    };
    let scaled = experiment(9, NormalizeBy::Count, true);
    let kept = experiment(9, NormalizeBy::Count, false);
    let pop = Population::new(Config::default().neat, plain.cppn_spec(), 3).unwrap();
    let g = &pop.genomes()[1];
    let (p, s, k) = (
        plain.controller(g).unwrap(),
        scaled.controller(g).unwrap(),
        kept.controller(g).unwrap(),
    );
    let f = 9.0 / 81.0;
    let mut checked = 0;
    for i in 0..81 {
        for j in 0..81 {
            let w = p.recurrent_weight(j, i);
            if w == 0.0 {
                continue;
            }
            checked += 1;
            assert_eq!(s.recurrent_weight(j, i), w * f);
            if i == j {
                assert!((k.recurrent_weight(j, i) - w).abs() <= 1e-15 * w.abs());
            } else {
                assert_eq!(k.recurrent_weight(j, i), w * f);
            }
        }
    }
    assert!(checked > 0, "the genome expresses recurrent links");
}

#[test]
fn recurrence_self_cuts_lateral_links_and_none_cuts_all() {
    let base = experiment(3, NormalizeBy::Count, true);
    let pop = Population::new(Config::default().neat, base.cppn_spec(), 5).unwrap();
    let g = &pop.genomes()[2];
    let full = base.controller(g).unwrap();
    for (recurrence, keep_self) in [(Recurrence::SelfLoops, true), (Recurrence::None, false)] {
        let mut c = Config::default();
        c.substrate.recurrence = recurrence;
        let cut = Episode::new(&c, &load_scenario(None).unwrap().scenario)
            .unwrap()
            .controller(g)
            .unwrap();
        for i in 0..9 {
            for j in 0..9 {
                let want = if i == j && keep_self {
                    full.recurrent_weight(j, i)
                } else {
                    0.0
                };
                assert_eq!(cut.recurrent_weight(j, i), want, "{recurrence:?} {j}->{i}");
            }
            for input in 0..15 {
                assert_eq!(cut.input_weight(input, i), full.input_weight(input, i));
            }
        }
    }
    assert!(
        (0..9).any(|i| (0..9).any(|j| i != j && full.recurrent_weight(j, i) != 0.0)),
        "the genome expresses lateral links"
    );
}

//! The shipped mazes load with the paper's start and goal, and hand-written
//! controllers reach the goal or not as the maze's geometry says.

use std::f64::consts::FRAC_PI_2;

use vivae_lab::tasks::maze::{FITNESS_BIAS, HARD_MAZE_SVG, Maze, MazeTask, STEPS, wheels};
use vivae_sim::{DVec2, LoadOptions, Scenario};

#[test]
fn shipped_mazes_load_with_start_and_goal_where_the_paper_puts_them() {
    // (maze, arena, start, goal) from Lehman's maze files (medium_maze.txt, hard_maze.txt).
    let cases = [
        (Maze::Medium, (300.0, 140.0), (30.0, 22.0), (270.0, 100.0)),
        (Maze::Hard, (205.0, 205.0), (36.0, 184.0), (31.0, 20.0)),
    ];
    for (maze, (w, h), start, goal) in cases {
        let sc = maze.scenario().unwrap();
        assert!(sc.warnings.is_empty(), "{:?}", sc.warnings);
        assert_eq!((sc.width(), sc.height()), (w, h));
        assert_eq!(
            sc.fixed_obstacles.len(),
            11,
            "4 boundary walls + 7 inner walls"
        );
        assert_eq!(sc.robots.len(), 1);
        let r = &sc.robots[0];
        assert!((r.pos - DVec2::from(start)).length() < 1e-9, "{:?}", r.pos);
        // Heading 0 in Lehman's files is +x: a quarter turn clockwise from up.
        assert!((r.heading - FRAC_PI_2).abs() < 1e-6, "{}", r.heading);
        let task = MazeTask::new(&sc).unwrap();
        assert!((task.goal() - DVec2::from(goal)).length() < 1e-9);
        assert!(
            (task.goal_radius() - 5.0).abs() < 1e-6,
            "the paper's 5 units"
        );
    }
}

/// Steers toward the goal slice of the radar and ignores the walls: the
/// greedy controller a deceptive maze is built to trap.
fn greedy(inputs: &[f64], out: &mut [f64]) {
    // Slices: left, ahead, right, behind; behind turns right like right does.
    let (left, ahead) = (inputs[6], inputs[7]);
    let (turn, forward) = if ahead == 1.0 {
        (0.5, 1.0)
    } else if left == 1.0 {
        (0.0, 0.0)
    } else {
        (1.0, 0.0)
    };
    out.copy_from_slice(&[turn, forward]);
}

/// The hard maze with only its boundary walls (wall-1 .. wall-4) left.
fn open_hard_maze() -> MazeTask {
    let inner = |line: &str| (5..=11).any(|k| line.contains(&format!("id=\"wall-{k}\"")));
    let mut kept = Vec::new();
    let mut skip = false;
    for line in HARD_MAZE_SVG.lines() {
        skip = skip || inner(line);
        if !skip {
            kept.push(line);
        }
        skip = skip && !line.trim_end().ends_with("/>");
    }
    let svg = kept.join("\n");
    let sc = Scenario::from_svg(&svg, "open.svg", &LoadOptions::default()).unwrap();
    assert_eq!(sc.fixed_obstacles.len(), 4);
    MazeTask::new(&sc).unwrap()
}

#[test]
fn greedy_goal_seeking_solves_the_open_maze_but_not_the_hard_one() {
    let open = open_hard_maze().run(greedy);
    assert!(open.solved, "{open:?}");
    assert!(open.steps < STEPS && open.distance <= 5.0);
    assert!(open.fitness() >= FITNESS_BIAS - 5.0);
    let hard = MazeTask::shipped(Maze::Hard).unwrap();
    let trapped = hard.run(greedy);
    assert!(!trapped.solved, "{trapped:?}");
    assert_eq!(trapped.steps, STEPS);
    // Deception: the greedy robot ends closer to the goal than it started.
    assert!(
        trapped.distance < hard.start().distance(hard.goal()),
        "{trapped:?}"
    );
}

#[test]
fn a_robot_driving_straight_on_slides_along_slanted_walls_and_stops_at_straight_ones() {
    let task = MazeTask::shipped(Maze::Hard).unwrap();
    let out = task.run(|_, o| o.copy_from_slice(&[0.5, 1.0]));
    // Eastward from (36, 184) the slanted wall (77, 200)–(108, 164) deflects
    // it north (our contacts slide; Lehman's robot would stop dead there),
    // then the east boundary x = 200 stops it: its rim 8 px and half the
    // 1 px stroke short, below the wall (87, 91)–(200, 146).
    assert!((out.end.x - (200.0 - 8.5)).abs() < 1e-6, "{out:?}");
    assert!(
        out.end.y < 184.0 - 8.0 && out.end.y > 146.0 + 8.0,
        "{out:?}"
    );
    assert!(!out.solved && out.steps == STEPS);
    assert_eq!(wheels(0.5, 1.0), [1.0, 1.0]);
}

#[test]
fn novelty_search_on_the_maze_gives_the_same_bits_twice() {
    use vivae_neat::driver::{Evolution, NoCheckpoints, ParallelEvaluator, StopCriteria};
    use vivae_neat::strategies::NoveltyParams;
    use vivae_neat::{NeatParams, NoveltySearch, Population};
    let run = || {
        let params = NeatParams {
            population_size: 20,
            ..NeatParams::plain_neat()
        };
        let pop = Population::new(params, MazeTask::spec(), 5).unwrap();
        let novelty = NoveltyParams {
            threshold: 6.0,
            ..NoveltyParams::default()
        };
        let ns = NoveltySearch::new(pop, novelty).unwrap();
        let task = MazeTask::shipped(Maze::Medium).unwrap();
        let mut evolution = Evolution::new(ns, ParallelEvaluator::new(task));
        let stop = StopCriteria::generations(3);
        evolution.run(&stop, &mut (), &mut NoCheckpoints).unwrap();
        serde_json::to_string(evolution.strategy()).unwrap()
    };
    let first = run();
    assert!(first.contains("archive"));
    assert_eq!(first, run());
}

//! The mazes as Lehman's robot sees them: wall segments, a start with a
//! heading and a goal, read from Lehman's maze files or from a scenario.
//!
//! Lehman's files (`scenarios/medium-maze.txt`, `scenarios/hard-maze.txt`,
//! verbatim from github.com/jal278/novelty-search-cpp at 9f53ede, the code
//! of Lehman & Stanley 2011) hold: the number of segments; the start x y;
//! the heading in degrees (0 = +x, growing clockwise on screen since y
//! points down); the goal x y; then one segment `x1 y1 x2 y2` per line. The
//! shipped SVGs of the same names re-draw these mazes for our robot on a
//! 5…200 frame (the hard maze's outer frame differs by up to 44 units).

use vivae_sim::{DVec2, Scenario};

use super::config::MazeWalls;
use super::{Maze, MazeError};

/// Lehman's medium maze file.
pub const MEDIUM_MAZE_TXT: &str = include_str!("../../../../../scenarios/medium-maze.txt");
/// Lehman's hard maze file.
pub const HARD_MAZE_TXT: &str = include_str!("../../../../../scenarios/hard-maze.txt");
/// Within this distance of the goal a maze is solved (Lehman's `dist < 5.0`).
pub const GOAL_RADIUS: f64 = 5.0;

/// A wall: the segment from `a` to `b`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    /// One end.
    pub a: DVec2,
    /// The other end.
    pub b: DVec2,
}

impl Segment {
    /// The distance from `p` to the segment (Lehman's `Line::distance`:
    /// beyond either end, the distance to the nearer end).
    pub fn distance(&self, p: DVec2) -> f64 {
        let ab = self.b - self.a;
        let len2 = ab.length_squared();
        if len2 == 0.0 {
            return self.a.distance(p);
        }
        let u = (p - self.a).dot(ab) / len2;
        if !(0.0..=1.0).contains(&u) {
            return self.a.distance(p).min(self.b.distance(p));
        }
        (self.a + ab * u).distance(p)
    }

    /// Where the segment `from → to` crosses this one strictly inside both
    /// (Lehman's `Line::intersection`: parallel segments never cross).
    pub fn crossing(&self, from: DVec2, to: DVec2) -> Option<DVec2> {
        let (a, b, c, d) = (self.a, self.b, from, to);
        let bot = (b.x - a.x) * (d.y - c.y) - (b.y - a.y) * (d.x - c.x);
        if bot == 0.0 {
            return None;
        }
        let r = ((a.y - c.y) * (d.x - c.x) - (a.x - c.x) * (d.y - c.y)) / bot;
        let s = ((a.y - c.y) * (b.x - a.x) - (a.x - c.x) * (b.y - a.y)) / bot;
        (r > 0.0 && r < 1.0 && s > 0.0 && s < 1.0).then(|| a + (b - a) * r)
    }
}

/// A maze for Lehman's robot.
#[derive(Debug, Clone, PartialEq)]
pub struct LehmanMaze {
    /// Where the maze came from (a file, or `hard-maze.txt (shipped)`).
    pub source: String,
    /// The walls.
    pub walls: Vec<Segment>,
    /// The robot's start.
    pub start: DVec2,
    /// Its heading there, degrees (0 = +x, clockwise on screen).
    pub heading: f64,
    /// The goal.
    pub goal: DVec2,
    /// Within this distance of the goal the maze is solved.
    pub goal_radius: f64,
}

impl LehmanMaze {
    /// Parses Lehman's maze file format (see the module's doc); the error
    /// names `source` and what is wrong.
    pub fn parse(text: &str, source: &str) -> Result<LehmanMaze, MazeError> {
        let bad = |why: String| MazeError::File {
            source_name: source.to_string(),
            why,
        };
        let mut numbers = text.split_whitespace().map(|w| {
            w.parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| bad(format!("{w:?} is not a number")))
        });
        let mut next = |what: &str| {
            numbers
                .next()
                .unwrap_or_else(|| Err(bad(format!("ends before {what}"))))
        };
        let count = next("the number of walls")?;
        if count.fract() != 0.0 || !(1.0..=10_000.0).contains(&count) {
            return Err(bad(format!("{count} walls: expected 1 to 10000")));
        }
        let start = DVec2::new(next("the start")?, next("the start")?);
        let heading = next("the heading")?;
        let goal = DVec2::new(next("the goal")?, next("the goal")?);
        let mut walls = Vec::with_capacity(count as usize);
        for k in 1..=count as usize {
            let what = format!("wall {k}");
            let a = DVec2::new(next(&what)?, next(&what)?);
            let b = DVec2::new(next(&what)?, next(&what)?);
            walls.push(Segment { a, b });
        }
        Ok(LehmanMaze {
            source: source.to_string(),
            walls,
            start,
            heading,
            goal,
            goal_radius: GOAL_RADIUS,
        })
    }

    /// Lehman's file of a shipped maze.
    pub fn shipped(maze: Maze) -> LehmanMaze {
        let (text, name) = match maze {
            Maze::Medium => (MEDIUM_MAZE_TXT, "medium-maze.txt (shipped)"),
            Maze::Hard => (HARD_MAZE_TXT, "hard-maze.txt (shipped)"),
        };
        LehmanMaze::parse(text, name).expect("the shipped maze files parse")
    }

    /// The maze a scenario draws: every edge of its fixed obstacles' outlines
    /// is a wall, its one robot the start, its `goal` mark the goal.
    pub fn from_scenario(scenario: &Scenario) -> Result<LehmanMaze, MazeError> {
        let goal = super::maze_goal(scenario)?;
        let mut walls = Vec::new();
        for ring in scenario.fixed_obstacles.iter().flat_map(|o| &o.shape.rings) {
            for (k, &a) in ring.iter().enumerate() {
                let b = ring[(k + 1) % ring.len()];
                if a != b {
                    walls.push(Segment { a, b });
                }
            }
        }
        let robot = &scenario.robots[0];
        Ok(LehmanMaze {
            source: scenario.source.clone(),
            walls,
            start: robot.pos,
            // Ours: radians clockwise from up; Lehman's: degrees clockwise from +x.
            heading: (robot.heading - std::f64::consts::FRAC_PI_2).to_degrees(),
            goal: goal.pos,
            goal_radius: goal.size.x.max(goal.size.y) / 2.0,
        })
    }

    /// The maze of a run's map: Lehman's file when the map is a shipped
    /// maze's SVG (its text, byte for byte) and `walls` asks for his,
    /// else the scenario's own walls.
    pub fn of_map(
        scenario: &Scenario,
        svg: &str,
        walls: MazeWalls,
    ) -> Result<LehmanMaze, MazeError> {
        let shipped = [Maze::Medium, Maze::Hard]
            .into_iter()
            .find(|m| m.svg() == svg);
        match (shipped, walls) {
            (Some(maze), MazeWalls::Lehman) => Ok(LehmanMaze::shipped(maze)),
            _ => LehmanMaze::from_scenario(scenario),
        }
    }

    /// The box `([0, 0], [max x, max y])` of the walls: every end position lies in it.
    pub fn bounds(&self) -> (Vec<f64>, Vec<f64>) {
        let ends = self.walls.iter().flat_map(|w| [w.a, w.b]);
        let max = ends.fold(DVec2::ZERO, DVec2::max);
        (vec![0.0, 0.0], vec![max.x, max.y])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lehmans_files_give_the_papers_starts_goals_and_walls() {
        let hard = LehmanMaze::shipped(Maze::Hard);
        assert_eq!(hard.walls.len(), 13);
        assert_eq!((hard.start, hard.heading), (DVec2::new(36.0, 184.0), 0.0));
        assert_eq!(hard.goal, DVec2::new(31.0, 20.0));
        // The outer frame is no rectangle: (41, 5) → (3, 8) → (4, 49) → …
        let first = hard.walls[0];
        assert_eq!(
            (first.a, first.b),
            (DVec2::new(41.0, 5.0), DVec2::new(3.0, 8.0))
        );
        let medium = LehmanMaze::shipped(Maze::Medium);
        assert_eq!(medium.walls.len(), 11);
        assert_eq!(medium.start, DVec2::new(30.0, 22.0));
        assert_eq!(medium.goal, DVec2::new(270.0, 100.0));
        assert_eq!(medium.bounds().1, vec![293.0, 134.0]);
    }

    #[test]
    fn a_bad_maze_file_is_named_with_what_is_wrong() {
        let e = LehmanMaze::parse("2\n1 2\n0\n3 4\n0 0 1 1\n", "m.txt").unwrap_err();
        assert!(
            e.to_string().contains("m.txt") && e.to_string().contains("wall 2"),
            "{e}"
        );
        let e = LehmanMaze::parse("1 x", "m.txt").unwrap_err().to_string();
        assert!(e.contains("\"x\" is not a number"), "{e}");
        let e = LehmanMaze::parse("-3", "m.txt").unwrap_err().to_string();
        assert!(e.contains("expected 1 to 10000"), "{e}");
    }

    #[test]
    fn segment_distance_and_crossing_follow_lehmans_lines() {
        let s = Segment {
            a: DVec2::new(0.0, 0.0),
            b: DVec2::new(10.0, 0.0),
        };
        assert_eq!(s.distance(DVec2::new(5.0, 3.0)), 3.0);
        assert_eq!(s.distance(DVec2::new(13.0, 4.0)), 5.0, "beyond an end");
        let hit = s.crossing(DVec2::new(5.0, -2.0), DVec2::new(5.0, 2.0));
        assert_eq!(hit, Some(DVec2::new(5.0, 0.0)));
        assert_eq!(
            s.crossing(DVec2::new(5.0, 0.0), DVec2::new(5.0, 2.0)),
            None,
            "touching an end"
        );
        assert_eq!(
            s.crossing(DVec2::new(0.0, 1.0), DVec2::new(9.0, 1.0)),
            None,
            "parallel"
        );
    }

    #[test]
    fn the_shipped_svg_gives_its_own_walls_on_request() {
        let sc = Maze::Hard.scenario().unwrap();
        let own = LehmanMaze::of_map(&sc, Maze::Hard.svg(), MazeWalls::Scenario).unwrap();
        assert!(own.walls.len() >= 11 * 3, "each stroked wall is an outline");
        assert!((own.start - DVec2::new(36.0, 184.0)).length() < 1e-9);
        assert!(own.heading.abs() < 1e-9, "{}", own.heading);
        assert!((own.goal_radius - GOAL_RADIUS).abs() < 1e-9);
        let lehman = LehmanMaze::of_map(&sc, Maze::Hard.svg(), MazeWalls::Lehman).unwrap();
        assert_eq!(lehman, LehmanMaze::shipped(Maze::Hard));
    }
}

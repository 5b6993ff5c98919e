//! Robots carry a team (`data-team`); robots of different teams touching is
//! reported as a contact, robots of one team or of none are not.

use vivae_sim::{LoadOptions, PhysicsParams, Scenario, ScenarioError, TeamContact, World};

fn arena(robots: &str) -> String {
    format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg"
            xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape"
            width="300" height="200" data-background="road">{robots}</svg>"#
    )
}

/// A robot at `x`, y = 100, facing right, of `team` (none when empty).
fn robot(id: &str, x: f64, team: &str, face: f64) -> String {
    let team = if team.is_empty() {
        String::new()
    } else {
        format!(r#" data-team="{team}""#)
    };
    format!(
        r#"<rect id="{id}" inkscape:label="Robot"{team} x="{}" y="94" width="12" height="12" transform="rotate({face} {x} 100)"/>"#,
        x - 6.0
    )
}

fn load(svg: &str) -> Result<Scenario, ScenarioError> {
    Scenario::from_svg(svg, "t.svg", &LoadOptions::default())
}

/// Drives robots 0 and 1 towards each other until they meet; the contacts
/// of each step.
fn meet(a: &str, b: &str) -> Vec<Vec<TeamContact>> {
    let svg = arena(&(robot("a", 100.0, a, 90.0) + &robot("b", 200.0, b, 270.0)));
    let mut world = World::new(&load(&svg).unwrap(), &PhysicsParams::default()).unwrap();
    (0..60)
        .map(|_| {
            world.step(&[[1.0, 1.0], [1.0, 1.0]]);
            world.team_contacts().to_vec()
        })
        .collect()
}

#[test]
fn robots_of_different_teams_touching_is_a_contact() {
    let steps = meet("hunter", "prey");
    let first = steps.iter().position(|c| !c.is_empty()).expect("they meet");
    assert!(first > 5, "not at the start: {first}");
    assert_eq!(steps[first], [TeamContact { a: 0, b: 1 }]);
    assert!(steps[..first].iter().all(Vec::is_empty));
}

#[test]
fn robots_of_one_team_or_none_touching_is_no_contact() {
    for (a, b) in [("prey", "prey"), ("", ""), ("hunter", "")] {
        assert!(meet(a, b).iter().all(Vec::is_empty), "{a:?} {b:?}");
    }
}

#[test]
fn team_is_read_from_the_robot_or_its_group_and_kept_by_snapshots() {
    let group = r#"<g inkscape:label="Robot" data-team="prey" id="g"><rect x="20" y="20" width="12" height="12"/></g>"#;
    let svg = arena(&(robot("a", 100.0, "hunter", 0.0) + group + &robot("c", 200.0, "", 0.0)));
    let sc = load(&svg).unwrap();
    let teams: Vec<&str> = sc.robots.iter().map(|r| r.team.as_str()).collect();
    assert_eq!(teams, ["hunter", "prey", ""]);
    let world = World::new(&sc, &PhysicsParams::default()).unwrap();
    assert!(world.opponents(0, 1) && !world.opponents(0, 2) && !world.opponents(1, 1));
    let again = load(&world.to_svg()).unwrap();
    let teams: Vec<&str> = again.robots.iter().map(|r| r.team.as_str()).collect();
    assert_eq!(teams, ["hunter", "prey", ""]);
    let json = serde_json::to_string(&sc.summary()).unwrap();
    assert!(json.contains(r#""team":"hunter""#), "{json}");
}

#[test]
fn a_bad_team_name_is_refused_naming_the_element() {
    let svg = arena(&robot("a", 100.0, "two words", 0.0));
    let err = load(&svg).unwrap_err().to_string();
    assert!(err.contains("'a'") && err.contains("data-team"), "{err}");
}

//! Bad scenario files give typed errors naming file, element and problem; odd ones warn.

use crate::common::*;
use vivae_sim::{LoadOptions, Scenario, ScenarioError};

fn err(text: &str) -> ScenarioError {
    Scenario::from_svg(text, "bad.svg", &LoadOptions::default()).unwrap_err()
}

#[test]
fn not_xml() {
    let e = err("<svg width='10'");
    assert!(matches!(e, ScenarioError::Xml { .. }), "{e:?}");
    assert!(e.to_string().starts_with("bad.svg: not XML"), "{e}");
}

#[test]
fn not_svg() {
    let e = err("<html><body/></html>");
    assert!(
        matches!(&e, ScenarioError::NotSvg { root, .. } if root == "html"),
        "{e:?}"
    );
}

#[test]
fn not_utf8() {
    let e = Scenario::from_svg_bytes(&[0x3c, 0xff, 0xfe], "bad.svg", &LoadOptions::default())
        .unwrap_err();
    assert!(matches!(e, ScenarioError::NotUtf8 { .. }), "{e:?}");
}

#[test]
fn zero_and_absurd_arena_sizes() {
    let e = err(&svg(0.0, 100.0, ""));
    assert!(matches!(e, ScenarioError::ArenaSize { .. }), "{e:?}");
    let e = err(&svg(1e9, 100.0, ""));
    assert!(matches!(e, ScenarioError::ArenaSize { .. }), "{e:?}");
    assert!(e.to_string().contains("bad.svg"), "{e}");
}

#[test]
fn malformed_path_data_names_the_element() {
    let e = err(&svg(
        100.0,
        100.0,
        r#"<path id="road7" inkscape:label="Road" d="M 10,10 L 20,x Z"/>"#,
    ));
    assert!(
        matches!(&e, ScenarioError::PathData { id, .. } if id == "road7"),
        "{e:?}"
    );
    assert!(
        e.to_string().contains("road7") && e.to_string().contains("bad.svg"),
        "{e}"
    );
}

#[test]
fn robot_outside_the_arena() {
    let e = err(&svg(100.0, 100.0, &robot("r9", 150.0, 50.0, 0.0)));
    assert!(
        matches!(&e, ScenarioError::RobotOutsideArena { id, .. } if id == "r9"),
        "{e:?}"
    );
}

#[test]
fn no_robots_loads_but_require_robots_fails() {
    let sc = load(&svg(
        100.0,
        100.0,
        r#"<rect id="g" inkscape:label="Grass" x="0" y="0" width="100" height="100"/>"#,
    ));
    let e = sc.require_robots().unwrap_err();
    assert!(matches!(e, ScenarioError::NoRobots { .. }), "{e:?}");
    assert!(e.to_string().contains("test.svg"), "{e}");
}

#[test]
fn unknown_label_is_a_warning_naming_id_and_label() {
    let sc = load(&svg(
        100.0,
        100.0,
        &format!(
            r#"<rect id="tree3" inkscape:label="Tree" x="0" y="0" width="10" height="10"/>{}"#,
            robot("r", 50.0, 50.0, 0.0)
        ),
    ));
    assert_eq!(sc.warnings.len(), 1);
    assert!(
        sc.warnings[0].contains("tree3") && sc.warnings[0].contains("Tree"),
        "{:?}",
        sc.warnings
    );
}

#[test]
fn bad_friction_attribute_is_an_error() {
    let e = err(&svg(
        100.0,
        100.0,
        r#"<rect id="s1" inkscape:label="Sand" data-friction="lots" x="0" y="0" width="10" height="10"/>"#,
    ));
    assert!(
        matches!(&e, ScenarioError::Attribute { id, .. } if id == "s1"),
        "{e:?}"
    );
}

#[test]
fn bad_load_options_are_rejected() {
    let e = Scenario::from_svg(
        &svg(10.0, 10.0, ""),
        "x.svg",
        &LoadOptions {
            cell_size: 0.0,
            ..Default::default()
        },
    )
    .unwrap_err();
    assert!(
        matches!(
            e,
            ScenarioError::Options {
                field: "cell_size",
                ..
            }
        ),
        "{e:?}"
    );
}

#[test]
fn obstacle_regions_where_nothing_could_be_placed_are_refused_by_name() {
    let region = |shape: &str| {
        err(&svg(
            100.0,
            100.0,
            &format!(r#"<rect id="zone" inkscape:label="ObstacleRegion" data-count="3" {shape}/>"#),
        ))
    };
    for (shape, says) in [
        (r#"x="10" y="10" width="0" height="50""#, "has no area"),
        (r#"x="10" y="10" width="50" height="0""#, "has no area"),
        (
            r#"x="150" y="10" width="50" height="50""#,
            "outside the 100 x 100 arena",
        ),
        (
            r#"x="10" y="-90" width="50" height="50""#,
            "outside the 100 x 100 arena",
        ),
    ] {
        let e = region(shape);
        assert!(
            matches!(&e, ScenarioError::Region { id, .. } if id == "zone"),
            "{shape}: {e:?}"
        );
        assert!(
            e.to_string().starts_with("bad.svg: obstacle region 'zone'"),
            "{e}"
        );
        assert!(e.to_string().contains(says), "{shape}: {e}");
    }
    // One reaching into the arena is kept.
    let sc = Scenario::from_svg(
        &svg(
            100.0,
            100.0,
            r#"<rect id="zone" inkscape:label="ObstacleRegion" data-count="3" x="-20" y="10" width="50" height="50"/>"#,
        ),
        "ok.svg",
        &LoadOptions::default(),
    )
    .unwrap();
    assert_eq!(sc.obstacle_regions.len(), 1);
}

#[test]
fn a_route_id_used_twice_is_refused_by_name() {
    let route = |id: &str, y: u32| {
        format!(
            r#"<path id="{id}" inkscape:label="Route" d="M 10,{y} L 90,{y}" style="fill:none;stroke:#fff"/>"#
        )
    };
    let e = err(&svg(
        100.0,
        100.0,
        &format!("{}\n{}", route("lane", 20), route("lane", 60)),
    ));
    assert!(
        matches!(&e, ScenarioError::RepeatedRouteId { id, .. } if id.starts_with("lane (<path> on line")),
        "{e:?}"
    );
    assert!(e.to_string().contains("used by another element too"), "{e}");
    // Ids of their own load both.
    let sc = Scenario::from_svg(
        &svg(
            100.0,
            100.0,
            &format!("{}\n{}", route("a", 20), route("b", 60)),
        ),
        "ok.svg",
        &LoadOptions::default(),
    )
    .unwrap();
    assert_eq!(sc.routes.len(), 2);
}

//! Hand-written SVG: elements without an `id`, and ids used twice, load as
//! drawn (the loader joins its two parsers by id, so both once went wrong: a
//! robot sharing a road's id sat on the road's centre, and elements without
//! an id were dropped as having "no usable geometry").

use vivae_sim::Scenario;

const NS: &str = r#"xmlns="http://www.w3.org/2000/svg" xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape""#;

fn load(body: &str) -> Scenario {
    let svg = format!(r#"<svg {NS} width="400" height="300">{body}</svg>"#);
    Scenario::from_svg(&svg, "hand.svg", &Default::default()).expect("loads")
}

#[test]
fn a_robot_with_a_roads_id_stays_where_it_is_drawn() {
    let sc = load(
        r#"<rect id="a" x="0" y="80" width="400" height="40" inkscape:label="Road"/>
           <rect id="a" x="300" y="200" width="10" height="10" inkscape:label="Robot"/>"#,
    );
    assert_eq!(sc.surfaces().len(), 1);
    let r = &sc.robots[0];
    assert_eq!(
        (r.pos.x, r.pos.y),
        (305.0, 205.0),
        "robot moved to {:?}",
        r.pos
    );
    assert!(r.id.starts_with("a (<rect> on line"), "{}", r.id);
    assert!(sc.warnings.is_empty(), "{:?}", sc.warnings);
}

#[test]
fn elements_without_ids_load_with_their_geometry() {
    let sc = load(
        r#"<rect x="0" y="80" width="400" height="40" inkscape:label="Road"/>
           <g inkscape:label="Robot"><rect x="20" y="90" width="10" height="10"/></g>
           <circle cx="200" cy="250" r="10" inkscape:label="Robot"/>"#,
    );
    assert_eq!(sc.surfaces().len(), 1, "{:?}", sc.warnings);
    let pos: Vec<(f64, f64)> = sc.robots.iter().map(|r| (r.pos.x, r.pos.y)).collect();
    assert_eq!(pos, [(25.0, 95.0), (200.0, 250.0)]);
    assert!(sc.warnings.is_empty(), "{:?}", sc.warnings);
}

#[test]
fn errors_name_an_element_without_id_by_its_line() {
    let svg = format!(
        "<svg {NS} width=\"400\" height=\"300\">\n<rect x=\"0\" y=\"0\" width=\"9\" height=\"9\"\n inkscape:label=\"Road\" data-friction=\"-1\"/></svg>"
    );
    let e = Scenario::from_svg(&svg, "hand.svg", &Default::default())
        .unwrap_err()
        .to_string();
    assert!(e.contains("<rect> on line 2"), "{e}");
    assert!(!e.contains('\n'), "{e}");
}

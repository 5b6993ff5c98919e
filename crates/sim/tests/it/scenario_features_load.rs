//! Format features of DESIGN §4: units and viewBox, groups, stroked roads, friction overrides.

use crate::common::*;
use vivae_sim::{DVec2, PhysicsParams, SurfaceKind, World};

#[test]
fn inkscape_1_document_in_mm_loads_at_px_scale() {
    let text = r#"<svg xmlns="http://www.w3.org/2000/svg" xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape"
        width="200mm" height="100mm" viewBox="0 0 200 100">
        <g inkscape:groupmode="layer" inkscape:label="Layer 1" id="layer1">
          <rect id="road" inkscape:label="Road" x="10" y="10" width="20" height="20"/>
          <rect id="bot" inkscape:label="Robot" x="40" y="40" width="4" height="4"/>
        </g></svg>"#;
    let sc = load(text);
    let mm = 96.0 / 25.4;
    assert!((sc.width() - 200.0 * mm).abs() < 0.01, "{}", sc.width());
    assert!((sc.height() - 100.0 * mm).abs() < 0.01);
    assert!(
        (sc.robots[0].pos - DVec2::splat(42.0 * mm)).length() < 0.01,
        "{:?}",
        sc.robots[0].pos
    );
    assert_eq!(
        sc.surface_exact(DVec2::splat(20.0 * mm)).unwrap().0,
        SurfaceKind::Road
    );
    assert_eq!(
        sc.surface_exact(DVec2::splat(35.0 * mm)).unwrap().0,
        SurfaceKind::Grass
    );
}

#[test]
fn robot_heading_comes_from_rotation_and_group_transforms() {
    let body = format!(
        r#"<g id="grp" transform="rotate(90 100 100)">{}</g>{}"#,
        robot("a", 100.0, 60.0, 0.0),
        robot("b", 50.0, 50.0, -45.0)
    );
    let sc = load(&svg(200.0, 200.0, &body));
    assert!((sc.robots[0].heading - std::f64::consts::FRAC_PI_2).abs() < 1e-6);
    assert!(
        (sc.robots[0].pos - DVec2::new(140.0, 100.0)).length() < 1e-3,
        "{:?}",
        sc.robots[0].pos
    );
    assert!((sc.robots[1].heading + std::f64::consts::FRAC_PI_4).abs() < 1e-6);
    let s = sc.summary();
    assert!((s.robots[0].heading_deg - 90.0).abs() < 1e-4);
    assert!((s.robots[1].heading_deg - 315.0).abs() < 1e-4);
}

#[test]
fn stroked_unfilled_path_is_a_road_as_wide_as_its_stroke() {
    let body = r#"<path id="line" inkscape:label="Road" d="M 20,100 L 180,100" style="fill:none;stroke:#000;stroke-width:40"/>"#;
    let sc = load(&svg(200.0, 200.0, body));
    assert_eq!(
        sc.surface_exact(DVec2::new(100.0, 85.0)).unwrap().0,
        SurfaceKind::Road
    );
    assert_eq!(
        sc.surface_exact(DVec2::new(100.0, 115.0)).unwrap().0,
        SurfaceKind::Road
    );
    assert_eq!(
        sc.surface_exact(DVec2::new(100.0, 125.0)).unwrap().0,
        SurfaceKind::Grass
    );
}

#[test]
fn group_labels_apply_to_children_and_later_shapes_cover_earlier() {
    let body = r#"<g id="roads" inkscape:label="road"><rect id="r1" x="0" y="0" width="50" height="50"/><a id="lnk"><rect id="r2" x="50" y="0" width="50" height="50"/></a></g>
        <rect id="s" inkscape:label="Sand" x="25" y="0" width="10" height="50"/>"#;
    let sc = load(&svg(100.0, 100.0, body));
    assert_eq!(sc.surface_count(SurfaceKind::Road), 2);
    assert!(sc.warnings.is_empty(), "{:?}", sc.warnings);
    let w = World::new(&sc, &PhysicsParams::default()).unwrap();
    assert_eq!(
        w.surface_at(DVec2::new(10.0, 10.0)).unwrap().kind,
        SurfaceKind::Road
    );
    assert_eq!(
        w.surface_at(DVec2::new(30.0, 10.0)).unwrap().kind,
        SurfaceKind::Sand
    );
    assert_eq!(
        w.surface_at(DVec2::new(75.0, 10.0)).unwrap().kind,
        SurfaceKind::Road
    );
    assert_eq!(
        w.surface_at(DVec2::new(75.0, 75.0)).unwrap().kind,
        SurfaceKind::Grass
    );
}

#[test]
fn data_friction_overrides_the_table() {
    let body = r#"<rect id="ice" inkscape:label="Road" data-friction="0.5" x="0" y="0" width="50" height="50"/>"#;
    let sc = load(&svg(100.0, 100.0, body));
    let w = World::new(&sc, &PhysicsParams::default()).unwrap();
    let s = w.surface_at(DVec2::new(10.0, 10.0)).unwrap();
    assert_eq!(s.friction, 0.5);
    assert_eq!(s.reading, 1.0, "readings clamp to [0, 1]");
}

#[test]
fn hidden_elements_and_layer_labels_are_ignored_silently() {
    let body = r#"<rect id="h" inkscape:label="Road" style="display:none" x="0" y="0" width="50" height="50"/>"#;
    let sc = load(&svg(100.0, 100.0, body));
    assert_eq!(sc.surfaces().len(), 0);
    assert!(sc.warnings.is_empty());
}

//! Every ViVAE corpus scenario loads with the objects its labels name.
//! Expected counts were written by reading each file's `inkscape:label`s.

use crate::common::{corpus_at, shared_corpus};
use vivae_sim::{LoadOptions, Scenario, SurfaceKind};

/// (file, robots, road, grass, sand, water, fixed, movable, pucks, marks)
/// One row of the table.
type Row = (
    &'static str,
    usize,
    usize,
    usize,
    usize,
    usize,
    usize,
    usize,
    usize,
    usize,
);

const TABLE: &[Row] = &[
    ("arena1.svg", 0, 5, 1, 0, 0, 3, 1, 1, 3),
    ("arena2.svg", 0, 5, 1, 0, 0, 3, 0, 0, 1),
    ("arena3_h.svg", 1, 5, 1, 0, 0, 3, 0, 0, 0),
    ("minimal1.svg", 0, 0, 1, 0, 0, 0, 0, 0, 2),
    ("minimal2.svg", 0, 0, 1, 0, 0, 0, 0, 0, 2),
    ("minimal3.svg", 0, 1, 1, 1, 0, 1, 1, 0, 2),
    ("oval1_h.svg", 1, 1, 1, 0, 0, 4, 0, 0, 0),
    ("oval2_h.svg", 1, 1, 1, 0, 0, 4, 0, 0, 0),
    ("scenar1_01.svg", 0, 0, 1, 0, 0, 0, 0, 0, 2),
    ("scenar2_01.svg", 0, 4, 1, 0, 0, 4, 0, 0, 10),
    ("scenario2.svg", 0, 12, 1, 1, 1, 15, 15, 4, 6),
    ("ushape.svg", 1, 0, 1, 0, 0, 1, 0, 0, 0),
];

#[test]
fn a_missing_corpus_is_skipped_with_a_note_by_default() {
    let missing = std::env::temp_dir().join("vivae-no-such-corpus-dir");
    assert_eq!(corpus_at(&missing, false), None);
}

#[test]
#[should_panic(expected = "VIVAE_REQUIRE_SHARED=1 requires it")]
fn a_missing_corpus_fails_when_required() {
    let missing = std::env::temp_dir().join("vivae-no-such-corpus-dir");
    corpus_at(&missing, true);
}

#[test]
fn every_corpus_file_loads_with_the_labelled_objects() {
    let Some(dir) = shared_corpus() else {
        return;
    };
    let mut files: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".svg"))
        .collect();
    files.sort();
    for name in &files {
        let row = TABLE
            .iter()
            .find(|r| r.0 == name)
            .unwrap_or_else(|| panic!("{name} is not in the table"));
        let text = std::fs::read(dir.join(name)).unwrap();
        let sc = Scenario::from_svg_bytes(&text, name, &LoadOptions::default())
            .unwrap_or_else(|e| panic!("{name} failed to load: {e}"));
        let got = (
            *name == row.0,
            sc.robots.len(),
            sc.surface_count(SurfaceKind::Road),
            sc.surface_count(SurfaceKind::Grass),
            sc.surface_count(SurfaceKind::Sand),
            sc.surface_count(SurfaceKind::Water),
            sc.fixed_obstacles.len(),
            sc.movable_obstacles.len(),
            sc.pucks.len(),
            sc.marks.len(),
        );
        assert_eq!(
            got,
            (
                true, row.1, row.2, row.3, row.4, row.5, row.6, row.7, row.8, row.9
            ),
            "{name}"
        );
        assert!(
            sc.warnings.is_empty(),
            "{name}: unexpected warnings {:?}",
            sc.warnings
        );
        if sc.robots.is_empty() {
            assert!(sc.require_robots().is_err());
        } else {
            sc.require_robots().unwrap();
        }
    }
    assert_eq!(
        files.len(),
        TABLE.len(),
        "corpus has files the table does not list, or lost some"
    );
}

#[test]
fn corpus_geometry_lands_where_the_files_put_it() {
    let Some(dir) = shared_corpus() else {
        return;
    };
    let load = |n: &str| {
        Scenario::from_svg(
            &std::fs::read_to_string(dir.join(n)).unwrap(),
            n,
            &LoadOptions::default(),
        )
        .unwrap()
    };
    // ushape: robot rect x=150..170, y=360..380 inside a layer translated by (-55, 0).
    let u = load("ushape.svg");
    assert_eq!((u.width(), u.height()), (210.0, 390.0));
    assert!((u.robots[0].pos - vivae_sim::DVec2::new(105.0, 370.0)).length() < 1e-3);
    assert_eq!(u.robots[0].heading, 0.0);
    // arena1: a road rect 160..590 x 50..90; the raster says road in its middle.
    let a = load("arena1.svg");
    assert_eq!(
        a.surface_exact(vivae_sim::DVec2::new(300.0, 70.0))
            .unwrap()
            .0,
        SurfaceKind::Road
    );
    assert_eq!(
        a.surface_exact(vivae_sim::DVec2::new(300.0, 200.0))
            .unwrap()
            .0,
        SurfaceKind::Grass
    );
    // the SmallPuck is a circle of radius 10 at (570, 400).
    assert!((a.pucks[0].pos - vivae_sim::DVec2::new(570.0, 400.0)).length() < 1e-3);
    assert!((a.pucks[0].radius - 10.0).abs() < 1e-2);
    // oval2_h: the robot rect 570..590 x 250..270.
    let o = load("oval2_h.svg");
    assert!((o.robots[0].pos - vivae_sim::DVec2::new(580.0, 260.0)).length() < 1e-3);
}

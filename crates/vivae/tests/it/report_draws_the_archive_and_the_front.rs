//! A map-elites run's report.html draws its archive as a heat map and an
//! nsga2 run's its Pareto front (with a table of the members to drive, and
//! the strategy's columns of generations.csv as curves), rebuilt the same by
//! `vivae report`, offline; an nsga2 run also draws `figures/front.png`.

use std::path::{Path, PathBuf};

use crate::common::browser::{Browser, shots};
use crate::common::{evolve, ok, read, scratch, vivae, write_small_config};

/// The data rows of a run's CSV file.
fn rows(dir: &Path, name: &str) -> usize {
    String::from_utf8(read(dir, name)).unwrap().lines().count() - 1
}

/// A small map-elites run and a small nsga2 run (4 generations) in `dir`.
fn strategy_runs(dir: &Path) -> (PathBuf, PathBuf) {
    let config = write_small_config(dir, 4);
    let (elites, front) = (dir.join("elites"), dir.join("front"));
    evolve(&config, &elites, &["--strategy", "map-elites"]);
    evolve(&config, &front, &["--strategy", "nsga2"]);
    (elites, front)
}

#[test]
fn a_strategy_runs_report_carries_its_archive_or_front_and_rebuilds_the_same() {
    let dir = scratch("report-strategies");
    let (elites, front) = strategy_runs(&dir);
    for (run, parts, figure) in [
        (
            &elites,
            vec![
                r#""strategy":{"kind":"map-elites","heading":"","note":"","grid":{"lower":[0.0,0.0],"upper":[1.0,1.0],"bins":[10,10]}"#,
                r#""columns":["filled_cells","coverage","qd_score","archive_best"]"#,
            ],
            "archive.png",
        ),
        (
            &front,
            vec![
                r#""strategy":{"kind":"nsga2""#,
                r#""objectives":["fitness (px/step), maximised","contacts per 1,000 robot-steps, minimised"]"#,
            ],
            "front.png",
        ),
    ] {
        let html = String::from_utf8(read(run, "report.html")).unwrap();
        for part in parts {
            assert!(html.contains(part), "{}: no {part}", run.display());
        }
        assert!(run.join("figures").join(figure).is_file(), "{figure}");
        let first = read(run, "report.html");
        std::fs::remove_file(run.join("report.html")).unwrap();
        ok(vivae().arg("report").arg(run));
        assert!(read(run, "report.html") == first, "rebuilt differently");
    }
    assert!(!elites.join("figures/front.png").exists());
    assert!(!front.join("figures/archive.png").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn three_objectives_draw_no_front_figure_and_the_report_keeps_all_three() {
    let dir = scratch("report-three-objectives");
    let config = dir.join("c.toml");
    std::fs::write(
        &config,
        format!(
            "{}\n[strategy]\nkind = \"nsga2\"\n\n[strategy.nsga2]\nobjectives = [\"fitness\", \"-contacts\", \"on_road\"]\n",
            crate::common::small_config(2)
        ),
    )
    .unwrap();
    let run = dir.join("run");
    evolve(&config, &run, &[]);
    assert!(run.join("front.csv").is_file());
    assert!(!run.join("figures/front.png").exists());
    let html = String::from_utf8(read(&run, "report.html")).unwrap();
    assert!(
        html.contains(r#""objectives":["fitness (px/step), maximised","contacts per 1,000 robot-steps, minimised","share of robot-steps on road, maximised"]"#),
        "{}",
        &html[html.find("\"strategy\"").unwrap()..][..400]
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_heat_map_and_the_front_are_on_the_page_with_networking_off() {
    let Some(b) = Browser::start(&[
        "--proxy-server=127.0.0.1:9",
        "--host-resolver-rules=MAP * ~NOTFOUND",
    ]) else {
        return;
    };
    let dir = scratch("browser-report-strategies");
    let (elites, front) = strategy_runs(&dir);
    b.goto(&format!("file://{}", elites.join("report.html").display()));
    b.wait_for(
        "return !!window.vivaeReport && window.vivaeReport.frames > 2;",
        "the report drawn",
    );
    let cells = b.eval(
        "return [document.querySelectorAll('#strategyplot rect.cell').length,
                 document.querySelectorAll('#strategyplot rect.elite').length,
                 document.querySelectorAll('#strategytable tbody tr').length,
                 document.querySelectorAll('#strategycurves svg polyline').length,
                 document.getElementById('strategysection').style.display];",
    );
    let elites_saved = rows(&elites, "archive.csv");
    assert_eq!(
        cells,
        serde_json::json!([100, elites_saved, elites_saved, 2, ""]),
        "cells, elites, table rows, curves (coverage, QD-score)"
    );
    let tip =
        b.eval("return document.querySelector('#strategyplot rect.elite title').textContent;");
    assert!(
        tip.as_str()
            .unwrap()
            .contains("; drive it: vivae view RUN --elite "),
        "{tip}"
    );
    b.eval("document.getElementById('strategysection').scrollIntoView(); return true;");
    b.save_screenshot(&shots().join("report-map-elites-heat-map.png"));

    b.goto(&format!("file://{}", front.join("report.html").display()));
    b.wait_for(
        "return !!window.vivaeReport && window.vivaeReport.frames > 2;",
        "the report drawn",
    );
    let members = b.eval(
        "return [document.querySelectorAll('#strategyplot circle.member').length > 0,
                 document.querySelectorAll('#strategytable tbody tr').length];",
    );
    assert_eq!(
        members,
        serde_json::json!([true, rows(&front, "front.csv")])
    );
    b.eval("document.getElementById('strategysection').scrollIntoView(); return true;");
    b.save_screenshot(&shots().join("report-nsga2-front.png"));
    let errors = b.console_errors();
    assert!(errors.is_empty(), "console errors: {errors:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

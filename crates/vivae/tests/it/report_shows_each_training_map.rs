//! report.html of a multi-map run shows the champion on every training map,
//! each panel named by its map with that map's fitness (issue 25 item 4), in
//! a real headless Chromium. Skipped, with a SKIPPED note, without chromium.

use crate::common::browser::{Browser, shots};
use crate::common::{evolve, field, scratch, write_small_config};

#[test]
fn each_training_map_has_a_panel_named_by_map_with_its_fitness() {
    let Some(b) = Browser::start(&[]) else { return };
    let dir = scratch("browser-report-maps");
    let config = write_small_config(&dir, 2);
    let run = dir.join("run");
    let out = evolve(
        &config,
        &run,
        &["--robots", "0", "--scenario", "roads", "--scenario", "oval"],
    );
    // per_map=roads:2.647,oval:3.398 on the summary line.
    let per_map: Vec<(String, String)> = field(&out, "per_map")
        .split(',')
        .map(|m| {
            let (name, f) = m.split_once(':').unwrap();
            (name.to_string(), f.to_string())
        })
        .collect();
    assert_eq!(per_map.len(), 2);
    b.goto(&format!("file://{}", run.join("report.html").display()));
    b.wait_for(
        "return !!window.vivaeReport && window.vivaeReport.frames > 5;",
        "the animation running",
    );
    let panels = b.eval(
        "return Array.prototype.map.call(document.querySelectorAll('#mappanels .mappanel'),
           function (p) { return [p.querySelector('h3').textContent, p.querySelector('.muted').textContent]; });",
    );
    assert_eq!(panels.as_array().unwrap().len(), 2, "{panels}");
    for (k, (name, fitness)) in per_map.iter().enumerate() {
        assert_eq!(panels[k][0], format!("{name} (map {} of 2)", k + 1));
        let info = panels[k][1].as_str().unwrap();
        assert!(
            info.starts_with(&format!("fitness {fitness} px/step")),
            "{info}"
        );
    }
    let buttons = b.eval(
        "return Array.prototype.map.call(document.getElementById('episodes').children,
           function (b) { return b.textContent; });",
    );
    assert!(
        buttons[1]
            .as_str()
            .unwrap()
            .ends_with("on oval, map 2 of 2"),
        "{buttons}"
    );
    assert!(
        buttons[2]
            .as_str()
            .unwrap()
            .starts_with("Best of generation 1 on roads"),
        "{buttons}"
    );
    // A panel animates its map: the stage shows oval.svg's arena.
    let oval = b.eval(
        "var c = document.querySelectorAll('#mappanels canvas')[1]; return [c.width, c.height];",
    );
    b.eval("document.getElementById('map-1').click(); return true;");
    b.wait_for(
        &format!(
            "var c = document.getElementById('scene');
             return window.vivaeReport.episode === 1 && c.width === {} && c.height === {};",
            oval[0], oval[1]
        ),
        "oval.svg on the stage",
    );
    assert!(
        b.eval("return document.getElementById('epinfo').textContent;")
            .as_str()
            .unwrap()
            .contains(&format!("fitness {}", per_map[1].1))
    );
    b.save_screenshot(&shots().join("report-map-oval.png"));
    b.eval("document.getElementById('mapsection').scrollIntoView(); return true;");
    b.save_screenshot(&shots().join("report-map-panels.png"));
    let errors = b.console_errors();
    assert!(errors.is_empty(), "console errors: {errors:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

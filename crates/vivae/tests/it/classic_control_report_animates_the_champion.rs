//! report.html of a classic-control run animates the champion's replay as
//! its task draws it (cart and pole, the acrobot's links, the mountain car
//! on its hill, the pendulum), beside the curves: the picture changes as it
//! plays, pause holds it, the slider picks a step, and the page logs no
//! error, in a real headless Chromium. Skipped, with a SKIPPED note, without
//! chromium.

use crate::a_plain_task_runs_reports_exports_and_resumes::plain;
use crate::common::browser::{Browser, shots};
use crate::common::scratch;

/// The film canvas's pixels, as a data URL (an expression).
const PIXELS: &str = "document.getElementById('filmcanvas').toDataURL()";

#[test]
fn each_classic_control_report_plays_the_champions_episodes() {
    let Some(b) = Browser::start(&[]) else { return };
    let dir = scratch("browser-report-classic");
    let tasks = [
        "cartpole",
        "acrobot",
        "mountain-car",
        "mountain-car-continuous",
        "pendulum",
    ];
    for task in tasks {
        let run = dir.join(task);
        let args = ["--generations", "2", "--population", "20", "--seed", "3"];
        plain(task, &run, &args);
        b.goto(&format!("file://{}", run.join("report.html").display()));
        b.wait_for(
            "return !!window.vivaeFilm && window.vivaeFilm.frames > 2;",
            "the film running",
        );
        let before = b.eval(&format!("return {PIXELS};"));
        b.wait_for(
            &format!("return window.vivaeFilm.frames > 10 && ({PIXELS}) !== {before};"),
            &format!("{task}: the picture changing"),
        );
        // The champion's replay: its episodes' buttons, its label.
        let buttons = b.eval(
            "return Array.prototype.map.call(document.getElementById('filmepisodes').children,
               function (b) { return b.textContent; });",
        );
        assert_eq!(buttons.as_array().unwrap().len(), 5, "{task}: {buttons}");
        assert!(
            buttons[0].as_str().unwrap().starts_with("episode 1: "),
            "{buttons}"
        );
        let info = b.eval("return document.getElementById('filminfo').textContent;");
        assert!(
            info.as_str().unwrap().starts_with("Champion (generation "),
            "{task}: {info}"
        );
        // Paused, it holds its step; the slider then picks one.
        b.eval("document.getElementById('filmplay').click(); return true;");
        let held = b.eval("return window.vivaeFilm.t;");
        std::thread::sleep(std::time::Duration::from_millis(300));
        assert_eq!(b.eval("return window.vivaeFilm.t;"), held, "{task}: paused");
        let shown = b.eval(&format!("return {PIXELS};"));
        b.eval(
            "var s = document.getElementById('filmslider');
             s.value = Math.floor(s.max / 2) === window.vivaeFilm.t ? 0 : Math.floor(s.max / 2);
             s.dispatchEvent(new Event('input')); return true;",
        );
        assert_eq!(
            b.eval("return window.vivaeFilm.t === +document.getElementById('filmslider').value;"),
            true,
            "{task}: the slider's step"
        );
        // A one-step episode leaves the slider nowhere else to go.
        if b.eval("return +document.getElementById('filmslider').max > 0;") == true {
            assert_ne!(
                b.eval(&format!("return {PIXELS};")),
                shown,
                "{task}: the slider's picture"
            );
        }
        b.eval("document.getElementById('filmplay').click(); return true;");
        b.save_screenshot(&shots().join(format!("report-{task}.png")));
        let errors = b.console_errors();
        assert!(errors.is_empty(), "{task}: console errors: {errors:?}");
    }
    // A run whose task draws no steps (the driving task) shows no film section.
    let _ = std::fs::remove_dir_all(&dir);
}

//! report.html of a Gymnasium run (Box2D, MuJoCo: played by the Python
//! package) animates the champion's episode from the frames Python rendered
//! into the run directory (`film.json`), beside the curves: the pictures
//! load and change as it plays, the slider picks a frame, and the page logs
//! no error, in a real headless Chromium. The run is a tiny LunarLander run
//! that `python/tests/test_gym.py` makes and checks against the stored copy
//! (`tests/data/gymnasium-run`): the program cannot play Gymnasium to make
//! one. A damaged `film.json` is refused by name, and LunarLander's
//! four-output network exports with its four outputs. Skipped, with a
//! SKIPPED note, without chromium (the export is checked either way).

use std::path::Path;

use crate::common::browser::{Browser, shots};
use crate::common::{ok, run, scratch, vivae};

/// The film canvas's pixels, as a data URL (an expression).
const PIXELS: &str = "document.getElementById('filmcanvas').toDataURL()";

/// A copy of the stored Gymnasium run in `dir`.
fn stored_run(dir: &Path) {
    let from = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/gymnasium-run");
    std::fs::create_dir_all(dir).unwrap();
    for entry in std::fs::read_dir(&from).unwrap() {
        let entry = entry.unwrap();
        std::fs::copy(entry.path(), dir.join(entry.file_name())).unwrap();
    }
}

#[test]
fn a_gymnasium_report_plays_the_frames_python_rendered() {
    let dir = scratch("gymnasium-report");
    let out = dir.join("run");
    stored_run(&out);
    // A damaged film is refused, naming the file and what is wrong.
    let film = std::fs::read_to_string(out.join("film.json")).unwrap();
    std::fs::write(
        out.join("film.json"),
        film.replacen("data:image/png;base64,", "data:text/html;base64,", 1),
    )
    .unwrap();
    let refused = run(vivae().arg("report").arg(&out));
    let err = String::from_utf8_lossy(&refused.stderr);
    assert_eq!(refused.status.code(), Some(2), "{err}");
    assert!(
        err.contains("film.json") && err.contains("not a PNG data URL"),
        "{err}"
    );
    std::fs::write(out.join("film.json"), &film).unwrap();
    ok(vivae().arg("report").arg(&out));
    let page = std::fs::read_to_string(out.join("report.html")).unwrap();
    let stored: serde_json::Value = serde_json::from_str(&film).unwrap();
    let images: Vec<&str> = (stored["frames"].as_array().unwrap().iter())
        .map(|f| f["image"].as_str().unwrap())
        .collect();
    let frames = images.len();
    assert!(frames >= 2, "{frames} frames stored");
    assert!(images.iter().all(|i| page.contains(i)), "a frame left out");

    // Its champion exports as a plain network does: LunarLander's four
    // outputs (one per action, the largest taken by the caller), in order.
    let lander = dir.join("lander.json");
    ok(vivae()
        .args(["export"])
        .arg(&out)
        .args(["--format", "json", "-o"])
        .arg(&lander));
    let doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&lander).unwrap()).unwrap();
    assert_eq!(doc["net"]["outputs"].as_array().map(Vec::len), Some(4));
    let meaning = doc["outputs"].as_str().unwrap();
    assert!(
        meaning.starts_with("4 outputs") && meaning.contains("discrete action"),
        "{meaning}"
    );

    let Some(b) = Browser::start(&[]) else { return };
    b.goto(&format!("file://{}", out.join("report.html").display()));
    b.wait_for(
        "return !!window.vivaeFilm && window.vivaeFilm.images > 2;",
        "the rendered frames drawn",
    );
    let before = b.eval(&format!("return {PIXELS};"));
    b.wait_for(
        &format!("return window.vivaeFilm.images > 5 && ({PIXELS}) !== {before};"),
        "the picture changing",
    );
    let info = b.eval("return document.getElementById('filminfo').textContent;");
    let info = info.as_str().unwrap();
    assert!(
        info.starts_with("Champion (generation ") && info.contains("LunarLander-v3"),
        "{info}"
    );
    // One episode, its frames on the slider; paused, the slider picks one.
    let buttons = b.eval("return document.getElementById('filmepisodes').children.length;");
    assert_eq!(buttons, 1);
    assert_eq!(
        b.eval("return +document.getElementById('filmslider').max;"),
        frames - 1
    );
    b.eval("document.getElementById('filmplay').click(); return true;");
    let shown = b.eval(&format!("return {PIXELS};"));
    b.eval(
        "var s = document.getElementById('filmslider');
         s.value = window.vivaeFilm.t === 0 ? s.max : 0;
         s.dispatchEvent(new Event('input')); return true;",
    );
    assert_ne!(
        b.eval(&format!("return {PIXELS};")),
        shown,
        "the slider's picture"
    );
    // The curves are there beside it.
    assert_eq!(
        b.eval("return document.getElementById('film').style.display;"),
        ""
    );
    b.eval("document.getElementById('filmplay').click(); return true;");
    b.save_screenshot(&shots().join("report-gymnasium.png"));
    let errors = b.console_errors();
    assert!(errors.is_empty(), "console errors: {errors:?}");
}

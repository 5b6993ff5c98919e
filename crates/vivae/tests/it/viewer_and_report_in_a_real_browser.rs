//! The viewer page and report.html in a real headless Chromium (WebDriver).
//!
//! Skipped, with a one-line SKIPPED note, where chromium or chromedriver is not installed;
//! `.ci/run` installs both so CI always runs these. Screenshots are left in
//! `target/browser-screenshots/` to look at.

use std::path::PathBuf;

use crate::common::browser::{Browser, Viewer, shots};
use crate::common::small_run;

/// Robot positions the page last drew.
const ROBOTS: &str = "return JSON.stringify(window.vivaeView && window.vivaeView.robots);";

#[test]
fn viewer_page_loads_cleanly_robots_move_and_resampling_shows() {
    let Some(b) = Browser::start(&[]) else { return };
    let run = small_run("browser-view", 3);
    let v = Viewer::start(&[run.as_os_str()]);
    b.goto(&v.url);
    b.wait_for(
        "return !!window.vivaeView && window.vivaeView.frames > 10 && window.vivaeView.step > 10;",
        "drawing frames",
    );
    let before = b.eval(ROBOTS);
    let shot1 = b.save_screenshot(&shots().join("view-1.png"));
    let step1 = b.eval("return window.vivaeView.step;").as_u64().unwrap();
    b.wait_for(
        &format!("return window.vivaeView.step > {} ;", step1 + 30),
        "thirty more simulation steps",
    );
    let after = b.eval(ROBOTS);
    let shot2 = b.save_screenshot(&shots().join("view-2.png"));
    assert_ne!(before, after, "robots did not move");
    assert_ne!(shot1, shot2, "two screenshots are identical");

    // Re-sample the neurons: the page shows the new substrate.
    let panel = "return document.getElementById('neuronpanel').toDataURL();";
    let neurons_before = b.eval(panel);
    assert_eq!(b.eval("return window.vivaeView.neurons;"), 9);
    b.eval(
        "document.getElementById('neurons').value = '9x9';
         document.getElementById('apply').click(); return true;",
    );
    b.wait_for(
        "return window.vivaeView.neurons === 81 && window.vivaeView.frames > 0;",
        "81 neurons shown",
    );
    let text = b.eval("return document.getElementById('neuroncount').textContent;");
    assert!(text.as_str().unwrap().contains("81 neurons"), "{text}");
    let step = b.eval("return window.vivaeView.step;").as_u64().unwrap();
    b.wait_for(
        &format!("return window.vivaeView.step > {};", step + 5),
        "frames after re-sampling",
    );
    assert_ne!(
        b.eval(panel),
        neurons_before,
        "the neuron panel did not change"
    );
    b.save_screenshot(&shots().join("view-9x9.png"));

    let errors = b.console_errors();
    assert!(errors.is_empty(), "console errors: {errors:?}");

    // The page's own requests cannot reach outside what the server lists.
    let status = b.eval(
        "var x = new XMLHttpRequest(); x.open('GET', '/run/..%2F..%2Fetc%2Fpasswd', false); x.send();
         return x.status;",
    );
    assert_eq!(status, 404);
    let _ = std::fs::remove_dir_all(run.parent().unwrap());
}

#[test]
fn report_html_animates_from_file_with_networking_off() {
    // Every network request fails: nothing on the page may need one.
    let Some(b) = Browser::start(&[
        "--proxy-server=127.0.0.1:9",
        "--host-resolver-rules=MAP * ~NOTFOUND",
    ]) else {
        return;
    };
    let run = small_run("browser-report", 10);
    let report = run.join("report.html");
    assert!(report.is_file());
    b.goto(&format!("file://{}", report.display()));
    b.wait_for(
        "return !!window.vivaeReport && window.vivaeReport.frames > 5;",
        "the animation running",
    );
    let t1 = b.eval("return window.vivaeReport.t;").as_u64().unwrap();
    let shot1 = b.save_screenshot(&shots().join("report-1.png"));
    b.wait_for(
        &format!(
            // Past the wrap-around to step 0 too, so that the slider is read mid-episode.
            // The slider value is kept as seen: the episode loops, so a later read may be 0 again.
            "window.seenSlider = document.getElementById('slider').value;
             return (window.vivaeReport.t > {} || window.vivaeReport.t < {}) && window.seenSlider !== '0';",
            t1 + 20,
            t1
        ),
        "the time slider advancing",
    );
    let shot2 = b.save_screenshot(&shots().join("report-2.png"));
    assert_ne!(shot1, shot2, "the animation did not change the picture");
    let slider = b.eval("return window.seenSlider;");
    assert_ne!(slider, "0");
    // Three episodes: champion, generation 1 and generation 10.
    assert_eq!(
        b.eval("return document.getElementById('episodes').children.length;"),
        3
    );
    assert_eq!(
        b.eval("return document.querySelectorAll('#species polygon').length > 0;"),
        true
    );
    let remote = b.eval(
        "return performance.getEntriesByType('resource').map(function (e) { return e.name; })
           .filter(function (n) { return !/^(data|file|blob):/.test(n); });",
    );
    assert_eq!(remote, serde_json::json!([]), "requests: {remote}");
    let errors = b.console_errors();
    assert!(errors.is_empty(), "console errors: {errors:?}");
    let _ = std::fs::remove_dir_all(run.parent().unwrap());
}

/// Measures the frame rate the page holds with five robots at 3×5 and 32×96
/// sensors (a measurement, not a check: run it by name with `--ignored`).
/// `VIVAE_SHOTS=DIR` also saves the screenshots the guide shows.
#[test]
#[ignore = "measurement for docs/howto/watch-runs.md; run with --ignored --nocapture"]
fn measure_viewer_frame_rate() {
    let Some(b) = Browser::start(&[]) else { return };
    // A run named by VIVAE_RUN is the user's and stays; only our own is removed.
    let (_own, run) = match std::env::var_os("VIVAE_RUN").map(PathBuf::from) {
        Some(run) => (None, run),
        None => {
            let own = small_run("browser-fps", 3);
            let run = own.to_path_buf();
            (Some(own), run)
        }
    };
    let v = Viewer::start(&[run.as_os_str()]);
    b.goto(&v.url);
    b.wait_for(
        "return !!window.vivaeView && window.vivaeView.frames > 10;",
        "drawing frames",
    );
    // 2× real time is 60 steps a second: a new picture for every display frame.
    b.eval("var s = document.getElementById('speed'); s.value = '2'; s.onchange(); return true;");
    for (sensors, neurons) in [("3x5", "3x3"), ("32x96", "3x3")] {
        b.eval(&format!(
            "document.getElementById('sensors').value = '{sensors}';
             document.getElementById('neurons').value = '{neurons}';
             document.getElementById('apply').click(); return true;"
        ));
        let n: usize = sensors
            .split('x')
            .map(|p| p.parse::<usize>().unwrap())
            .product();
        b.wait_for(
            &format!("return window.vivaeView.sensors === {n};"),
            "the new substrate",
        );
        std::thread::sleep(std::time::Duration::from_secs(2));
        let (f0, s0) = (
            b.eval("return window.vivaeView.frames;").as_f64().unwrap(),
            b.eval("return window.vivaeView.step;").as_f64().unwrap(),
        );
        let t = std::time::Instant::now();
        std::thread::sleep(std::time::Duration::from_secs(10));
        let secs = t.elapsed().as_secs_f64();
        let (f1, s1) = (
            b.eval("return window.vivaeView.frames;").as_f64().unwrap(),
            b.eval("return window.vivaeView.step;").as_f64().unwrap(),
        );
        println!(
            "viewer sensors={sensors} neurons={neurons} robots=5: {:.1} frames/s drawn, {:.1} steps/s simulated",
            (f1 - f0) / secs,
            (s1 - s0) / secs
        );
        if let Some(dir) = std::env::var_os("VIVAE_SHOTS") {
            b.save_screenshot(&PathBuf::from(dir).join(format!("view-{sensors}.png")));
        }
    }
}

#[test]
fn arrow_keys_drive_a_robot_and_dragging_moves_one() {
    let Some(b) = Browser::start(&[]) else { return };
    // No genome: robots stand still unless driven by hand.
    let v = Viewer::start(&[]);
    b.goto(&v.url);
    b.wait_for(
        "return !!window.vivaeView && window.vivaeView.frames > 3 && !!window.vivaeView.robots;",
        "drawing frames",
    );
    let pos = |i: usize| -> (f64, f64) {
        let v = b.eval(&format!("return window.vivaeView.robots[{i}];"));
        (v[0].as_f64().unwrap(), v[1].as_f64().unwrap())
    };
    let start = pos(0);
    b.eval(
        "var d = document.getElementById('drive'); d.checked = true; d.onchange(); return true;",
    );
    b.wait_for(
        "return document.getElementById('drive').checked && window.vivaeView.step > 0;",
        "driving mode",
    );
    let key = |kind: &str| b.key(kind, "\u{E013}");
    key("keyDown");
    // Held until robot 1 has gone 20 px: a count of steps would race the key
    // event on a loaded machine (the page may step before it sees the key).
    b.wait_for(
        &format!(
            "var r = window.vivaeView.robots[0];
             return Math.hypot(r[0] - {}, r[1] - {}) > 20;",
            start.0, start.1
        ),
        "robot 1 driven 20 px by the up arrow",
    );
    key("keyUp");
    let other = pos(1);

    // Drag robot 2 by the mouse to another place on the canvas.
    b.drag_on_scene(other, (other.0 + 60.0, other.1 + 40.0));
    b.wait_for(
        &format!(
            "var r = window.vivaeView.robots[1];
             return Math.abs(r[0] - {}) < 4 && Math.abs(r[1] - {}) < 4;",
            other.0 + 60.0,
            other.1 + 40.0
        ),
        "robot 2 at the place it was dragged to",
    );
    b.save_screenshot(&shots().join("view-driven.png"));
    let errors = b.console_errors();
    assert!(errors.is_empty(), "console errors: {errors:?}");
}

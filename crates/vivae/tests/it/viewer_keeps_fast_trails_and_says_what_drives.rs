//! The viewer page in a real headless Chromium (issue 25 items 10 to 14 and
//! 4): trails that survive 50× speed, readable errors that end with the next
//! action, arrow keys that take a robot over, labels that name the genome
//! that really drives, maps without robots greyed out, and a multi-map run's
//! maps offered by name. Skipped, with a SKIPPED note, without chromium.
//! Screenshots are left in `target/…/browser-screenshots/` to look at.

use std::path::Path;

use crate::common::browser::{Browser, Viewer, shots};
use crate::common::{evolve, scratch, small_run, vivae, write_small_config};

/// Waits for the page's first frames.
fn wait_for_frames(b: &Browser) {
    b.wait_for(
        "return !!window.vivaeView && window.vivaeView.frames > 5 && !!window.vivaeView.robots;",
        "drawing frames",
    );
}

/// Chooses `value` in the `<select>` with id `id`, as a user would.
fn choose(b: &Browser, id: &str, value: &str) {
    b.eval(&format!(
        "var s = document.getElementById('{id}'); s.value = '{value}'; s.onchange(); return true;"
    ));
}

fn text_of(b: &Browser, id: &str) -> String {
    b.eval(&format!(
        "return document.getElementById('{id}').textContent;"
    ))
    .as_str()
    .unwrap()
    .to_string()
}

/// Whether some robot's trail is longer than `px` (summed along it).
fn trail_longer_than(px: f64) -> String {
    format!(
        "var v = window.vivaeView;
         for (var i = 0; i < v.trails.length; i++) {{
           var t = v.trail(i), len = 0;
           for (var k = 2; k + 1 < t.length; k += 2) {{ len += Math.hypot(t[k] - t[k - 2], t[k + 1] - t[k - 1]); }}
           if (len > {px}) {{ return true; }}
         }}
         return false;"
    )
}

#[test]
fn trails_survive_fifty_times_speed_and_restart_on_drag_and_reset() {
    let Some(b) = Browser::start(&[]) else { return };
    let run = small_run("browser-trails", 3);
    let v = Viewer::start(&[run.as_os_str()]);
    b.goto(&v.url);
    wait_for_frames(&b);
    choose(&b, "speed", "50");
    // At 50× a robot goes 25 steps (tens of px) or more between frames; the
    // trail keeps all of it (it was reset on every move of over 40 px).
    b.wait_for(&trail_longer_than(600.0), "a trail 600 px long at 50×");
    b.save_screenshot(&shots().join("view-trails-50x-3x5.png"));

    // At the highest substrate resolution too.
    b.eval(
        "document.getElementById('sensors').value = '32x96';
         document.getElementById('apply').click(); return true;",
    );
    b.wait_for("return window.vivaeView.sensors === 3072;", "32×96 sensors");
    b.wait_for(
        &trail_longer_than(300.0),
        "a trail 300 px long at 32×96 and 50×",
    );
    b.save_screenshot(&shots().join("view-trails-50x-32x96.png"));

    // Paused, reset starts every trail afresh.
    b.eval("document.getElementById('play').click(); return true;");
    b.wait_for(
        "return document.getElementById('play').textContent === 'Play';",
        "paused",
    );
    b.eval("document.getElementById('reset').click(); return true;");
    b.wait_for(
        "return window.vivaeView.step === 0 && window.vivaeView.trails.every(function (n) { return n <= 1; });",
        "every trail cleared by reset",
    );
    // Five single steps from the start (robots well apart), then a dragged
    // robot starts its trail afresh and the others keep theirs.
    for _ in 0..5 {
        let step = b.eval("return window.vivaeView.step;").as_u64().unwrap();
        b.eval("document.getElementById('step').click(); return true;");
        b.wait_for(
            &format!("return window.vivaeView.step === {};", step + 1),
            "one more step",
        );
    }
    assert_eq!(b.eval("return window.vivaeView.trails[1];"), 6);
    let at = b.eval("return window.vivaeView.robots[0];");
    let from = (at[0].as_f64().unwrap(), at[1].as_f64().unwrap());
    b.drag_on_scene(from, (from.0 + 60.0, from.1 + 40.0));
    b.wait_for(
        "return window.vivaeView.trails[0] <= 1;",
        "the dragged robot's trail started afresh",
    );
    assert_eq!(b.eval("return window.vivaeView.trails[1];"), 6);
    let errors = b.console_errors();
    assert!(errors.is_empty(), "console errors: {errors:?}");
    let _ = std::fs::remove_dir_all(run.parent().unwrap());
}

/// A folder of scenarios: `bare.svg` (the road map without its robots)
/// and `oval.svg`.
fn scenario_folder(dir: &Path) -> std::path::PathBuf {
    let maps = dir.join("maps");
    std::fs::create_dir_all(&maps).unwrap();
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios");
    let roads = std::fs::read_to_string(root.join("roads.svg")).unwrap();
    let bare: String = roads
        .lines()
        .filter(|l| !l.contains("ControlledRobot"))
        .collect::<Vec<_>>()
        .join("\n");
    std::fs::write(maps.join("bare.svg"), bare).unwrap();
    std::fs::copy(root.join("oval.svg"), maps.join("oval.svg")).unwrap();
    maps
}

/// WCAG contrast ratio of the status text against what it is drawn on.
const STATUS_CONTRAST: &str = "
    function rgb(c) { return c.match(/[\\d.]+/g).map(Number); }
    function lum(c) {
      var v = rgb(c).slice(0, 3).map(function (x) {
        x /= 255; return x <= 0.03928 ? x / 12.92 : Math.pow((x + 0.055) / 1.055, 2.4);
      });
      return 0.2126 * v[0] + 0.7152 * v[1] + 0.0722 * v[2];
    }
    var el = document.getElementById('status'), bg = el;
    while (bg && (getComputedStyle(bg).backgroundColor === 'rgba(0, 0, 0, 0)' ||
                  getComputedStyle(bg).backgroundColor === 'transparent')) { bg = bg.parentElement; }
    var a = lum(getComputedStyle(el).color), b = lum(getComputedStyle(bg).backgroundColor);
    return (Math.max(a, b) + 0.05) / (Math.min(a, b) + 0.05);";

#[test]
fn errors_are_readable_end_with_the_next_action_and_a_failed_switch_keeps_the_map() {
    let Some(b) = Browser::start(&[]) else { return };
    let dir = scratch("browser-errors");
    let maps = scenario_folder(&dir);
    let v = Viewer::start(&["--scenarios".as_ref(), maps.as_os_str()]);
    b.goto(&v.url);
    wait_for_frames(&b);
    // Offered: the embedded map, bare.svg (greyed out, with the reason), oval.svg.
    let options = b.eval(
        "return Array.prototype.map.call(document.getElementById('scenario').options,
           function (o) { return [o.textContent, o.disabled]; });",
    );
    assert_eq!(options.as_array().unwrap().len(), 3, "{options}");
    assert_eq!(options[1][1], true, "{options}");
    assert!(
        options[1][0]
            .as_str()
            .unwrap()
            .contains("bare.svg — cannot be driven: no robots"),
        "{options}"
    );
    assert_eq!(options[2][1], false, "{options}");
    assert!(text_of(&b, "scenarionote").contains("1 of 3 scenarios cannot be driven"));

    // A page that still picks it (an old list, a script) is refused; the
    // list goes back to the map that runs.
    b.eval(
        "var s = document.getElementById('scenario'); s.options[1].disabled = false;
         s.value = '1'; s.onchange(); return true;",
    );
    b.wait_for(
        "return document.getElementById('status').className.indexOf('error') >= 0;",
        "the error shown",
    );
    assert!(text_of(&b, "status").contains("cannot be driven: no robots"));
    b.wait_for(
        "return document.getElementById('scenario').value === '0';",
        "the scenario list back on the running map",
    );
    let contrast = b.eval(STATUS_CONTRAST).as_f64().unwrap();
    assert!(contrast >= 4.5, "error text contrast {contrast:.2} < 4.5");
    b.save_screenshot(&shots().join("view-error.png"));
    // The error stays while nothing else happens…
    std::thread::sleep(std::time::Duration::from_millis(1500));
    assert!(text_of(&b, "status").contains("cannot be driven"));
    // …and ends with the next action that succeeds.
    choose(&b, "scenario", "2");
    b.wait_for(
        "return document.getElementById('status').className.indexOf('error') < 0 &&
                document.getElementById('status').textContent.indexOf('cannot') < 0;",
        "the error gone after a successful switch",
    );
    b.wait_for(
        "return document.getElementById('scenario').value === '2' && window.vivaeView.frames > 0;",
        "oval.svg running",
    );
    b.save_screenshot(&shots().join("view-after-error.png"));
    let errors = b.console_errors();
    assert!(errors.is_empty(), "console errors: {errors:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn an_arrow_key_takes_the_selected_robot_over_and_the_driver_line_says_so() {
    let Some(b) = Browser::start(&[]) else { return };
    let run = small_run("browser-keys", 3);
    let v = Viewer::start(&[run.as_os_str()]);
    b.goto(&v.url);
    wait_for_frames(&b);
    assert!(text_of(&b, "driver").starts_with("controller: champion (generation"));
    // An arrow key in a list moves the list, not a robot.
    b.eval("document.getElementById('speed').focus(); return true;");
    b.key("keyDown", "\u{E015}");
    b.key("keyUp", "\u{E015}");
    assert_eq!(
        b.eval("return document.getElementById('drive').checked;"),
        false
    );

    b.eval("document.activeElement.blur(); return true;");
    let start = b.eval("return window.vivaeView.robots[0];");
    b.key("keyDown", "\u{E013}");
    b.wait_for(
        "return document.getElementById('drive').checked &&
                document.getElementById('driver').textContent.indexOf('driven by you') === 0;",
        "robot 1 driven by hand",
    );
    let step = b.eval("return window.vivaeView.step;").as_u64().unwrap();
    b.wait_for(
        &format!("return window.vivaeView.step > {};", step + 30),
        "thirty steps with the up arrow held",
    );
    b.key("keyUp", "\u{E013}");
    let driver = text_of(&b, "driver");
    assert!(
        driver.starts_with("driven by you with the arrow keys (the other robots: champion"),
        "{driver}"
    );
    assert!(!driver.starts_with("controller:"), "{driver}");
    let end = b.eval("return window.vivaeView.robots[0];");
    assert_ne!(start, end, "robot 1 did not move");
    b.save_screenshot(&shots().join("view-arrow-keys.png"));
    // Unticking hands the robot back.
    b.eval(
        "var d = document.getElementById('drive'); d.checked = false; d.onchange(); return true;",
    );
    b.wait_for(
        "return document.getElementById('driver').textContent.indexOf('controller: champion') === 0;",
        "the champion driving again",
    );
    let errors = b.console_errors();
    assert!(errors.is_empty(), "console errors: {errors:?}");
    let _ = std::fs::remove_dir_all(run.parent().unwrap());
}

#[test]
fn a_followed_run_labels_the_champion_that_drives_until_the_new_one_is_watched() {
    let Some(b) = Browser::start(&[]) else { return };
    // Seed 7: generation 2 holds the champion after 2 generations, generation 3 after 8.
    let run = small_run("browser-follow", 2);
    let v = Viewer::start(&[run.as_os_str()]);
    b.goto(&v.url);
    wait_for_frames(&b);
    b.wait_for(
        "return document.getElementById('driver').textContent.indexOf('champion (generation 2,') >= 0;",
        "generation 2's champion driving",
    );
    let status = vivae()
        .args(["resume", "-q", "--generations", "8"])
        .arg(&run)
        .status()
        .unwrap();
    assert!(status.success());
    b.wait_for(
        "return document.getElementById('gencount').textContent.indexOf('generation 8 of 8') === 0;",
        "the page told of generation 8",
    );
    let option = b.eval(
        "var s = document.getElementById('controller');
         return s.options[s.selectedIndex].textContent;",
    );
    assert_eq!(
        option,
        "champion of generation 2 (driving; newest: generation 3)"
    );
    let notice = text_of(&b, "newchamptext");
    assert!(
        notice.starts_with(
            "New champion: generation 3, fitness 3.304 (the champion of generation 2 drives now)"
        ),
        "{notice}"
    );
    assert!(text_of(&b, "gencount").contains("champion from generation 3"));
    assert!(text_of(&b, "driver").contains("champion (generation 2,"));
    b.save_screenshot(&shots().join("view-follow-before.png"));

    b.eval("document.getElementById('watchnew').click(); return true;");
    b.wait_for(
        "return document.getElementById('driver').textContent.indexOf('champion (generation 3,') >= 0;",
        "generation 3's champion driving",
    );
    b.wait_for(
        "var s = document.getElementById('controller');
         return s.options[s.selectedIndex].textContent === 'champion (generation 3, fitness 3.304)';",
        "the list naming generation 3's champion",
    );
    b.save_screenshot(&shots().join("view-follow-after.png"));
    let errors = b.console_errors();
    assert!(errors.is_empty(), "console errors: {errors:?}");
    let _ = std::fs::remove_dir_all(run.parent().unwrap());
}

#[test]
fn a_multi_map_run_offers_each_training_map_by_name() {
    let Some(b) = Browser::start(&[]) else { return };
    let dir = scratch("browser-maps");
    let config = write_small_config(&dir, 2);
    let run = dir.join("run");
    evolve(
        &config,
        &run,
        &["--robots", "0", "--scenario", "roads", "--scenario", "oval"],
    );
    let v = Viewer::start(&[run.as_os_str()]);
    b.goto(&v.url);
    wait_for_frames(&b);
    let names = b.eval(
        "return Array.prototype.map.call(document.getElementById('scenario').options,
           function (o) { return o.textContent; });",
    );
    assert_eq!(
        names,
        serde_json::json!([
            "roads.svg (training map 1 of 2)",
            "oval.svg (training map 2 of 2)"
        ])
    );
    choose(&b, "scenario", "1");
    b.wait_for(
        "return document.getElementById('scenario').value === '1' && window.vivaeView.step > 20 &&
                document.getElementById('status').className.indexOf('error') < 0;",
        "the run's champion driving on oval.svg",
    );
    b.save_screenshot(&shots().join("view-multi-map-oval.png"));
    let errors = b.console_errors();
    assert!(errors.is_empty(), "console errors: {errors:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

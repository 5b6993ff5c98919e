//! `vivae view RUN --elite CELL` and `--front N` start the pages on that
//! archive elite or front member (as `vivae replay` runs it), the page's
//! controller list offers every one, and a page picking one sees the driver
//! line name it; a cell or member that is not there is refused in one line.

use std::path::{Path, PathBuf};

use futures_util::{SinkExt, StreamExt};
use tokio_tungstenite::tungstenite::Message;

use crate::common::browser::{Browser, Viewer, shots};
use crate::common::{evolve, read, run, scratch, vivae, write_small_config};

/// The data rows of a run's CSV file, split at commas.
fn rows(dir: &Path, name: &str) -> Vec<Vec<String>> {
    let text = String::from_utf8(read(dir, name)).unwrap();
    (text.lines().skip(1))
        .map(|r| r.split(',').map(String::from).collect())
        .collect()
}

/// A small map-elites run and a small nsga2 run (3 generations) in `dir`.
fn strategy_runs(dir: &Path) -> (PathBuf, PathBuf) {
    let config = write_small_config(dir, 3);
    let (elites, front) = (dir.join("elites"), dir.join("front"));
    evolve(&config, &elites, &["--strategy", "map-elites"]);
    evolve(&config, &front, &["--strategy", "nsga2"]);
    (elites, front)
}

/// The first `frame` after the page's messages, and every `error` on the way.
async fn next_frame<S>(ws: &mut S) -> (serde_json::Value, Vec<String>)
where
    S: StreamExt<Item = Result<Message, tokio_tungstenite::tungstenite::Error>> + Unpin,
{
    let mut errors = Vec::new();
    loop {
        let m = ws.next().await.expect("socket open").expect("message");
        let Message::Text(t) = m else { continue };
        let v: serde_json::Value = serde_json::from_str(t.as_str()).unwrap();
        if v["type"] == "error" {
            errors.push(v["message"].as_str().unwrap().to_string());
        }
        if v["type"] == "frame" {
            return (v, errors);
        }
    }
}

#[test]
fn view_starts_on_the_elite_or_front_member_asked_for_and_refuses_missing_ones() {
    let dir = scratch("view-members");
    let (elites, front) = strategy_runs(&dir);
    let archive = rows(&elites, "archive.csv");
    let cell = archive[0][0].clone();

    for (args, says) in [
        (vec!["--elite", "100000"], "no elite in cell 100000"),
        (
            vec!["--front", "0"],
            "no such file (only a run whose strategy keeps a Pareto front has one)",
        ),
    ] {
        let out = run(vivae().arg("view").arg(&elites).args(&args));
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(says) && err.lines().count() == 1, "{err}");
    }
    let out = run(vivae().args(["view", "--elite", "0"]));
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("--elite 0: needs a run directory"), "{err}");

    let v = Viewer::start(&[elites.as_os_str(), "--elite".as_ref(), cell.as_ref()]);
    let rt = tokio::runtime::Runtime::new().unwrap();
    rt.block_on(async {
        let mut ws = v.connect().await;
        let (frame, errors) = next_frame(&mut ws).await;
        assert!(errors.is_empty(), "{errors:?}");
        assert_eq!(frame["choice"], format!("elite:{cell}"));
        let driver = frame["driver"].as_str().unwrap();
        assert!(
            driver.starts_with(&format!("elite of cell {cell} (generation ")),
            "{driver}"
        );
        // A front in a map-elites run, and a hostile choice, are refused; the elite drives on.
        for bad in [r#"{"front":0}"#, r#"{"elite":-1}"#, r#"{"elite":{"x":1}}"#] {
            let msg = format!(r#"{{"type":"controller","which":{bad}}}"#);
            ws.send(Message::Text(msg.into())).await.unwrap();
            // Frames of playing may come before the answer: up to the error, then one more.
            let mut errors = Vec::new();
            while errors.is_empty() {
                errors = next_frame(&mut ws).await.1;
            }
            assert_eq!(errors.len(), 1, "{bad}: {errors:?}");
            let (frame, more) = next_frame(&mut ws).await;
            assert!(more.is_empty(), "{more:?}");
            assert_eq!(frame["choice"], format!("elite:{cell}"));
        }
    });
    drop(v);

    let members = rows(&front, "front.csv");
    let v = Viewer::start(&[front.as_os_str(), "--front".as_ref(), "0".as_ref()]);
    rt.block_on(async {
        let mut ws = v.connect().await;
        let (frame, _) = next_frame(&mut ws).await;
        assert_eq!(frame["choice"], "front:0");
        let fitness: f64 = members[0][1].parse().unwrap();
        let driver = frame["driver"].as_str().unwrap();
        assert!(
            driver.starts_with(&format!("front member 0 (fitness {fitness:.3}; fitness ")),
            "{driver}"
        );
        assert!(driver.contains(", contacts "), "{driver}");
    });
    drop(v);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Chooses `value` in the `<select>` with id `id`, as a user would.
fn choose(b: &Browser, id: &str, value: &str) {
    b.eval(&format!(
        "var s = document.getElementById('{id}'); s.value = '{value}'; s.onchange(); return true;"
    ));
}

#[test]
fn a_page_picks_an_elite_and_a_front_member_and_the_driver_line_names_them() {
    let Some(b) = Browser::start(&[]) else { return };
    let dir = scratch("browser-members");
    let (elites, front) = strategy_runs(&dir);
    let archive = rows(&elites, "archive.csv");
    // The fittest elite heads the archive's group of the list.
    let best = (archive.iter())
        .max_by(|a, b| {
            let f = |r: &Vec<String>| r[r.len() - 2].parse::<f64>().unwrap();
            f(a).total_cmp(&f(b))
        })
        .unwrap();
    let v = Viewer::start(&[elites.as_os_str()]);
    b.goto(&v.url);
    b.wait_for(
        "return document.getElementById('driver').textContent.indexOf('controller: champion') === 0;",
        "the champion driving",
    );
    let group = b.eval(
        "var g = document.querySelector('#controller optgroup');
         return g ? [g.label, g.children.length, g.children[0].value] : null;",
    );
    assert_eq!(
        group,
        serde_json::json!([
            format!(
                "MAP-Elites archive: {} elites, fittest first",
                archive.len()
            ),
            archive.len(),
            format!("elite:{}", best[0])
        ])
    );
    choose(&b, "controller", &format!("elite:{}", best[0]));
    b.wait_for(
        &format!(
            "return document.getElementById('driver').textContent.indexOf('controller: elite of cell {} (generation ') === 0;",
            best[0]
        ),
        "the elite driving",
    );
    b.wait_for(
        "return window.vivaeView.step > 30;",
        "the elite driving a while",
    );
    assert_eq!(
        b.eval("return document.getElementById('controller').value;"),
        format!("elite:{}", best[0])
    );
    b.save_screenshot(&shots().join("view-elite.png"));
    drop(v);

    let v = Viewer::start(&[front.as_os_str()]);
    b.goto(&v.url);
    b.wait_for(
        "return document.querySelectorAll('#controller optgroup').length === 1;",
        "the front listed",
    );
    choose(&b, "controller", "front:0");
    b.wait_for(
        "return document.getElementById('driver').textContent.indexOf('controller: front member 0 (fitness ') === 0;",
        "front member 0 driving",
    );
    b.save_screenshot(&shots().join("view-front-member.png"));
    let errors = b.console_errors();
    assert!(errors.is_empty(), "console errors: {errors:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

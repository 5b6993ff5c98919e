//! A page watching a run directory is told about each generation the run
//! adds, and can switch at once to a genome that appeared meanwhile.

use crate::common::browser::Viewer;
use crate::common::{evolve, scratch, vivae, write_small_config};
use futures_util::{SinkExt, StreamExt};
use tokio_tungstenite::tungstenite::Message;

#[test]
fn progress_grows_as_generations_finish() {
    let dir = scratch("view-follow");
    let config = write_small_config(&dir, 2);
    let run = dir.join("run");
    evolve(&config, &run, &[]);
    let v = Viewer::start(&[run.as_os_str()]);
    let rt = tokio::runtime::Runtime::new().unwrap();
    rt.block_on(async {
        let mut ws = v.connect().await;
        let mut generations = 0;
        let mut genomes = Vec::new();
        // The run continues while the page watches.
        let mut resume = vivae()
            .args(["resume", "-q", "--generations", "6"])
            .arg(&run)
            .spawn()
            .unwrap();
        while generations < 6 {
            let m = ws.next().await.expect("socket open").expect("message");
            let Message::Text(t) = m else { continue };
            let v: serde_json::Value = serde_json::from_str(t.as_str()).unwrap();
            if v["type"] == "progress" {
                generations = v["generations"].as_array().unwrap().len();
                genomes = v["genomes"].as_array().unwrap().clone();
                assert_eq!(v["species"].as_array().unwrap().len(), genomes.len());
            }
        }
        assert!(resume.wait().unwrap().success());
        assert_eq!(genomes.len(), 6);
        // A generation that did not exist when the page opened can be watched.
        ws.send(Message::Text(
            "{\"type\":\"controller\",\"which\":6}".into(),
        ))
        .await
        .unwrap();
        loop {
            let m = ws.next().await.expect("socket open").expect("message");
            let Message::Text(t) = m else { continue };
            let v: serde_json::Value = serde_json::from_str(t.as_str()).unwrap();
            assert_ne!(v["type"], "error", "{v}");
            if v["type"] == "frame" && v["choice"] == "6" {
                assert!(v["driver"].as_str().unwrap().contains("generation 6"));
                break;
            }
        }
    });
    let _ = std::fs::remove_dir_all(&dir);
}

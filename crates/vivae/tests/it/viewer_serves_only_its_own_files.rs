//! `vivae view` serves its own assets and the given run's files and nothing
//! else, survives hostile WebSocket messages, bounds its viewers, frees a
//! closed page's slot, and refuses a busy port with exit 2.

use crate::common::browser::{Viewer, http};
use crate::common::{scratch, small_run, vivae};
use futures_util::{SinkExt, StreamExt};
use tokio_tungstenite::tungstenite::Message;

#[test]
fn only_own_assets_and_listed_run_files_are_served() {
    let run = small_run("view-files", 2);
    let v = Viewer::start(&[run.as_os_str()]);
    for ok in [
        "/",
        "/assets/view.js",
        "/assets/style.css",
        "/run/config.toml",
        "/run/champion.json",
        "/run/best-genomes.jsonl",
    ] {
        assert_eq!(http(v.port, "GET", ok, None).status, 200, "{ok}");
    }
    let page = String::from_utf8(http(v.port, "GET", "/", None).body).unwrap();
    assert!(page.contains("vivae view"));
    for bad in [
        "/../../etc/passwd",
        "/run/../../etc/passwd",
        "/run/..%2F..%2Fetc%2Fpasswd",
        "/run/%2e%2e/config.toml",
        "/assets/../../Cargo.toml",
        "/assets/..%2F..%2FCargo.toml",
        "/run/checkpoints",
        "/run/figures/network.png",
        "/etc/passwd",
        "/run//etc/passwd",
        "//etc/passwd",
        "/run/timing.csv/..",
    ] {
        let r = http(v.port, "GET", bad, None);
        assert_eq!(r.status, 404, "{bad} gave {}", r.status);
        assert!(!String::from_utf8_lossy(&r.body).contains("root:"));
    }
    let _ = std::fs::remove_dir_all(run.parent().unwrap());
}

#[test]
fn a_genome_or_scenario_source_serves_no_run_files() {
    let run = small_run("view-genome", 2);
    let v = Viewer::start(&[run.join("champion.json").as_os_str()]);
    assert_eq!(http(v.port, "GET", "/run/champion.json", None).status, 404);
    assert_eq!(http(v.port, "GET", "/", None).status, 200);
    let _ = std::fs::remove_dir_all(run.parent().unwrap());
}

/// Reads messages until one of `kind` arrives; returns it.
async fn next_of(
    ws: &mut (impl StreamExt<Item = Result<Message, tokio_tungstenite::tungstenite::Error>> + Unpin),
    kind: &str,
) -> serde_json::Value {
    loop {
        let m = ws.next().await.expect("socket open").expect("message");
        if let Message::Text(t) = m {
            let v: serde_json::Value = serde_json::from_str(t.as_str()).unwrap();
            if v["type"] == kind {
                return v;
            }
        }
    }
}

#[test]
fn hostile_messages_get_an_error_reply_and_the_server_lives_on() {
    let run = small_run("view-hostile", 2);
    let v = Viewer::start(&[run.as_os_str(), "--max-viewers".as_ref(), "1".as_ref()]);
    let url = v.ws_url();
    let rt = tokio::runtime::Runtime::new().unwrap();
    rt.block_on(async {
        let mut ws = v.connect().await;
        let frame = next_of(&mut ws, "frame").await;
        assert_eq!(frame["robots"].as_array().unwrap().len(), 5);
        // A second page is refused while the only slot is taken.
        assert!(
            tokio_tungstenite::connect_async(url.as_str())
                .await
                .is_err()
        );
        let huge = "x".repeat(1 << 20);
        for bad in [
            "not json",
            "{\"type\":\"resolution\",\"sensors\":\"99999x99999\",\"neurons\":\"3x3\"}",
            "{\"type\":\"drag\",\"robot\":0,\"x\":1e999,\"y\":0}",
            "{\"type\":\"scenario\",\"index\":-1}",
            "{\"type\":\"controller\",\"which\":{\"$gt\":1}}",
            "{\"type\":\"step\",\"n\":0}",
        ] {
            ws.send(Message::Text(bad.into())).await.unwrap();
            let e = next_of(&mut ws, "error").await;
            assert!(!e["message"].as_str().unwrap().is_empty(), "{bad}");
        }
        ws.send(Message::Binary(vec![0u8; 16].into()))
            .await
            .unwrap();
        next_of(&mut ws, "error").await;
        // Still simulating: a valid command is obeyed.
        ws.send(Message::Text("{\"type\":\"step\",\"n\":3}".into()))
            .await
            .unwrap();
        // Frames sent before the step was read may still be on the way (seen
        // under CI load); the step's own pauses the page within a few frames.
        let mut f = next_of(&mut ws, "frame").await;
        for _ in 0..20 {
            if f["playing"] == false {
                break;
            }
            f = next_of(&mut ws, "frame").await;
        }
        assert_eq!(f["playing"], false);
        // An oversized message closes that page's connection, not the server.
        let _ = ws.send(Message::Text(huge.into())).await;
        while let Some(Ok(m)) = ws.next().await {
            if matches!(m, Message::Close(_)) {
                break;
            }
        }
        drop(ws);
        // The closed page's slot comes free (its simulation has stopped).
        let mut again = None;
        for _ in 0..100 {
            if let Ok((ws, _)) = tokio_tungstenite::connect_async(url.as_str()).await {
                again = Some(ws);
                break;
            }
            tokio::time::sleep(std::time::Duration::from_millis(50)).await;
        }
        let mut ws = again.expect("a new page is served once the old one closed");
        next_of(&mut ws, "frame").await;
    });
    assert_eq!(http(v.port, "GET", "/", None).status, 200);
    let _ = std::fs::remove_dir_all(run.parent().unwrap());
}

#[test]
fn a_port_in_use_is_one_line_and_exit_2() {
    let taken = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let port = taken.local_addr().unwrap().port().to_string();
    let out = vivae().args(["view", "--port", &port]).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(err.contains("port already in use"), "{err}");
}

#[test]
fn bad_sources_are_one_line_and_exit_2() {
    let dir = scratch("view-bad");
    let junk = dir.join("junk.json");
    std::fs::write(&junk, "{\"format\":").unwrap();
    for arg in [dir.join("missing.svg"), junk, dir.to_path_buf()] {
        let out = vivae().arg("view").arg(&arg).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{}", arg.display());
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Starts `vivae view --host HOST --port 0`, reads its URL line, stops it:
/// (the URL line, everything it said on stderr before serving).
fn said_on_start(host: &str) -> (String, String) {
    use std::io::{BufRead, BufReader, Read};
    let mut child = vivae()
        .args(["view", "--host", host, "--port", "0"])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut url = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut url)
        .unwrap();
    // Everything said before serving is said by now: stop it, read stderr.
    let _ = child.kill();
    let _ = child.wait();
    let mut err = String::new();
    let _ = child.stderr.take().unwrap().read_to_string(&mut err);
    (url, err)
}

#[test]
fn listening_beyond_loopback_warns_that_the_network_can_watch() {
    // Listening on all interfaces; the test itself talks only to 127.0.0.1.
    let (url, err) = said_on_start("0.0.0.0");
    assert!(err.starts_with("warning:"), "{err}");
    assert!(err.contains("anyone"), "{err}");
    assert!(url.starts_with("vivae view: http://127.0.0.1:"), "{url}");
}

/// `::ffff:127.0.0.1` (IPv4 loopback written as an IPv4-mapped IPv6
/// address) is loopback: no warning that the network can watch (issue 24).
#[test]
fn a_mapped_loopback_address_gets_no_network_warning() {
    let (url, err) = said_on_start("::ffff:127.0.0.1");
    assert!(url.starts_with("vivae view: http://"), "{url} {err}");
    assert!(!err.contains("warning"), "{err}");
    assert!(!err.contains("anyone"), "{err}");
}

#[test]
fn another_site_cannot_open_the_websocket() {
    use tokio_tungstenite::tungstenite::client::IntoClientRequest;
    let v = Viewer::start(&[]);
    let url = v.ws_url();
    let rt = tokio::runtime::Runtime::new().unwrap();
    rt.block_on(async {
        let mut foreign = url.as_str().into_client_request().unwrap();
        foreign
            .headers_mut()
            .insert("Origin", "http://evil.example".parse().unwrap());
        assert!(tokio_tungstenite::connect_async(foreign).await.is_err());
        let mut own = url.as_str().into_client_request().unwrap();
        let origin = format!("http://127.0.0.1:{}", v.port);
        own.headers_mut().insert("Origin", origin.parse().unwrap());
        let (mut ws, _) = tokio_tungstenite::connect_async(own).await.unwrap();
        next_of(&mut ws, "frame").await;
    });
}

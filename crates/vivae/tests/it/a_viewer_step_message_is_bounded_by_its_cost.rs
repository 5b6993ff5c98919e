//! One `step` message to `vivae view` may ask for only about a second of
//! work at the page's resolution: at the highest resolution a huge step
//! count is refused with an error reply naming the limit (it used to run
//! for minutes, and on after the page closed); a small one is obeyed.

use crate::common::browser::Viewer;
use futures_util::{SinkExt, StreamExt};
use std::time::Duration;
use tokio_tungstenite::tungstenite::Message;

/// The next message of one of `kinds` (bounded wait, so a busy server fails the test).
async fn next_of(
    ws: &mut (impl StreamExt<Item = Result<Message, tokio_tungstenite::tungstenite::Error>> + Unpin),
    kinds: &[&str],
) -> serde_json::Value {
    let wait = async {
        loop {
            let m = ws.next().await.expect("socket open").expect("message");
            if let Message::Text(t) = m {
                let v: serde_json::Value = serde_json::from_str(t.as_str()).unwrap();
                if kinds.iter().any(|k| v["type"] == *k) {
                    return v;
                }
            }
        }
    };
    tokio::time::timeout(Duration::from_secs(120), wait)
        .await
        .unwrap_or_else(|_| panic!("no {kinds:?} message from the viewer"))
}

#[test]
fn a_huge_step_at_high_resolution_gets_an_error_reply() {
    let v = Viewer::start(&[]);
    let rt = tokio::runtime::Runtime::new().unwrap();
    rt.block_on(async {
        let mut ws = v.connect().await;
        next_of(&mut ws, &["frame"]).await;
        let high = r#"{"type":"resolution","sensors":"64x128","neurons":"20x20"}"#;
        ws.send(Message::Text(high.into())).await.unwrap();
        let scene = next_of(&mut ws, &["scene", "error"]).await;
        assert_eq!(scene["type"], "scene", "{}", scene["message"]);
        assert_eq!(scene["sensors"], "64x128");
        // Paused, so frames come only in answer to messages.
        ws.send(Message::Text(r#"{"type":"pause"}"#.into()))
            .await
            .unwrap();
        ws.send(Message::Text(r#"{"type":"step","n":10000}"#.into()))
            .await
            .unwrap();
        let message = loop {
            let reply = next_of(&mut ws, &["error", "frame"]).await;
            if reply["type"] == "error" {
                break reply["message"].as_str().unwrap().to_string();
            }
            let step = reply["step"].as_u64().unwrap();
            assert!(step < 10_000, "a huge step was obeyed (now at step {step})");
        };
        assert!(message.contains("at most"), "{message}");
        // A step within the limit is still obeyed.
        ws.send(Message::Text(r#"{"type":"step","n":1}"#.into()))
            .await
            .unwrap();
        let frame = next_of(&mut ws, &["frame", "error"]).await;
        assert_eq!(frame["type"], "frame", "{}", frame["message"]);
    });
}

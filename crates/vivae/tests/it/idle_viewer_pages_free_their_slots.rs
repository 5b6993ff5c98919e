//! `vivae view` drops pages that have been silent past its idle timeout (no
//! message, not even the answer to its pings), so silent clients cannot hold
//! every viewer slot: after the (here shortened) timeout a new page connects.

use crate::common::browser::Viewer;
use std::time::Duration;

#[test]
fn silent_pages_lose_their_slots_after_the_idle_timeout() {
    let v = Viewer::start(&[
        "--max-viewers".as_ref(),
        "2".as_ref(),
        "--idle-timeout".as_ref(),
        "1".as_ref(),
    ]);
    let url = format!("ws://127.0.0.1:{}/ws", v.port);
    let rt = tokio::runtime::Runtime::new().unwrap();
    rt.block_on(async {
        // Connected, then never read from nor written to.
        let mut silent = Vec::new();
        for _ in 0..2 {
            let (ws, _) = tokio_tungstenite::connect_async(url.as_str())
                .await
                .expect("a free slot");
            silent.push(ws);
        }
        assert!(
            tokio_tungstenite::connect_async(url.as_str())
                .await
                .is_err(),
            "every slot is taken"
        );
        // Bounded wait (not a timing assertion): the slots come free.
        let mut page = None;
        for _ in 0..300 {
            tokio::time::sleep(Duration::from_millis(100)).await;
            if let Ok((ws, _)) = tokio_tungstenite::connect_async(url.as_str()).await {
                page = Some(ws);
                break;
            }
        }
        assert!(page.is_some(), "silent pages still hold every slot");
        drop(silent);
    });
}

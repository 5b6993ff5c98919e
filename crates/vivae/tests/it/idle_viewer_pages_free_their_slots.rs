//! `vivae view` drops pages that have been silent past its idle timeout (no
//! message, not even the answer to its pings), so silent clients cannot hold
//! every viewer slot: after the (here shortened) timeout a new page connects.
//! Pages beyond the limit are refused with 503 until one closes.

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
    let url = v.ws_url();
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

/// The HTTP status a refused WebSocket request got (0 if it was not an HTTP refusal).
fn refusal_status(e: tokio_tungstenite::tungstenite::Error) -> u16 {
    match e {
        tokio_tungstenite::tungstenite::Error::Http(response) => response.status().as_u16(),
        _ => 0,
    }
}

#[test]
fn pages_beyond_the_limit_get_503_until_one_closes() {
    let v = Viewer::start(&[]);
    let url = v.ws_url();
    let rt = tokio::runtime::Runtime::new().unwrap();
    rt.block_on(async {
        // The default limit: 8 pages at once.
        let mut pages = Vec::new();
        for _ in 0..8 {
            let (ws, _) = tokio_tungstenite::connect_async(url.as_str())
                .await
                .expect("a free slot");
            pages.push(ws);
        }
        for k in 9..=40 {
            let refused = tokio_tungstenite::connect_async(url.as_str()).await;
            let status = refused.map(|_| 101).unwrap_or_else(refusal_status);
            assert_eq!(status, 503, "page {k} was not refused with 503");
        }
        // A page that closes frees its slot (bounded wait, not a timing assertion).
        drop(pages.pop());
        let mut page = None;
        for _ in 0..300 {
            if let Ok((ws, _)) = tokio_tungstenite::connect_async(url.as_str()).await {
                page = Some(ws);
                break;
            }
            tokio::time::sleep(Duration::from_millis(100)).await;
        }
        assert!(page.is_some(), "a closed page's slot was never freed");
    });
}

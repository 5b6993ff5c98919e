//! `vivae view` answers only Host names it knows (issue 24: DNS rebinding):
//! its own address, `localhost`, and names given with `--allow-host`. Any
//! other name gets 403, on plain HTTP and on the WebSocket upgrade, so that a
//! rebinding page naming its own site can neither read the run nor drive robots.

use std::io::{Read, Write};
use std::net::TcpStream;

use crate::common::browser::Viewer;
use crate::common::{evolve, scratch, write_small_config};

/// Sends one raw request (`GET target`, the given Host, extra header lines)
/// and returns the status code of the answer.
fn status(port: u16, host: Option<&str>, target: &str, extra: &str) -> u16 {
    let mut s = TcpStream::connect(("127.0.0.1", port)).unwrap();
    let host = host.map_or(String::new(), |h| format!("Host: {h}\r\n"));
    let req = format!("GET {target} HTTP/1.1\r\n{host}{extra}Connection: close\r\n\r\n");
    s.write_all(req.as_bytes()).unwrap();
    let mut head = Vec::new();
    let mut b = [0u8; 1];
    while !head.ends_with(b"\r\n") && s.read(&mut b).unwrap() == 1 {
        head.push(b[0]);
    }
    let line = String::from_utf8_lossy(&head).into_owned();
    line.split_whitespace()
        .nth(1)
        .and_then(|c| c.parse().ok())
        .unwrap_or_else(|| panic!("no status in {line:?}"))
}

const UPGRADE: &str = "Upgrade: websocket\r\nConnection: Upgrade\r\nSec-WebSocket-Version: 13\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n";

#[test]
fn foreign_host_names_are_refused_on_http_and_websocket() {
    let dir = scratch("view-hosts");
    let config = write_small_config(&dir, 1);
    let run = dir.join("run");
    evolve(&config, &run, &[]);
    let v = Viewer::start(&[
        run.as_os_str(),
        "--allow-host".as_ref(),
        "mybox.lan".as_ref(),
    ]);
    let own = format!("127.0.0.1:{}", v.port);
    for host in [
        own.as_str(),
        "127.0.0.1",
        "localhost",
        "localhost:7878",
        "mybox.lan:7878",
    ] {
        assert_eq!(
            status(v.port, Some(host), "/run/config.toml", ""),
            200,
            "{host}"
        );
    }
    for host in [
        "evil.example:7878",
        "evil.example",
        "127.0.0.1.evil.example",
        "localhost.evil.example:7878",
        "10.1.2.3:7878",
    ] {
        for target in ["/run/config.toml", "/", "/assets/view.js", "/nowhere"] {
            assert_eq!(
                status(v.port, Some(host), target, ""),
                403,
                "{host} {target}"
            );
        }
        assert_eq!(
            status(v.port, Some(host), "/ws", UPGRADE),
            403,
            "{host} /ws"
        );
    }
    // Without any Host header (HTTP/1.1 requires one) nothing is served either.
    assert_eq!(status(v.port, None, "/run/config.toml", ""), 403);
    // The WebSocket still opens for the server's own name.
    assert_eq!(status(v.port, Some(&own), "/ws", UPGRADE), 101);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_port_in_an_allowed_name_is_one_line_and_exit_2() {
    let out = crate::common::vivae()
        .args(["view", "--port", "0", "--allow-host", "mybox.lan:80"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(err.contains("--allow-host"), "{err}");
}

//! `vivae view --host ::ffff:127.0.0.1` (IPv4 loopback, written as an
//! IPv4-mapped IPv6 address) is loopback: no warning that the network can
//! watch (issue 24). The warning for a real network address is tested in
//! `viewer_serves_only_its_own_files`.

use std::io::{BufRead, BufReader, Read};

use crate::common::vivae;

#[test]
fn a_mapped_loopback_address_gets_no_network_warning() {
    let mut child = vivae()
        .args(["view", "--host", "::ffff:127.0.0.1", "--port", "0"])
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
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut err)
        .unwrap();
    assert!(url.starts_with("vivae view: http://"), "{url} {err}");
    assert!(!err.contains("warning"), "{err}");
    assert!(!err.contains("anyone"), "{err}");
}

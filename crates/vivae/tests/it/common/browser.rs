//! A real headless Chromium driven over WebDriver (chromedriver), plus a tiny
//! HTTP/1.1 client: all the browser tests need, with no extra crate.
//!
//! Chromium and chromedriver come from Debian (`apt-get install chromium
//! chromium-driver`, which `.ci/run` does). Where they are missing the browser
//! tests print a one-line SKIPPED note and pass without running: see [`Browser::start`].
#![allow(dead_code)]

use std::io::{Read, Write};
use std::net::{TcpListener, TcpStream};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::Duration;

use serde_json::{Value, json};

/// How long to keep polling a page for a condition before failing (a safety cap, not a speed test).
pub const PATIENCE: Duration = Duration::from_secs(180);

/// An HTTP response: status and body.
pub struct HttpResponse {
    /// Status code.
    pub status: u16,
    /// Body bytes (de-chunked).
    pub body: Vec<u8>,
}

/// Sends one raw HTTP/1.1 request (the target is sent exactly as given, unnormalised).
pub fn http(port: u16, method: &str, target: &str, body: Option<&str>) -> HttpResponse {
    try_http(port, method, target, body).expect("HTTP exchange")
}

/// [`http`], but a refused or broken connection is an error instead of a panic.
pub fn try_http(
    port: u16,
    method: &str,
    target: &str,
    body: Option<&str>,
) -> std::io::Result<HttpResponse> {
    let broken =
        |what: &str| std::io::Error::new(std::io::ErrorKind::UnexpectedEof, what.to_string());
    // A signal to the test process (other tests start and stop children)
    // interrupts a blocking read, which `read` reports instead of retrying.
    let read = |s: &mut TcpStream, buf: &mut [u8]| loop {
        match s.read(buf) {
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
            other => break other,
        }
    };
    let mut s = TcpStream::connect(("127.0.0.1", port))?;
    s.set_read_timeout(Some(PATIENCE))?;
    let body = body.unwrap_or("");
    let req = format!(
        "{method} {target} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nConnection: close\r\nContent-Type: application/json\r\nContent-Length: {}\r\n\r\n{body}",
        body.len()
    );
    s.write_all(req.as_bytes())?;
    // Read the head, then exactly the body it announces: a keep-alive server
    // (chromedriver) may not close the connection.
    let mut raw = Vec::new();
    let mut buf = [0u8; 8192];
    let split = loop {
        if let Some(p) = raw.windows(4).position(|w| w == b"\r\n\r\n") {
            break p;
        }
        let n = read(&mut s, &mut buf)?;
        if n == 0 {
            return Err(broken("connection closed before the HTTP head ended"));
        }
        raw.extend_from_slice(&buf[..n]);
    };
    let head = String::from_utf8_lossy(&raw[..split]).to_ascii_lowercase();
    let mut payload = raw[split + 4..].to_vec();
    let status: u16 = head
        .split_whitespace()
        .nth(1)
        .and_then(|c| c.parse().ok())
        .ok_or_else(|| broken("no status code"))?;
    let length = head
        .lines()
        .find_map(|l| l.strip_prefix("content-length:"))
        .and_then(|v| v.trim().parse::<usize>().ok());
    let chunked = head.contains("transfer-encoding: chunked");
    loop {
        let done = match length {
            Some(n) => payload.len() >= n,
            None if chunked => payload.windows(5).any(|w| w == b"0\r\n\r\n"),
            None => false,
        };
        if done {
            break;
        }
        let n = read(&mut s, &mut buf)?;
        if n == 0 {
            break;
        }
        payload.extend_from_slice(&buf[..n]);
    }
    if chunked {
        payload = dechunk(&payload);
    }
    Ok(HttpResponse {
        status,
        body: payload,
    })
}

fn dechunk(mut data: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    loop {
        let Some(eol) = data.windows(2).position(|w| w == b"\r\n") else {
            return out;
        };
        let size_text = String::from_utf8_lossy(&data[..eol]);
        let size =
            usize::from_str_radix(size_text.split(';').next().unwrap().trim(), 16).unwrap_or(0);
        if size == 0 {
            return out;
        }
        let start = eol + 2;
        out.extend_from_slice(&data[start..start + size]);
        data = &data[start + size + 2..];
    }
}

/// Decodes standard base64 (screenshots).
pub fn base64_decode(text: &str) -> Vec<u8> {
    let val = |c: u8| -> Option<u32> {
        Some(match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' => 62,
            b'/' => 63,
            _ => return None,
        } as u32)
    };
    let mut out = Vec::with_capacity(text.len() * 3 / 4);
    let (mut acc, mut bits) = (0u32, 0);
    for v in text.bytes().filter_map(val) {
        acc = (acc << 6) | v;
        bits += 6;
        if bits >= 8 {
            bits -= 8;
            out.push((acc >> bits) as u8);
        }
    }
    out
}

/// A free TCP port on the loopback interface.
pub fn free_port() -> u16 {
    TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port()
}

fn which(name: &str) -> Option<PathBuf> {
    std::env::var_os("PATH").and_then(|paths| {
        std::env::split_paths(&paths)
            .map(|d| d.join(name))
            .find(|p| p.is_file())
    })
}

/// A headless Chromium session.
pub struct Browser {
    driver: Child,
    port: u16,
    session: String,
    profile: PathBuf,
}

impl Browser {
    /// Starts chromedriver and a fresh headless Chromium; `None` (with a one-line
    /// SKIPPED note on stderr) where either is not installed. Extra Chromium flags in `extra`.
    pub fn start(extra: &[&str]) -> Option<Browser> {
        let chromium = ["chromium", "chromium-browser", "google-chrome"]
            .iter()
            .find_map(|n| which(n));
        let driver = which("chromedriver");
        let (Some(chromium), Some(driver)) = (chromium, driver) else {
            // CI installs the browser (.ci/run): there a missing one is a failure.
            assert!(
                std::env::var("CI").as_deref() != Ok("true"),
                "CI=true but chromium or chromedriver is missing (.ci/run installs them)"
            );
            crate::common::skipped(
                "browser test needs chromium and chromedriver (apt-get install chromium chromium-driver); .ci/run installs them",
            );
            return None;
        };
        let mut args: Vec<String> = [
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--disable-dev-shm-usage",
            "--window-size=1400,1100",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        args.extend(extra.iter().map(|s| s.to_string()));
        // The port comes from a listener that is closed before chromedriver
        // binds it, so another test's chromedriver or Chromium may take it in
        // between (then our driver exits, or our requests reach a stranger):
        // such a start is abandoned and retried on a fresh port.
        let mut last_failure = String::new();
        for _ in 0..8 {
            match Self::try_start(&chromium, &driver, &args) {
                Ok(browser) => return Some(browser),
                Err(why) => last_failure = why,
            }
        }
        panic!("could not start chromedriver with a session: {last_failure}");
    }

    /// One attempt at a driver on a fresh port with one session.
    fn try_start(chromium: &Path, driver: &Path, args: &[String]) -> Result<Browser, String> {
        let port = free_port();
        let profile =
            std::env::temp_dir().join(format!("vivae-chromium-{}-{port}", std::process::id()));
        let _ = std::fs::remove_dir_all(&profile);
        // Chromium makes its own `org.chromium.Chromium.scoped_dir.*` in
        // TMPDIR and leaves them when the session ends: inside the profile,
        // they go with it.
        let tmp = profile.join("tmp");
        std::fs::create_dir_all(&tmp).expect("a scratch directory for Chromium");
        let child = Command::new(driver)
            .arg(format!("--port={port}"))
            .env("TMPDIR", &tmp)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("chromedriver starts");
        // Dropping `browser` on any failure below kills this driver.
        let mut browser = Browser {
            driver: child,
            port,
            session: String::new(),
            profile: profile.clone(),
        };
        // Ready only when *our* driver is alive and its /status says so.
        let mut up = false;
        for _ in 0..200 {
            if let Ok(Some(status)) = browser.driver.try_wait() {
                return Err(format!("chromedriver on port {port} exited: {status}"));
            }
            if let Ok(r) = try_http(port, "GET", "/status", None) {
                let v: Value = serde_json::from_slice(&r.body).unwrap_or(Value::Null);
                if v["value"]["ready"] == Value::Bool(true) {
                    up = true;
                    break;
                }
            }
            std::thread::sleep(Duration::from_millis(100));
        }
        if !up {
            return Err(format!("chromedriver on port {port} never became ready"));
        }
        let mut args = args.to_vec();
        args.push(format!("--user-data-dir={}", profile.display()));
        let caps = json!({
            "capabilities": {
                "alwaysMatch": {
                    "browserName": "chrome",
                    "goog:chromeOptions": {
                        "binary": chromium.to_string_lossy(),
                        "args": args,
                    },
                    "goog:loggingPrefs": { "browser": "ALL" },
                }
            }
        });
        let r = try_http(port, "POST", "/session", Some(&caps.to_string()))
            .map_err(|e| format!("POST /session on port {port}: {e}"))?;
        let v: Value = serde_json::from_slice(&r.body).unwrap_or(Value::Null);
        match v["value"]["sessionId"].as_str() {
            Some(id) if r.status == 200 => {
                browser.session = id.to_string();
                Ok(browser)
            }
            _ => Err(format!(
                "no WebDriver session on port {port}: {}",
                String::from_utf8_lossy(&r.body)
            )),
        }
    }

    /// One WebDriver command; returns its `value`, panicking on a WebDriver error.
    pub fn call(&self, method: &str, path: &str, body: Option<Value>) -> Value {
        let text = body.map(|b| b.to_string());
        let r = http(self.port, method, path, text.as_deref());
        let v: Value = serde_json::from_slice(&r.body)
            .unwrap_or_else(|_| panic!("WebDriver answer: {}", String::from_utf8_lossy(&r.body)));
        assert!(r.status == 200, "WebDriver {method} {path}: {v}");
        v["value"].clone()
    }

    pub fn at(&self, rest: &str) -> String {
        format!("/session/{}{rest}", self.session)
    }

    /// Opens `url` and waits for it to load.
    pub fn goto(&self, url: &str) {
        self.call("POST", &self.at("/url"), Some(json!({ "url": url })));
    }

    /// Runs `script` (a function body; `return` gives the value) in the page.
    pub fn eval(&self, script: &str) -> Value {
        self.call(
            "POST",
            &self.at("/execute/sync"),
            Some(json!({ "script": script, "args": [] })),
        )
    }

    /// Polls `script` until it returns `true`; panics after [`PATIENCE`] with `what`.
    pub fn wait_for(&self, script: &str, what: &str) {
        let start = std::time::Instant::now();
        while start.elapsed() < PATIENCE {
            if self.eval(script) == Value::Bool(true) {
                return;
            }
            std::thread::sleep(Duration::from_millis(100));
        }
        panic!("the page never got to: {what}");
    }

    /// A PNG screenshot of the window.
    pub fn screenshot(&self) -> Vec<u8> {
        let v = self.call("GET", &self.at("/screenshot"), None);
        base64_decode(v.as_str().expect("base64 screenshot"))
    }

    /// Saves a screenshot to `path` (folders created) and returns its bytes.
    pub fn save_screenshot(&self, path: &Path) -> Vec<u8> {
        let png = self.screenshot();
        if let Some(d) = path.parent() {
            std::fs::create_dir_all(d).unwrap();
        }
        std::fs::write(path, &png).unwrap();
        png
    }

    /// Console messages of level SEVERE (errors) since the last call.
    pub fn console_errors(&self) -> Vec<String> {
        let v = self.call(
            "POST",
            &self.at("/se/log"),
            Some(json!({ "type": "browser" })),
        );
        v.as_array()
            .map(|a| {
                a.iter()
                    .filter(|e| e["level"] == "SEVERE")
                    .map(|e| e["message"].as_str().unwrap_or_default().to_string())
                    .collect()
            })
            .unwrap_or_default()
    }
}

impl Browser {
    /// Presses (`keyDown`) or releases (`keyUp`) WebDriver key `key` (e.g.
    /// `"\u{E013}"`, the up arrow) on whatever has the focus.
    pub fn key(&self, kind: &str, key: &str) {
        self.call(
            "POST",
            &self.at("/actions"),
            Some(json!({"actions": [{"type": "key", "id": "kb", "actions": [
                {"type": kind, "value": key}
            ]}]})),
        );
    }

    /// Drags with the mouse on the viewer's arena canvas from world point
    /// `from` to world point `to` (arena px).
    pub fn drag_on_scene(&self, from: (f64, f64), to: (f64, f64)) {
        let el = self.call(
            "POST",
            &self.at("/element"),
            Some(json!({"using": "css selector", "value": "#scene"})),
        );
        let id = el
            .as_object()
            .and_then(|o| o.values().next())
            .and_then(|v| v.as_str())
            .unwrap()
            .to_string();
        let geom = self.eval(
            "var r = document.getElementById('scene').getBoundingClientRect();
             var c = document.getElementById('scene');
             return [r.width / c.width, r.height / c.height, r.width, r.height];",
        );
        let (sx, sy) = (geom[0].as_f64().unwrap(), geom[1].as_f64().unwrap());
        let (w, h) = (geom[2].as_f64().unwrap(), geom[3].as_f64().unwrap());
        // Pointer offsets are from the element's centre.
        let at = |(x, y): (f64, f64)| ((x * sx - w / 2.0).round(), (y * sy - h / 2.0).round());
        let ((x0, y0), (x1, y1)) = (at(from), at(to));
        let origin = json!({"element-6066-11e4-a52e-4f735466cecf": id});
        self.call(
            "POST",
            &self.at("/actions"),
            Some(json!({"actions": [{"type": "pointer", "id": "mouse",
                "parameters": {"pointerType": "mouse"}, "actions": [
                {"type": "pointerMove", "origin": origin, "x": x0, "y": y0},
                {"type": "pointerDown", "button": 0},
                {"type": "pointerMove", "origin": origin, "x": x1, "y": y1, "duration": 200},
                {"type": "pointerUp", "button": 0}
            ]}]})),
        );
    }
}

/// Where browser tests leave their screenshots (to look at).
pub fn shots() -> PathBuf {
    PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("browser-screenshots")
}

impl Drop for Browser {
    fn drop(&mut self) {
        if !self.session.is_empty() {
            let _ = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                let _ = http(self.port, "DELETE", &self.at(""), None);
            }));
        }
        let _ = self.driver.kill();
        let _ = self.driver.wait();
        let _ = std::fs::remove_dir_all(&self.profile);
    }
}

/// A running `vivae view`, stopped when dropped.
pub struct Viewer {
    child: Child,
    /// The page's URL.
    pub url: String,
    /// Its port.
    pub port: u16,
}

impl Viewer {
    /// Starts `vivae view ARGS --port 0` and reads the URL it prints.
    pub fn start(args: &[&std::ffi::OsStr]) -> Viewer {
        let mut child = crate::common::vivae()
            .arg("view")
            .args(args)
            .args(["--port", "0"])
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("vivae view starts");
        let mut out = child.stdout.take().unwrap();
        let mut line = Vec::new();
        let mut b = [0u8; 1];
        // `read_exact` retries a read that a signal interrupted.
        while out.read_exact(&mut b).is_ok() && b[0] != b'\n' {
            line.push(b[0]);
        }
        let line = String::from_utf8(line).unwrap();
        let url = line
            .strip_prefix("vivae view: ")
            .unwrap_or_else(|| panic!("unexpected first line {line:?}"))
            .trim()
            .to_string();
        let port = url
            .trim_end_matches('/')
            .rsplit(':')
            .next()
            .unwrap()
            .parse()
            .unwrap();
        Viewer { child, url, port }
    }

    /// The viewer's WebSocket address.
    pub fn ws_url(&self) -> String {
        format!("ws://127.0.0.1:{}/ws", self.port)
    }

    /// Opens a page's WebSocket to the viewer.
    pub async fn connect(
        &self,
    ) -> tokio_tungstenite::WebSocketStream<tokio_tungstenite::MaybeTlsStream<tokio::net::TcpStream>>
    {
        tokio_tungstenite::connect_async(self.ws_url().as_str())
            .await
            .expect("the viewer accepts a WebSocket")
            .0
    }
}

impl Drop for Viewer {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

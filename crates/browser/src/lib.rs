//! Headless Chromium, driven over the DevTools protocol on a pipe.
//!
//! Chromium's `--remote-debugging-pipe` reads protocol messages (JSON, each
//! ended by a NUL byte) on file descriptor 3 and writes its answers and
//! events on descriptor 4. [`Browser::launch`] starts the distribution's
//! `chromium` through `sh`, which gives it our stdin as descriptor 3 and our
//! stdout as descriptor 4, so no socket, no port and no crate beyond
//! `serde_json` is needed. What the tests and `cargo xtask figures` use:
//! open a page, evaluate JavaScript in it (awaiting promises), collect the
//! page's console errors and uncaught exceptions, and take a PNG screenshot.
//!
//! This crate is a development tool: the product never starts a browser.
//! Every wait has a deadline ([`TIMEOUT`]), every error is a `String`, and
//! the browser is closed (then killed) when the [`Browser`] is dropped.
//!
//! Its files:
//! * `base64.rs`: Standard base64 (RFC 4648, with padding) decoding, for screenshots.

use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError};
use std::time::{Duration, Instant};

use serde_json::{json, Value};

mod base64;

/// The longest wait for one protocol answer or event.
pub const TIMEOUT: Duration = Duration::from_secs(60);

/// The largest protocol message read (a screenshot is a few MB of base64).
const MAX_MESSAGE_BYTES: usize = 256 << 20;

/// The most events kept between two reads of them (older ones are dropped).
const MAX_EVENTS: usize = 10_000;

/// The Chromium executable: `$CHROMIUM` if set, else the first of
/// `chromium`, `chromium-browser`, `google-chrome` on `PATH`.
pub fn find() -> Option<PathBuf> {
    if let Some(path) = std::env::var_os("CHROMIUM").filter(|p| !p.is_empty()) {
        let path = PathBuf::from(path);
        return path.is_file().then_some(path);
    }
    let dirs = std::env::var_os("PATH")?;
    ["chromium", "chromium-browser", "google-chrome"]
        .iter()
        .flat_map(|name| std::env::split_paths(&dirs).map(move |d| d.join(name)))
        .find(|p| p.is_file())
}

/// A PNG screenshot of the page `html` (its text) at `width` x `height`
/// CSS pixels, after evaluating `script` in it: the page is written to a
/// scratch folder named after `tag` (removed afterwards), and a page that
/// logs a console error or throws is an error listing them.
pub fn screenshot_page(
    chromium: &Path,
    tag: &str,
    html: &str,
    (width, height): (u32, u32),
    script: &str,
) -> Result<Vec<u8>, String> {
    let scratch = std::env::temp_dir().join(format!("falling-chain-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&scratch).map_err(|e| format!("{}: {e}", scratch.display()))?;
    let page = scratch.join("page.html");
    let shot = std::fs::write(&page, html)
        .map_err(|e| format!("{}: {e}", page.display()))
        .and_then(|()| {
            let mut b = Browser::launch(chromium, &scratch, width, height)?;
            b.open(&page)?;
            b.eval(script)?;
            let errors = b.errors();
            if !errors.is_empty() {
                return Err(format!("the page logged errors: {errors:?}"));
            }
            b.screenshot()
        });
    let _ = std::fs::remove_dir_all(&scratch);
    shot
}

/// One headless Chromium with one page attached.
pub struct Browser {
    child: Child,
    commands: ChildStdin,
    messages: Receiver<Value>,
    next_id: u64,
    session: String,
    events: Vec<Value>,
    profile: PathBuf,
}

impl Browser {
    /// Starts `chromium` headless with a fresh profile under `scratch` and a
    /// `width` x `height` CSS-pixel page at device scale 1.
    pub fn launch(
        chromium: &Path,
        scratch: &Path,
        width: u32,
        height: u32,
    ) -> Result<Self, String> {
        let profile = scratch.join(format!("chromium-profile-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&profile);
        std::fs::create_dir_all(&profile)
            .map_err(|e| format!("cannot make '{}': {e}", profile.display()))?;
        // Descriptor 3 := our pipe into its stdin, 4 := its stdout to us.
        let mut child = Command::new("sh")
            .arg("-c")
            .arg(r#"exec "$0" "$@" 3<&0 4>&1 0</dev/null 1>/dev/null"#)
            .arg(chromium)
            .args([
                "--headless",
                "--no-sandbox",
                "--disable-gpu",
                "--no-first-run",
                "--no-default-browser-check",
                "--disable-extensions",
                "--disable-background-networking",
                "--disable-component-update",
                "--disable-sync",
                "--hide-scrollbars",
                "--mute-audio",
                "--force-device-scale-factor=1",
                "--remote-debugging-pipe",
            ])
            .arg(format!("--user-data-dir={}", profile.display()))
            .arg(format!("--window-size={width},{height}"))
            .arg("about:blank")
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .map_err(|e| format!("cannot start '{}': {e}", chromium.display()))?;
        let (Some(commands), Some(out)) = (child.stdin.take(), child.stdout.take()) else {
            let _ = child.kill();
            return Err("chromium's pipes were not opened".into());
        };
        let (tx, messages) = mpsc::channel();
        std::thread::spawn(move || read_messages(out, &tx));
        let mut browser = Self {
            child,
            commands,
            messages,
            next_id: 0,
            session: String::new(),
            events: Vec::new(),
            profile,
        };
        let target = browser.call("Target.createTarget", json!({ "url": "about:blank" }))?;
        let target_id = target["targetId"].clone();
        let attached = browser.call(
            "Target.attachToTarget",
            json!({ "targetId": target_id, "flatten": true }),
        )?;
        browser.session = attached["sessionId"]
            .as_str()
            .ok_or("Target.attachToTarget gave no sessionId")?
            .to_string();
        for method in ["Page.enable", "Runtime.enable", "Log.enable"] {
            browser.call(method, json!({}))?;
        }
        browser.call(
            "Emulation.setDeviceMetricsOverride",
            json!({ "width": width, "height": height, "deviceScaleFactor": 1, "mobile": false }),
        )?;
        Ok(browser)
    }

    /// Sends one command (to the page once attached) and waits for its
    /// answer; events that arrive meanwhile are kept for [`Self::errors`].
    pub fn call(&mut self, method: &str, params: Value) -> Result<Value, String> {
        self.next_id += 1;
        let id = self.next_id;
        let mut message = json!({ "id": id, "method": method, "params": params });
        if !self.session.is_empty() {
            message["sessionId"] = Value::String(self.session.clone());
        }
        let mut bytes = message.to_string().into_bytes();
        bytes.push(0);
        self.commands
            .write_all(&bytes)
            .and_then(|()| self.commands.flush())
            .map_err(|e| format!("{method}: cannot write to chromium: {e}"))?;
        let reply = self.wait_for(method, |m| m["id"].as_u64() == Some(id))?;
        if let Some(error) = reply.get("error") {
            return Err(format!("{method}: {error}"));
        }
        Ok(reply["result"].clone())
    }

    /// Waits for the first message that `wanted` accepts; keeps the others
    /// as events.
    fn wait_for(&mut self, what: &str, wanted: impl Fn(&Value) -> bool) -> Result<Value, String> {
        let deadline = Instant::now() + TIMEOUT;
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            match self.messages.recv_timeout(left) {
                Ok(m) if wanted(&m) => return Ok(m),
                Ok(m) => {
                    if self.events.len() >= MAX_EVENTS {
                        self.events.remove(0);
                    }
                    self.events.push(m);
                }
                Err(RecvTimeoutError::Timeout) => {
                    return Err(format!("{what}: no answer from chromium in {TIMEOUT:?}"))
                }
                Err(RecvTimeoutError::Disconnected) => {
                    return Err(format!("{what}: chromium closed its pipe"))
                }
            }
        }
    }

    /// Opens `path` (a local file) and waits for its load event.
    pub fn open(&mut self, path: &Path) -> Result<(), String> {
        let path = path
            .canonicalize()
            .map_err(|e| format!("cannot open '{}': {e}", path.display()))?;
        let url = format!("file://{}", path.display());
        self.call("Page.navigate", json!({ "url": url }))?;
        self.wait_for("Page.loadEventFired", |m| {
            m["method"] == "Page.loadEventFired"
        })
        .map(|_| ())
    }

    /// Evaluates `expression` in the page (awaiting a promise) and returns
    /// its value as JSON; a thrown exception is an error.
    pub fn eval(&mut self, expression: &str) -> Result<Value, String> {
        let result = self.call(
            "Runtime.evaluate",
            json!({ "expression": expression, "returnByValue": true, "awaitPromise": true }),
        )?;
        if let Some(details) = result.get("exceptionDetails") {
            let text = details["exception"]["description"]
                .as_str()
                .or_else(|| details["text"].as_str())
                .unwrap_or("exception");
            return Err(format!("evaluating a script threw: {text}"));
        }
        Ok(result["result"]["value"].clone())
    }

    /// A PNG of the page's viewport.
    pub fn screenshot(&mut self) -> Result<Vec<u8>, String> {
        let shot = self.call(
            "Page.captureScreenshot",
            json!({ "format": "png", "fromSurface": true }),
        )?;
        let data = shot["data"]
            .as_str()
            .ok_or("Page.captureScreenshot gave no data")?;
        base64::decode(data).ok_or_else(|| "Page.captureScreenshot: bad base64".to_string())
    }

    /// The page printed to PDF: A4 portrait, margins of 18 mm (0.7 in),
    /// backgrounds printed, the page's own `@page` rules honoured, no
    /// browser header or footer.
    pub fn print_pdf(&mut self) -> Result<Vec<u8>, String> {
        let pdf = self.call(
            "Page.printToPDF",
            json!({
                "paperWidth": 8.27, "paperHeight": 11.69,
                "marginTop": 0.7, "marginBottom": 0.7,
                "marginLeft": 0.7, "marginRight": 0.7,
                "printBackground": true, "preferCSSPageSize": true,
                "displayHeaderFooter": false,
            }),
        )?;
        let data = pdf["data"].as_str().ok_or("Page.printToPDF gave no data")?;
        let bytes =
            base64::decode(data).ok_or_else(|| "Page.printToPDF: bad base64".to_string())?;
        if !bytes.starts_with(b"%PDF-") {
            return Err("Page.printToPDF: the answer is not a PDF".into());
        }
        Ok(bytes)
    }

    /// Every console error, failed `console.assert`, uncaught exception and
    /// browser log entry of level error seen so far, one line each.
    pub fn errors(&mut self) -> Vec<String> {
        // Let messages already sent arrive.
        while let Ok(m) = self.messages.recv_timeout(Duration::from_millis(50)) {
            if self.events.len() < MAX_EVENTS {
                self.events.push(m);
            }
        }
        self.events.iter().filter_map(error_line).collect()
    }
}

/// The one-line text of an event that reports an error, if it does.
fn error_line(event: &Value) -> Option<String> {
    let p = &event["params"];
    match event["method"].as_str()? {
        "Runtime.exceptionThrown" => Some(format!(
            "uncaught: {}",
            p["exceptionDetails"]["exception"]["description"]
                .as_str()
                .or_else(|| p["exceptionDetails"]["text"].as_str())
                .unwrap_or("exception")
        )),
        "Runtime.consoleAPICalled" if matches!(p["type"].as_str(), Some("error" | "assert")) => {
            Some(format!("console.{}: {}", p["type"], p["args"]))
        }
        "Log.entryAdded" if p["entry"]["level"] == "error" => {
            Some(format!("log: {}", p["entry"]["text"]))
        }
        _ => None,
    }
}

/// Splits chromium's output into NUL-ended JSON messages until it closes.
fn read_messages(mut out: impl Read, tx: &mpsc::Sender<Value>) {
    let mut pending = Vec::new();
    let mut chunk = vec![0u8; 1 << 16];
    loop {
        let read = match out.read(&mut chunk) {
            Ok(0) | Err(_) => return,
            Ok(k) => k,
        };
        pending.extend_from_slice(&chunk[..read]);
        while let Some(end) = pending.iter().position(|&b| b == 0) {
            let message: Vec<u8> = pending.drain(..=end).collect();
            if let Ok(value) = serde_json::from_slice(&message[..end]) {
                if tx.send(value).is_err() {
                    return;
                }
            }
        }
        if pending.len() > MAX_MESSAGE_BYTES {
            return;
        }
    }
}

impl Drop for Browser {
    fn drop(&mut self) {
        self.session.clear();
        let _ = self.call("Browser.close", json!({}));
        let deadline = Instant::now() + Duration::from_secs(5);
        while Instant::now() < deadline {
            if matches!(self.child.try_wait(), Ok(Some(_))) {
                break;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        let _ = self.child.kill();
        let _ = self.child.wait();
        let _ = std::fs::remove_dir_all(&self.profile);
    }
}

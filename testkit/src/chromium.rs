//! Headless Chromium for the WebGL tests: Debian's `chromium`, a page served from memory on the
//! loopback interface (module scripts do not load from `file:` URLs), and the page's results
//! read back from the DOM Chromium dumps once the page has loaded.
//!
//! Pixel local storage is a draft WebGL extension: Chromium offers it only with
//! `--enable-webgl-draft-extensions`. Two GPUs run it here, both ANGLE over Vulkan:
//! SwiftShader (Chromium's own), and Mesa's lavapipe, which Chromium refuses for WebGL 2 ("ES3
//! is blocklisted") until told to ignore its GPU blocklist and driver workarounds, and which
//! reads every plane as zero until ANGLE's dynamic rendering is turned off.

use std::collections::HashMap;
use std::io::{BufRead, BufReader, Write};
use std::net::{TcpListener, TcpStream};
use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use gbuffer_core::Named;

/// The GPU Chromium's ANGLE renders with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Backend {
    /// SwiftShader, Chromium's software Vulkan.
    SwiftShader,
    /// Mesa's lavapipe, through the system's Vulkan loader.
    Lavapipe,
}

// Both, in the order the tests run them.
gbuffer_core::named!(
    /// The backend's name in messages.
    Backend {
        SwiftShader => "SwiftShader",
        Lavapipe => "lavapipe",
    }
);

impl Backend {
    /// Chromium's switches that select it.
    fn switches(self) -> &'static [&'static str] {
        match self {
            // Chromium no longer falls back to SwiftShader for WebGL unless asked.
            Backend::SwiftShader => &["--use-angle=swiftshader", "--enable-unsafe-swiftshader"],
            Backend::Lavapipe => &[
                "--use-angle=vulkan",
                "--enable-features=Vulkan",
                "--ignore-gpu-blocklist",
                "--disable-gpu-driver-bug-workarounds",
                "--disable-angle-features=preferDynamicRendering",
            ],
        }
    }
}

/// Debian's Chromium, found on the `PATH`.
pub struct Chromium {
    path: PathBuf,
}

impl Chromium {
    /// The browser, or why there is none.
    pub fn find() -> Result<Chromium, String> {
        let path = std::env::var_os("PATH")
            .into_iter()
            .flat_map(|paths| std::env::split_paths(&paths).collect::<Vec<_>>())
            .map(|folder| folder.join("chromium"))
            .find(|candidate| candidate.is_file())
            .ok_or("no `chromium` on PATH: install Debian's chromium package")?;
        Ok(Chromium { path })
    }

    /// Serves `files` (name and contents) and loads `page`, one of them, with WebGL's draft
    /// extensions on `backend`; returns the page's DOM once it has loaded (every module script
    /// imported statically has run by then). A browser that does not finish within `limit` is
    /// killed and is an error.
    pub fn dump_dom(
        &self,
        files: HashMap<String, Vec<u8>>,
        page: &str,
        backend: Backend,
        limit: Duration,
    ) -> Result<String, String> {
        let server = Server::start(files)?;
        let profile = std::env::temp_dir().join(format!(
            "gbuffer-chromium-{}-{}",
            std::process::id(),
            backend.name()
        ));
        let mut child = Command::new(&self.path)
            .args([
                "--headless=new",
                "--no-sandbox",
                "--no-first-run",
                "--disable-extensions",
                "--enable-webgl-draft-extensions",
                "--dump-dom",
            ])
            .args(backend.switches())
            .arg(format!("--user-data-dir={}", profile.display()))
            .arg(format!("http://{}/{page}", server.address))
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .map_err(|error| format!("cannot start {}: {error}", self.path.display()))?;
        let stdout = child.stdout.take().expect("piped");
        let stderr = child.stderr.take().expect("piped");
        let read_out = std::thread::spawn(move || std::io::read_to_string(stdout));
        let read_err = std::thread::spawn(move || std::io::read_to_string(stderr));
        let start = Instant::now();
        let status = loop {
            if let Some(status) = child.try_wait().map_err(|error| error.to_string())? {
                break Some(status);
            }
            if start.elapsed() > limit {
                let _ = child.kill();
                let _ = child.wait();
                break None;
            }
            std::thread::sleep(Duration::from_millis(50));
        };
        let dom = read_out
            .join()
            .ok()
            .and_then(Result::ok)
            .unwrap_or_default();
        let log = read_err
            .join()
            .ok()
            .and_then(Result::ok)
            .unwrap_or_default();
        let _ = std::fs::remove_dir_all(&profile);
        server.stop();
        match status {
            Some(status) if status.success() => Ok(dom),
            Some(status) => Err(format!("chromium exited with {status}: {}", tail(&log))),
            None => Err(format!(
                "chromium did not finish within {} s: {}",
                limit.as_secs(),
                tail(&log)
            )),
        }
    }
}

/// The last lines of Chromium's log that are not its usual complaints about D-Bus.
fn tail(log: &str) -> String {
    let lines: Vec<&str> = log
        .lines()
        .filter(|line| !line.contains("dbus") && !line.trim().is_empty())
        .collect();
    lines[lines.len().saturating_sub(8)..].join("\n")
}

/// The text of the element `<pre id="{id}">` in a dumped DOM, its entities decoded.
pub fn element_text(dom: &str, id: &str) -> Option<String> {
    let open = format!("<pre id=\"{id}\">");
    let start = dom.find(&open)? + open.len();
    let end = start + dom[start..].find("</pre>")?;
    Some(
        dom[start..end]
            .replace("&lt;", "<")
            .replace("&gt;", ">")
            .replace("&quot;", "\"")
            .replace("&#39;", "'")
            .replace("&amp;", "&"),
    )
}

/// A file server on the loopback interface, for one page and what it imports.
struct Server {
    address: String,
    thread: JoinHandle<()>,
}

impl Server {
    fn start(files: HashMap<String, Vec<u8>>) -> Result<Server, String> {
        let listener = TcpListener::bind("127.0.0.1:0").map_err(|error| error.to_string())?;
        let address = listener
            .local_addr()
            .map_err(|error| error.to_string())?
            .to_string();
        let files = Arc::new(files);
        let thread = std::thread::spawn(move || {
            for stream in listener.incoming() {
                let Ok(stream) = stream else { continue };
                if serve(stream, &files) == Served::Stop {
                    return;
                }
            }
        });
        Ok(Server { address, thread })
    }

    fn stop(self) {
        if let Ok(mut stream) = TcpStream::connect(&self.address) {
            let _ = stream.write_all(b"GET /.stop HTTP/1.0\r\n\r\n");
        }
        let _ = self.thread.join();
    }
}

/// What a request asked for.
#[derive(PartialEq)]
enum Served {
    /// A file, or one that is not there (404).
    File,
    /// The server's end.
    Stop,
}

/// Answers one request: the file it names, or 404.
fn serve(stream: TcpStream, files: &HashMap<String, Vec<u8>>) -> Served {
    let _ = stream.set_read_timeout(Some(Duration::from_secs(10)));
    let mut reader = BufReader::new(&stream);
    let mut request = String::new();
    if reader.read_line(&mut request).is_err() {
        return Served::File;
    }
    // The headers are read and ignored.
    let mut header = String::new();
    while reader.read_line(&mut header).is_ok_and(|read| read > 2) {
        header.clear();
    }
    let path = request.split_whitespace().nth(1).unwrap_or("/");
    let name = path.trim_start_matches('/');
    if name == ".stop" {
        return Served::Stop;
    }
    let mut stream = &stream;
    let (status, kind, body) = match files.get(name) {
        Some(body) => {
            let kind = match name.rsplit('.').next() {
                Some("html") => "text/html; charset=utf-8",
                Some("js" | "mjs") => "text/javascript; charset=utf-8",
                Some("json") => "application/json",
                _ => "text/plain; charset=utf-8",
            };
            ("200 OK", kind, body.as_slice())
        }
        None => ("404 Not Found", "text/plain", &b"not found"[..]),
    };
    let head = format!(
        "HTTP/1.0 {status}\r\nContent-Type: {kind}\r\nContent-Length: {}\r\nCache-Control: no-store\r\n\r\n",
        body.len()
    );
    let _ = stream.write_all(head.as_bytes());
    let _ = stream.write_all(body);
    Served::File
}

//! Running the helper: where the setup put it, the command line and environment for a target
//! (natively, or under qemu with the arm64 root), a time limit, and its output split into one
//! section a shader.

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

use crate::target::{Architecture, Compiler, Target};
use crate::CostError;

/// The folder `scripts/cost-setup.sh` installs into unless `GBUFFER_COST_ROOT` names another.
pub const DEFAULT_ROOT: &str = "/opt/gbuffer-cost";

/// The qemu that runs the arm64 side.
const QEMU: &str = "/usr/bin/qemu-aarch64-static";

/// How long one run of the helper may take: starting a driver under qemu takes about a second,
/// a large shader a few more.
const TIME_LIMIT: Duration = Duration::from_secs(300);

/// What `scripts/cost-setup.sh` installed, found.
#[derive(Clone, Debug)]
pub struct Setup {
    root: PathBuf,
}

impl Setup {
    /// The setup in `GBUFFER_COST_ROOT`, or in [`DEFAULT_ROOT`]; checked per target by
    /// [`Setup::check`].
    pub fn find() -> Setup {
        let root = std::env::var_os("GBUFFER_COST_ROOT")
            .map(PathBuf::from)
            .unwrap_or_else(|| PathBuf::from(DEFAULT_ROOT));
        Setup { root }
    }

    /// The folder the setup installed into.
    pub fn root(&self) -> &Path {
        &self.root
    }

    fn helper(&self, architecture: Architecture) -> PathBuf {
        self.root.join("bin").join(match architecture {
            Architecture::X86_64 => "shader-stats-x86_64",
            Architecture::Aarch64 => "shader-stats-aarch64",
        })
    }

    fn arm64_root(&self) -> PathBuf {
        self.root.join("arm64")
    }

    /// The drm-shim's path as the driver's process sees it (under qemu, inside the arm64 root).
    fn shim(target: &Target) -> String {
        match target.architecture {
            Architecture::X86_64 => format!("/usr/lib/x86_64-linux-gnu/{}", target.shim),
            Architecture::Aarch64 => format!("/usr/lib/aarch64-linux-gnu/{}", target.shim),
        }
    }

    /// What is missing for any target, or `None` when every target is set up: for a test's
    /// skip rule, or a report's reason to leave the compilers' columns out.
    pub fn missing(&self) -> Option<String> {
        crate::target::TARGETS
            .iter()
            .find_map(|target| self.check(target).err())
            .map(|error| error.to_string())
    }

    /// Whether everything `target` needs is in place; the error names the first thing missing.
    pub fn check(&self, target: &Target) -> Result<(), CostError> {
        let missing = |what: String| {
            Err(CostError::NotSetUp(format!(
                "{what} is missing for {}: run scripts/cost-setup.sh (as root) to install it",
                target.name
            )))
        };
        let helper = self.helper(target.architecture);
        if !helper.is_file() {
            return missing(format!("the helper {}", helper.display()));
        }
        match target.architecture {
            Architecture::X86_64 => {
                let shim = Setup::shim(target);
                if !Path::new(&shim).is_file() {
                    return missing(format!(
                        "{shim} (Debian's mesa-drm-shim from bookworm-backports)"
                    ));
                }
            }
            Architecture::Aarch64 => {
                if !Path::new(QEMU).is_file() {
                    return missing(format!("{QEMU} (Debian's qemu-user-static)"));
                }
                let shim = self
                    .arm64_root()
                    .join(Setup::shim(target).trim_start_matches('/'));
                if !shim.is_file() {
                    return missing(format!("the arm64 drm-shim {}", shim.display()));
                }
            }
        }
        Ok(())
    }

    /// Runs the helper for `target` with `arguments`; `disassembly` switches on the GL
    /// compilers' listings, which they print on standard error. Returns standard output and
    /// standard error.
    pub fn run(
        &self,
        target: &Target,
        arguments: &[String],
        disassembly: bool,
    ) -> Result<(String, String), CostError> {
        self.check(target)?;
        let helper = self.helper(target.architecture);
        let mut command = match target.architecture {
            Architecture::X86_64 => {
                let mut command = Command::new(&helper);
                command.env_clear().env("LD_PRELOAD", Setup::shim(target));
                command
            }
            Architecture::Aarch64 => {
                // qemu's -E splits its value at commas: only LD_PRELOAD goes through it (it must
                // not reach qemu itself); the rest is qemu's environment, which it passes on.
                let mut command = Command::new(QEMU);
                command
                    .env_clear()
                    .arg("-L")
                    .arg(self.arm64_root())
                    .arg("-E")
                    .arg(format!("LD_PRELOAD={}", Setup::shim(target)))
                    .arg(&helper);
                command
            }
        };
        // Statistics arrive through KHR_debug only from an unthreaded gallium context; a cached
        // shader would not be compiled (and so not reported) again.
        command
            .env("GALLIUM_THREAD", "0")
            .env("MESA_SHADER_CACHE_DISABLE", "true")
            .envs(target.environment.iter().copied());
        match target.compiler {
            Compiler::Bifrost | Compiler::Valhall => {
                let flags = if disassembly {
                    "shaderdb,shaders"
                } else {
                    "shaderdb"
                };
                command.env("BIFROST_MESA_DEBUG", flags);
            }
            Compiler::Ir3 => {
                command.env("FD_MESA_DEBUG", "shaderdb");
                if disassembly {
                    command.env("IR3_SHADER_DEBUG", "disasm");
                }
            }
            Compiler::Nouveau if disassembly => {
                command.env("NV50_PROG_DEBUG", "1");
            }
            _ => {}
        }
        command.args(arguments);
        let what = format!("the {} compiler ({})", target.name, helper.display());
        run_with_limit(command, &what)
    }
}

/// Runs `command` to its end or [`TIME_LIMIT`], reading its output as it comes.
fn run_with_limit(mut command: Command, what: &str) -> Result<(String, String), CostError> {
    let mut child = command
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|error| CostError::Driver(format!("cannot start {what}: {error}")))?;
    let mut stdout = child.stdout.take().expect("stdout is piped");
    let mut stderr = child.stderr.take().expect("stderr is piped");
    let out = std::thread::spawn(move || {
        let mut text = String::new();
        stdout.read_to_string(&mut text).map(|_| text)
    });
    let err = std::thread::spawn(move || {
        let mut text = String::new();
        stderr.read_to_string(&mut text).map(|_| text)
    });
    let start = Instant::now();
    let status = loop {
        match child.try_wait() {
            Ok(Some(status)) => break status,
            Ok(None) if start.elapsed() > TIME_LIMIT => {
                let _ = child.kill();
                let _ = child.wait();
                return Err(CostError::Driver(format!(
                    "{what} ran past {} s and was stopped",
                    TIME_LIMIT.as_secs()
                )));
            }
            Ok(None) => std::thread::sleep(Duration::from_millis(5)),
            Err(error) => return Err(CostError::Driver(format!("{what}: {error}"))),
        }
    };
    let text = |thread: std::thread::JoinHandle<std::io::Result<String>>| {
        thread.join().ok().and_then(Result::ok).unwrap_or_default()
    };
    let (stdout, stderr) = (text(out), text(err));
    if !status.success() {
        let reason = stderr
            .lines()
            .rev()
            .find(|line| line.starts_with("shader-stats: "))
            .or_else(|| stderr.lines().rev().find(|line| !line.trim().is_empty()))
            .unwrap_or("no message");
        return Err(CostError::Driver(format!(
            "{what} failed ({status}): {reason}"
        )));
    }
    Ok((stdout, stderr))
}

/// A folder of this process's own for the shader files of one run, removed when dropped.
pub struct Scratch {
    path: PathBuf,
}

impl Scratch {
    /// A new, empty folder under the system's temporary folder.
    pub fn new() -> Result<Scratch, CostError> {
        static COUNT: AtomicU64 = AtomicU64::new(0);
        let path = std::env::temp_dir().join(format!(
            "gbuffer-cost-{}-{}",
            std::process::id(),
            COUNT.fetch_add(1, Ordering::Relaxed)
        ));
        std::fs::create_dir_all(&path).map_err(|error| {
            CostError::Driver(format!("cannot create {}: {error}", path.display()))
        })?;
        Ok(Scratch { path })
    }

    /// Writes `bytes` into the folder as `name`; returns its path as an argument.
    pub fn write(&self, name: &str, bytes: &[u8]) -> Result<String, CostError> {
        let path = self.path.join(name);
        std::fs::write(&path, bytes).map_err(|error| {
            CostError::Driver(format!("cannot write {}: {error}", path.display()))
        })?;
        Ok(path.display().to_string())
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.path);
    }
}

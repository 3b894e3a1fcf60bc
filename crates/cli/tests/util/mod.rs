//! Runs the real `semsim` binary in a temporary folder (as ripgrep's tests/util.rs).

#![allow(dead_code, clippy::new_without_default)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A temporary working folder for one test.
pub struct Dir {
    tmp: tempfile::TempDir,
}

impl Dir {
    /// A new empty folder.
    pub fn new() -> Dir {
        Dir {
            tmp: tempfile::tempdir().expect("temporary folder"),
        }
    }

    /// The folder.
    pub fn path(&self) -> &Path {
        self.tmp.path()
    }

    /// A path inside the folder.
    pub fn join(&self, p: &str) -> PathBuf {
        self.tmp.path().join(p)
    }

    /// Writes a file inside the folder.
    pub fn write(&self, name: &str, bytes: impl AsRef<[u8]>) -> PathBuf {
        let p = self.join(name);
        std::fs::write(&p, bytes).expect("write test file");
        p
    }

    /// Runs `semsim ARGS...` in the folder.
    pub fn run(&self, args: &[&str]) -> Run {
        let out = Command::new(env!("CARGO_BIN_EXE_semsim"))
            .args(args)
            .current_dir(self.path())
            .output()
            .expect("semsim runs");
        Run(out)
    }

    /// The built-in default building written into the folder as `b.toml`.
    pub fn default_building(&self) -> PathBuf {
        self.write(
            "b.toml",
            include_str!("../../../scanner/data/default_building.toml"),
        )
    }

    /// `semsim scan` of the default building (written as `b.toml`) from `poses` (`x,y,yaw`)
    /// into `out`, with `config`.
    pub fn scan_default_building(&self, out: &str, poses: &[&str], config: &Path) -> Run {
        let b = self.default_building();
        let (b, config) = (
            b.to_str().expect("utf-8 path"),
            config.to_str().expect("utf-8 path"),
        );
        let mut args = vec!["scan", "--building", b, "--out", out, "--config", config];
        for p in poses {
            args.extend(["--pose", p]);
        }
        self.run(&args)
    }

    /// A small, fast laser configuration file for tests.
    pub fn small_config(&self) -> PathBuf {
        self.write(
            "small.toml",
            "[laser]\nbeams = 121\nrotation_steps = 61\n[odometry]\nseed = 5\n",
        )
    }

    /// Names of the files in the folder (sorted).
    pub fn listing(&self, sub: &str) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(self.join(sub))
            .expect("listable")
            .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    /// Generates the office of `seed`, scans it with the realistic laser (`scan_args`: the
    /// poses, or `--survey`), registers the scans as a sequence from their simulated odometry
    /// and returns `registration.json`'s entries, one per scan.
    pub fn registered_office(&self, seed: u64, scan_args: &[&str]) -> Vec<serde_json::Value> {
        let seed = seed.to_string();
        self.run(&[
            "building", "generate", "--style", "office", "--seed", &seed, "--out", "o.toml",
        ])
        .ok();
        let mut scan = vec![
            "scan",
            "--building",
            "o.toml",
            "--laser",
            "real",
            "--out",
            "s",
        ];
        scan.extend_from_slice(scan_args);
        self.run(&scan).ok();
        self.run(&["register", "--sequence", "s", "--out", "r"])
            .ok();
        let text = std::fs::read_to_string(self.join("r/registration.json")).expect("written");
        serde_json::from_str(&text).expect("json")
    }
}

/// The outcome of one run.
pub struct Run(pub Output);

impl Run {
    /// Exit code (-1 if killed by a signal).
    pub fn code(&self) -> i32 {
        self.0.status.code().unwrap_or(-1)
    }

    /// Standard output.
    pub fn stdout(&self) -> String {
        String::from_utf8_lossy(&self.0.stdout).into_owned()
    }

    /// Standard error.
    pub fn stderr(&self) -> String {
        String::from_utf8_lossy(&self.0.stderr).into_owned()
    }

    /// Asserts success and returns stdout.
    pub fn ok(&self) -> String {
        assert_eq!(
            self.code(),
            0,
            "failed:\nstdout: {}\nstderr: {}",
            self.stdout(),
            self.stderr()
        );
        self.stdout()
    }

    /// Asserts exit code 2 (bad input), no panic, and a message containing every `needle`.
    pub fn bad_input(&self, needles: &[&str]) {
        let err = self.stderr();
        assert_eq!(
            self.code(),
            2,
            "expected exit 2:\nstdout: {}\nstderr: {err}",
            self.stdout()
        );
        assert!(!err.contains("panicked"), "panic: {err}");
        for n in needles {
            assert!(err.contains(n), "stderr lacks '{n}': {err}");
        }
    }
}

/// The shared real-data folder, or `None` (with a message) where it is absent.
pub fn real_data() -> Option<PathBuf> {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data/real");
    if p.is_dir() {
        Some(p)
    } else {
        eprintln!("skipping: real data folder {} not found", p.display());
        None
    }
}

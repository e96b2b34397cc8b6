//! What the kill tests (`save_kill.rs`, `export_kill.rs`) share: a child
//! process that is the test executable itself, filtered to one test, told
//! its target file by an environment variable; killed after a random delay
//! once it says it started; and the folder's leftovers counted.

use std::io::{BufRead as _, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Duration;

/// A seeded xorshift generator: the delays are reproducible from the seed
/// the tests print.
pub struct Rng(pub u64);

impl Rng {
    /// The next number in [0, 1).
    pub fn next_unit(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A fresh scratch folder named `name` and this process's id.
pub fn scratch_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("a scratch folder");
    dir
}

/// The full name of test `name` of this module's sibling, as the test
/// binary lists it (`save_kill::saver_child_process`): the kill tests are
/// modules of one suite binary, and `--exact` needs the module path.
pub fn child_test_name(module: &str, name: &str) -> String {
    let path = module.split_once("::").map_or(module, |(_, rest)| rest);
    format!("{path}::{name}")
}

/// Starts this test executable filtered to `child_test`, with `var` set
/// to `target`; waits until it prints a line ending in `started`, sleeps
/// `delay`, and kills it (SIGKILL).
pub fn run_and_kill(child_test: &str, var: &str, target: &Path, started: &str, delay: Duration) {
    let mut child = Command::new(std::env::current_exe().expect("the test executable"))
        .args([child_test, "--exact", "--nocapture", "--test-threads=1"])
        .env(var, target)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("the child starts");
    // The test harness prints its own words first, on the same line.
    let mut lines = BufReader::new(child.stdout.take().expect("its stdout")).lines();
    while !lines
        .next()
        .expect("the child says it started")
        .expect("a line")
        .ends_with(started)
    {}
    std::thread::sleep(delay);
    child.kill().expect("killed");
    child.wait().expect("reaped");
}

/// Removes every file of `dir` but `target` (the temporary files of
/// interrupted writes); returns whether there was one.
pub fn clear_leftovers(dir: &Path, target: &Path) -> bool {
    let mut left = false;
    for entry in std::fs::read_dir(dir).expect("the folder lists") {
        let path = entry.expect("an entry").path();
        if path != target {
            left = true;
            std::fs::remove_file(&path).expect("a temporary file goes");
        }
    }
    left
}

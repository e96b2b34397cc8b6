//! Running an independent library's Python script from a test and reading
//! what it prints: shared by `usdc_pxr.rs` and `abc_alembic.rs`.

use std::process::Command;

use glam::Vec3;

/// Runs `python3` with `args` and returns its stdout lines; fails the test
/// with the script's stderr when it fails.
pub fn python(args: &[&str]) -> Vec<String> {
    let output = Command::new("python3")
        .args(args)
        .output()
        .expect("python3 runs");
    assert!(
        output.status.success(),
        "python failed:\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8_lossy(&output.stdout)
        .lines()
        .map(str::to_string)
        .collect()
}

/// The numbers of a printed line after its first word (a label).
pub fn numbers(line: &str) -> Vec<f64> {
    line.split_whitespace()
        .skip(1)
        .map(|word| word.parse().expect("a number"))
        .collect()
}

/// The largest distance between matching points, metres.
pub fn max_distance(a: &[Vec3], b: &[Vec3]) -> f64 {
    assert_eq!(a.len(), b.len(), "point counts");
    a.iter()
        .zip(b)
        .map(|(p, q)| f64::from(p.distance(*q)))
        .fold(0.0, f64::max)
}

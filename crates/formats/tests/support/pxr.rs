//! Whether Pixar's USD library (`pxr`, from PyPI's `usd-core`) can be
//! used by a test: shared by the formats crate's `usd_pxr.rs` and the
//! app's export round trip (which includes this file by path).

use std::process::Command;

/// Whether pxr can be used; fails the test when it must be and cannot.
pub fn pxr_available() -> bool {
    let works = Command::new("python3")
        .args(["-c", "import pxr"])
        .output()
        .is_ok_and(|output| output.status.success());
    if !works {
        let required = std::env::var("HELIXHAIR_REQUIRE_USD").is_ok_and(|v| v == "1");
        assert!(
            !required,
            "HELIXHAIR_REQUIRE_USD=1 but `python3 -c \"import pxr\"` fails: pip install usd-core"
        );
        println!(
            "SKIPPED: Pixar's USD (python3 -c \"import pxr\") is not installed; pip install usd-core"
        );
    }
    works
}

//! Whether the Alembic library's Python bindings (PyPI's `alembic3d`,
//! imported as `alembic3d`) can be used by a test: shared by the formats
//! crate's `abc_alembic.rs` and the app's export round trip.

use std::process::Command;

/// Whether PyAlembic can be used; fails the test when it must be
/// (`HELIXHAIR_REQUIRE_ALEMBIC=1`, as CI sets) and cannot.
pub fn alembic_available() -> bool {
    let works = Command::new("python3")
        .args(["-c", "import alembic3d.AbcGeom"])
        .output()
        .is_ok_and(|output| output.status.success());
    if !works {
        let required = std::env::var("HELIXHAIR_REQUIRE_ALEMBIC").is_ok_and(|v| v == "1");
        assert!(
            !required,
            "HELIXHAIR_REQUIRE_ALEMBIC=1 but `python3 -c \"import alembic3d.AbcGeom\"` fails: pip install alembic3d"
        );
        println!(
            "SKIPPED: PyAlembic (python3 -c \"import alembic3d\") is not installed; pip install alembic3d"
        );
    }
    works
}

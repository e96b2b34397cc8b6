//! Where a command's summary and JSON report go (`sim --json`, `import
//! --json`): the report to a file, written atomically into a folder made
//! if needed, or with `-` to standard output, and the human summary then
//! to standard error so the two never mix.

use std::io::Write;
use std::path::Path;

use anyhow::Context as _;
use serde::Serialize;

use crate::atomic_write::write_atomically;

/// The stream for the summary: standard error when the report goes to
/// standard output (`--json -`), standard output otherwise.
pub fn summary_stream<'a>(
    json: Option<&Path>,
    stdout: &'a mut dyn Write,
    stderr: &'a mut dyn Write,
) -> &'a mut dyn Write {
    if json == Some(Path::new("-")) {
        stderr
    } else {
        stdout
    }
}

/// Writes `report` as pretty JSON to `path` (`-`: standard output); for a
/// file, says so on standard output (the summary's stream then).
pub fn write_json_report(
    report: &impl Serialize,
    path: &Path,
    stdout: &mut dyn Write,
) -> anyhow::Result<()> {
    let mut json = serde_json::to_string_pretty(report).context("cannot encode the JSON report")?;
    json.push('\n');
    if path == Path::new("-") {
        stdout.write_all(json.as_bytes())?;
        return Ok(());
    }
    let write = || {
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir)?;
        }
        write_atomically(path, json.as_bytes())
    };
    write().with_context(|| format!("cannot write the JSON report to {}", path.display()))?;
    writeln!(stdout, "  wrote {}", path.display())?;
    Ok(())
}

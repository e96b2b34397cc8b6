//! Writing a file so that readers see the old content or the new, never a
//! part: write a temporary file in the same directory, flush it to disk,
//! then rename it over the target (a rename within one file system is
//! atomic).

use std::fs::{self, File};
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// Distinguishes temporary files of concurrent writes in one process.
static NEXT_TEMP: AtomicU64 = AtomicU64::new(0);

/// Replaces the file at `path` with `contents` atomically; creates it if
/// missing. On error the target is untouched and the temporary file removed.
pub fn write_atomically(path: &Path, contents: &[u8]) -> io::Result<()> {
    let file_name = path
        .file_name()
        .ok_or_else(|| io::Error::new(io::ErrorKind::InvalidInput, "the path names no file"))?;
    let dir = match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir,
        _ => Path::new("."),
    };
    let temp = temp_path(dir, &file_name.to_string_lossy());
    let result = write_and_rename(&temp, path, contents);
    if result.is_err() {
        // The temporary file may not exist (creation failed); nothing to do then.
        let _ = fs::remove_file(&temp);
    } else {
        sync_dir(dir);
    }
    result
}

fn temp_path(dir: &Path, file_name: &str) -> PathBuf {
    let n = NEXT_TEMP.fetch_add(1, Ordering::Relaxed);
    dir.join(format!(".{file_name}.{}-{n}.tmp", std::process::id()))
}

fn write_and_rename(temp: &Path, path: &Path, contents: &[u8]) -> io::Result<()> {
    let mut file = File::create(temp)?;
    file.write_all(contents)?;
    file.sync_all()?;
    drop(file);
    fs::rename(temp, path)
}

/// Flushes the directory entry of the rename, where the platform can; a
/// failure here (some file systems refuse) leaves the data written, so it
/// is not reported.
fn sync_dir(dir: &Path) {
    #[cfg(unix)]
    if let Ok(handle) = File::open(dir) {
        let _ = handle.sync_all();
    }
    #[cfg(not(unix))]
    let _ = dir;
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch_dir(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("helixhair-atomic-{name}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).expect("create scratch dir");
        dir
    }

    #[test]
    fn creates_then_replaces_and_leaves_no_temporary_file() {
        let dir = scratch_dir("replace");
        let target = dir.join("out.txt");
        write_atomically(&target, b"first").expect("first write");
        write_atomically(&target, b"second").expect("second write");
        assert_eq!(fs::read(&target).expect("read back"), b"second");
        let names: Vec<_> = fs::read_dir(&dir)
            .expect("list")
            .map(|e| e.expect("entry").file_name())
            .collect();
        assert_eq!(names, ["out.txt"]);
        fs::remove_dir_all(&dir).expect("clean up");
    }

    #[test]
    fn failure_leaves_the_target_alone() {
        let dir = scratch_dir("fail");
        let missing = dir.join("no-such-dir").join("out.txt");
        assert!(write_atomically(&missing, b"x").is_err());
        assert!(write_atomically(Path::new("/"), b"x").is_err());
        fs::remove_dir_all(&dir).expect("clean up");
    }
}

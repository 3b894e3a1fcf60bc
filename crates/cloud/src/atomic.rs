//! Atomic file output: write to a temporary file beside the target, then rename,
//! so that a failed or interrupted write never leaves a partial file under the final name.

use crate::error::{CloudError, Result};
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// Writes `path` atomically: `write` fills a buffered temporary file in the same folder,
/// which is renamed over `path` only if `write` succeeds. On failure the temporary file is removed.
pub fn write_atomically<E>(
    path: &Path,
    write: impl FnOnce(&mut BufWriter<File>) -> std::result::Result<(), E>,
) -> std::result::Result<(), E>
where
    E: From<CloudError>,
{
    let tmp = temp_path(path);
    let file = File::create(&tmp).map_err(|e| CloudError::io(path, e))?;
    let mut w = BufWriter::with_capacity(1 << 20, file);
    let result = write(&mut w).and_then(|()| {
        w.flush().map_err(|e| E::from(CloudError::io(path, e)))?;
        w.get_ref()
            .sync_all()
            .map_err(|e| E::from(CloudError::io(path, e)))
    });
    drop(w);
    match result {
        Ok(()) => std::fs::rename(&tmp, path).map_err(|e| {
            let _ = std::fs::remove_file(&tmp);
            E::from(CloudError::io(path, e))
        }),
        Err(e) => {
            let _ = std::fs::remove_file(&tmp);
            Err(e)
        }
    }
}

/// Writes a whole byte buffer atomically.
pub fn write_bytes_atomically(path: &Path, bytes: &[u8]) -> Result<()> {
    write_atomically(path, |w| {
        w.write_all(bytes).map_err(|e| CloudError::io(path, e))
    })
}

fn temp_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "out".into());
    path.with_file_name(format!(".{name}.{}.tmp", std::process::id()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn failed_write_leaves_no_file() {
        let dir = tempfile::tempdir().expect("tempdir");
        let path = dir.path().join("out.txt");
        let r: Result<()> = write_atomically(&path, |w| {
            w.write_all(b"partial")
                .map_err(|e| CloudError::io("x", e))?;
            Err(CloudError::Inconsistent("boom".into()))
        });
        assert!(r.is_err());
        let left: Vec<_> = std::fs::read_dir(dir.path()).expect("readable").collect();
        assert!(left.is_empty(), "left behind: {left:?}");
        write_bytes_atomically(&path, b"whole").expect("writes");
        assert_eq!(std::fs::read(&path).expect("exists"), b"whole");
    }
}

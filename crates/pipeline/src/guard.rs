//! No command overwrites one of its own inputs: before any work, every output path is compared
//! with every input path (both resolved through the file system, so `dir/./poses.txt` and a
//! symbolic link to it are the same file), and a clash is bad input naming both.

use crate::error::{PipelineError, Result};
use std::path::{Path, PathBuf};

/// `Err` naming the file if any of `outputs` is one of `inputs`. Outputs need not exist yet
/// (their folder is resolved); inputs that do not exist are skipped (reading them fails later
/// with its own message).
pub fn refuse_overwriting_inputs(outputs: &[PathBuf], inputs: &[PathBuf]) -> Result<()> {
    let inputs: Vec<(PathBuf, &PathBuf)> = inputs
        .iter()
        .filter_map(|p| std::fs::canonicalize(p).ok().map(|c| (c, p)))
        .collect();
    for out in outputs {
        let Some(resolved) = resolve_output(out) else {
            continue;
        };
        if let Some((_, given)) = inputs.iter().find(|(c, _)| *c == resolved) {
            return Err(PipelineError::bad_input(format!(
                "{}: this output would replace the input {}; give another output path \
                 (no command overwrites its own inputs)",
                out.display(),
                given.display()
            )));
        }
    }
    Ok(())
}

/// `Err` (bad input, naming the path) if `dir` cannot become an output folder: it is a file,
/// or one of its ancestors is. Checked before any work, so a run does not compute for minutes
/// and then fail to write.
pub fn check_output_dir(dir: &Path) -> Result<()> {
    let mut at = Some(dir);
    while let Some(p) = at {
        if p.exists() && !p.is_dir() {
            let msg = if p == dir {
                "the output folder is a file".to_string()
            } else {
                format!("{} is a file, not a folder", p.display())
            };
            return Err(cloud::CloudError::io(
                dir,
                std::io::Error::new(std::io::ErrorKind::NotADirectory, msg),
            )
            .into());
        }
        at = p.parent().filter(|q| !q.as_os_str().is_empty());
    }
    Ok(())
}

/// An output path resolved through its folder (which must exist to clash with anything).
fn resolve_output(out: &Path) -> Option<PathBuf> {
    if let Ok(c) = std::fs::canonicalize(out) {
        return Some(c);
    }
    let name = out.file_name()?;
    let parent = match out.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    std::fs::canonicalize(parent).ok().map(|p| p.join(name))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_output_that_is_an_input_is_refused_by_any_spelling() {
        let dir = tempfile::tempdir().expect("temp dir");
        let truth = dir.path().join("poses.txt");
        std::fs::write(&truth, "# poses\n").expect("write");
        let same = dir.path().join(".").join("poses.txt");
        let e = refuse_overwriting_inputs(&[same], std::slice::from_ref(&truth))
            .expect_err("the same file");
        assert!(e.to_string().contains("would replace the input"), "{e}");
        assert!(cloud::BadInput::is_bad_input(&e));
        let other = dir.path().join("registered.txt");
        assert!(refuse_overwriting_inputs(&[other], std::slice::from_ref(&truth)).is_ok());
        assert!(check_output_dir(&truth).is_err());
        assert!(check_output_dir(&truth.join("below")).is_err());
        assert!(check_output_dir(&dir.path().join("new/folder")).is_ok());
    }
}

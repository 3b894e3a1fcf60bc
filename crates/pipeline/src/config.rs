//! The configuration of a whole run: one section per stage, each the stage's own
//! `Default + serde` struct. Every run writes the configuration it used beside its outputs.

use crate::error::{PipelineError, Result};
use registration::SequenceConfig;
use scanner::{GeneratorConfig, LaserConfig, OdometryConfig};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// Everything configurable, by stage (`--config FILE` of every command).
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Config {
    /// The virtual 3D laser.
    pub laser: LaserConfig,
    /// Simulated odometry.
    pub odometry: OdometryConfig,
    /// The procedural building generator.
    pub generator: GeneratorConfig,
    /// Registration: ICP (`[registration.icp]`) and the sequence's voxel sizes.
    pub registration: SequenceConfig,
    /// The semantic map: one section per stage (`[semantic.projection]`, `[semantic.hough]`, ...).
    pub semantic: semantic::SemanticConfig,
}

impl Config {
    /// Reads a configuration file (TOML).
    pub fn load(path: &Path) -> Result<Config> {
        let text = std::fs::read_to_string(path).map_err(|e| cloud::CloudError::io(path, e))?;
        toml::from_str(&text).map_err(|e| PipelineError::Config {
            path: path.to_path_buf(),
            msg: e.to_string().trim_end().to_string(),
        })
    }

    /// Writes the configuration to `dir/config.toml` (atomically).
    pub fn write_beside(&self, dir: &Path) -> Result<()> {
        let body = toml::to_string(self).map_err(|e| PipelineError::Serialise {
            what: "the configuration",
            msg: e.to_string(),
        })?;
        let text = format!("# The configuration this run used (pass it back with --config).\n{body}");
        cloud::write_bytes_atomically(&dir.join("config.toml"), text.as_bytes())?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_written_configuration_reads_back_equal_and_unknown_sections_are_refused() {
        let dir = tempfile::tempdir().expect("temp dir");
        let mut c = Config::default();
        c.laser.beams = 99;
        c.write_beside(dir.path()).expect("written");
        let back = Config::load(&dir.path().join("config.toml")).expect("reads");
        assert_eq!(back.laser.beams, 99);
        let bad = dir.path().join("bad.toml");
        std::fs::write(&bad, "[lasr]\nbeams = 3\n").expect("write");
        let e = Config::load(&bad).expect_err("unknown section");
        assert!(e.to_string().starts_with(&bad.display().to_string()), "{e}");
        assert!(cloud::BadInput::is_bad_input(&e));
    }
}

//! The optional configuration file: one section per stage, each the stage's own `Default + serde` struct.

use anyhow::Context;
use registration::SequenceConfig;
use scanner::{GeneratorConfig, LaserConfig, OdometryConfig};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// Everything configurable, by stage.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SemsimConfig {
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

impl SemsimConfig {
    /// Loads the file if one is given, else the defaults.
    pub fn load(path: Option<&Path>) -> anyhow::Result<SemsimConfig> {
        let Some(path) = path else {
            return Ok(SemsimConfig::default());
        };
        let text = std::fs::read_to_string(path)
            .map_err(|e| cloud::CloudError::io(path, e))
            .context("reading the configuration file")?;
        toml::from_str(&text).map_err(|e| {
            crate::exit::bad_input(format!("{}: {}", path.display(), e.to_string().trim_end()))
        })
    }

    /// Writes the configuration in use to `dir/config.toml`.
    pub fn write_beside(&self, dir: &Path) -> anyhow::Result<()> {
        let text = format!(
            "# The configuration this run used (pass it back with --config).\n{}",
            toml::to_string(self).context("serialising the configuration")?
        );
        cloud::write_bytes_atomically(&dir.join("config.toml"), text.as_bytes())?;
        Ok(())
    }
}

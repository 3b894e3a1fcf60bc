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
    /// The scenario planned in a world when none is given (`run`, `simulate --map`).
    pub plan: sim::PlanConfig,
    /// Statistical outlier removal of every scan read (isolated returns in mid-air).
    pub outliers: crate::OutlierConfig,
    /// Mixed-pixel removal of every organised scan read (returns between two surfaces at a
    /// depth edge).
    pub mixed_pixels: crate::MixedPixelConfig,
    /// Moving things (people walking past) seen by one scan of a sequence, dropped when the
    /// scans are merged.
    pub transients: crate::TransientConfig,
    /// How `semsim scan --survey` chooses the stop-and-scan poses.
    pub survey: scanner::SurveyConfig,
}

impl Config {
    /// Reads a configuration file (TOML) and checks every section, whichever stages the
    /// command at hand runs: a bad value is an error naming the file and the section.
    pub fn load(path: &Path) -> Result<Config> {
        let text = std::fs::read_to_string(path).map_err(|e| cloud::CloudError::io(path, e))?;
        let config: Config = toml::from_str(&text).map_err(|e| PipelineError::Config {
            path: path.to_path_buf(),
            msg: e.to_string().trim_end().to_string(),
        })?;
        config.validate().map_err(|msg| PipelineError::Config {
            path: path.to_path_buf(),
            msg,
        })?;
        Ok(config)
    }

    /// Checks every section's parameters; the message names the section.
    pub fn validate(&self) -> std::result::Result<(), String> {
        let section = |name: &str, e: &dyn std::fmt::Display| format!("[{name}] {e}");
        self.laser.validate().map_err(|e| section("laser", &e))?;
        self.odometry
            .validate()
            .map_err(|e| section("odometry", &e))?;
        self.registration
            .icp
            .validate()
            .map_err(|e| section("registration.icp", &e))?;
        for (name, v) in [
            ("scan_voxel_m", self.registration.scan_voxel_m),
            ("map_voxel_m", self.registration.map_voxel_m),
        ] {
            cloud::check_range(name, v, 1e-4, 100.0, "within 0.1 mm..100 m")
                .map_err(|e| section("registration", &e))?;
        }
        self.semantic
            .validate()
            .map_err(|e| section("semantic", &e))?;
        self.plan.validate().map_err(|e| section("plan", &e))?;
        self.outliers
            .validate()
            .map_err(|e| section("outliers", &e))?;
        self.mixed_pixels
            .validate()
            .map_err(|e| section("mixed_pixels", &e))?;
        self.transients
            .validate()
            .map_err(|e| section("transients", &e))?;
        self.survey.validate().map_err(|e| section("survey", &e))?;
        Ok(())
    }

    /// Writes the configuration to `dir/config.toml` (atomically).
    pub fn write_beside(&self, dir: &Path) -> Result<()> {
        let body = toml::to_string(self).map_err(|e| PipelineError::Serialise {
            what: "the configuration",
            msg: e.to_string(),
        })?;
        let text =
            format!("# The configuration this run used (pass it back with --config).\n{body}");
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
        let zero = dir.path().join("zero.toml");
        std::fs::write(&zero, "[registration.icp]\nmax_iterations = 0\n").expect("write");
        let e = Config::load(&zero).expect_err("max_iterations = 0 is refused by every command");
        let msg = e.to_string();
        assert!(
            msg.contains("zero.toml")
                && msg.contains("[registration.icp]")
                && msg.contains("max_iterations"),
            "{msg}"
        );
    }

    #[test]
    fn the_laser_preset_is_named_in_the_laser_section_and_written_back_in_full() {
        let dir = tempfile::tempdir().expect("temp dir");
        let named = dir.path().join("real.toml");
        std::fs::write(&named, "[laser]\nrealism = \"real\"\n").expect("write");
        let c = Config::load(&named).expect("the real preset by name");
        assert_eq!(c.laser.realism, scanner::Realism::real());
        // Written beside a run as a full table, it reads back equal.
        c.write_beside(dir.path()).expect("written");
        let text = std::fs::read_to_string(dir.path().join("config.toml")).expect("read");
        assert!(text.contains("[laser.realism.returns]"), "{text}");
        let back = Config::load(&dir.path().join("config.toml")).expect("reads");
        assert_eq!(back.laser, c.laser);
        // A bad preset or value names the section.
        for (body, what) in [
            ("[laser]\nrealism = \"perfect\"\n", "perfect"),
            (
                "[laser.realism]\nno_echo_range_m = 10.0\n",
                "no_echo_range_m",
            ),
        ] {
            let bad = dir.path().join("bad.toml");
            std::fs::write(&bad, body).expect("write");
            let e = Config::load(&bad).expect_err(body).to_string();
            assert!(e.contains("bad.toml") && e.contains(what), "{e}");
        }
    }

    #[test]
    fn the_outliers_section_is_read_checked_and_written_back() {
        let dir = tempfile::tempdir().expect("temp dir");
        // On by default, and written beside a run.
        assert!(Config::default().outliers.enabled);
        let off = dir.path().join("off.toml");
        std::fs::write(&off, "[outliers]\nenabled = false\nneighbours_k = 10\n").expect("write");
        let c = Config::load(&off).expect("reads");
        assert!(!c.outliers.enabled);
        assert_eq!(c.outliers.neighbours_k, 10);
        c.write_beside(dir.path()).expect("written");
        let back = Config::load(&dir.path().join("config.toml")).expect("reads back");
        assert_eq!(back.outliers, c.outliers);
        for (body, what) in [
            ("[outliers]\nneighbours_k = 0\n", "neighbours_k"),
            ("[outliers]\nmin_ratio = 0.5\n", "min_ratio"),
            ("[outliers]\nsigma = 3.0\n", "sigma"),
        ] {
            let bad = dir.path().join("bad.toml");
            std::fs::write(&bad, body).expect("write");
            let e = Config::load(&bad).expect_err(body).to_string();
            assert!(e.contains("bad.toml") && e.contains(what), "{e}");
        }
    }
    #[test]
    fn the_mixed_pixels_section_is_read_checked_and_written_back() {
        let dir = tempfile::tempdir().expect("temp dir");
        assert!(Config::default().mixed_pixels.enabled);
        let off = dir.path().join("off.toml");
        std::fs::write(&off, "[mixed_pixels]\nenabled = false\nmin_gap_m = 0.1\n").expect("write");
        let c = Config::load(&off).expect("reads");
        assert!(!c.mixed_pixels.enabled);
        assert_eq!(c.mixed_pixels.min_gap_m, 0.1);
        c.write_beside(dir.path()).expect("written");
        let back = Config::load(&dir.path().join("config.toml")).expect("reads back");
        assert_eq!(back.mixed_pixels, c.mixed_pixels);
        for (body, what) in [
            ("[mixed_pixels]\nmin_jump_ratio = 0.5\n", "min_jump_ratio"),
            ("[mixed_pixels]\ngap_m = 3.0\n", "gap_m"),
        ] {
            let bad = dir.path().join("bad.toml");
            std::fs::write(&bad, body).expect("write");
            let e = Config::load(&bad).expect_err(body).to_string();
            assert!(e.contains("bad.toml") && e.contains(what), "{e}");
        }
    }
}

//! Checkpoints: the whole simulation state (rapier's sets, broad and narrow phase, our event
//! detectors, the judge, the command cursor, time, events and trajectory so far) as CBOR after
//! a short header, written atomically. Resuming gives the same results as running straight on.

use crate::error::{Result, SimError};
use crate::simulation::Simulation;
use std::io::Write as _;
use std::path::Path;

/// The first bytes of a checkpoint file (format version 1).
const MAGIC: &[u8; 16] = b"semsim-ckpt-v1\n\0";

impl Simulation {
    /// Encodes the whole state.
    pub fn checkpoint_bytes(&self) -> Result<Vec<u8>> {
        let mut out = MAGIC.to_vec();
        ciborium::into_writer(self, &mut out).map_err(|e| SimError::Checkpoint {
            path: "<memory>".into(),
            msg: format!("cannot encode: {e}"),
        })?;
        Ok(out)
    }

    /// Decodes a state made by [`Simulation::checkpoint_bytes`].
    pub fn from_checkpoint_bytes(bytes: &[u8]) -> Result<Simulation> {
        Self::decode(bytes, Path::new("<memory>"))
    }

    fn decode(bytes: &[u8], path: &Path) -> Result<Simulation> {
        let body = bytes
            .strip_prefix(MAGIC.as_slice())
            .ok_or_else(|| SimError::Checkpoint {
                path: path.to_path_buf(),
                msg: "not a semsim checkpoint (or another format version)".into(),
            })?;
        ciborium::from_reader(body).map_err(|e| SimError::Checkpoint {
            path: path.to_path_buf(),
            msg: format!("cannot decode: {e}"),
        })
    }

    /// Saves the state to `path` atomically.
    pub fn save_checkpoint(&self, path: &Path) -> Result<()> {
        cloud::write_atomically(path, |w| {
            w.write_all(MAGIC)
                .map_err(|e| cloud::CloudError::io(path, e))?;
            ciborium::into_writer(self, &mut *w).map_err(|e| SimError::Checkpoint {
                path: path.to_path_buf(),
                msg: format!("cannot encode: {e}"),
            })
        })
    }

    /// Loads a state saved by [`Simulation::save_checkpoint`].
    pub fn load_checkpoint(path: &Path) -> Result<Simulation> {
        let bytes = std::fs::read(path).map_err(|error| SimError::Io {
            path: path.to_path_buf(),
            error,
        })?;
        Self::decode(&bytes, path)
    }
}

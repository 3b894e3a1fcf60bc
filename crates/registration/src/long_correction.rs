//! A long correction checked: where a scan's ICP from the odometry's guess ends further from
//! the guess than a final-gate ICP could have moved, the ICP's wide first gate may have
//! pulled it into a neighbouring minimum. Half the scan can be new to the map (a scan after a
//! long move sees rooms the map has not), and those points pair with whatever lies within a
//! metre; along a corridor nothing holds the pose against them. (A generated office's scan
//! 22, after a 9.7 m move, started 0.15 m from its true pose and ended 1.13 m along the
//! corridor; started exactly at its true pose, it ended at the same wrong place. Both poses
//! pair 48-49 % of the scan at the final gate.)
//!
//! The check registers the scan again from the guess with a narrow schedule (first gate
//! [`NARROW_GATES`] final gates) and keeps whichever of the two poses the evidence prefers:
//! agreement with the map's surface minus contradiction of what either side saw free, as
//! the initial alignment scores its hypotheses; where the scores cannot be told apart, the
//! pose nearer the odometry's guess.

use crate::config::IcpConfig;
use crate::error::Result;
use crate::initial;
use crate::registrar::Registrar;
use crate::result::IcpResult;
use crate::target::Target;
use cloud::PointCloud;
use glam::{DAffine3, Vec3};
use serde::{Deserialize, Serialize};

/// The narrow schedule's first gate, and the correction beyond which the check runs, in final
/// gates: an ICP whose gate never exceeds it cannot move the pose much further.
const NARROW_GATES: f64 = 3.0;

/// What the check of one scan found.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CorrectionCheck {
    /// How far the ICP from the guess moved the scan's sensor (metres).
    pub correction_m: f64,
    /// How far the narrow schedule's ICP moved it; `None` where it failed.
    pub narrow_correction_m: Option<f64>,
    /// The evidence's scores of the ICP's end and of the narrow schedule's (agreement minus
    /// contradiction, at most 1), where the two ends differed and were compared.
    pub scores: Option<[f64; 2]>,
    /// Whether the narrow schedule's pose was kept.
    pub narrow_kept: bool,
}

/// The map a scan is registered to: its points (world), the sensor position each was seen
/// from, and the target built from them.
pub(crate) struct MapView<'a> {
    pub(crate) points: &'a [Vec3],
    pub(crate) views: &'a [Vec3],
    pub(crate) target: &'a Target,
}

/// Checks `result`, the registration of `source` from `guess` to `map`, if it moved the
/// sensor further than the narrow schedule's first gate; returns the result to keep and the
/// check (`None` where it did not run). `cell` is the initial alignment's cell and range
/// knee, on which the poses are scored.
pub(crate) fn check(
    registrar: &mut Registrar,
    map: MapView<'_>,
    source: &PointCloud,
    guess: &DAffine3,
    result: IcpResult,
    icp: &IcpConfig,
    cell: (f64, f64),
) -> Result<(IcpResult, Option<CorrectionCheck>)> {
    let sensor = source.sensor_origin.as_dvec3();
    let at = |pose: &DAffine3| pose.transform_point3(sensor);
    let gate = NARROW_GATES * icp.final_correspondence_distance_m;
    let correction_m = (at(&result.target_from_source) - at(guess)).length();
    if correction_m <= gate {
        return Ok((result, None));
    }
    let mut check = CorrectionCheck {
        correction_m,
        narrow_correction_m: None,
        scores: None,
        narrow_kept: false,
    };
    // 1. The narrow schedule from the guess (where it fails, the ICP's end stands).
    let narrow = IcpConfig {
        max_correspondence_distance_m: gate.min(icp.max_correspondence_distance_m),
        ..icp.clone()
    };
    let Ok(alternative) = registrar.register_to(map.target, source, *guess, &narrow) else {
        return Ok((result, Some(check)));
    };
    let narrow_end = at(&alternative.target_from_source);
    check.narrow_correction_m = Some((narrow_end - at(guess)).length());
    // 2. Both ends within the final gate of each other: one minimum, the ICP's end stands.
    if (narrow_end - at(&result.target_from_source)).length() <= icp.final_correspondence_distance_m
    {
        return Ok((result, Some(check)));
    }
    // 3. The evidence's choice between the two ends.
    let poses = [result.target_from_source, alternative.target_from_source];
    let chosen = initial::prefer(map.points, map.views, source, &poses, guess, cell)?;
    if let Some((kept, scores)) = chosen {
        check.scores = Some([scores[0], scores[1]]);
        check.narrow_kept = kept == 1;
    }
    Ok((
        if check.narrow_kept {
            alternative
        } else {
            result
        },
        Some(check),
    ))
}

#[cfg(test)]
#[path = "long_correction_tests.rs"]
mod tests;

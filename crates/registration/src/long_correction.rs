//! A long correction checked: where a scan's ICP from the odometry's guess ends further from
//! the guess than a final-gate ICP could have moved, the ICP's wide first gate may have
//! pulled it into a neighbouring minimum. Half the scan can be new to the map (a scan after a
//! long move sees rooms the map has not), and those points pair with whatever lies within a
//! metre; along a corridor nothing holds the pose against them. (A generated office's scan
//! 22, after a 9.7 m move, started 0.15 m from its true pose and ended 1.13 m along the
//! corridor; started exactly at its true pose, it ended at the same wrong place. Both poses
//! pair 48-49 % of the scan at the final gate.)
//!
//! The check registers the scan again twice: from the guess with a narrow schedule (first
//! gate [`NARROW_GATES`] final gates), and from the initial alignment's search about the
//! previous scan (every yaw and position, verified in 3D by a coarse ICP; [`crate::initial`])
//! with the final gate alone. A narrow schedule can slide too: a generated office's scan 21,
//! after a 3.5 m move and with half of it new to the map, went 1.06 m along the corridor
//! from a guess 5 cm from its true pose, and so did the narrow schedule; the search's
//! coarse ICP stayed within 2 cm of the truth, and the final gate from there stays.
//! It keeps whichever of the ends the evidence prefers: agreement with the map's surface minus
//! contradiction of what either side saw free, as the initial alignment scores its
//! hypotheses; where the scores cannot be told apart, the pose nearest the odometry's guess.

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

/// Which end of a checked scan's registrations was kept.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum CheckedEnd {
    /// The ICP's from the odometry's guess.
    #[default]
    Icp,
    /// The narrow schedule's from the guess.
    Narrow,
    /// The final gate's from the initial alignment's search.
    Searched,
}

/// What the check of one scan found.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CorrectionCheck {
    /// How far the ICP from the guess moved the scan's sensor (metres).
    pub correction_m: f64,
    /// How far the narrow schedule's ICP moved it; `None` where it failed.
    pub narrow_correction_m: Option<f64>,
    /// How far from the guess the final-gate ICP from the search's start ended; `None` where
    /// it failed.
    pub searched_correction_m: Option<f64>,
    /// The evidence's score of each end compared (an end that failed or lay within a final
    /// gate of the ICP's is not); empty where no end differed from the ICP's.
    pub scores: Vec<EndScore>,
    /// The end kept.
    pub kept: CheckedEnd,
}

/// One compared end's score.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct EndScore {
    /// Which end.
    pub end: CheckedEnd,
    /// Agreement minus contradiction with the map, at most 1.
    pub score: f64,
}

/// The map a scan is registered to: its points (world), the sensor position each was seen
/// from, the target built from them, and the initial alignment's cell and range knee, on
/// which poses are scored against it.
pub(crate) struct MapView<'a> {
    pub(crate) points: &'a [Vec3],
    pub(crate) views: &'a [Vec3],
    pub(crate) target: &'a Target,
    pub(crate) cell: (f64, f64),
}

/// Checks `result`, the registration of `source` from `guess` to `map`, if it moved the
/// sensor further than the narrow schedule's first gate; returns the result to keep and the
/// check (`None` where it did not run). `search` runs the initial alignment's search and
/// returns its start.
pub(crate) fn check(
    registrar: &mut Registrar,
    map: MapView<'_>,
    source: &PointCloud,
    guess: &DAffine3,
    result: IcpResult,
    icp: &IcpConfig,
    search: impl FnOnce() -> Result<DAffine3>,
) -> Result<(IcpResult, Option<CorrectionCheck>)> {
    let sensor = source.sensor_origin.as_dvec3();
    let at = |pose: &DAffine3| pose.transform_point3(sensor);
    let gate = NARROW_GATES * icp.final_correspondence_distance_m;
    let correction_m = (at(&result.target_from_source) - at(guess)).length();
    if correction_m <= gate {
        return Ok((result, None));
    }
    let moved = |r: &IcpResult| (at(&r.target_from_source) - at(guess)).length();
    // 1. The narrow schedule from the guess (where it fails, it is no candidate).
    let narrow = IcpConfig {
        max_correspondence_distance_m: gate.min(icp.max_correspondence_distance_m),
        ..icp.clone()
    };
    let narrow = registrar
        .register_to(map.target, source, *guess, &narrow)
        .ok();
    // 2. The final gate alone from the search's start (idem, and where the search fails):
    //    the search's pose is within a few centimetres of a minimum, and a wider gate lets
    //    the half of the scan that is new to the map carry it along a corridor again.
    let polish = IcpConfig {
        max_correspondence_distance_m: icp.final_correspondence_distance_m,
        ..icp.clone()
    };
    let searched = search().ok().and_then(|start| {
        registrar
            .register_to(map.target, source, start, &polish)
            .ok()
    });
    let mut check = CorrectionCheck {
        correction_m,
        narrow_correction_m: narrow.as_ref().map(moved),
        searched_correction_m: searched.as_ref().map(moved),
        scores: Vec::new(),
        kept: CheckedEnd::Icp,
    };
    // 3. Ends within the final gate of the ICP's are its minimum: no alternative.
    let icp_end = at(&result.target_from_source);
    let differs = |r: &IcpResult| {
        (at(&r.target_from_source) - icp_end).length() > icp.final_correspondence_distance_m
    };
    let alternatives: Vec<(CheckedEnd, IcpResult)> = [
        (CheckedEnd::Narrow, narrow),
        (CheckedEnd::Searched, searched),
    ]
    .into_iter()
    .filter_map(|(end, r)| r.filter(differs).map(|r| (end, r)))
    .collect();
    if alternatives.is_empty() {
        return Ok((result, Some(check)));
    }
    // 4. The evidence's choice among the ends.
    let poses: Vec<DAffine3> = std::iter::once(&result)
        .chain(alternatives.iter().map(|(_, r)| r))
        .map(|r| r.target_from_source)
        .collect();
    let chosen = initial::prefer(map.points, map.views, source, &poses, guess, map.cell)?;
    let Some((kept, scores)) = chosen else {
        return Ok((result, Some(check)));
    };
    let ends = std::iter::once(CheckedEnd::Icp).chain(alternatives.iter().map(|(end, _)| *end));
    check.scores = ends
        .zip(scores)
        .map(|(end, score)| EndScore { end, score })
        .collect();
    match kept
        .checked_sub(1)
        .and_then(|i| alternatives.into_iter().nth(i))
    {
        Some((end, alternative)) => {
            check.kept = end;
            Ok((alternative, Some(check)))
        }
        None => Ok((result, Some(check))),
    }
}

#[cfg(test)]
#[path = "long_correction_tests.rs"]
mod tests;

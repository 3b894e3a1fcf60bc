//! What the pipeline hands back: the map, the labels, the images and the stage timings.

use crate::image_frame::ImageFrame;
use crate::map::SemanticMap;
use crate::merge::Segment;
use cloud::{Label, PointCloud};
use image::GrayImage;
use serde::{Deserialize, Serialize};
use std::time::Instant;

/// How long one stage took.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StageTime {
    /// Stage name (`levelling`, `projection`, `noise_filter`, `dilation`, `skeleton`, `hough`,
    /// `merge`, `walls`, `openings`, `stairs`, `net`, `labels`).
    pub stage: String,
    /// Wall time in milliseconds.
    pub ms: f64,
}

/// Everything [`build_semantic_map`](crate::build_semantic_map) produces.
#[derive(Debug, Clone)]
pub struct MapOutput {
    /// The semantic map.
    pub map: SemanticMap,
    /// One label per input point (same order; missing returns and points outside the image
    /// are `Label::default()`); `entity` is a map entity id.
    pub labels: Vec<Label>,
    /// Where the images lie in the map frame.
    pub frame: ImageFrame,
    /// The projection image (values 0..1 as 0..255).
    pub projection: GrayImage,
    /// The binary image after the noise filter.
    pub filtered: GrayImage,
    /// ... after the dilation.
    pub dilated: GrayImage,
    /// ... after the skeletonisation.
    pub skeleton: GrayImage,
    /// The Hough segments (map frame).
    pub hough_segments: Vec<Segment>,
    /// The segments after merging (the wall prerequisites).
    pub merged_segments: Vec<Segment>,
    /// Floor height in the map frame, if found.
    pub floor_z_m: Option<f64>,
    /// Ceiling height in the map frame, if found.
    pub ceiling_z_m: Option<f64>,
    /// Tilt of the input's floor plane (levelled away if above `floor_ceiling.min_tilt_deg`).
    pub tilt_deg: f64,
    /// Per-stage wall times.
    pub timings: Vec<StageTime>,
}

impl MapOutput {
    /// Sum of the stage times in milliseconds.
    pub fn total_ms(&self) -> f64 {
        self.timings.iter().map(|t| t.ms).sum()
    }

    /// A copy of `input` carrying the computed labels (replacing any it had).
    pub fn labelled_cloud(&self, input: &PointCloud) -> PointCloud {
        let mut out = input.clone();
        if self.labels.len() == out.len() {
            out.labels = Some(self.labels.clone());
        }
        out
    }
}

/// The stage timings, one lap per stage.
pub(crate) struct Clock {
    t: Instant,
    pub times: Vec<StageTime>,
}

impl Clock {
    pub fn start() -> Clock {
        Clock {
            t: Instant::now(),
            times: Vec::new(),
        }
    }

    pub fn lap(&mut self, stage: &str) {
        let now = Instant::now();
        self.times.push(StageTime {
            stage: stage.into(),
            ms: (now - self.t).as_secs_f64() * 1e3,
        });
        self.t = now;
    }
}

//! ROS 2 bags in MCAP (`.mcap`): the messages of one `sensor_msgs/msg/PointCloud2` topic as
//! scans, with poses from a `nav_msgs/msg/Odometry` topic where the bag has one.
//!
//! The `mcap` crate walks the container (chunks compressed with zstd or lz4 included); this
//! module parses the schema, channel and message records ([`records`], [`stream`]) and decodes
//! the CDR messages ([`cdr`]) itself. A topic is taken where its channel's
//! schema is named `sensor_msgs/msg/PointCloud2` (or `nav_msgs/msg/Odometry`) and its message
//! encoding is `cdr`. Messages are read in log-time order (file order for equal times); each
//! becomes a scan named `<topic>#<index>` with its header's stamp and frame id.
//!
//! Poses: for each scan the odometry pose at its stamp ([`odometry::pose_at`]) goes to
//! [`ScanSet::odometry`]. Where the cloud's frame id is the odometry's child frame, that pose is
//! also the scan's `world_from_scan`; where it is the odometry frame itself the cloud is
//! already in the world frame (identity); otherwise the bag would need a transform between
//! them (tf, not read) and `world_from_scan` stays `None`, with a note.

mod cdr;
mod container;
mod odometry;
mod pointcloud2;
mod records;
mod stream;

use super::util::{clean, note, try_push};
use super::{ImportedScan, ReadOptions, ScanSet};
use crate::error::{InteropError, Result};
use glam::{DAffine3, DVec3};
use odometry::Odometry;
use std::collections::BTreeMap;
use std::path::Path;

/// The schema name of the clouds read.
const POINTCLOUD2: &str = "sensor_msgs/msg/PointCloud2";
/// The schema name of the odometry read.
const ODOMETRY: &str = "nav_msgs/msg/Odometry";

/// A message kept for decoding.
struct RawMessage {
    log_time: u64,
    data: Vec<u8>,
}

/// The messages of the topics of one kind, by topic; `None` once they are not kept.
#[derive(Default)]
struct TopicsOfKind {
    topics: BTreeMap<String, Vec<RawMessage>>,
}

impl TopicsOfKind {
    /// Keeps a message of `topic` where it may be the one read: the wanted topic, or with no
    /// topic wanted, while the bag has shown only this one of its kind.
    fn add(
        &mut self,
        path: &Path,
        topic: &str,
        wanted: Option<&str>,
        message: RawMessage,
    ) -> Result<()> {
        let keep = match wanted {
            Some(t) => t == topic,
            None => self.topics.keys().all(|t| t == topic),
        };
        if wanted.is_none() && !keep {
            // Ambiguous: the bag is refused at the end, naming every topic; keep no data.
            self.topics.values_mut().for_each(Vec::clear);
        }
        let messages = self.topics.entry(topic.to_string()).or_default();
        if keep {
            try_push(path, messages, message, "the bag's messages")?;
        }
        Ok(())
    }

    fn names(&self) -> String {
        let names: Vec<String> = self
            .topics
            .keys()
            .map(|t| format!("{:?}", clean(t)))
            .collect();
        names.join(", ")
    }

    /// The topic to read: the wanted one, else the only one. `None` where there is none and
    /// none was wanted.
    fn choose(
        &mut self,
        path: &Path,
        wanted: Option<&str>,
        kind: &str,
        option: &str,
    ) -> Result<Option<(String, Vec<RawMessage>)>> {
        if let Some(t) = wanted {
            return match self.topics.remove(t) {
                Some(messages) => Ok(Some((t.to_string(), messages))),
                None => Err(InteropError::format(
                    path,
                    format!(
                        "no {kind} topic {:?} in the bag ({kind} topics: {})",
                        clean(t),
                        if self.topics.is_empty() {
                            "none".to_string()
                        } else {
                            self.names()
                        }
                    ),
                )),
            };
        }
        match self.topics.len() {
            0 => Ok(None),
            1 => Ok(self.topics.pop_first()),
            _ => Err(InteropError::format(
                path,
                format!(
                    "the bag has several {kind} topics ({}); choose one ({option})",
                    self.names()
                ),
            )),
        }
    }
}

/// Reads the scans of the MCAP bag in `bytes`.
pub(super) fn parse_mcap(path: &Path, bytes: &[u8], options: &ReadOptions) -> Result<ScanSet> {
    let mut clouds = TopicsOfKind::default();
    let mut odometry = TopicsOfKind::default();
    let mut others: BTreeMap<String, String> = BTreeMap::new();
    stream::for_each_message(path, bytes, |channel, log_time, data| {
        let raw = || RawMessage {
            log_time,
            data: data.to_vec(),
        };
        let schema = channel.schema_name.as_str();
        match (schema, channel.message_encoding == "cdr") {
            (POINTCLOUD2, true) => {
                clouds.add(path, &channel.topic, options.topic.as_deref(), raw())?
            }
            (ODOMETRY, true) => odometry.add(
                path,
                &channel.topic,
                options.odometry_topic.as_deref(),
                raw(),
            )?,
            _ => {
                others.entry(channel.topic.clone()).or_insert_with(|| {
                    format!(
                        "{:?} ({} in {})",
                        clean(&channel.topic),
                        clean(schema),
                        clean(&channel.message_encoding)
                    )
                });
            }
        }
        Ok(())
    })?;
    let Some((topic, mut messages)) = clouds.choose(
        path,
        options.topic.as_deref(),
        POINTCLOUD2,
        "a topic option",
    )?
    else {
        let seen: Vec<&str> = others.values().map(String::as_str).collect();
        return Err(InteropError::format(
            path,
            format!(
                "no {POINTCLOUD2} topic with CDR messages (topics: {})",
                if seen.is_empty() {
                    "none".to_string()
                } else {
                    seen.join(", ")
                }
            ),
        ));
    };
    messages.sort_by_key(|m| m.log_time);
    let mut notes = vec![note(
        path,
        format!(
            "{} {POINTCLOUD2} messages read from {:?}",
            messages.len(),
            clean(&topic)
        ),
    )];
    let mut scans = Vec::new();
    let mut dropped = 0;
    for (index, raw) in messages.iter().enumerate() {
        let decoded = pointcloud2::decode_pointcloud2(&raw.data).map_err(|e| {
            InteropError::format(
                path,
                format!(
                    "message {index} of {:?} (log time {} ns): {POINTCLOUD2}: {}",
                    clean(&topic),
                    raw.log_time,
                    clean(&e)
                ),
            )
        })?;
        dropped += decoded.dropped;
        try_push(
            path,
            &mut scans,
            ImportedScan {
                name: format!("{}#{index}", clean(&topic)),
                cloud: decoded.cloud,
                world_from_scan: None,
                stamp_ns: Some(decoded.stamp_ns),
                frame_id: Some(clean(&decoded.frame_id)).filter(|f| !f.is_empty()),
            },
            "the bag's scans",
        )?;
    }
    drop(messages);
    if dropped > 0 {
        notes.push(note(
            path,
            format!("{dropped} points with non-finite coordinates dropped from unorganised clouds"),
        ));
    }
    let track = match odometry.choose(
        path,
        options.odometry_topic.as_deref(),
        ODOMETRY,
        "an odometry topic option",
    )? {
        Some((odom_topic, odom_messages)) => Some(read_track(path, &odom_topic, odom_messages)?),
        None => None,
    };
    let odometry = track
        .map(|(odom_topic, track)| place_scans(path, &odom_topic, &track, &mut scans, &mut notes));
    Ok(ScanSet {
        scans,
        local_origin_m: DVec3::ZERO,
        odometry,
        notes,
    })
}

/// The decoded odometry messages of `topic`, sorted by stamp.
fn read_track(
    path: &Path,
    topic: &str,
    messages: Vec<RawMessage>,
) -> Result<(String, Vec<Odometry>)> {
    let mut track = Vec::new();
    for (index, raw) in messages.iter().enumerate() {
        let o = odometry::decode_odometry(&raw.data).map_err(|e| {
            InteropError::format(
                path,
                format!(
                    "message {index} of {:?} (log time {} ns): {ODOMETRY}: {}",
                    clean(topic),
                    raw.log_time,
                    clean(&e)
                ),
            )
        })?;
        try_push(path, &mut track, o, "the bag's odometry")?;
    }
    track.sort_by_key(|o| o.stamp_ns);
    Ok((topic.to_string(), track))
}

/// The odometry pose at each scan's stamp; sets `world_from_scan` where the frames allow.
fn place_scans(
    path: &Path,
    topic: &str,
    track: &[Odometry],
    scans: &mut [ImportedScan],
    notes: &mut Vec<String>,
) -> Vec<DAffine3> {
    let mut poses = Vec::with_capacity(scans.len());
    let Some(first) = track.first() else {
        return poses;
    };
    let (odom_frame, child_frame) = (clean(&first.frame_id), clean(&first.child_frame_id));
    let mut outside = 0;
    let mut unplaced = 0;
    for scan in scans.iter_mut() {
        let stamp = scan.stamp_ns.unwrap_or(first.stamp_ns);
        let (pose, out) = odometry::pose_at(track, stamp).unwrap_or((first.pose, true));
        outside += usize::from(out);
        poses.push(pose);
        scan.world_from_scan = match scan.frame_id.as_deref() {
            Some(f) if f == child_frame => Some(pose),
            Some(f) if f == odom_frame => Some(DAffine3::IDENTITY),
            _ => {
                unplaced += 1;
                None
            }
        };
    }
    notes.push(note(
        path,
        format!(
            "odometry from {:?}: {} messages of {child_frame:?} in {odom_frame:?}",
            clean(topic),
            track.len()
        ),
    ));
    if outside > 0 {
        notes.push(note(path, format!("{outside} scans lie outside the odometry's time span: the nearest odometry pose is used")));
    }
    if unplaced > 0 {
        notes.push(note(
            path,
            format!("{unplaced} clouds are in a frame other than {child_frame:?} or {odom_frame:?}: their world_from_scan is unset (the bag's transforms between frames are not read)"),
        ));
    }
    poses
}

//! Options of every command that reads scans: which topics of a ROS 2 bag to read.

use clap::Args;

/// How multi-scan files are read (flattened into each command's arguments).
#[derive(Args, Clone, Default)]
pub struct ScanReadArgs {
    /// ROS 2 bags (.mcap): the sensor_msgs/msg/PointCloud2 topic to read (default: the only one).
    #[arg(long, value_name = "TOPIC")]
    topic: Option<String>,
    /// ROS 2 bags (.mcap): the nav_msgs/msg/Odometry topic giving each scan's odometry
    /// (default: the only one, if any).
    #[arg(long, value_name = "TOPIC")]
    odometry_topic: Option<String>,
}

impl ScanReadArgs {
    /// The library's read options.
    pub fn options(&self) -> pipeline::ReadOptions {
        pipeline::ReadOptions {
            topic: self.topic.clone(),
            odometry_topic: self.odometry_topic.clone(),
        }
    }
}

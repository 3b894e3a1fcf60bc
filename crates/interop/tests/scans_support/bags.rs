//! Bags for the tests, written with the `mcap` crate's writer and hand-encoded CDR messages
//! (no oracle needed).

use mcap::records::MessageHeader;
use std::collections::BTreeMap;
use std::io::Cursor;

/// A little-endian CDR PointCloud2 of FLOAT32 x y z (`x_datatype` for x) with `points`.
pub fn pointcloud2(points: &[[f32; 3]], x_datatype: u8, data_len_extra: u32) -> Vec<u8> {
    let mut m = vec![0u8, 1, 0, 0];
    let put = |m: &mut Vec<u8>, v: u32| {
        while (m.len() - 4) & 3 != 0 {
            m.push(0);
        }
        m.extend(v.to_le_bytes());
    };
    put(&mut m, 1); // stamp.sec
    put(&mut m, 2); // stamp.nanosec
    put(&mut m, 6);
    m.extend(b"lidar\0");
    put(&mut m, 1); // height
    put(&mut m, points.len() as u32); // width
    put(&mut m, 3);
    for (name, offset, datatype) in [("x", 0, x_datatype), ("y", 4, 7), ("z", 8, 7)] {
        put(&mut m, 2);
        m.extend([name.as_bytes()[0], 0]);
        put(&mut m, offset);
        m.push(datatype);
        put(&mut m, 1);
    }
    m.push(0); // is_bigendian
    put(&mut m, 12);
    put(&mut m, 12 * points.len() as u32);
    put(&mut m, 12 * points.len() as u32 + data_len_extra);
    for p in points {
        for c in p {
            m.extend(c.to_le_bytes());
        }
    }
    m.push(1); // is_dense
    m
}

pub fn cut(mut bytes: Vec<u8>, by: usize) -> Vec<u8> {
    bytes.truncate(bytes.len() - by);
    bytes
}

/// A channel: topic, schema name, messages.
pub type Channel<'a> = (&'a str, &'a str, Vec<Vec<u8>>);

/// A bag with one channel per (topic, schema name, messages).
pub fn bag(compression: Option<mcap::Compression>, channels: &[Channel]) -> Vec<u8> {
    let options = mcap::WriteOptions::new()
        .compression(compression)
        .profile("ros2");
    let mut w = options.create(Cursor::new(Vec::new())).unwrap();
    for (topic, schema, messages) in channels {
        let schema_id = w.add_schema(schema, "ros2msg", b"").unwrap();
        let channel = w
            .add_channel(schema_id, topic, "cdr", &BTreeMap::new())
            .unwrap();
        for (i, data) in messages.iter().enumerate() {
            let header = MessageHeader {
                channel_id: channel,
                sequence: i as u32,
                log_time: 1000 + i as u64,
                publish_time: 1000 + i as u64,
            };
            w.write_to_known_channel(&header, data).unwrap();
        }
    }
    w.finish().unwrap();
    w.into_inner().into_inner()
}

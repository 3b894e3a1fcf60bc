//! The three MCAP records the bag reader needs, parsed here rather than by the `mcap` crate.
//!
//! The crate parses records with `binrw`, which reserves a string's or byte array's length
//! (a u32 from the file) before reading it: a schema name claiming 2 GiB asked for 2 GiB (the
//! `mcap` fuzz target found it). Here every length is checked against the record first.
//!
//! Layouts (MCAP v0, little endian; a string is a u32 byte length and UTF-8 bytes):
//! - Schema (opcode 3): id u16, name string, encoding string, data (u32 length, bytes).
//! - Channel (opcode 4): id u16, schema id u16, topic string, message encoding string,
//!   metadata (u32 byte length, string pairs).
//! - Message (opcode 5): channel id u16, sequence u32, log time u64, publish time u64, data
//!   (the rest of the record).

/// The opcodes read.
pub(super) const SCHEMA: u8 = 0x03;
pub(super) const CHANNEL: u8 = 0x04;
pub(super) const MESSAGE: u8 = 0x05;

/// A schema: its id and name (e.g. `sensor_msgs/msg/PointCloud2`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) struct Schema {
    pub id: u16,
    pub name: String,
}

/// A channel: its id, schema id (0: none), topic and message encoding (e.g. `cdr`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) struct Channel {
    pub id: u16,
    pub schema_id: u16,
    pub topic: String,
    pub message_encoding: String,
}

/// A message: its channel, log time (ns) and data, borrowed from the record.
#[derive(Debug)]
pub(super) struct Message<'a> {
    pub channel_id: u16,
    pub log_time: u64,
    pub data: &'a [u8],
}

/// Reads a record's fields in order, every length checked against what remains.
struct Fields<'a> {
    body: &'a [u8],
    at: usize,
    record: &'static str,
}

impl<'a> Fields<'a> {
    fn take(&mut self, n: usize, what: &str) -> Result<&'a [u8], String> {
        let end = self.at.checked_add(n).filter(|&e| e <= self.body.len());
        let Some(end) = end else {
            return Err(format!(
                "{} record: {what} needs {n} bytes at byte {}, the record has {}",
                self.record,
                self.at,
                self.body.len()
            ));
        };
        let bytes = &self.body[self.at..end];
        self.at = end;
        Ok(bytes)
    }

    fn u16(&mut self, what: &str) -> Result<u16, String> {
        let b = self.take(2, what)?;
        Ok(u16::from_le_bytes([b[0], b[1]]))
    }

    fn u32(&mut self, what: &str) -> Result<u32, String> {
        let b = self.take(4, what)?;
        Ok(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }

    fn u64(&mut self, what: &str) -> Result<u64, String> {
        let mut b = [0u8; 8];
        b.copy_from_slice(self.take(8, what)?);
        Ok(u64::from_le_bytes(b))
    }

    /// A u32-length-prefixed byte string.
    fn prefixed(&mut self, what: &str) -> Result<&'a [u8], String> {
        let n = self.u32(what)? as usize;
        self.take(n, what)
    }

    fn string(&mut self, what: &str) -> Result<String, String> {
        Ok(String::from_utf8_lossy(self.prefixed(what)?).into_owned())
    }
}

/// A Schema record's id and name.
pub(super) fn schema(body: &[u8]) -> Result<Schema, String> {
    let mut f = Fields {
        body,
        at: 0,
        record: "schema",
    };
    let id = f.u16("id")?;
    let name = f.string("name")?;
    f.prefixed("encoding")?;
    f.prefixed("data")?;
    if id == 0 {
        return Err("schema record: id 0 is reserved for \"no schema\"".to_string());
    }
    Ok(Schema { id, name })
}

/// A Channel record's ids, topic and encoding (the metadata is checked, not kept).
pub(super) fn channel(body: &[u8]) -> Result<Channel, String> {
    let mut f = Fields {
        body,
        at: 0,
        record: "channel",
    };
    let id = f.u16("id")?;
    let schema_id = f.u16("schema id")?;
    let topic = f.string("topic")?;
    let message_encoding = f.string("message encoding")?;
    f.prefixed("metadata")?;
    Ok(Channel {
        id,
        schema_id,
        topic,
        message_encoding,
    })
}

/// A Message record's channel, log time and data.
pub(super) fn message(body: &[u8]) -> Result<Message<'_>, String> {
    let mut f = Fields {
        body,
        at: 0,
        record: "message",
    };
    let channel_id = f.u16("channel id")?;
    f.u32("sequence")?;
    let log_time = f.u64("log time")?;
    f.u64("publish time")?;
    Ok(Message {
        channel_id,
        log_time,
        data: &body[f.at..],
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn string(s: &str) -> Vec<u8> {
        let mut v = (s.len() as u32).to_le_bytes().to_vec();
        v.extend(s.as_bytes());
        v
    }

    #[test]
    fn records_parse_and_lengths_are_checked() {
        let mut body = 7u16.to_le_bytes().to_vec();
        body.extend(string("sensor_msgs/msg/PointCloud2"));
        body.extend(string("ros2msg"));
        body.extend(string("uint32 height"));
        assert_eq!(
            schema(&body),
            Ok(Schema {
                id: 7,
                name: "sensor_msgs/msg/PointCloud2".into()
            })
        );
        body[2] = 0xff; // the name claims more than the record holds
        assert!(schema(&body).expect_err("too long").contains("name needs"));

        let mut body = vec![1, 0, 7, 0];
        body.extend(string("/points"));
        body.extend(string("cdr"));
        body.extend(0u32.to_le_bytes());
        let c = channel(&body).expect("a channel");
        assert_eq!((c.id, c.schema_id, c.topic.as_str()), (1, 7, "/points"));
        assert!(channel(&body[..body.len() - 1]).is_err());

        let mut body = vec![1, 0, 9, 0, 0, 0];
        body.extend(5u64.to_le_bytes());
        body.extend(6u64.to_le_bytes());
        body.extend([1, 2, 3]);
        let m = message(&body).expect("a message");
        assert_eq!((m.channel_id, m.log_time, m.data), (1, 5, &[1u8, 2, 3][..]));
        assert!(message(&body[..10]).is_err());
    }
}

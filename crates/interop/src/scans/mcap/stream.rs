//! The messages of a bag in file order, each with its channel.
//!
//! The `mcap` crate's sans-io `LinearReader` walks the container: magic bytes, records,
//! chunks (decompressed with zstd or lz4), the end magic. Its records are parsed here
//! ([`super::records`]) and linked as the MCAP spec says: a channel names a schema defined
//! before it (or none), a message a channel defined before it, and a redefinition (the summary
//! repeats schemas and channels) must match the first definition.

use super::container;
use super::records::{self, Channel, Schema};
use crate::error::{InteropError, Result};
use crate::scans::util::clean;
use std::collections::HashMap;
use std::path::Path;

/// The longest record the `mcap` crate may buffer (a message inside a compressed chunk
/// included): 64 times the file, at least 64 MiB. The crate sizes its buffer by the record's
/// length field before decompressing, and sets no limit of its own for records inside chunks,
/// so a corrupt length there made it allocate without bound (a byte flipped inside a zstd
/// chunk, in `tests/scans_bad_input.rs`). Point data does not compress 64-fold, and single
/// messages beyond 64 MiB in small bags are rarer still.
fn record_length_limit(file_bytes: usize) -> usize {
    file_bytes.saturating_mul(64).max(64 << 20)
}

/// What a message's channel says about it.
pub(super) struct ChannelInfo {
    /// The topic.
    pub topic: String,
    /// The schema's name (empty for a channel without schema).
    pub schema_name: String,
    /// The message encoding (`cdr` for ROS 2).
    pub message_encoding: String,
}

/// Calls `visit` with every message of the bag in `bytes` (its channel, log time and data).
pub(super) fn for_each_message(
    path: &Path,
    bytes: &[u8],
    mut visit: impl FnMut(&ChannelInfo, u64, &[u8]) -> Result<()>,
) -> Result<()> {
    let bad =
        |what: String| InteropError::format(path, format!("not a readable MCAP file: {what}"));
    container::check_chunks(bytes).map_err(bad)?;
    let options = mcap::sans_io::LinearReaderOptions::default()
        .with_record_length_limit(record_length_limit(bytes.len()));
    let mut reader = mcap::sans_io::LinearReader::new_with_options(options);
    let mut schemas: HashMap<u16, Schema> = HashMap::new();
    let mut channels: HashMap<u16, (Channel, ChannelInfo)> = HashMap::new();
    let mut rest = bytes;
    while let Some(event) = reader.next_event() {
        let event = event.map_err(|e| bad(clean(&e.to_string())))?;
        let (opcode, data) = match event {
            mcap::sans_io::LinearReadEvent::ReadRequest(need) => {
                let n = need.min(rest.len());
                reader.insert(n).copy_from_slice(&rest[..n]);
                reader.notify_read(n);
                rest = &rest[n..];
                continue;
            }
            mcap::sans_io::LinearReadEvent::Record { opcode, data } => (opcode, data),
        };
        match opcode {
            records::SCHEMA => {
                let schema = records::schema(data).map_err(|e| bad(clean(&e)))?;
                match schemas.get(&schema.id) {
                    Some(first) if *first != schema => {
                        return Err(bad(format!(
                            "schema {} is defined twice, differently",
                            schema.id
                        )))
                    }
                    Some(_) => {}
                    None => {
                        schemas.insert(schema.id, schema);
                    }
                }
            }
            records::CHANNEL => {
                let channel = records::channel(data).map_err(|e| bad(clean(&e)))?;
                let schema_name = match channel.schema_id {
                    0 => String::new(),
                    id => match schemas.get(&id) {
                        Some(s) => s.name.clone(),
                        None => {
                            return Err(bad(format!(
                            "channel {} ({:?}) names schema {id}, which is not defined before it",
                            channel.id,
                            clean(&channel.topic)
                        )))
                        }
                    },
                };
                match channels.get(&channel.id) {
                    Some((first, _)) if *first != channel => {
                        return Err(bad(format!(
                            "channel {} is defined twice, differently",
                            channel.id
                        )))
                    }
                    Some(_) => {}
                    None => {
                        let info = ChannelInfo {
                            topic: channel.topic.clone(),
                            schema_name,
                            message_encoding: channel.message_encoding.clone(),
                        };
                        channels.insert(channel.id, (channel, info));
                    }
                }
            }
            records::MESSAGE => {
                let message = records::message(data).map_err(|e| bad(clean(&e)))?;
                let Some((_, info)) = channels.get(&message.channel_id) else {
                    return Err(bad(format!(
                        "a message on channel {}, which is not defined before it",
                        message.channel_id
                    )));
                };
                visit(info, message.log_time, message.data)?;
            }
            _ => {}
        }
    }
    Ok(())
}

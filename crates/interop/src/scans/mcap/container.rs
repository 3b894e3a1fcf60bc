//! A walk over an MCAP file's top-level records before the `mcap` crate reads it, checking what
//! the crate trusts: the records inside an uncompressed chunk must end within the chunk.
//!
//! (The `mcap` crate 0.26 subtracts each inner record's length from the chunk's remaining size
//! unchecked, which panics on a record that runs past its chunk; a corrupt length byte is
//! enough, as the corruption sweep of `tests/scans_bad_input.rs` found.)
//!
//! Layout (MCAP v0): an 8-byte magic, then records of an opcode (u8), a length (u64 LE) and
//! that many bytes. A chunk (opcode 6) holds start and end times (u64 each), the uncompressed
//! size (u64), the uncompressed CRC (u32), the compression (a string: u32 length and bytes) and
//! the records (u64 length and bytes), compressed unless the compression is empty.

/// The chunk record's opcode.
const CHUNK: u8 = 0x06;
/// An opcode and a length.
const RECORD_HEADER: usize = 9;
/// The file's magic.
const MAGIC_BYTES: usize = 8;

fn u64_at(b: &[u8], at: usize) -> Option<u64> {
    let bytes: [u8; 8] = b.get(at..at.checked_add(8)?)?.try_into().ok()?;
    Some(u64::from_le_bytes(bytes))
}

fn u32_at(b: &[u8], at: usize) -> Option<u32> {
    let bytes: [u8; 4] = b.get(at..at.checked_add(4)?)?.try_into().ok()?;
    Some(u32::from_le_bytes(bytes))
}

/// Fails where an inner record of an uncompressed chunk would run past the chunk's declared
/// record bytes (`declared`); `available` is what the file holds of them. Stops quietly where
/// the file ends first (the `mcap` crate then reports the end of the file).
fn check_chunk_records(available: &[u8], declared: u64, chunk_at: usize) -> Result<(), String> {
    let mut at = 0u64;
    while at < declared {
        let Some(len) = usize::try_from(at)
            .ok()
            .and_then(|a| u64_at(available, a + 1))
        else {
            return Ok(());
        };
        let left = declared - at;
        if left < RECORD_HEADER as u64 || len > left - RECORD_HEADER as u64 {
            return Err(format!(
                "the record at byte {at} of the uncompressed chunk at byte {chunk_at} runs past the chunk's end"
            ));
        }
        at += RECORD_HEADER as u64 + len;
    }
    Ok(())
}

/// Walks the top-level records; stops quietly where the structure breaks (the `mcap` crate
/// reports that), fails where an uncompressed chunk's records overrun it. A chunk that runs
/// past the end of the file is checked as far as the file goes: the crate starts on its
/// records before it reaches the end.
pub(super) fn check_chunks(bytes: &[u8]) -> Result<(), String> {
    let mut at = MAGIC_BYTES;
    while let (Some(&opcode), Some(len)) = (bytes.get(at), u64_at(bytes, at + 1)) {
        let body_at = at + RECORD_HEADER;
        let body = bytes.get(body_at..).unwrap_or(&[]);
        if opcode == CHUNK {
            // start, end, uncompressed size (24), CRC (4), compression string, records.
            let (Some(name_len), Some(records_len)) = (
                u32_at(body, 28),
                u32_at(body, 28).and_then(|n| u64_at(body, 32usize.checked_add(n as usize)?)),
            ) else {
                return Ok(());
            };
            let records_at = 40 + name_len as usize;
            // The crate refuses a chunk whose records do not fit in the chunk record.
            let fits = (records_at as u64)
                .checked_add(records_len)
                .is_some_and(|end| end <= len);
            if !fits {
                return Ok(());
            }
            if name_len == 0 {
                check_chunk_records(body.get(records_at..).unwrap_or(&[]), records_len, at)?;
            }
        }
        let next = usize::try_from(len)
            .ok()
            .and_then(|l| body_at.checked_add(l));
        match next {
            Some(next) if next <= bytes.len() => at = next,
            _ => return Ok(()),
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn chunk(records: &[u8]) -> Vec<u8> {
        let mut body = vec![0u8; 24 + 4];
        body.extend(0u32.to_le_bytes()); // compression ""
        body.extend((records.len() as u64).to_le_bytes());
        body.extend(records);
        let mut file = b"\x89MCAP0\r\n".to_vec();
        file.push(CHUNK);
        file.extend((body.len() as u64).to_le_bytes());
        file.extend(body);
        file
    }

    #[test]
    fn inner_records_must_end_within_their_chunk() {
        let mut good = vec![0x05u8];
        good.extend(2u64.to_le_bytes());
        good.extend([1, 2]);
        assert_eq!(check_chunks(&chunk(&good)), Ok(()));
        let mut bad = good.clone();
        bad[1] = 3; // one byte longer than there is
        assert!(check_chunks(&chunk(&bad))
            .expect_err("overrun")
            .contains("runs past"));
        // Records of 5 bytes cannot hold a record header: the crate would read past them.
        let mut short = chunk(&good[..5]);
        short.extend([0u8; 16]);
        assert!(check_chunks(&short).is_err());
        assert_eq!(check_chunks(b"\x89MCAP0\r\n\x06\xff"), Ok(()));
        // A chunk record longer than the file: its records are still checked.
        let mut cut = chunk(&bad);
        let n = cut.len() as u64 + 1000;
        cut[9..17].copy_from_slice(&n.to_le_bytes());
        assert!(check_chunks(&cut).is_err());
    }
}

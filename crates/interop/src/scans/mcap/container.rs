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

/// The records of an uncompressed chunk's record bytes overrun it: where, as text.
fn check_chunk_records(records: &[u8], chunk_at: usize) -> Result<(), String> {
    let mut at = 0;
    while at < records.len() {
        let left = records.len() - at;
        let len = u64_at(records, at + 1).filter(|_| left >= RECORD_HEADER);
        let fits = len.is_some_and(|len| len <= (left - RECORD_HEADER) as u64);
        let Some(len) = len.filter(|_| fits) else {
            return Err(format!(
                "the record at byte {at} of the uncompressed chunk at byte {chunk_at} runs past the chunk's end"
            ));
        };
        at += RECORD_HEADER + len as usize;
    }
    Ok(())
}

/// Walks the top-level records; stops quietly where the structure breaks (the `mcap` crate
/// reports that), fails where an uncompressed chunk's records overrun it.
pub(super) fn check_chunks(bytes: &[u8]) -> Result<(), String> {
    let mut at = MAGIC_BYTES;
    while let (Some(&opcode), Some(len)) = (bytes.get(at), u64_at(bytes, at + 1)) {
        let body_at = at + RECORD_HEADER;
        let Some(body) = usize::try_from(len)
            .ok()
            .and_then(|len| bytes.get(body_at..body_at.checked_add(len)?))
        else {
            return Ok(());
        };
        if opcode == CHUNK {
            // start, end, uncompressed size (24), CRC (4), compression string.
            let Some(name_len) = u32_at(body, 28) else {
                return Ok(());
            };
            let name_at = 32usize;
            let records_len_at = name_at.saturating_add(name_len as usize);
            let Some(records_len) = u64_at(body, records_len_at) else {
                return Ok(());
            };
            let records_at = records_len_at + 8;
            let records = usize::try_from(records_len)
                .ok()
                .and_then(|n| body.get(records_at..records_at.checked_add(n)?));
            if let (0, Some(records)) = (name_len, records) {
                check_chunk_records(records, at)?;
            }
        }
        at = body_at + body.len();
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
        assert!(check_chunks(&chunk(&good[..5])).is_err());
        assert_eq!(check_chunks(b"\x89MCAP0\r\n\x06\xff"), Ok(()));
    }
}

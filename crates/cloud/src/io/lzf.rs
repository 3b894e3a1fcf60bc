//! LZF (de)compression, as used by PCD `DATA binary_compressed`.
//!
//! The stream format is liblzf's (so PCL reads what we write and we read what PCL writes):
//! a control byte `c < 32` starts a literal run of `c + 1` bytes; otherwise `c >> 5` is the
//! match length minus 2 (7 meaning "add the next byte"), and the back-reference offset minus 1
//! is `(c & 0x1f) << 8` plus the next byte. Decompression is fully bounds-checked: corrupt input
//! gives an error message, never a panic or an out-of-bounds read.

/// Hash table size (log2) of the compressor.
const HLOG: u32 = 16;
/// Longest literal run one control byte can announce.
const MAX_LIT: usize = 32;
/// Farthest back-reference (offset 1..=8192).
const MAX_OFF: usize = 1 << 13;
/// Longest match: 2 + 7 + 255.
const MAX_REF: usize = 264;
/// Largest expansion of LZF data: a 3-byte back-reference yields at most 264 bytes, so `n`
/// compressed bytes never expand to more than `88 n`. A header promising more is refused
/// before anything is allocated.
pub(crate) const LZF_MAX_RATIO: usize = MAX_REF / 3;

/// Decompresses `input`, which must expand to exactly `expected_len` bytes.
///
/// The output never grows past `expected_len`, so a corrupt stream cannot make us allocate
/// more than the caller allowed. The error says what is wrong and where in the stream.
#[cfg(test)]
pub(crate) fn decompress(input: &[u8], expected_len: usize) -> Result<Vec<u8>, String> {
    let mut out = Vec::new();
    decompress_into(input, expected_len, &mut out)?;
    Ok(out)
}

/// [`decompress`] appending to `out`, which should have room for `expected_len` bytes (the
/// caller allocates, so that it can report a failed allocation); `out` must start empty.
/// An `expected_len` beyond [`LZF_MAX_RATIO`] times the input is refused at once.
pub(crate) fn decompress_into(
    input: &[u8],
    expected_len: usize,
    out: &mut Vec<u8>,
) -> Result<(), String> {
    if expected_len > input.len().saturating_mul(LZF_MAX_RATIO) {
        return Err(format!(
            "{} compressed bytes cannot expand to {expected_len} bytes (LZF expands at most {LZF_MAX_RATIO}-fold)",
            input.len()
        ));
    }
    out.clear();
    out.reserve_exact(expected_len);
    let mut i = 0usize;
    while let Some(&ctrl) = input.get(i) {
        let at = i;
        i += 1;
        let ctrl = usize::from(ctrl);
        if ctrl < MAX_LIT {
            let len = ctrl + 1;
            let lit = input.get(i..i + len).ok_or_else(|| {
                format!("literal run at byte {at} runs past the end of the compressed data")
            })?;
            if out.len() + len > expected_len {
                return Err(overflow(at, expected_len));
            }
            out.extend_from_slice(lit);
            i += len;
        } else {
            let mut len = ctrl >> 5;
            if len == 7 {
                len += usize::from(*input.get(i).ok_or_else(|| cut_short(at))?);
                i += 1;
            }
            let low = usize::from(*input.get(i).ok_or_else(|| cut_short(at))?);
            i += 1;
            let back = ((ctrl & 0x1f) << 8) + low + 1;
            len += 2;
            if back > out.len() {
                return Err(format!(
                    "back-reference at byte {at} points {back} bytes back, before the start of the output ({} bytes so far)",
                    out.len()
                ));
            }
            if out.len() + len > expected_len {
                return Err(overflow(at, expected_len));
            }
            copy_back(out, back, len);
        }
    }
    if out.len() != expected_len {
        return Err(format!(
            "compressed data expands to {} bytes, the header promises {expected_len}",
            out.len()
        ));
    }
    Ok(())
}

/// Appends `len` bytes copied from `back` bytes before the end (`1 <= back <= out.len()`);
/// the source may overlap what is being written (a repeating pattern).
fn copy_back(out: &mut Vec<u8>, back: usize, len: usize) {
    // The copied bytes repeat with period `back`, so copying from the fixed start doubles
    // the run each time (a long run of one byte takes a few copies, not one per byte).
    let src = out.len() - back;
    let mut left = len;
    while left > 0 {
        let n = left.min(out.len() - src);
        out.extend_from_within(src..src + n);
        left -= n;
    }
}

fn overflow(at: usize, expected_len: usize) -> String {
    format!(
        "compressed data at byte {at} expands past the {expected_len} bytes the header promises"
    )
}

fn cut_short(at: usize) -> String {
    format!("back-reference at byte {at} is cut short by the end of the compressed data")
}

/// Compresses `input` into a liblzf-compatible stream (hash-table matcher, one candidate per hash).
pub(crate) fn compress(input: &[u8]) -> Vec<u8> {
    let n = input.len();
    let mut out = Vec::with_capacity(n + n / 16 + 64);
    let mut table = vec![usize::MAX; 1 << HLOG];
    let mut lit_start = 0usize;
    let mut i = 0usize;
    while i + 2 < n {
        let h = hash(input[i], input[i + 1], input[i + 2]);
        let cand = table[h];
        table[h] = i;
        if cand != usize::MAX && i - cand <= MAX_OFF && input[cand..cand + 3] == input[i..i + 3] {
            let max_len = (n - i).min(MAX_REF);
            let mut len = 3;
            while len < max_len && input[cand + len] == input[i + len] {
                len += 1;
            }
            push_literals(&mut out, &input[lit_start..i]);
            let off = i - cand - 1;
            let code = len - 2;
            let high = (off >> 8) as u8;
            if code < 7 {
                out.push(high | ((code as u8) << 5));
            } else {
                out.push(high | (7 << 5));
                out.push((code - 7) as u8);
            }
            out.push((off & 0xff) as u8);
            // Index the positions inside the match so later data can refer to them.
            let end = i + len;
            let mut j = i + 1;
            while j < end && j + 2 < n {
                table[hash(input[j], input[j + 1], input[j + 2])] = j;
                j += 1;
            }
            i = end;
            lit_start = i;
        } else {
            i += 1;
        }
    }
    push_literals(&mut out, &input[lit_start..]);
    out
}

fn hash(a: u8, b: u8, c: u8) -> usize {
    let v = (u32::from(a) << 16) | (u32::from(b) << 8) | u32::from(c);
    (v.wrapping_mul(2_654_435_761) >> (32 - HLOG)) as usize
}

fn push_literals(out: &mut Vec<u8>, lits: &[u8]) {
    for run in lits.chunks(MAX_LIT) {
        out.push((run.len() - 1) as u8);
        out.extend_from_slice(run);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn round_trip(data: &[u8]) {
        let c = compress(data);
        let d = decompress(&c, data.len()).expect("decompresses");
        assert_eq!(d, data);
    }

    #[test]
    fn round_trips_assorted_inputs() {
        round_trip(b"");
        round_trip(b"a");
        round_trip(b"ab");
        round_trip(b"abc");
        round_trip(&[7u8; 10_000]);
        round_trip(b"abcabcabcabcabcabcabcabcabcabcabcabcabcxyzabcabc");
        let mut x = 12345u32;
        let noise: Vec<u8> = (0..70_000)
            .map(|_| {
                x = x.wrapping_mul(1_103_515_245).wrapping_add(12345);
                (x >> 16) as u8
            })
            .collect();
        round_trip(&noise);
        let floats: Vec<u8> = (0..50_000)
            .flat_map(|k| ((k / 7) as f32 * 0.01).to_le_bytes())
            .collect();
        round_trip(&floats);
        assert!(compress(&floats).len() < floats.len());
    }

    #[test]
    fn the_largest_expansion_is_the_ratio() {
        // One literal byte, then back-references of the longest length (2 + 7 + 255).
        let mut stream = vec![0u8, 7];
        let refs = 1000;
        for _ in 0..refs {
            stream.extend([0xe0, 255, 0]);
        }
        let n = 1 + refs * MAX_REF;
        assert_eq!(decompress(&stream, n).expect("valid").len(), n);
        assert!(n <= stream.len() * LZF_MAX_RATIO);
    }

    #[test]
    fn decodes_a_hand_made_liblzf_stream() {
        // literal "ab", then a match of length 4 at offset 2: "abab" -> "ababab".
        let stream = [1u8, b'a', b'b', (2 << 5), 1];
        assert_eq!(decompress(&stream, 6).expect("valid"), b"ababab");
    }

    #[test]
    fn corrupt_streams_are_errors_not_panics() {
        // back-reference before the start
        assert!(decompress(&[0x20, 0x05], 10).is_err());
        // literal run past the end
        assert!(decompress(&[5, b'a'], 6).is_err());
        // long match missing its length byte
        assert!(decompress(&[0, b'a', 0xe0], 20).is_err());
        // expands past the promised size
        assert!(decompress(&[3, 1, 2, 3, 4], 2).is_err());
        // expands to less than promised
        assert!(decompress(&[0, 1], 2).is_err());
        // promises more than any stream of that length can hold: refused before allocating
        let e = decompress(&[0, 1], usize::MAX).unwrap_err();
        assert!(e.contains("cannot expand"), "{e}");
        // every truncation and every single-byte corruption of a real stream: no panic
        let data: Vec<u8> = (0..3000u32).flat_map(|k| (k % 97).to_le_bytes()).collect();
        let c = compress(&data);
        for cut in 0..c.len() {
            let _ = decompress(&c[..cut], data.len());
        }
        for pos in 0..c.len().min(400) {
            let mut bad = c.clone();
            bad[pos] ^= 0xa5;
            let _ = decompress(&bad, data.len());
        }
    }
}

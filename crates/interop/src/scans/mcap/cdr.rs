//! A reader of OMG CDR (XCDR version 1), the encoding of ROS 2 messages in bags.
//!
//! A message starts with a 4-byte encapsulation header: `00 00` (CDR, big endian) or `00 01`
//! (CDR, little endian), then two option bytes. Every primitive of n bytes (1, 2, 4, 8) is
//! aligned to a multiple of n counted from the end of that header. A string is a `u32` length
//! that counts the terminating NUL, then the bytes; a sequence is a `u32` element count, then
//! the elements. Every length is checked against the bytes that remain before anything is
//! taken or allocated. Errors are text naming the byte offset in the message (header included)
//! and the field; the caller adds the file, topic and message.

/// Bytes of the encapsulation header.
const HEADER_BYTES: usize = 4;

/// Reads the fields of one CDR-encoded message in order.
pub(super) struct CdrReader<'a> {
    /// The message after the encapsulation header.
    data: &'a [u8],
    /// Position in `data`.
    pos: usize,
    /// Byte order of the encapsulation.
    big_endian: bool,
}

impl<'a> CdrReader<'a> {
    /// A reader of `message`, checking its encapsulation header.
    pub(super) fn new(message: &'a [u8]) -> Result<Self, String> {
        let Some(header) = message.get(..HEADER_BYTES) else {
            return Err(format!(
                "truncated: {} bytes, the CDR encapsulation header takes {HEADER_BYTES}",
                message.len()
            ));
        };
        let big_endian = match (header[0], header[1]) {
            (0, 0) => true,
            (0, 1) => false,
            (a, b) => {
                return Err(format!(
                    "encapsulation 0x{a:02x}{b:02x} is not plain CDR (0x0000 big endian or 0x0001 little endian)"
                ))
            }
        };
        Ok(CdrReader {
            data: &message[HEADER_BYTES..],
            pos: 0,
            big_endian,
        })
    }

    /// Bytes left after the current position.
    pub(super) fn remaining(&self) -> usize {
        self.data.len() - self.pos
    }

    fn truncated(&self, need: usize, what: &str) -> String {
        format!(
            "truncated at byte {}: {what} needs {need} bytes, {} remain",
            self.pos + HEADER_BYTES,
            self.remaining()
        )
    }

    /// Skips the padding before a primitive of `size` bytes.
    fn align(&mut self, size: usize, what: &str) -> Result<(), String> {
        let pad = (size - self.pos % size) % size;
        if pad > self.remaining() {
            return Err(self.truncated(pad, what));
        }
        self.pos += pad;
        Ok(())
    }

    /// The next `n` bytes.
    fn take(&mut self, n: usize, what: &str) -> Result<&'a [u8], String> {
        if n > self.remaining() {
            return Err(self.truncated(n, what));
        }
        let bytes = &self.data[self.pos..self.pos + n];
        self.pos += n;
        Ok(bytes)
    }

    /// The next primitive of `N` bytes, aligned, in the message's byte order (as little endian).
    fn primitive<const N: usize>(&mut self, what: &str) -> Result<[u8; N], String> {
        self.align(N, what)?;
        let mut bytes = [0u8; N];
        bytes.copy_from_slice(self.take(N, what)?);
        if self.big_endian {
            bytes.reverse();
        }
        Ok(bytes)
    }

    /// A `uint8` (also `char`, `byte`).
    pub(super) fn u8(&mut self, what: &str) -> Result<u8, String> {
        Ok(self.take(1, what)?[0])
    }

    /// A `bool` (any non-zero byte is true).
    pub(super) fn bool(&mut self, what: &str) -> Result<bool, String> {
        Ok(self.u8(what)? != 0)
    }

    /// A `uint32`.
    pub(super) fn u32(&mut self, what: &str) -> Result<u32, String> {
        self.primitive::<4>(what).map(u32::from_le_bytes)
    }

    /// An `int32`.
    pub(super) fn i32(&mut self, what: &str) -> Result<i32, String> {
        self.primitive::<4>(what).map(i32::from_le_bytes)
    }

    /// A `float64`.
    pub(super) fn f64(&mut self, what: &str) -> Result<f64, String> {
        self.primitive::<8>(what).map(f64::from_le_bytes)
    }

    /// A `string`: its bytes without the terminating NUL, invalid UTF-8 replaced.
    pub(super) fn string(&mut self, what: &str) -> Result<String, String> {
        let len = self.u32(what)? as usize;
        let bytes = self.take(len, what)?;
        let text = bytes.strip_suffix(&[0]).unwrap_or(bytes);
        Ok(String::from_utf8_lossy(text).into_owned())
    }

    /// A `sequence<uint8>` (or `uint8[]`): the bytes, borrowed.
    pub(super) fn byte_sequence(&mut self, what: &str) -> Result<&'a [u8], String> {
        let len = self.u32(what)? as usize;
        self.take(len, what)
    }

    /// The element count of a sequence whose elements take at least `min_bytes` each, checked
    /// against the bytes that remain (so it can size an allocation).
    pub(super) fn sequence_len(&mut self, min_bytes: usize, what: &str) -> Result<usize, String> {
        let n = self.u32(what)? as usize;
        let need = n.saturating_mul(min_bytes);
        if need > self.remaining() {
            return Err(format!(
                "at byte {}: {n} {what} need at least {need} bytes, {} remain",
                self.pos + HEADER_BYTES,
                self.remaining()
            ));
        }
        Ok(n)
    }

    /// Skips `n` `float64` values (a fixed array such as a covariance), checking they are there.
    pub(super) fn skip_f64s(&mut self, n: usize, what: &str) -> Result<(), String> {
        self.align(8, what)?;
        self.take(n * 8, what).map(|_| ())
    }

    /// A `std_msgs/msg/Header`: the stamp in nanoseconds since the epoch and the frame id.
    pub(super) fn header(&mut self) -> Result<(i64, String), String> {
        let sec = self.i32("header.stamp.sec")?;
        let nanosec = self.u32("header.stamp.nanosec")?;
        let frame_id = self.string("header.frame_id")?;
        Ok((
            i64::from(sec) * 1_000_000_000 + i64::from(nanosec),
            frame_id,
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn little_and_big_endian_with_alignment() {
        // LE: u8 7, pad 3, u32 5, string "ab" (payload bytes 8..15), pad 1, f64 1.5
        let mut le = vec![
            0, 1, 0, 0, 7, 0, 0, 0, 5, 0, 0, 0, 3, 0, 0, 0, b'a', b'b', 0,
        ];
        le.push(0);
        le.extend(1.5f64.to_le_bytes());
        let mut r = CdrReader::new(&le).expect("LE header");
        assert_eq!(r.u8("a").expect("u8"), 7);
        assert_eq!(r.u32("b").expect("u32"), 5);
        assert_eq!(r.string("c").expect("string"), "ab");
        assert_eq!(r.f64("d").expect("f64"), 1.5);
        assert_eq!(r.remaining(), 0);

        let mut be = vec![0, 0, 0, 0, 0, 0, 0, 9, 0xff, 0xff, 0xff, 0xfe];
        be.extend((-2.25f64).to_be_bytes());
        let mut r = CdrReader::new(&be).expect("BE header");
        assert_eq!(r.u32("a").expect("u32"), 9);
        assert_eq!(r.i32("b").expect("i32"), -2);
        assert_eq!(r.f64("c").expect("f64"), -2.25);
    }

    #[test]
    fn lengths_are_checked_before_use() {
        let msg = [0, 1, 0, 0, 0xff, 0xff, 0xff, 0x7f, 1, 2];
        let e = CdrReader::new(&msg)
            .expect("header")
            .byte_sequence("data")
            .expect_err("too long");
        assert!(e.contains("data needs 2147483647 bytes"), "{e}");
        let e = CdrReader::new(&msg)
            .expect("header")
            .sequence_len(13, "fields")
            .expect_err("too many");
        assert!(e.contains("fields need at least"), "{e}");
        assert!(CdrReader::new(&[0, 2, 0, 0]).is_err());
        assert!(CdrReader::new(&[0, 1]).is_err());
    }
}

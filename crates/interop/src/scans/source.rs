//! Where a reader's bytes come from: a file on disk, read as needed, or bytes already in memory
//! (the fuzz targets). Readers that take a [`ByteSource`] never hold a whole file: a 10 M-point
//! LAZ or E57 file is read in pieces, and only the points themselves are kept.

use crate::error::Result;
use std::fs::File;
use std::io::{Cursor, Read, Seek, SeekFrom};
use std::path::{Path, PathBuf};

/// The buffer of each file reader: large enough that the decoders' small reads stay in memory.
const FILE_BUFFER_BYTES: usize = 1 << 20;

/// Random access to a file's bytes. Each [`ByteSource::reader`] is independent (its own
/// position), so that two threads can decode two halves of a file.
pub(super) trait ByteSource: Sync {
    /// A reader positioned at byte 0.
    type Reader<'a>: Read + Seek + Send
    where
        Self: 'a;

    /// The size in bytes.
    fn len(&self) -> u64;

    /// A new reader at byte 0.
    fn reader(&self) -> std::io::Result<Self::Reader<'_>>;

    /// The `n` bytes at `at`, or `None` where they lie (partly) beyond the end or cannot be
    /// read. Meant for headers and tables: `n` is small, or bounded by the file's size.
    fn bytes_at(&self, at: u64, n: usize) -> Option<Vec<u8>> {
        if at.checked_add(n as u64)? > self.len() {
            return None;
        }
        let mut reader = self.reader().ok()?;
        reader.seek(SeekFrom::Start(at)).ok()?;
        let mut out = Vec::new();
        out.try_reserve_exact(n).ok()?;
        out.resize(n, 0);
        reader.read_exact(&mut out).ok()?;
        Some(out)
    }

    /// The little-endian `u32` at `at`.
    fn u32_at(&self, at: u64) -> Option<u32> {
        let b = self.bytes_at(at, 4)?;
        Some(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }

    /// The little-endian `u64` at `at`.
    fn u64_at(&self, at: u64) -> Option<u64> {
        let b: [u8; 8] = self.bytes_at(at, 8)?.try_into().ok()?;
        Some(u64::from_le_bytes(b))
    }
}

/// A file on disk, opened anew (buffered) for each reader; small reads go straight to the file.
pub(super) struct FileSource {
    path: PathBuf,
    file: File,
    len: u64,
}

impl FileSource {
    /// Opens `path` (a folder or an unreadable file is the `cloud` crate's I/O error naming it).
    pub(super) fn open(path: &Path) -> Result<FileSource> {
        let io_error = |e| crate::error::InteropError::from(cloud::CloudError::io(path, e));
        if path.is_dir() {
            return Err(io_error(std::io::Error::new(
                std::io::ErrorKind::IsADirectory,
                "is a folder, not a file",
            )));
        }
        let file = File::open(path).map_err(io_error)?;
        let len = file.metadata().map_err(io_error)?.len();
        Ok(FileSource {
            path: path.to_path_buf(),
            file,
            len,
        })
    }
}

impl ByteSource for FileSource {
    type Reader<'a> = SeekBuffered;

    fn len(&self) -> u64 {
        self.len
    }

    /// One positioned read (no buffer): the LAZ checks read a few bytes at each chunk.
    fn bytes_at(&self, at: u64, n: usize) -> Option<Vec<u8>> {
        if at.checked_add(n as u64)? > self.len {
            return None;
        }
        let mut out = Vec::new();
        out.try_reserve_exact(n).ok()?;
        out.resize(n, 0);
        read_exact_at(&self.file, &mut out, at).ok()?;
        Some(out)
    }

    fn reader(&self) -> std::io::Result<SeekBuffered> {
        Ok(SeekBuffered {
            file: File::open(&self.path)?,
            buffer: Vec::new(),
            buffer_at: 0,
            pos: 0,
            len: self.len,
        })
    }
}

#[cfg(unix)]
fn read_exact_at(file: &File, out: &mut [u8], at: u64) -> std::io::Result<()> {
    std::os::unix::fs::FileExt::read_exact_at(file, out, at)
}

#[cfg(not(unix))]
fn read_exact_at(file: &File, out: &mut [u8], at: u64) -> std::io::Result<()> {
    let mut file = file.try_clone()?;
    file.seek(SeekFrom::Start(at))?;
    file.read_exact(out)
}

/// A buffered file reader whose seeks keep the buffer. `std::io::BufReader` drops its buffer on
/// every seek, and the `e57` crate seeks before each 1 KiB page it reads: with `BufReader` a
/// 160 MB E57 file read 14 s instead of 1 (bench/read_formats.sh).
pub(super) struct SeekBuffered {
    file: File,
    buffer: Vec<u8>,
    /// The file offset of `buffer[0]`.
    buffer_at: u64,
    /// The reading position in the file.
    pos: u64,
    len: u64,
}

impl Read for SeekBuffered {
    fn read(&mut self, out: &mut [u8]) -> std::io::Result<usize> {
        let end = self.buffer_at + self.buffer.len() as u64;
        if self.pos < self.buffer_at || self.pos >= end {
            if out.len() >= FILE_BUFFER_BYTES {
                // A large read goes straight to the caller.
                self.file.seek(SeekFrom::Start(self.pos))?;
                let n = self.file.read(out)?;
                self.pos += n as u64;
                return Ok(n);
            }
            self.buffer.resize(FILE_BUFFER_BYTES, 0);
            self.file.seek(SeekFrom::Start(self.pos))?;
            let mut filled = 0;
            while filled < self.buffer.len() {
                match self.file.read(&mut self.buffer[filled..]) {
                    Ok(0) => break,
                    Ok(n) => filled += n,
                    Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
                    Err(e) => return Err(e),
                }
            }
            self.buffer.truncate(filled);
            self.buffer_at = self.pos;
            if filled == 0 {
                return Ok(0);
            }
        }
        let start = (self.pos - self.buffer_at) as usize;
        let n = out.len().min(self.buffer.len() - start);
        out[..n].copy_from_slice(&self.buffer[start..start + n]);
        self.pos += n as u64;
        Ok(n)
    }
}

impl Seek for SeekBuffered {
    fn seek(&mut self, to: SeekFrom) -> std::io::Result<u64> {
        let target = match to {
            SeekFrom::Start(at) => Some(at),
            SeekFrom::Current(delta) => self.pos.checked_add_signed(delta),
            SeekFrom::End(delta) => self.len.checked_add_signed(delta),
        };
        self.pos = target.ok_or_else(|| {
            std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                "seek before the start of the file",
            )
        })?;
        Ok(self.pos)
    }
}

/// Bytes in memory.
pub(super) struct MemorySource<'s>(pub &'s [u8]);

impl<'s> ByteSource for MemorySource<'s> {
    type Reader<'a>
        = Cursor<&'s [u8]>
    where
        Self: 'a;

    fn len(&self) -> u64 {
        self.0.len() as u64
    }

    fn reader(&self) -> std::io::Result<Cursor<&'s [u8]>> {
        Ok(Cursor::new(self.0))
    }

    fn bytes_at(&self, at: u64, n: usize) -> Option<Vec<u8>> {
        let start = usize::try_from(at).ok()?;
        Some(self.0.get(start..start.checked_add(n)?)?.to_vec())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn file_and_memory_sources_read_the_same_bytes() {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("bytes.bin");
        let data: Vec<u8> = (0..=255u8).cycle().take(3000).collect();
        std::fs::write(&path, &data).expect("write");
        let file = FileSource::open(&path).expect("open");
        let memory = MemorySource(&data);
        assert_eq!(file.len(), 3000);
        assert_eq!(file.bytes_at(250, 10), memory.bytes_at(250, 10));
        assert_eq!(file.u32_at(4), Some(u32::from_le_bytes([4, 5, 6, 7])));
        assert_eq!(
            memory.u64_at(2992),
            memory
                .bytes_at(2992, 8)
                .map(|b| { u64::from_le_bytes(b.try_into().expect("8 bytes")) })
        );
        assert_eq!(file.bytes_at(2995, 8), None);
        assert_eq!(memory.bytes_at(2995, 8), None);
        assert!(FileSource::open(dir.path()).is_err());
        // Reads across the buffer's end, seeks back into it, and past the end.
        let mut reader = file.reader().expect("reader");
        let mut all = Vec::new();
        reader.read_to_end(&mut all).expect("read");
        assert_eq!(all, data);
        reader.seek(SeekFrom::Start(1000)).expect("seek");
        let mut ten = [0u8; 10];
        reader.read_exact(&mut ten).expect("read after seek");
        assert_eq!(&ten[..], &data[1000..1010]);
        reader.seek(SeekFrom::Current(-20)).expect("seek back");
        reader
            .read_exact(&mut ten)
            .expect("read after seeking back");
        assert_eq!(&ten[..], &data[990..1000]);
        assert_eq!(reader.seek(SeekFrom::End(-3)).expect("seek end"), 2997);
        assert_eq!(reader.read(&mut ten).expect("tail"), 3);
        assert_eq!(reader.read(&mut ten).expect("eof"), 0);
        assert!(reader.seek(SeekFrom::Current(-5000)).is_err());
    }
}

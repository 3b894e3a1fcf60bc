//! No allocation a file can dictate: the numbers in a header (COUNT, WIDTH, element counts,
//! LZF sizes) never size an allocation beyond what the file's bytes can hold, and memory that
//! cannot be had is an `OutOfMemory` error (the job failed, exit 1), never an abort.
//!
//! This test binary counts allocations per thread: it records the largest request and refuses
//! (returns null for) requests above a per-thread limit, as a machine without the memory would.
//! Without the fixes these tests abort the process (an infallible allocation failing).

use cloud::fuzzing::{read_3d_bytes, read_pcd_bytes, read_ply_bytes, read_xyz_bytes};
use cloud::{BadInput, CloudError, PcdEncoding, PointCloud};
use glam::Vec3;
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::path::Path;

struct Tracking;

thread_local! {
    static LARGEST: Cell<usize> = const { Cell::new(0) };
    static LIMIT: Cell<usize> = const { Cell::new(usize::MAX) };
}

/// Records a request of `size` bytes; false where it is over this thread's limit.
fn allowed(size: usize) -> bool {
    let _ = LARGEST.try_with(|c| c.set(c.get().max(size)));
    LIMIT.try_with(|l| size <= l.get()).unwrap_or(true)
}

// SAFETY: forwards to the system allocator, or returns null (an allowed allocation failure).
unsafe impl GlobalAlloc for Tracking {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if !allowed(layout.size()) {
            return std::ptr::null_mut();
        }
        unsafe { System.alloc(layout) }
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if !allowed(layout.size()) {
            return std::ptr::null_mut();
        }
        unsafe { System.alloc_zeroed(layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if !allowed(new_size) {
            return std::ptr::null_mut();
        }
        unsafe { System.realloc(ptr, layout, new_size) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Tracking = Tracking;

/// Runs `f` with allocations above `limit` bytes refused; its result and the largest request.
fn measured<T>(limit: usize, f: impl FnOnce() -> T) -> (T, usize) {
    LARGEST.with(|c| c.set(0));
    LIMIT.with(|l| l.set(limit));
    let out = f();
    LIMIT.with(|l| l.set(usize::MAX));
    (out, LARGEST.with(Cell::get))
}

/// The most a reader may allocate at once for a file of `len` bytes.
fn bound(len: usize) -> usize {
    (64 * len).max(1 << 16)
}

/// Reads `bytes` as `name` with allocations above 1 GB refused; must fail and stay within
/// [`bound`].
fn refused_cheaply(name: &str, bytes: &[u8]) -> CloudError {
    let path = Path::new(name);
    let read = || match path.extension().and_then(|e| e.to_str()) {
        Some("pcd") => read_pcd_bytes(path, bytes).map(|(c, _)| c),
        Some("ply") => read_ply_bytes(path, bytes).map(|(c, _)| c),
        Some("xyz") => read_xyz_bytes(path, bytes),
        _ => read_3d_bytes(path, bytes),
    };
    let (result, largest) = measured(1 << 30, read);
    let e = result.expect_err("must be refused");
    assert!(e.to_string().contains(name), "names the file: {e}");
    assert!(
        largest <= bound(bytes.len()),
        "{name}: {largest} bytes allocated at once for a {}-byte file ({e})",
        bytes.len()
    );
    e
}

#[test]
fn pcd_ascii_count_does_not_size_an_allocation() {
    // The 68 GB request of the original finding (Vec::with_capacity(COUNT sum) of &str).
    let bytes = include_bytes!("data/bad/pcd_ascii_count_4294967296.pcd");
    let e = refused_cheaply("pcd_ascii_count_4294967296.pcd", bytes);
    assert!(
        e.to_string()
            .contains("expected 4294967298 values, found 3"),
        "{e}"
    );
}

#[test]
fn pcd_header_sizes_do_not_size_allocations() {
    let head = |w: &str, data: &str| {
        format!("FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH {w}\nHEIGHT 1\nDATA {data}\n")
    };
    for data in ["ascii", "binary", "binary_compressed"] {
        let bytes = format!("{}1 2 3\n", head("1000000000", data));
        refused_cheaply("width.pcd", bytes.as_bytes());
    }
    // An uncompressed size that the compressed bytes cannot hold (ratio above 88).
    let n = 100_000u32;
    let mut bytes = head(&n.to_string(), "binary_compressed").into_bytes();
    bytes.extend(4u32.to_le_bytes());
    bytes.extend((n * 12).to_le_bytes());
    bytes.extend([0, 0, 0xe0, 0]);
    let e = refused_cheaply("ratio.pcd", &bytes);
    assert!(e.to_string().contains("cannot expand"), "{e}");
}

#[test]
fn ply_element_counts_do_not_size_allocations() {
    let ascii = "ply\nformat ascii 1.0\nelement vertex 1000000000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n1 2 3\n";
    refused_cheaply("many.ply", ascii.as_bytes());
    let mut binary = ascii
        .replace("ascii", "binary_little_endian")
        .replace("float", "uchar")
        .into_bytes();
    binary.truncate(binary.len() - 6);
    binary.extend([1, 2, 3]);
    refused_cheaply("many_bin.ply", &binary);
    let lists = "ply\nformat binary_little_endian 1.0\nelement pad 1000000000000000000\nproperty list uchar int p\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n\0\0\0";
    refused_cheaply("lists.ply", lists.as_bytes());
}

#[test]
fn threedtk_shape_line_does_not_overflow() {
    // rows x cols overflows usize: the shape is ignored (no panic), the point is read.
    let path = Path::new("shape.3d");
    let c = read_3d_bytes(path, b"99999999999 x 99999999999\n100 0 0\n").expect("valid");
    assert_eq!((c.len(), c.organized), (1, None));
}

#[test]
fn text_readers_allocate_in_proportion_to_the_file() {
    let text = "1 2 3\n".repeat(1000);
    let (c, largest) = measured(1 << 30, || {
        read_xyz_bytes(Path::new("a.xyz"), text.as_bytes())
    });
    assert_eq!(c.expect("valid").len(), 1000);
    assert!(largest <= bound(text.len()), "{largest}");
    let blank = "\n".repeat(100_000);
    refused_cheaply("blank.xyz", blank.as_bytes());
    refused_cheaply("blank.3d", blank.as_bytes());
}

/// A `binary_compressed` PCD of `n` points at the origin (compresses about 88-fold).
fn zeros_lzf(n: usize) -> (tempfile::TempDir, std::path::PathBuf) {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("zeros.pcd");
    let cloud = PointCloud::from_points(vec![Vec3::ZERO; n]);
    cloud::io::pcd::write_pcd(&path, &cloud, PcdEncoding::BinaryCompressed).expect("write");
    (dir, path)
}

#[test]
fn memory_that_cannot_be_had_is_out_of_memory_not_an_abort() {
    // 1 M points: 12 MB decompressed from ~140 KB; allow 8 MB at once.
    let (_dir, path) = zeros_lzf(1_000_000);
    let bytes = std::fs::read(&path).expect("read");
    assert!(bytes.len() < 200_000, "{}", bytes.len());
    let (result, _) = measured(8 << 20, || read_pcd_bytes(&path, &bytes));
    let e = result.expect_err("out of memory");
    assert!(
        matches!(
            e,
            CloudError::OutOfMemory {
                bytes: 12_000_000,
                ..
            }
        ),
        "{e}"
    );
    assert!(!e.is_bad_input(), "not the file's fault: exit code 1");
    let text = e.to_string();
    assert!(
        text.contains("zeros.pcd") && text.contains("12000000 bytes") && text.contains("12.00 MB"),
        "{text}"
    );
    // With the memory, the same file reads.
    let (result, _) = measured(usize::MAX, || read_pcd_bytes(&path, &bytes));
    assert_eq!(result.expect("reads").0.len(), 1_000_000);
    // Every reader's big buffers: points of a binary PCD, PLY and XYZ.
    let c = PointCloud::from_points(vec![Vec3::ONE; 200_000]);
    let dir = tempfile::tempdir().expect("tempdir");
    for name in ["b.pcd", "b.ply", "b.xyz", "b.3d"] {
        let p = dir.path().join(name);
        cloud::write_cloud(&p, &c).expect("write");
        let bytes = std::fs::read(&p).expect("read");
        let (result, _) = measured(1 << 20, || cloud::fuzzing::read_cloud_bytes(&p, &bytes));
        let e = result.expect_err("out of memory");
        assert!(matches!(e, CloudError::OutOfMemory { .. }), "{name}: {e}");
    }
}

//! The sparse cell index shared by the bucket grid and voxel downsampling: integer cell
//! coordinates packed into one key over the cloud's bounding box, and an open-addressing hash
//! table from keys to dense cell ids, so only occupied cells cost memory.

/// The most cells a key space may span (2^40).
pub(crate) const MAX_CELLS: f64 = (1u64 << 40) as f64;

/// The bucket key of in-range bucket coordinates.
#[inline(always)]
pub(crate) fn pack(c: [i64; 3], dims: [i64; 3]) -> u64 {
    (c[0] + dims[0] * (c[1] + dims[1] * c[2])) as u64
}

/// An open-addressing hash table (linear probing) from bucket keys to dense bucket ids.
pub(crate) struct CellTable {
    keys: Vec<u64>,
    vals: Vec<u32>,
    shift: u32,
    len: usize,
}

const EMPTY: u64 = u64::MAX;

impl CellTable {
    pub(crate) fn with_capacity(n: usize) -> CellTable {
        let slots = (2 * n.max(8)).next_power_of_two();
        CellTable {
            keys: vec![EMPTY; slots],
            vals: vec![0; slots],
            shift: 64 - slots.trailing_zeros(),
            len: 0,
        }
    }

    /// Number of keys held.
    pub(crate) fn len(&self) -> usize {
        self.len
    }

    #[inline(always)]
    fn slot(&self, key: u64) -> usize {
        (key.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> self.shift) as usize
    }

    #[inline(always)]
    pub(crate) fn get(&self, key: u64) -> Option<u32> {
        let mask = self.keys.len() - 1;
        let mut s = self.slot(key);
        loop {
            let k = self.keys[s];
            if k == key {
                return Some(self.vals[s]);
            }
            if k == EMPTY {
                return None;
            }
            s = (s + 1) & mask;
        }
    }

    /// The id of `key`, inserting it with `new_id` if absent.
    pub(crate) fn get_or_insert(&mut self, key: u64, new_id: u32) -> u32 {
        if 2 * (self.len + 1) > self.keys.len() {
            self.grow();
        }
        let mask = self.keys.len() - 1;
        let mut s = self.slot(key);
        loop {
            let k = self.keys[s];
            if k == key {
                return self.vals[s];
            }
            if k == EMPTY {
                self.keys[s] = key;
                self.vals[s] = new_id;
                self.len += 1;
                return new_id;
            }
            s = (s + 1) & mask;
        }
    }

    fn grow(&mut self) {
        let old_keys = std::mem::take(&mut self.keys);
        let old_vals = std::mem::take(&mut self.vals);
        *self = CellTable::with_capacity(old_keys.len());
        for (k, v) in old_keys.into_iter().zip(old_vals) {
            if k != EMPTY {
                self.get_or_insert(k, v);
            }
        }
    }
}

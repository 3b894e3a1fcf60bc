//! ASPRS classification values (LAS `classification`: 2 ground, 6 building...) as PCD fields
//! and PLY properties store them, made into the cloud's codes. semsim's own type (`U1` /
//! `uchar`) is taken as it is; any other numeric type (PDAL, for one, writes `classification`
//! as `F 8` by default) is converted with a note where every value is an integer 0..=255.
//! Where a value is not (negative, above 255, a fraction, NaN), the whole column is skipped
//! with a note and the cloud has no classification: never a reason to refuse the file, as a
//! `class` column holding values that are no class code.

use super::scalar::Scalar;
use super::text::Notes;
use crate::error::{try_vec, Result};
use std::path::Path;

/// The ASPRS code of a file value, `None` where it is none.
fn code(v: f64) -> Option<u8> {
    (v.fract() == 0.0 && (0.0..=255.0).contains(&v)).then_some(v as u8)
}

/// Values that are no ASPRS code: how many, and the first (point index and value).
#[derive(Default)]
struct Bad {
    count: usize,
    first: Option<(usize, f64)>,
}

impl Bad {
    /// The code for the value of point `i`, remembering a value that is none (read as 0).
    fn code(&mut self, i: usize, v: f64) -> u8 {
        code(v).unwrap_or_else(|| {
            self.count += 1;
            self.first.get_or_insert((i, v));
            0
        })
    }
}

/// Collects one file's classification column, remembering what it could not convert.
pub(crate) struct AsprsConv {
    /// How the column is named in notes (e.g. `field classification (TYPE F, SIZE 8)`).
    desc: String,
    /// True for semsim's own type (unsigned, 1 byte): no note.
    own: bool,
    codes: Vec<u8>,
    bad: Bad,
}

impl AsprsConv {
    /// An empty column with room for `cap` codes (the callers bound `cap` by the file's size).
    pub(crate) fn new(path: &Path, desc: String, ty: Scalar, cap: usize) -> Result<Self> {
        Ok(AsprsConv {
            desc,
            own: ty == Scalar::U8,
            codes: try_vec(path, cap, "the ASPRS classification")?,
            bad: Bad::default(),
        })
    }

    /// Adds the value of the next point (text data, PLY binary data).
    pub(crate) fn push(&mut self, v: f64) {
        let c = self.bad.code(self.codes.len(), v);
        self.codes.push(c);
    }

    /// Decodes a whole little-endian column of `n` values of type `ty`, spaced `stride` bytes
    /// from the start of `src` (see [`Scalar::decode_into`]); `None` if `src` is too short. `n`
    /// must not exceed the room [`AsprsConv::new`] was given.
    pub(crate) fn decode(&mut self, ty: Scalar, src: &[u8], stride: usize, n: usize) -> Option<()> {
        self.codes.resize(n, 0);
        let (bad, mut i) = (&mut self.bad, 0);
        ty.decode_into(src, stride, &mut self.codes, |c, v| {
            *c = bad.code(i, v);
            i += 1;
        })
    }

    /// The codes, or `None` where a value is no ASPRS code; notes a conversion or the skip.
    pub(crate) fn finish(self, notes: &mut Notes) -> Option<Vec<u8>> {
        let desc = &self.desc;
        if let Some((i, v)) = self.bad.first {
            let n = self.bad.count;
            notes.add(format_args!(
                "{desc} holds {n} value(s) that are no ASPRS class (an integer 0..=255), e.g. {v} at point {i}: skipped, no classification read"
            ));
            return None;
        }
        if !self.own {
            notes.add(format_args!("{desc} read as ASPRS classification"));
        }
        Some(self.codes)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn conv(ty: Scalar) -> AsprsConv {
        AsprsConv::new(Path::new("a"), "column c".into(), ty, 8).expect("small")
    }

    #[test]
    fn whole_values_0_to_255_are_codes_and_others_skip_the_column() {
        let mut notes = Notes::new(Path::new("a"));
        let mut c = conv(Scalar::U8);
        [0.0, 2.0, 255.0].into_iter().for_each(|v| c.push(v));
        assert_eq!(c.finish(&mut notes), Some(vec![0, 2, 255]));
        assert!(notes.list.is_empty(), "{:?}", notes.list);

        let mut c = conv(Scalar::F64);
        [6.0, -0.0].into_iter().for_each(|v| c.push(v));
        assert_eq!(c.finish(&mut notes), Some(vec![6, 0]));
        assert_eq!(notes.list, ["a: column c read as ASPRS classification"]);

        for bad in [256.0, -1.0, 2.5, f64::NAN] {
            let mut notes = Notes::new(Path::new("a"));
            let mut c = conv(Scalar::I32);
            [1.0, bad, bad].into_iter().for_each(|v| c.push(v));
            assert_eq!(c.finish(&mut notes), None, "{bad}");
            assert_eq!(notes.list.len(), 1);
            assert!(
                notes.list[0].contains("holds 2 value(s)")
                    && notes.list[0].contains("at point 1: skipped"),
                "{:?}",
                notes.list
            );
        }
    }

    #[test]
    fn binary_columns_decode_with_a_stride() {
        let data: Vec<u8> = [3u16, 999, 7, 1000]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let mut notes = Notes::new(Path::new("a"));
        let mut c = conv(Scalar::U16);
        assert_eq!(c.decode(Scalar::U16, &data, 4, 2), Some(()));
        assert_eq!(c.finish(&mut notes), Some(vec![3, 7]));
        let mut c = conv(Scalar::U16);
        assert_eq!(c.decode(Scalar::U16, &data, 2, 4), Some(()));
        assert_eq!(c.finish(&mut notes), None);
        assert!(
            notes.list[1].contains("e.g. 999 at point 1"),
            "{:?}",
            notes.list
        );
        assert_eq!(conv(Scalar::U16).decode(Scalar::U16, &data, 4, 3), None);
    }
}

//! Numeric field types shared by the PCD and PLY readers: decoded from bytes (either byte
//! order) or from text, always to `f64` (exact for every type except 64-bit integers above 2^53).

/// A numeric type a file field can have.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Scalar {
    F32,
    F64,
    U8,
    U16,
    U32,
    U64,
    I8,
    I16,
    I32,
    I64,
}

macro_rules! decode_as {
    ($t:ty, $b:expr, $big:expr) => {{
        let a = *$b.first_chunk::<{ std::mem::size_of::<$t>() }>()?;
        (if $big {
            <$t>::from_be_bytes(a)
        } else {
            <$t>::from_le_bytes(a)
        }) as f64
    }};
}

impl Scalar {
    /// Size in bytes.
    pub(crate) fn size(self) -> usize {
        match self {
            Scalar::U8 | Scalar::I8 => 1,
            Scalar::U16 | Scalar::I16 => 2,
            Scalar::F32 | Scalar::U32 | Scalar::I32 => 4,
            Scalar::F64 | Scalar::U64 | Scalar::I64 => 8,
        }
    }

    /// True for `F32` and `F64`.
    pub(crate) fn is_float(self) -> bool {
        matches!(self, Scalar::F32 | Scalar::F64)
    }

    /// The PCD `TYPE` letter: `F`, `U` or `I`.
    pub(crate) fn pcd_letter(self) -> char {
        match self {
            Scalar::F32 | Scalar::F64 => 'F',
            Scalar::U8 | Scalar::U16 | Scalar::U32 | Scalar::U64 => 'U',
            Scalar::I8 | Scalar::I16 | Scalar::I32 | Scalar::I64 => 'I',
        }
    }

    /// The PLY type name (`uint64`/`int64` for the 8-byte integers PLY does not have).
    pub(crate) fn ply_name(self) -> &'static str {
        match self {
            Scalar::F32 => "float",
            Scalar::F64 => "double",
            Scalar::U8 => "uchar",
            Scalar::U16 => "ushort",
            Scalar::U32 => "uint",
            Scalar::U64 => "uint64",
            Scalar::I8 => "char",
            Scalar::I16 => "short",
            Scalar::I32 => "int",
            Scalar::I64 => "int64",
        }
    }

    /// True for the unsigned integer types.
    pub(crate) fn is_unsigned(self) -> bool {
        matches!(self, Scalar::U8 | Scalar::U16 | Scalar::U32 | Scalar::U64)
    }

    /// Decodes the value at the start of `b`; `None` if `b` is too short.
    #[inline]
    pub(crate) fn decode(self, b: &[u8], big_endian: bool) -> Option<f64> {
        Some(match self {
            Scalar::F32 => decode_as!(f32, b, big_endian),
            Scalar::F64 => decode_as!(f64, b, big_endian),
            Scalar::U8 => f64::from(*b.first()?),
            Scalar::U16 => decode_as!(u16, b, big_endian),
            Scalar::U32 => decode_as!(u32, b, big_endian),
            Scalar::U64 => decode_as!(u64, b, big_endian),
            Scalar::I8 => f64::from(*b.first()? as i8),
            Scalar::I16 => decode_as!(i16, b, big_endian),
            Scalar::I32 => decode_as!(i32, b, big_endian),
            Scalar::I64 => decode_as!(i64, b, big_endian),
        })
    }

    /// Decodes `out.len()` little-endian values spaced `stride` bytes apart from the start of
    /// `src`, handing each to `set` with its slot; `None` (and nothing written) if `src` is too
    /// short. One tight loop per type, no allocation.
    pub(crate) fn decode_into<T>(
        self,
        src: &[u8],
        stride: usize,
        out: &mut [T],
        mut set: impl FnMut(&mut T, f64),
    ) -> Option<()> {
        let stride = stride.max(self.size());
        let n = out.len();
        if n > 0 && (n - 1).checked_mul(stride)?.checked_add(self.size())? > src.len() {
            return None;
        }
        macro_rules! run {
            ($t:ty) => {
                for (c, o) in src.chunks(stride).zip(out.iter_mut()) {
                    let a = *c.first_chunk::<{ std::mem::size_of::<$t>() }>()?;
                    set(o, <$t>::from_le_bytes(a) as f64);
                }
            };
        }
        match self {
            Scalar::F32 => run!(f32),
            Scalar::F64 => run!(f64),
            Scalar::U8 => run!(u8),
            Scalar::U16 => run!(u16),
            Scalar::U32 => run!(u32),
            Scalar::U64 => run!(u64),
            Scalar::I8 => run!(i8),
            Scalar::I16 => run!(i16),
            Scalar::I32 => run!(i32),
            Scalar::I64 => run!(i64),
        }
        Some(())
    }

    /// Parses a text token of this type (`nan`/`inf` are accepted for floats); `None` if it is not one.
    pub(crate) fn parse(self, s: &str) -> Option<f64> {
        match self {
            Scalar::F32 => s.parse::<f32>().ok().map(f64::from),
            Scalar::F64 => s.parse::<f64>().ok(),
            Scalar::U8 => s.parse::<u8>().ok().map(f64::from),
            Scalar::U16 => s.parse::<u16>().ok().map(f64::from),
            Scalar::U32 => s.parse::<u32>().ok().map(f64::from),
            Scalar::U64 => s.parse::<u64>().ok().map(|v| v as f64),
            Scalar::I8 => s.parse::<i8>().ok().map(f64::from),
            Scalar::I16 => s.parse::<i16>().ok().map(f64::from),
            Scalar::I32 => s.parse::<i32>().ok().map(f64::from),
            Scalar::I64 => s.parse::<i64>().ok().map(|v| v as f64),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decodes_both_byte_orders_and_text() {
        assert_eq!(Scalar::F32.decode(&1.5f32.to_le_bytes(), false), Some(1.5));
        assert_eq!(Scalar::F32.decode(&1.5f32.to_be_bytes(), true), Some(1.5));
        assert_eq!(Scalar::I16.decode(&(-3i16).to_be_bytes(), true), Some(-3.0));
        assert_eq!(Scalar::U32.decode(&[1, 2], false), None);
        assert_eq!(Scalar::I8.decode(&[0xff], false), Some(-1.0));
        let data: Vec<u8> = [1.0f32, 2.0, 3.0]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let column = |ty: Scalar, stride: usize, n: usize| {
            let mut out = vec![0.0; n];
            ty.decode_into(&data, stride, &mut out, |o, v| *o = v)
                .map(|()| out)
        };
        assert_eq!(column(Scalar::F32, 4, 3), Some(vec![1.0, 2.0, 3.0]));
        assert_eq!(column(Scalar::U16, 8, 2), Some(vec![0.0, 0.0]));
        assert_eq!(column(Scalar::F32, 4, 4), None);
        assert_eq!(column(Scalar::F32, 4, 0), Some(vec![]));
        assert_eq!(Scalar::U8.parse("255"), Some(255.0));
        assert_eq!(Scalar::U8.parse("256"), None);
        assert!(Scalar::F32.parse("nan").is_some_and(f64::is_nan));
    }
}

//! Field values of a crate file, from their 64-bit value reps.
//!
//! # How a value is stored
//!
//! A value rep is a `u64`: bit 63 says array, bit 62 inlined, bit 61
//! compressed, bits 48..56 give the type ([`kind`]) and the low 48 bits
//! the payload. An inlined value *is* its payload (a token or string
//! index, a float's bits, an `i8` per vector component, a matrix's
//! diagonal as `i8`s); otherwise the payload is the byte offset of the
//! value. An array there is its element count (`u64`; `u32` before 0.7.0,
//! after a `u32` rank before 0.5.0) and the elements, or, when compressed
//! (integer and floating-point arrays of 16 or more), its count then the
//! integer coding ([`crate::usdc::integers`]) of the values, or for
//! floating point a code byte: `i` (the values are integers, coded as
//! such) or `t` (a lookup table of distinct values, then coded indexes).
//! Time samples are two offsets: to the times (a `double` vector) and to
//! one value rep per time.
//!
//! Every read here is bounds-checked and charged to the file's
//! [`Budget`]; a value of a type a caller did not ask for reads as `None`
//! (a layer may hold any value; only the curves' matter).

use crate::error::ReadErrorKind;
use crate::usdc::cursor::{Budget, Cursor, error};
use crate::usdc::sections::{CrateFile, compressed_ints};

/// The type codes (`crateDataTypes.h`) this reader decodes.
pub(crate) mod kind {
    pub const BOOL: u8 = 1;
    pub const UCHAR: u8 = 2;
    pub const INT: u8 = 3;
    pub const UINT: u8 = 4;
    pub const INT64: u8 = 5;
    pub const UINT64: u8 = 6;
    pub const HALF: u8 = 7;
    pub const FLOAT: u8 = 8;
    pub const DOUBLE: u8 = 9;
    pub const STRING: u8 = 10;
    pub const TOKEN: u8 = 11;
    pub const MATRIX4D: u8 = 15;
    pub const QUATD: u8 = 16;
    pub const QUATF: u8 = 17;
    pub const QUATH: u8 = 18;
    pub const VEC3D: u8 = 23;
    pub const VEC3F: u8 = 24;
    pub const VEC3H: u8 = 25;
    pub const VEC3I: u8 = 26;
    pub const TOKEN_VECTOR: u8 = 41;
    pub const SPECIFIER: u8 = 42;
    pub const VARIABILITY: u8 = 44;
    pub const TIME_SAMPLES: u8 = 46;
    pub const DOUBLE_VECTOR: u8 = 48;
    pub const VALUE_BLOCK: u8 = 51;
    pub const TIME_CODE: u8 = 56;
}

/// A value rep's parts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Rep(pub u64);

impl Rep {
    pub fn kind(self) -> u8 {
        ((self.0 >> 48) & 0xFF) as u8
    }
    pub fn is_array(self) -> bool {
        self.0 & (1 << 63) != 0
    }
    pub fn is_inlined(self) -> bool {
        self.0 & (1 << 62) != 0
    }
    pub fn is_compressed(self) -> bool {
        self.0 & (1 << 61) != 0
    }
    pub fn payload(self) -> u64 {
        self.0 & ((1 << 48) - 1)
    }
    fn inline_bits(self) -> u32 {
        self.payload() as u32
    }
}

/// Arrays of 16 or more values may be compressed.
const MIN_COMPRESSED: usize = 16;

type Result<T> = std::result::Result<T, crate::ReadError>;

/// Decodes values of one crate file.
pub(crate) struct Values<'a> {
    pub file: &'a CrateFile,
    pub bytes: &'a [u8],
    pub budget: &'a Budget,
}

impl Values<'_> {
    fn at(&self, rep: Rep) -> Cursor<'_> {
        Cursor::new(self.bytes, rep.payload())
    }

    fn version_at_least(&self, minor: u8) -> bool {
        self.file.version.1 >= minor
    }

    /// A token or string scalar.
    pub fn token(&self, rep: Rep) -> Result<Option<String>> {
        if rep.is_array() {
            return Ok(None);
        }
        let index = u64::from(rep.inline_bits());
        match rep.kind() {
            kind::TOKEN => Ok(Some(self.file.token(index, 0)?.to_owned())),
            kind::STRING => {
                let token = self.file.strings.get(index as usize).ok_or_else(|| {
                    error(
                        0,
                        ReadErrorKind::BadValue,
                        format!("string {index} is past the strings"),
                    )
                })?;
                Ok(Some(self.file.token(u64::from(*token), 0)?.to_owned()))
            }
            _ => Ok(None),
        }
    }

    /// A token vector or token array (`xformOpOrder`).
    pub fn tokens(&self, rep: Rep) -> Result<Option<Vec<String>>> {
        let array = rep.kind() == kind::TOKEN && rep.is_array();
        if !(array || rep.kind() == kind::TOKEN_VECTOR) {
            return Ok(None);
        }
        if array && rep.payload() == 0 {
            return Ok(Some(Vec::new()));
        }
        let mut cursor = self.at(rep);
        let count = if array {
            self.array_count(&mut cursor)?
        } else {
            cursor.count(4, "tokens")?
        };
        self.budget
            .charge(count.saturating_mul(32), rep.payload(), "a token list")?;
        let mut tokens = Vec::with_capacity(count);
        for _ in 0..count {
            let at = cursor.at;
            let index = cursor.u32("a token index")?;
            tokens.push(self.file.token(u64::from(index), at)?.to_owned());
        }
        Ok(Some(tokens))
    }

    /// A number scalar (booleans, integers, floating point, time codes).
    pub fn number(&self, rep: Rep) -> Result<Option<f64>> {
        if rep.is_array() {
            return Ok(None);
        }
        let bits = rep.inline_bits();
        let value = match rep.kind() {
            kind::BOOL | kind::UCHAR | kind::UINT => f64::from(bits),
            kind::INT => f64::from(bits as i32),
            kind::HALF => f64::from(half(bits as u16)),
            kind::FLOAT => f64::from(f32::from_bits(bits)),
            kind::INT64 | kind::UINT64 if rep.is_inlined() => {
                if rep.kind() == kind::INT64 {
                    f64::from(bits as i32)
                } else {
                    f64::from(bits)
                }
            }
            kind::INT64 => self.at(rep).i64("an int64")? as f64,
            kind::UINT64 => self.at(rep).u64("a uint64")? as f64,
            kind::DOUBLE | kind::TIME_CODE if rep.is_inlined() => f64::from(f32::from_bits(bits)),
            kind::DOUBLE | kind::TIME_CODE => self.at(rep).f64("a double")?,
            _ => return Ok(None),
        };
        Ok(Some(value))
    }

    /// A small fixed-size value's numbers: a vector, a quaternion (real
    /// part first, as `.usda` writes it), a matrix (rows), or one number.
    pub fn flat(&self, rep: Rep) -> Result<Option<Vec<f64>>> {
        if rep.is_array() {
            return Ok(None);
        }
        let inline_i8s = |n: usize| -> Vec<f64> {
            rep.inline_bits().to_le_bytes()[..n]
                .iter()
                .map(|&b| f64::from(b as i8))
                .collect()
        };
        let values = match rep.kind() {
            kind::VEC3D | kind::VEC3F | kind::VEC3H | kind::VEC3I if rep.is_inlined() => {
                inline_i8s(3)
            }
            kind::VEC3D => self.read_scalars(rep, 3, Element::F64)?,
            kind::VEC3F => self.read_scalars(rep, 3, Element::F32)?,
            kind::VEC3H => self.read_scalars(rep, 3, Element::F16)?,
            kind::VEC3I => self.read_scalars(rep, 3, Element::I32)?,
            kind::QUATD | kind::QUATF | kind::QUATH => {
                let element = match rep.kind() {
                    kind::QUATD => Element::F64,
                    kind::QUATF => Element::F32,
                    _ => Element::F16,
                };
                // Stored imaginary (x, y, z) then real.
                let q = self.read_scalars(rep, 4, element)?;
                vec![q[3], q[0], q[1], q[2]]
            }
            kind::MATRIX4D if rep.is_inlined() => {
                let diagonal = inline_i8s(4);
                let mut m = vec![0.0; 16];
                for (i, d) in diagonal.into_iter().enumerate() {
                    m[5 * i] = d;
                }
                m
            }
            kind::MATRIX4D => self.read_scalars(rep, 16, Element::F64)?,
            _ => match self.number(rep)? {
                Some(value) => vec![value],
                None => return Ok(None),
            },
        };
        Ok(Some(values))
    }

    fn read_scalars(&self, rep: Rep, n: usize, element: Element) -> Result<Vec<f64>> {
        let mut cursor = self.at(rep);
        let data = cursor.take((n * element.bytes()) as u64, "a value")?;
        Ok(element.decode(data))
    }

    /// An array's element count, after the version's prefix. Not checked
    /// against the file here: compressed arrays take far less room than
    /// their elements, so callers charge the [`Budget`] before allocating.
    fn array_count(&self, cursor: &mut Cursor) -> Result<usize> {
        if !self.version_at_least(5) {
            cursor.u32("an array's rank")?;
        }
        let count = if self.version_at_least(7) {
            cursor.u64("an array's size")?
        } else {
            u64::from(cursor.u32("an array's size")?)
        };
        Ok(usize::try_from(count).unwrap_or(usize::MAX))
    }

    /// A number array (`int[]`, `float[]`, `double[]`, `half[]`).
    pub fn numbers(&self, rep: Rep) -> Result<Option<Vec<f64>>> {
        let element = match rep.kind() {
            kind::INT => Element::I32,
            kind::UINT => Element::U32,
            kind::FLOAT => Element::F32,
            kind::DOUBLE => Element::F64,
            kind::HALF => Element::F16,
            _ => return Ok(None),
        };
        if !rep.is_array() {
            return Ok(None);
        }
        if rep.payload() == 0 {
            return Ok(Some(Vec::new()));
        }
        let mut cursor = self.at(rep);
        let count = self.array_count(&mut cursor)?;
        self.budget
            .charge(count.saturating_mul(8), rep.payload(), "a number array")?;
        let compressed = rep.is_compressed() && self.version_at_least(5) && count >= MIN_COMPRESSED;
        if !compressed {
            let size = (count as u64).saturating_mul(element.bytes() as u64);
            let data = cursor.take(size, "an array's elements")?;
            return Ok(Some(element.decode(data)));
        }
        if matches!(element, Element::I32 | Element::U32) {
            let ints = compressed_ints(&mut cursor, count as u64, self.budget, "an int array")?;
            return Ok(Some(
                ints.into_iter().map(|v| element.int_value(v)).collect(),
            ));
        }
        let code_at = cursor.at;
        match cursor.u8("a compressed array's code")? {
            b'i' => {
                let ints = compressed_ints(&mut cursor, count as u64, self.budget, "an array")?;
                Ok(Some(ints.into_iter().map(f64::from).collect()))
            }
            b't' => {
                let table_size = u64::from(cursor.u32("a lookup table's size")?);
                let table = cursor.take(table_size * element.bytes() as u64, "a lookup table")?;
                let table = element.decode(table);
                let indexes =
                    compressed_ints(&mut cursor, count as u64, self.budget, "lookup indexes")?;
                indexes
                    .into_iter()
                    .map(|index| {
                        table.get(index as u32 as usize).copied().ok_or_else(|| {
                            error(
                                code_at,
                                ReadErrorKind::BadValue,
                                format!(
                                    "lookup index {index} is past the {} table entries",
                                    table.len()
                                ),
                            )
                        })
                    })
                    .collect::<Result<Vec<f64>>>()
                    .map(Some)
            }
            code => Err(error(
                code_at,
                ReadErrorKind::BadValue,
                format!("compressed array code {code} is neither 'i' nor 't'"),
            )),
        }
    }

    /// A 3-vector array (`point3f[]`, `color3f[]`, `double3[]`, `half3[]`).
    pub fn vec3s(&self, rep: Rep) -> Result<Option<Vec<[f64; 3]>>> {
        let element = match rep.kind() {
            kind::VEC3F => Element::F32,
            kind::VEC3D => Element::F64,
            kind::VEC3H => Element::F16,
            _ => return Ok(None),
        };
        if !rep.is_array() {
            return Ok(None);
        }
        if rep.payload() == 0 {
            return Ok(Some(Vec::new()));
        }
        let mut cursor = self.at(rep);
        let count = self.array_count(&mut cursor)?;
        self.budget
            .charge(count.saturating_mul(48), rep.payload(), "a vector array")?;
        let size = (count as u64).saturating_mul(3 * element.bytes() as u64);
        let data = cursor.take(size, "an array's vectors")?;
        let flat = element.decode(data);
        Ok(Some(
            flat.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect(),
        ))
    }

    /// Time samples: (time, value rep) pairs, in the file's order.
    pub fn time_samples(&self, rep: Rep) -> Result<Option<Vec<(f64, Rep)>>> {
        if rep.kind() != kind::TIME_SAMPLES || rep.is_array() {
            return Ok(None);
        }
        let mut cursor = self.at(rep);
        let jump_at = cursor.at;
        let jump = cursor.i64("the jump to the sample times")?;
        cursor.seek(jump_at.wrapping_add(jump as u64));
        let times_rep = Rep(cursor.u64("the sample times' rep")?);
        let times = self.doubles(times_rep)?;
        let jump_at = cursor.at;
        let jump = cursor.i64("the jump to the sample values")?;
        cursor.seek(jump_at.wrapping_add(jump as u64));
        let count = cursor.count(8, "sample values")?;
        if count != times.len() {
            return Err(error(
                cursor.at - 8,
                ReadErrorKind::CountMismatch,
                format!("{} sample times but {count} sample values", times.len()),
            ));
        }
        self.budget
            .charge(count * 16, rep.payload(), "time samples")?;
        let mut samples = Vec::with_capacity(count);
        for time in times {
            samples.push((time, Rep(cursor.u64("a sample's value rep")?)));
        }
        Ok(Some(samples))
    }

    /// A `double` vector (sample times) or `double[]`.
    fn doubles(&self, rep: Rep) -> Result<Vec<f64>> {
        if rep.kind() == kind::DOUBLE_VECTOR && !rep.is_array() {
            let mut cursor = self.at(rep);
            let count = cursor.count(8, "sample times")?;
            self.budget
                .charge(count * 8, rep.payload(), "sample times")?;
            let data = cursor.take(count as u64 * 8, "sample times")?;
            return Ok(Element::F64.decode(data));
        }
        match self.numbers(rep)? {
            Some(times) => Ok(times),
            None => Err(error(
                rep.payload(),
                ReadErrorKind::BadValue,
                format!("sample times of type {} are not doubles", rep.kind()),
            )),
        }
    }
}

/// An array element's storage.
#[derive(Clone, Copy)]
enum Element {
    I32,
    U32,
    F16,
    F32,
    F64,
}

impl Element {
    fn bytes(self) -> usize {
        match self {
            Element::F16 => 2,
            Element::F64 => 8,
            _ => 4,
        }
    }

    fn int_value(self, value: i32) -> f64 {
        match self {
            Element::U32 => f64::from(value as u32),
            _ => f64::from(value),
        }
    }

    fn decode(self, data: &[u8]) -> Vec<f64> {
        data.chunks_exact(self.bytes())
            .map(|c| match self {
                Element::I32 => f64::from(i32::from_le_bytes([c[0], c[1], c[2], c[3]])),
                Element::U32 => f64::from(u32::from_le_bytes([c[0], c[1], c[2], c[3]])),
                Element::F16 => f64::from(half(u16::from_le_bytes([c[0], c[1]]))),
                Element::F32 => f64::from(f32::from_le_bytes([c[0], c[1], c[2], c[3]])),
                Element::F64 => {
                    let mut word = [0; 8];
                    word.copy_from_slice(c);
                    f64::from_le_bytes(word)
                }
            })
            .collect()
    }
}

/// An IEEE half-precision float's value.
pub(crate) fn half(bits: u16) -> f32 {
    let sign = if bits & 0x8000 != 0 { -1.0 } else { 1.0 };
    let exponent = i32::from((bits >> 10) & 0x1F);
    let fraction = f32::from(bits & 0x3FF);
    sign * match exponent {
        0 => fraction * 2f32.powi(-24),
        31 if fraction == 0.0 => f32::INFINITY,
        31 => f32::NAN,
        _ => (1.0 + fraction / 1024.0) * 2f32.powi(exponent - 15),
    }
}

#[cfg(test)]
mod tests {
    use super::half;

    #[test]
    fn halves_decode() {
        assert_eq!(half(0x3C00), 1.0);
        assert_eq!(half(0xC000), -2.0);
        assert_eq!(half(0x3555), 0.333_251_95);
        assert_eq!(half(0x0001), 2f32.powi(-24));
        assert!(half(0x7C00).is_infinite() && half(0x7E00).is_nan());
    }
}

//! USD's integer coding (`Usd_IntegerCompression`), used for every index
//! list of a crate file and for `int[]` arrays of 16 or more values.
//!
//! # How it works
//!
//! The list becomes differences (each value minus the one before, the
//! first minus 0), which are small for sorted or regular lists. The most
//! common difference is written once as an `i32`; then each difference
//! gets a 2-bit code, four to a byte, low bits first (0: the common
//! value, 1: an `i8` follows, 2: an `i16`, 3: an `i32`); then the `i8`,
//! `i16` and `i32` values themselves, in order. The whole encoding is then
//! LZ4-compressed ([`crate::usdc::lz4`]). A list of `n` integers encodes to
//! at most `4 + ⌈n/4⌉ + 4n` bytes ([`encoded_bound`]), which bounds what a
//! reader decompresses before decoding.

use std::collections::HashMap;

/// The largest encoding of `n` 32-bit integers.
pub(crate) fn encoded_bound(n: usize) -> usize {
    if n == 0 {
        return 0;
    }
    n.saturating_mul(4)
        .saturating_add(n.div_ceil(4))
        .saturating_add(4)
}

/// Decodes `n` integers from their (decompressed) encoding.
pub(crate) fn decode(encoded: &[u8], n: usize) -> Result<Vec<i32>, String> {
    if n == 0 {
        return Ok(Vec::new());
    }
    let cut = || format!("the coding of {n} integers is cut off");
    let common = encoded.get(..4).ok_or_else(cut)?;
    let common = i32::from_le_bytes([common[0], common[1], common[2], common[3]]);
    let codes_end = 4 + n.div_ceil(4);
    let codes = encoded.get(4..codes_end).ok_or_else(cut)?;
    let mut at = codes_end;
    let mut take = |size: usize| -> Result<i32, String> {
        let bytes = encoded.get(at..at + size).ok_or_else(cut)?;
        at += size;
        Ok(match size {
            1 => i32::from(bytes[0] as i8),
            2 => i32::from(i16::from_le_bytes([bytes[0], bytes[1]])),
            _ => i32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]),
        })
    };
    let mut values = Vec::with_capacity(n);
    let mut previous = 0i32;
    for index in 0..n {
        let code = (codes[index / 4] >> (2 * (index % 4))) & 3;
        let difference = match code {
            0 => common,
            1 => take(1)?,
            2 => take(2)?,
            _ => take(4)?,
        };
        previous = previous.wrapping_add(difference);
        values.push(previous);
    }
    Ok(values)
}

/// Encodes integers (before LZ4).
pub(crate) fn encode(values: &[i32]) -> Vec<u8> {
    if values.is_empty() {
        return Vec::new();
    }
    let mut previous = 0i32;
    let differences: Vec<i32> = values
        .iter()
        .map(|&value| {
            let difference = value.wrapping_sub(previous);
            previous = value;
            difference
        })
        .collect();
    let mut counts: HashMap<i32, usize> = HashMap::new();
    for &difference in &differences {
        *counts.entry(difference).or_default() += 1;
    }
    // The most common difference; the smallest of equals, so the output
    // does not depend on the map's order.
    let common = counts
        .iter()
        .max_by(|a, b| a.1.cmp(b.1).then(b.0.cmp(a.0)))
        .map_or(0, |(&value, _)| value);
    let mut codes = vec![0u8; values.len().div_ceil(4)];
    let mut data = Vec::new();
    for (index, &difference) in differences.iter().enumerate() {
        let code = if difference == common {
            0
        } else if let Ok(small) = i8::try_from(difference) {
            data.push(small as u8);
            1
        } else if let Ok(medium) = i16::try_from(difference) {
            data.extend_from_slice(&medium.to_le_bytes());
            2
        } else {
            data.extend_from_slice(&difference.to_le_bytes());
            3
        };
        codes[index / 4] |= code << (2 * (index % 4));
    }
    let mut out = Vec::with_capacity(4 + codes.len() + data.len());
    out.extend_from_slice(&common.to_le_bytes());
    out.extend_from_slice(&codes);
    out.extend_from_slice(&data);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pixars_example_encodes_as_documented() {
        // integerCoding.cpp's example: the common difference 1, two bytes
        // of codes (01 00 00 11 | 01 00 01), then i8 123, i32 100000,
        // i8 0, i8 0: 13 bytes (its comment counts 12).
        let values = [123, 124, 125, 100_125, 100_125, 100_126, 100_126];
        let encoded = encode(&values);
        assert_eq!(encoded.len(), 13);
        assert_eq!(&encoded[4..6], &[0b1100_0001, 0b0001_0001]);
        assert_eq!(&encoded[..4], &1i32.to_le_bytes());
        assert_eq!(decode(&encoded, values.len()), Ok(values.to_vec()));
    }

    #[test]
    fn extremes_round_trip_and_short_input_is_refused() {
        let values = [i32::MIN, i32::MAX, 0, -1, 300, -40_000, 7, 7, 7];
        let encoded = encode(&values);
        assert!(encoded.len() <= encoded_bound(values.len()));
        assert_eq!(decode(&encoded, values.len()), Ok(values.to_vec()));
        for cut in 0..encoded.len() {
            assert!(decode(&encoded[..cut], values.len()).is_err());
        }
    }
}

//! The compression inside crate files: Pixar's `TfFastCompression`, which
//! is LZ4 blocks behind one byte that counts chunks.
//!
//! # How it works
//!
//! A compressed buffer starts with a chunk count: 0 means "one LZ4 block
//! follows", n > 0 means n chunks, each an `i32` byte size then an LZ4
//! block (only inputs over about 2 GB are split). An LZ4 block is a run of
//! sequences, each a token byte (high nibble: literal count, low nibble:
//! match length − 4; 15 means "more length bytes follow, each added, until
//! one is not 255"), the literals, then a 2-byte back offset into what was
//! already decoded; the last sequence has literals only.
//!
//! [`decompress`] checks every length and offset against the input and
//! against the size the caller expects, so a hostile buffer can neither
//! read out of bounds nor grow the output beyond it. [`compress`] writes
//! one block of literals only: valid LZ4 that any reader accepts, a little
//! larger than the input; the writer's sizes come from point arrays, which
//! LZ4 would barely shrink anyway.

/// Decompresses a `TfFastCompression` buffer into at most `max_out` bytes.
pub(crate) fn decompress(input: &[u8], max_out: usize) -> Result<Vec<u8>, String> {
    let (&chunks, rest) = input
        .split_first()
        .ok_or_else(|| "the compressed data is empty".to_string())?;
    let mut out = Vec::with_capacity(max_out.min(input.len().saturating_mul(255)));
    if chunks == 0 {
        block(rest, &mut out, max_out)?;
        return Ok(out);
    }
    if chunks > 127 {
        return Err(format!("{chunks} is not a chunk count"));
    }
    let mut at = 0usize;
    for chunk in 0..chunks {
        let size_bytes = rest
            .get(at..at + 4)
            .ok_or_else(|| format!("chunk {chunk}'s size is cut off"))?;
        let size = i32::from_le_bytes([size_bytes[0], size_bytes[1], size_bytes[2], size_bytes[3]]);
        let size = usize::try_from(size).map_err(|_| format!("chunk {chunk} has size {size}"))?;
        at += 4;
        let data = at
            .checked_add(size)
            .and_then(|end| rest.get(at..end))
            .ok_or_else(|| format!("chunk {chunk} runs past the data"))?;
        block(data, &mut out, max_out)?;
        at += size;
    }
    Ok(out)
}

/// Decodes one LZ4 block, appending to `out`, never past `max_out` bytes.
fn block(input: &[u8], out: &mut Vec<u8>, max_out: usize) -> Result<(), String> {
    let mut at = 0usize;
    let byte = |at: usize| {
        input
            .get(at)
            .copied()
            .ok_or_else(|| "an LZ4 sequence is cut off".to_string())
    };
    let length = |at: &mut usize, mut value: usize| -> Result<usize, String> {
        if value == 15 {
            loop {
                let more = byte(*at)?;
                *at += 1;
                value = value.saturating_add(usize::from(more));
                if more != 255 {
                    break;
                }
            }
        }
        Ok(value)
    };
    loop {
        let token = byte(at)?;
        at += 1;
        let literals = length(&mut at, usize::from(token >> 4))?;
        let end = at
            .checked_add(literals)
            .filter(|&end| end <= input.len())
            .ok_or_else(|| "LZ4 literals run past the data".to_string())?;
        if out.len() + literals > max_out {
            return Err(format!(
                "the data decompresses to more than {max_out} bytes"
            ));
        }
        out.extend_from_slice(&input[at..end]);
        at = end;
        if at == input.len() {
            return Ok(());
        }
        let offset = usize::from(u16::from_le_bytes([byte(at)?, byte(at + 1)?]));
        at += 2;
        if offset == 0 || offset > out.len() {
            return Err(format!(
                "an LZ4 match reaches {offset} bytes back, before the start"
            ));
        }
        let matched = length(&mut at, usize::from(token & 15))?.saturating_add(4);
        if out.len().saturating_add(matched) > max_out {
            return Err(format!(
                "the data decompresses to more than {max_out} bytes"
            ));
        }
        let from = out.len() - offset;
        for index in 0..matched {
            out.push(out[from + index]);
        }
    }
}

/// Compresses `input` as one LZ4 block of literals, behind the chunk
/// count 0 (inputs under 2 GB; the writer's are).
pub(crate) fn compress(input: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(input.len() + input.len() / 255 + 3);
    out.push(0);
    let count = input.len();
    if count < 15 {
        out.push((count as u8) << 4);
    } else {
        out.push(0xF0);
        let mut rest = count - 15;
        while rest >= 255 {
            out.push(255);
            rest -= 255;
        }
        out.push(rest as u8);
    }
    out.extend_from_slice(input);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn literals_round_trip_at_every_length_class() {
        for len in [0, 1, 14, 15, 16, 269, 270, 271, 1000] {
            let input: Vec<u8> = (0..len).map(|i| (i * 7) as u8).collect();
            assert_eq!(
                decompress(&compress(&input), len).as_deref(),
                Ok(&input[..])
            );
        }
    }

    #[test]
    fn matches_copy_overlapping_runs() {
        // "ab" then a match of 6 at offset 2: "abababab".
        let block = [0x22, b'a', b'b', 2, 0, 0x00];
        let data: Vec<u8> = std::iter::once(0).chain(block).collect();
        assert_eq!(decompress(&data, 64).as_deref(), Ok(&b"abababab"[..]));
        assert!(
            decompress(&data, 7).is_err(),
            "bounded by the expected size"
        );
    }

    #[test]
    fn hostile_offsets_and_lengths_are_refused() {
        assert!(decompress(&[0, 0x10, b'a', 9, 0], 64).is_err());
        assert!(decompress(&[0, 0xF0, 255], 64).is_err());
        assert!(decompress(&[], 64).is_err());
        assert!(decompress(&[1, 255, 255, 255, 127], 64).is_err());
    }
}

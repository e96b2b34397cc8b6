//! A crate file's structure: its header, table of contents and the six
//! structural sections, decoded into tables ([`CrateFile`]).
//!
//! # How a crate file is laid out
//!
//! - **Bootstrap** (88 bytes at 0): `PXR-USDC`, the version (major, minor,
//!   patch bytes), the offset of the table of contents.
//! - **Table of contents**: a count, then per section a 16-byte name, its
//!   start and size.
//! - **TOKENS**: every name and token of the layer, NUL-terminated, LZ4
//!   compressed. Everything else refers to tokens by index.
//! - **STRINGS**: string values, as token indexes.
//! - **FIELDS**: (token index, value rep) pairs: a field's name and where
//!   and how its value is stored ([`crate::usdc::values`]).
//! - **FIELDSETS**: runs of field indexes, each run ended by `u32::MAX`.
//! - **PATHS**: the prim and property paths, as a tree flattened depth
//!   first: per node its path index, its name's token (negative for a
//!   property) and a jump (−2 leaf, −1 child only, 0 sibling only, else
//!   the distance to the sibling after the child's subtree).
//! - **SPECS**: (path index, field set index, spec type) triples: a prim,
//!   an attribute, the layer itself (the pseudo-root)…
//!
//! From version 0.4.0 every index list is compressed
//! ([`crate::usdc::integers`]); older files (USD before 2018) are refused.

use crate::error::ReadErrorKind;
use crate::usdc::cursor::{Budget, Cursor, error};
use crate::usdc::{integers, lz4};

/// The bootstrap header's size in bytes.
pub const BOOTSTRAP_BYTES: u64 = 88;
/// What a crate file starts with.
pub const MAGIC: &[u8; 8] = b"PXR-USDC";

/// Spec types (`SdfSpecType`) this reader uses.
pub(crate) mod spec_type {
    pub const ATTRIBUTE: u32 = 1;
    pub const PRIM: u32 = 6;
    pub const PSEUDO_ROOT: u32 = 7;
}

/// One node of the path tree: its parent's path index (`None` for the
/// root), its name's token, and whether it names a property.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PathNode {
    pub parent: Option<usize>,
    pub token: usize,
    pub property: bool,
}

/// A spec: a path, its fields (by field set) and its type.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Spec {
    pub path: usize,
    pub field_set: usize,
    pub spec_type: u32,
}

/// The decoded structural sections.
#[derive(Debug)]
pub(crate) struct CrateFile {
    pub version: (u8, u8, u8),
    pub tokens: Vec<String>,
    pub strings: Vec<u32>,
    /// Per field: its name's token index and its value rep.
    pub fields: Vec<(u32, u64)>,
    pub field_sets: Vec<u32>,
    /// Per path index, its node; `None` for indexes the tree never names.
    pub paths: Vec<Option<PathNode>>,
    /// Path indexes in the tree's depth-first order (parents first).
    pub path_order: Vec<usize>,
    pub specs: Vec<Spec>,
}

impl CrateFile {
    /// A token by index, or an error naming the index.
    pub fn token(&self, index: u64, at: u64) -> Result<&str, crate::ReadError> {
        usize::try_from(index)
            .ok()
            .and_then(|index| self.tokens.get(index))
            .map(String::as_str)
            .ok_or_else(|| {
                error(
                    at,
                    ReadErrorKind::BadValue,
                    format!("token {index} is past the {} tokens", self.tokens.len()),
                )
            })
    }

    /// The field (name, value rep) pairs of a field set.
    pub fn fields_of(&self, field_set: usize) -> impl Iterator<Item = (u32, u64)> + '_ {
        self.field_sets
            .get(field_set..)
            .unwrap_or(&[])
            .iter()
            .take_while(|&&index| index != u32::MAX)
            .filter_map(|&index| self.fields.get(index as usize).copied())
    }
}

/// Decodes the structural sections of a crate file.
pub(crate) fn read_sections(bytes: &[u8], budget: &Budget) -> Result<CrateFile, crate::ReadError> {
    let mut header = Cursor::new(bytes, 0);
    if !bytes.starts_with(MAGIC) {
        return Err(error(
            0,
            ReadErrorKind::BadMagic,
            "a usdc crate file starts with \"PXR-USDC\"",
        ));
    }
    header.take(BOOTSTRAP_BYTES, "the 88-byte header")?;
    let version = (bytes[8], bytes[9], bytes[10]);
    if version.0 != 0 || version.1 < 4 {
        return Err(error(
            8,
            ReadErrorKind::UnsupportedVersion,
            format!(
                "crate version {}.{}.{} is not read (0.4.0 and later are: USD 2018 and later)",
                version.0, version.1, version.2
            ),
        ));
    }
    header.seek(16);
    let toc_offset = header.u64("the table of contents' offset")?;
    let mut toc = Cursor::new(bytes, toc_offset);
    let count = toc.count(32, "sections")?;
    let mut sections = Vec::with_capacity(count);
    for _ in 0..count {
        let name = toc.take(16, "a section name")?;
        let name_end = name.iter().position(|&b| b == 0).unwrap_or(16);
        let start = toc.u64("a section's start")?;
        let size = toc.u64("a section's size")?;
        sections.push((&name[..name_end], start, size));
    }
    let section = |name: &str| {
        sections
            .iter()
            .find(|(found, _, _)| *found == name.as_bytes())
            .map(|&(_, start, _)| Cursor::new(bytes, start))
    };
    let missing = |name: &str| {
        error(
            toc_offset,
            ReadErrorKind::CountMismatch,
            format!("the table of contents has no {name} section"),
        )
    };
    let tokens = read_tokens(section("TOKENS").ok_or_else(|| missing("TOKENS"))?, budget)?;
    let strings = match section("STRINGS") {
        Some(mut cursor) => {
            let count = cursor.count(4, "strings")?;
            budget.charge(4 * count, cursor.at, "the strings")?;
            (0..count)
                .map(|_| cursor.u32("a string's token"))
                .collect::<Result<_, _>>()?
        }
        None => Vec::new(),
    };
    let fields = read_fields(section("FIELDS").ok_or_else(|| missing("FIELDS"))?, budget)?;
    let field_sets = {
        let mut cursor = section("FIELDSETS").ok_or_else(|| missing("FIELDSETS"))?;
        let count = cursor.u64("the field set count")?;
        compressed_ints(&mut cursor, count, budget, "field sets")?
            .into_iter()
            .map(|v| v as u32)
            .collect()
    };
    let (paths, path_order) = read_paths(
        section("PATHS").ok_or_else(|| missing("PATHS"))?,
        tokens.len(),
        budget,
    )?;
    let specs = read_specs(section("SPECS").ok_or_else(|| missing("SPECS"))?, budget)?;
    Ok(CrateFile {
        version,
        tokens,
        strings,
        fields,
        field_sets,
        paths,
        path_order,
        specs,
    })
}

/// A compressed list of `count` 32-bit integers: its compressed size, then
/// the LZ4-compressed coding.
pub(crate) fn compressed_ints(
    cursor: &mut Cursor,
    count: u64,
    budget: &Budget,
    what: &str,
) -> Result<Vec<i32>, crate::ReadError> {
    let at = cursor.at;
    let n = usize::try_from(count).unwrap_or(usize::MAX);
    let bound = integers::encoded_bound(n);
    budget.charge(bound.saturating_add(n.saturating_mul(4)), at, what)?;
    let size = cursor.u64(&format!("the compressed size of {what}"))?;
    let data = cursor.take(size, &format!("the compressed {what}"))?;
    if n == 0 {
        return Ok(Vec::new());
    }
    let encoded = lz4::decompress(data, bound).map_err(|message| {
        error(
            at + 8,
            ReadErrorKind::BadValue,
            format!("{what}: {message}"),
        )
    })?;
    integers::decode(&encoded, n).map_err(|message| {
        error(
            at + 8,
            ReadErrorKind::BadValue,
            format!("{what}: {message}"),
        )
    })
}

fn read_tokens(mut cursor: Cursor, budget: &Budget) -> Result<Vec<String>, crate::ReadError> {
    let at = cursor.at;
    let count = cursor.u64("the token count")?;
    let size = cursor.u64("the tokens' size")?;
    let compressed = cursor.u64("the tokens' compressed size")?;
    let data = cursor.take(compressed, "the compressed tokens")?;
    let size = usize::try_from(size).unwrap_or(usize::MAX);
    budget.charge(size, at + 8, "the tokens")?;
    let text = lz4::decompress(data, size).map_err(|message| {
        error(
            at + 24,
            ReadErrorKind::BadValue,
            format!("tokens: {message}"),
        )
    })?;
    let mut tokens = Vec::new();
    for piece in text.split(|&b| b == 0) {
        if tokens.len() as u64 == count {
            break;
        }
        budget.charge(24, at, "the tokens")?;
        tokens.push(String::from_utf8_lossy(piece).into_owned());
    }
    if tokens.len() as u64 != count {
        return Err(error(
            at,
            ReadErrorKind::CountMismatch,
            format!(
                "the file claims {count} tokens, its token data holds {}",
                tokens.len()
            ),
        ));
    }
    Ok(tokens)
}

fn read_fields(mut cursor: Cursor, budget: &Budget) -> Result<Vec<(u32, u64)>, crate::ReadError> {
    let count = cursor.u64("the field count")?;
    let names = compressed_ints(&mut cursor, count, budget, "field names")?;
    let at = cursor.at;
    let size = cursor.u64("the value reps' compressed size")?;
    let data = cursor.take(size, "the compressed value reps")?;
    let reps_bytes = names.len() * 8;
    budget.charge(2 * reps_bytes, at, "the value reps")?;
    let reps = lz4::decompress(data, reps_bytes).map_err(|message| {
        error(
            at + 8,
            ReadErrorKind::BadValue,
            format!("value reps: {message}"),
        )
    })?;
    if reps.len() != reps_bytes {
        return Err(error(
            at,
            ReadErrorKind::CountMismatch,
            format!(
                "{} fields need {reps_bytes} bytes of value reps, the data holds {}",
                names.len(),
                reps.len()
            ),
        ));
    }
    Ok(names
        .iter()
        .zip(reps.chunks_exact(8))
        .map(|(&name, rep)| {
            let mut word = [0; 8];
            word.copy_from_slice(rep);
            (name as u32, u64::from_le_bytes(word))
        })
        .collect())
}

type Paths = (Vec<Option<PathNode>>, Vec<usize>);

fn read_paths(
    mut cursor: Cursor,
    token_count: usize,
    budget: &Budget,
) -> Result<Paths, crate::ReadError> {
    let at = cursor.at;
    let path_count = cursor.u64("the path count")?;
    let path_count = usize::try_from(path_count).unwrap_or(usize::MAX);
    budget.charge(
        path_count.saturating_mul(std::mem::size_of::<Option<PathNode>>() + 8),
        at,
        "the paths",
    )?;
    let encoded = cursor.u64("the encoded path count")?;
    let indexes = compressed_ints(&mut cursor, encoded, budget, "path indexes")?;
    let names = compressed_ints(&mut cursor, encoded, budget, "path names")?;
    let jumps = compressed_ints(&mut cursor, encoded, budget, "path jumps")?;
    let bad = |message: String| error(at, ReadErrorKind::BadValue, message);
    let mut paths: Vec<Option<PathNode>> = vec![None; path_count];
    let mut order = Vec::with_capacity(indexes.len());
    let mut visited = vec![false; indexes.len()];
    // Depth first: (encoded element, parent path index); siblings wait on
    // a stack while a child's subtree is walked.
    let mut pending: Vec<(usize, Option<usize>)> = Vec::new();
    let mut next = (!indexes.is_empty()).then_some((0usize, None));
    while let Some((element, parent)) = next {
        if element >= indexes.len() || visited[element] {
            return Err(bad(format!(
                "the path tree revisits or leaves its {} entries",
                indexes.len()
            )));
        }
        visited[element] = true;
        let path = indexes[element] as u32 as usize;
        if path >= path_count || paths[path].is_some() {
            return Err(bad(format!(
                "path index {path} is out of range or repeated"
            )));
        }
        let name = names[element];
        let token = name.unsigned_abs() as usize;
        if parent.is_some() && token >= token_count {
            return Err(bad(format!(
                "path name token {token} is past the {token_count} tokens"
            )));
        }
        paths[path] = Some(PathNode {
            parent,
            token,
            property: name < 0,
        });
        order.push(path);
        let jump = jumps[element];
        let has_child = jump > 0 || jump == -1;
        let has_sibling = jump >= 0;
        if has_child && has_sibling {
            let sibling = element
                .checked_add(jump as usize)
                .ok_or_else(|| bad(format!("path jump {jump} overflows")))?;
            pending.push((sibling, parent));
        }
        next = if has_child {
            Some((element + 1, Some(path)))
        } else if has_sibling {
            if parent.is_none() {
                return Err(bad("the root path has a sibling".to_string()));
            }
            Some((element + 1, parent))
        } else {
            pending.pop()
        };
    }
    Ok((paths, order))
}

fn read_specs(mut cursor: Cursor, budget: &Budget) -> Result<Vec<Spec>, crate::ReadError> {
    let at = cursor.at;
    let count = cursor.u64("the spec count")?;
    let paths = compressed_ints(&mut cursor, count, budget, "spec paths")?;
    let sets = compressed_ints(&mut cursor, count, budget, "spec field sets")?;
    let types = compressed_ints(&mut cursor, count, budget, "spec types")?;
    budget.charge(paths.len() * std::mem::size_of::<Spec>(), at, "the specs")?;
    Ok(paths
        .iter()
        .zip(&sets)
        .zip(&types)
        .map(|((&path, &set), &spec_type)| Spec {
            path: path as u32 as usize,
            field_set: set as u32 as usize,
            spec_type: spec_type as u32,
        })
        .collect())
}

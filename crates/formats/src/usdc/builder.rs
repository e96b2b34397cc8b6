//! Assembles a crate file: values appended as they are added, then the
//! structural sections, the table of contents and the header.
//!
//! # How it works
//!
//! A [`Builder`] holds the value bytes (after the 88-byte header) and the
//! tables every crate file has: tokens, strings, fields, field sets, the
//! path tree and the specs. The caller adds a prim tree ([`Node`]) whose
//! nodes carry their fields; [`Builder::finish`] numbers the paths depth
//! first, writes the sections ([`crate::usdc::sections`] describes them)
//! with index lists integer-coded and LZ4-wrapped, and puts the table of
//! contents' offset in the header. Arrays are written uncompressed (always
//! allowed; `points` would not compress anyway) and aligned to 8 bytes;
//! `double`s are written at an offset, never inlined. The result is crate
//! version 0.8.0, which every USD since 2019 reads.

use std::collections::HashMap;

use crate::usdc::sections::{BOOTSTRAP_BYTES, MAGIC, spec_type};
use crate::usdc::values::kind;
use crate::usdc::{integers, lz4};

/// The crate version written.
pub const VERSION: [u8; 3] = [0, 8, 0];

const ARRAY: u64 = 1 << 63;
const INLINED: u64 = 1 << 62;

/// A node of the layer's path tree: a prim or a property, its name and
/// fields (name, value rep), and its children.
pub(crate) struct Node {
    pub name: String,
    pub property: bool,
    pub spec_type: u32,
    pub fields: Vec<(String, u64)>,
    pub children: Vec<Node>,
}

impl Node {
    /// A prim spec.
    pub fn prim(name: &str, fields: Vec<(String, u64)>, children: Vec<Node>) -> Node {
        Node {
            name: name.to_owned(),
            property: false,
            spec_type: spec_type::PRIM,
            fields,
            children,
        }
    }

    /// An attribute spec.
    pub fn attribute(name: &str, fields: Vec<(String, u64)>) -> Node {
        Node {
            name: name.to_owned(),
            property: true,
            spec_type: spec_type::ATTRIBUTE,
            fields,
            children: Vec::new(),
        }
    }
}

/// A crate file being written.
pub(crate) struct Builder {
    data: Vec<u8>,
    tokens: Vec<String>,
    token_index: HashMap<String, u32>,
    strings: Vec<u32>,
}

fn rep(kind: u8, flags: u64, payload: u64) -> u64 {
    flags | (u64::from(kind) << 48) | payload
}

impl Builder {
    pub fn new() -> Builder {
        let mut builder = Builder {
            data: vec![0; BOOTSTRAP_BYTES as usize],
            tokens: Vec::new(),
            token_index: HashMap::new(),
            strings: Vec::new(),
        };
        // Token 0 is the root's (empty) name, as USD writes it.
        builder.token("");
        builder
    }

    pub fn token(&mut self, text: &str) -> u32 {
        if let Some(&index) = self.token_index.get(text) {
            return index;
        }
        let index = self.tokens.len() as u32;
        self.tokens.push(text.to_owned());
        self.token_index.insert(text.to_owned(), index);
        index
    }

    fn align(&mut self) -> u64 {
        while !self.data.len().is_multiple_of(8) {
            self.data.push(0);
        }
        self.data.len() as u64
    }

    /// A token value (inlined).
    pub fn token_value(&mut self, text: &str) -> u64 {
        let index = self.token(text);
        rep(kind::TOKEN, INLINED, u64::from(index))
    }

    /// A string value (inlined, by the strings table).
    pub fn string_value(&mut self, text: &str) -> u64 {
        let token = self.token(text);
        self.strings.push(token);
        rep(kind::STRING, INLINED, (self.strings.len() - 1) as u64)
    }

    /// A `double` value.
    pub fn double(&mut self, value: f64) -> u64 {
        let at = self.align();
        self.data.extend_from_slice(&value.to_le_bytes());
        rep(kind::DOUBLE, 0, at)
    }

    /// `def` (the specifier, inlined).
    pub fn specifier_def(&self) -> u64 {
        rep(kind::SPECIFIER, INLINED, 0)
    }

    /// `uniform` (the variability, inlined).
    pub fn uniform(&self) -> u64 {
        rep(kind::VARIABILITY, INLINED, 1)
    }

    /// A token list (`primChildren`, `properties`).
    pub fn token_vector(&mut self, items: &[&str]) -> u64 {
        let indexes: Vec<u32> = items.iter().map(|item| self.token(item)).collect();
        let at = self.align();
        self.data
            .extend_from_slice(&(indexes.len() as u64).to_le_bytes());
        for index in indexes {
            self.data.extend_from_slice(&index.to_le_bytes());
        }
        rep(kind::TOKEN_VECTOR, 0, at)
    }

    /// A `token[]` value.
    pub fn token_array(&mut self, items: &[&str]) -> u64 {
        let indexes: Vec<u32> = items.iter().map(|item| self.token(item)).collect();
        let at = self.array_start(indexes.len());
        for index in indexes {
            self.data.extend_from_slice(&index.to_le_bytes());
        }
        rep(kind::TOKEN, ARRAY, at)
    }

    fn array_start(&mut self, count: usize) -> u64 {
        let at = self.align();
        self.data.extend_from_slice(&(count as u64).to_le_bytes());
        at
    }

    /// An `int[]` value.
    pub fn ints(&mut self, values: impl ExactSizeIterator<Item = i32>) -> u64 {
        let at = self.array_start(values.len());
        for value in values {
            self.data.extend_from_slice(&value.to_le_bytes());
        }
        rep(kind::INT, ARRAY, at)
    }

    /// A `float[]` value.
    pub fn floats(&mut self, values: impl ExactSizeIterator<Item = f32>) -> u64 {
        let at = self.array_start(values.len());
        for value in values {
            self.data.extend_from_slice(&value.to_le_bytes());
        }
        rep(kind::FLOAT, ARRAY, at)
    }

    /// A `float3[]` (`point3f[]`, `color3f[]`) value.
    pub fn vec3fs(&mut self, values: impl ExactSizeIterator<Item = [f32; 3]>) -> u64 {
        let at = self.array_start(values.len());
        for value in values {
            for component in value {
                self.data.extend_from_slice(&component.to_le_bytes());
            }
        }
        rep(kind::VEC3F, ARRAY, at)
    }

    /// A `matrix4d` value, rows in order.
    pub fn matrix4d(&mut self, rows: [[f64; 4]; 4]) -> u64 {
        let at = self.align();
        for value in rows.iter().flatten() {
            self.data.extend_from_slice(&value.to_le_bytes());
        }
        rep(kind::MATRIX4D, 0, at)
    }

    /// Time samples of values already added (`(time, value rep)`, times
    /// increasing).
    pub fn time_samples(&mut self, samples: &[(f64, u64)]) -> u64 {
        let times = {
            let at = self.align();
            self.data
                .extend_from_slice(&(samples.len() as u64).to_le_bytes());
            for (time, _) in samples {
                self.data.extend_from_slice(&time.to_le_bytes());
            }
            rep(kind::DOUBLE_VECTOR, 0, at)
        };
        let at = self.align();
        // A jump over itself to the times' rep, then one to the values.
        self.data.extend_from_slice(&8i64.to_le_bytes());
        self.data.extend_from_slice(&times.to_le_bytes());
        self.data.extend_from_slice(&8i64.to_le_bytes());
        self.data
            .extend_from_slice(&(samples.len() as u64).to_le_bytes());
        for (_, value) in samples {
            self.data.extend_from_slice(&value.to_le_bytes());
        }
        rep(kind::TIME_SAMPLES, 0, at)
    }

    /// Writes the file: the layer's own fields (the pseudo-root's) and
    /// its root prims.
    pub fn finish(mut self, layer_fields: Vec<(String, u64)>, prims: Vec<Node>) -> Vec<u8> {
        let root = Node {
            name: String::new(),
            property: false,
            spec_type: spec_type::PSEUDO_ROOT,
            fields: layer_fields,
            children: prims,
        };
        let mut tables = Tables::default();
        self.flatten(&root, &mut tables, false);
        let mut sections: Vec<(&str, u64, u64)> = Vec::new();
        let mut section = |builder: &mut Builder, name: &'static str, bytes: Vec<u8>| {
            let start = builder.align();
            builder.data.extend_from_slice(&bytes);
            sections.push((name, start, bytes.len() as u64));
        };
        let tokens = {
            let mut text = Vec::new();
            for token in &self.tokens {
                text.extend_from_slice(token.as_bytes());
                text.push(0);
            }
            let compressed = lz4::compress(&text);
            let mut out = Vec::new();
            put_u64(&mut out, self.tokens.len() as u64);
            put_u64(&mut out, text.len() as u64);
            put_u64(&mut out, compressed.len() as u64);
            out.extend_from_slice(&compressed);
            out
        };
        section(&mut self, "TOKENS", tokens);
        let mut strings = Vec::new();
        put_u64(&mut strings, self.strings.len() as u64);
        for index in &self.strings {
            strings.extend_from_slice(&index.to_le_bytes());
        }
        section(&mut self, "STRINGS", strings);
        let mut fields = Vec::new();
        put_u64(&mut fields, tables.fields.len() as u64);
        let names: Vec<i32> = tables.fields.iter().map(|f| f.0 as i32).collect();
        put_ints(&mut fields, &names);
        let reps: Vec<u8> = tables
            .fields
            .iter()
            .flat_map(|f| f.1.to_le_bytes())
            .collect();
        let reps = lz4::compress(&reps);
        put_u64(&mut fields, reps.len() as u64);
        fields.extend_from_slice(&reps);
        section(&mut self, "FIELDS", fields);
        let mut field_sets = Vec::new();
        put_u64(&mut field_sets, tables.field_sets.len() as u64);
        put_ints(&mut field_sets, &tables.field_sets);
        section(&mut self, "FIELDSETS", field_sets);
        let mut paths = Vec::new();
        let count = tables.path_names.len();
        put_u64(&mut paths, count as u64);
        put_u64(&mut paths, count as u64);
        put_ints(&mut paths, &(0..count as i32).collect::<Vec<_>>());
        put_ints(&mut paths, &tables.path_names);
        put_ints(&mut paths, &tables.jumps);
        section(&mut self, "PATHS", paths);
        let mut specs = Vec::new();
        put_u64(&mut specs, tables.specs.len() as u64);
        for column in 0..3 {
            let values: Vec<i32> = tables.specs.iter().map(|s| s[column] as i32).collect();
            put_ints(&mut specs, &values);
        }
        section(&mut self, "SPECS", specs);
        let toc = self.align();
        put_u64(&mut self.data, sections.len() as u64);
        for (name, start, size) in sections {
            let mut padded = [0u8; 16];
            padded[..name.len()].copy_from_slice(name.as_bytes());
            self.data.extend_from_slice(&padded);
            put_u64(&mut self.data, start);
            put_u64(&mut self.data, size);
        }
        self.data[..8].copy_from_slice(MAGIC);
        self.data[8..11].copy_from_slice(&VERSION);
        self.data[16..24].copy_from_slice(&toc.to_le_bytes());
        self.data
    }

    /// Numbers `node` and its subtree depth first (path index = order),
    /// recording fields, field sets, specs and the tree's jumps.
    fn flatten(&mut self, node: &Node, tables: &mut Tables, has_sibling: bool) {
        let index = tables.path_names.len();
        let name = self.token(&node.name) as i32;
        tables
            .path_names
            .push(if node.property { -name } else { name });
        tables.jumps.push(0);
        let field_set = tables.field_sets.len() as u32;
        for (field, value) in &node.fields {
            let name = self.token(field);
            tables.field_sets.push(tables.fields.len() as i32);
            tables.fields.push((name, *value));
        }
        tables.field_sets.push(-1);
        tables.specs.push([index as u32, field_set, node.spec_type]);
        let count = node.children.len();
        for (position, child) in node.children.iter().enumerate() {
            self.flatten(child, tables, position + 1 < count);
        }
        let has_child = count > 0;
        tables.jumps[index] = match (has_child, has_sibling) {
            (true, true) => (tables.path_names.len() - index) as i32,
            (false, true) => 0,
            (true, false) => -1,
            (false, false) => -2,
        };
    }
}

/// The structural tables, filled depth first.
#[derive(Default)]
struct Tables {
    fields: Vec<(u32, u64)>,
    field_sets: Vec<i32>,
    path_names: Vec<i32>,
    jumps: Vec<i32>,
    specs: Vec<[u32; 3]>,
}

fn put_u64(out: &mut Vec<u8>, value: u64) {
    out.extend_from_slice(&value.to_le_bytes());
}

/// A compressed integer list: its compressed size, then the data.
fn put_ints(out: &mut Vec<u8>, values: &[i32]) {
    let compressed = lz4::compress(&integers::encode(values));
    put_u64(out, compressed.len() as u64);
    out.extend_from_slice(&compressed);
}

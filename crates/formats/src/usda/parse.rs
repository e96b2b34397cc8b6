//! The `.usda` subset this crate reads, parsed into prims.
//!
//! The whole layer syntax is walked (layer and prim metadata, nested prims,
//! properties of every type, time samples, relationships, variant sets,
//! dictionaries), but only what curves need is kept: layer metadata
//! (`metersPerUnit`, `upAxis`, time codes per second), each prim's path,
//! type, transform ops, and for `BasisCurves` prims `type`, `basis`, `wrap`,
//! `curveVertexCounts`, `points` (default and time samples), `widths` (or
//! `primvars:widths`) and `primvars:displayColor` with their
//! interpolation. Every other value is skipped without being stored.
//! Composition (references, payloads, inherits, variants) is not followed;
//! prims under a `class` or marked `active = false` are skipped.
//!
//! Nesting (prims, brackets) deeper than [`MAX_DEPTH`] is refused, so
//! hostile input cannot exhaust the stack.

use crate::error::{Location, ReadError, ReadErrorKind};
use crate::format::Format;
use crate::usda::lexer::{Lexer, Token};
use crate::warnings::{Warnings, short};

/// The deepest nesting of prims or brackets read.
pub const MAX_DEPTH: usize = 64;

/// Layer metadata that curves need.
#[derive(Debug, Default)]
pub(crate) struct LayerMetadata {
    pub meters_per_unit: Option<(usize, f64)>,
    pub up_axis: Option<(usize, String)>,
    pub time_codes_per_second: Option<f64>,
    pub frames_per_second: Option<f64>,
}

/// A primvar or attribute array with its line and interpolation.
#[derive(Debug)]
pub(crate) struct ArrayValue<T> {
    pub line: usize,
    pub values: Vec<T>,
    pub interpolation: Option<String>,
}

/// A prim: its place in the tree and its transform ops.
#[derive(Debug)]
pub(crate) struct Prim {
    /// The name, cut to [`crate::warnings::MAX_QUOTED_CHARS`] characters
    /// (it is only ever shown in messages).
    pub name: String,
    pub parent: Option<usize>,
    /// `xformOpOrder`, when authored.
    pub xform_op_order: Option<Vec<String>>,
    /// Transform op values by name (`xformOp:translate` …), default values
    /// only.
    pub xform_ops: Vec<(String, usize, Vec<f64>)>,
    /// Whether any transform op is time-sampled (not applied).
    pub animated_xform: bool,
}

/// What a `BasisCurves` prim holds.
#[derive(Debug, Default)]
pub(crate) struct CurvesPrim {
    pub prim: usize,
    pub line: usize,
    pub curve_type: Option<String>,
    pub basis: Option<String>,
    pub wrap: Option<String>,
    pub counts: Option<ArrayValue<f64>>,
    pub points: Option<ArrayValue<[f64; 3]>>,
    /// Time samples of `points`.
    pub point_samples: Vec<PointSample>,
    pub widths: Option<ArrayValue<f64>>,
    pub colours: Option<ArrayValue<[f64; 3]>>,
}

/// One time sample of `points`: time code, line, values (`None` when
/// blocked).
pub(crate) type PointSample = (f64, usize, Option<Vec<[f64; 3]>>);

/// A parsed layer.
#[derive(Debug, Default)]
pub(crate) struct Layer {
    pub metadata: LayerMetadata,
    pub prims: Vec<Prim>,
    pub curves: Vec<CurvesPrim>,
    pub warnings: Warnings,
}

/// A prim's path for messages (`/root/hair`), written from its shortened
/// names only when shown.
pub(crate) struct PrimPath<'a> {
    pub prims: &'a [Prim],
    pub index: usize,
}

impl std::fmt::Display for PrimPath<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let mut names = Vec::new();
        let mut at = Some(self.index);
        while let Some(index) = at {
            names.push(self.prims[index].name.as_str());
            at = self.prims[index].parent;
        }
        names.iter().rev().try_for_each(|name| write!(f, "/{name}"))
    }
}

/// Parses a layer's text (the `#usda` line already checked and removed
/// by the caller, `first_line` being the line the text starts on).
pub(crate) fn parse_layer(text: &str, first_line: usize) -> Result<Layer, ReadError> {
    let mut parser = Parser {
        lexer: Lexer::new(text),
        peeked: None,
        line_offset: first_line - 1,
        layer: Layer::default(),
    };
    if parser.peek()? == Token::Punct(b'(') {
        parser.next()?;
        parser.metadata(Owner::Layer)?;
    }
    loop {
        match parser.next()? {
            (Token::End, _) => break,
            (Token::Ident(specifier @ ("def" | "over" | "class")), _) => {
                parser.prim(specifier, None, 0, false)?;
            }
            (token, line) => return Err(parser.unexpected(token, line, "def, over or class")),
        }
    }
    Ok(parser.layer)
}

#[derive(Clone, Copy, PartialEq)]
enum Owner {
    Layer,
    Prim,
    Property,
}

/// What a metadata block said that matters here.
#[derive(Default)]
struct Said {
    interpolation: Option<String>,
    inactive: bool,
}

struct Parser<'a> {
    lexer: Lexer<'a>,
    peeked: Option<(Token<'a>, usize)>,
    line_offset: usize,
    layer: Layer,
}

impl<'a> Parser<'a> {
    fn error(&self, line: usize, kind: ReadErrorKind, message: String) -> ReadError {
        ReadError::new(Format::Usda, Location::Line(line), kind, message)
    }

    fn unexpected(&self, token: Token, line: usize, wanted: &str) -> ReadError {
        let found = match token {
            Token::Ident(name) => format!("{name:?}"),
            Token::Number(value) => format!("the number {value}"),
            Token::Str(_) => "a string".to_string(),
            Token::Path(path) => format!("the path <{path}>"),
            Token::Asset(_) => "an asset path".to_string(),
            Token::Punct(byte) => format!("{:?}", char::from(byte)),
            Token::End => "the end of the file".to_string(),
        };
        self.error(
            line,
            ReadErrorKind::Syntax,
            format!("expected {wanted}, found {found}"),
        )
    }

    fn next(&mut self) -> Result<(Token<'a>, usize), ReadError> {
        match self.peeked.take() {
            Some(peeked) => Ok(peeked),
            None => {
                let (token, line) = self.lexer.next_token().map_err(|mut error| {
                    if let Location::Line(line) = &mut error.location {
                        *line += self.line_offset;
                    }
                    error
                })?;
                Ok((token, line + self.line_offset))
            }
        }
    }

    fn peek(&mut self) -> Result<Token<'a>, ReadError> {
        if self.peeked.is_none() {
            self.peeked = Some(self.next()?);
        }
        Ok(self.peeked.map_or(Token::End, |(token, _)| token))
    }

    fn expect(&mut self, byte: u8) -> Result<usize, ReadError> {
        match self.next()? {
            (Token::Punct(found), line) if found == byte => Ok(line),
            (token, line) => Err(self.unexpected(token, line, &format!("{:?}", char::from(byte)))),
        }
    }

    fn skip_if(&mut self, byte: u8) -> Result<bool, ReadError> {
        if self.peek()? == Token::Punct(byte) {
            self.next()?;
            return Ok(true);
        }
        Ok(false)
    }

    fn ident(&mut self, wanted: &str) -> Result<(&'a str, usize), ReadError> {
        match self.next()? {
            (Token::Ident(name), line) => Ok((name, line)),
            (token, line) => Err(self.unexpected(token, line, wanted)),
        }
    }

    fn string(&mut self, wanted: &str) -> Result<&'a str, ReadError> {
        match self.next()? {
            (Token::Str(text), _) => Ok(text),
            (token, line) => Err(self.unexpected(token, line, wanted)),
        }
    }

    /// A prim after its specifier: `[Type] "name" [(metadata)] { body }`.
    fn prim(
        &mut self,
        specifier: &str,
        parent: Option<usize>,
        depth: usize,
        skipped: bool,
    ) -> Result<(), ReadError> {
        let (type_name, line) = match self.next()? {
            (Token::Ident(type_name), line) => (Some(type_name), line),
            (Token::Str(name), line) => {
                self.peeked = Some((Token::Str(name), line));
                (None, line)
            }
            (token, line) => return Err(self.unexpected(token, line, "a prim type or name")),
        };
        let name = self.string("the prim's name in quotes")?;
        if depth >= MAX_DEPTH {
            return Err(self.error(
                line,
                ReadErrorKind::TooLarge,
                format!("prims nest deeper than {MAX_DEPTH} levels"),
            ));
        }
        let said = if self.skip_if(b'(')? {
            self.metadata(Owner::Prim)?
        } else {
            Said::default()
        };
        let skipped = skipped || specifier == "class" || said.inactive;
        let index = self.layer.prims.len();
        self.layer.prims.push(Prim {
            name: short(name),
            parent,
            xform_op_order: None,
            xform_ops: Vec::new(),
            animated_xform: false,
        });
        let mut curves = (type_name == Some("BasisCurves") && !skipped).then(|| CurvesPrim {
            prim: index,
            line,
            ..CurvesPrim::default()
        });
        self.expect(b'{')?;
        loop {
            match self.next()? {
                (Token::Punct(b'}'), _) => break,
                (Token::Ident(child @ ("def" | "over" | "class")), _) => {
                    self.prim(child, Some(index), depth + 1, skipped)?;
                }
                (Token::Ident("variantSet"), line) => {
                    self.string("the variant set's name")?;
                    self.expect(b'=')?;
                    self.skip_value()?;
                    let path = PrimPath {
                        prims: &self.layer.prims,
                        index,
                    };
                    self.layer
                        .warnings
                        .push(|| format!("line {line}: the variant set in <{path}> is not read"));
                }
                (Token::Ident("reorder"), _) => {
                    self.ident("nameChildren or properties")?;
                    self.expect(b'=')?;
                    self.skip_value()?;
                }
                (Token::Ident(first), line) => {
                    self.property(first, line, index, curves.as_mut())?;
                }
                (token, line) => {
                    return Err(self.unexpected(token, line, "a property, a prim or '}'"));
                }
            }
        }
        if let Some(curves) = curves {
            self.layer.curves.push(curves);
        }
        Ok(())
    }

    /// A property, from its first word: `[custom] [uniform] type[[]] name
    /// [= value] [(metadata)]`, `rel name [= targets]`, or
    /// `name.timeSamples = { … }` forms.
    fn property(
        &mut self,
        first: &'a str,
        first_line: usize,
        prim: usize,
        curves: Option<&mut CurvesPrim>,
    ) -> Result<(), ReadError> {
        let mut word = (first, first_line);
        while matches!(
            word.0,
            "custom" | "uniform" | "varying" | "config" | "prepend" | "append" | "add" | "delete"
        ) {
            word = self.ident("a property type")?;
        }
        if word.0 == "rel" {
            self.ident("the relationship's name")?;
            if self.skip_if(b'=')? {
                self.skip_value()?;
            }
            if self.skip_if(b'(')? {
                self.metadata(Owner::Property)?;
            }
            return Ok(());
        }
        let type_name = word.0;
        if self.skip_if(b'[')? {
            self.expect(b']')?;
        }
        let (name, line) = self.ident("the property's name")?;
        let (base, suffix) = match name.rsplit_once('.') {
            Some((base, suffix @ ("timeSamples" | "connect" | "spline"))) => (base, Some(suffix)),
            _ => (name, None),
        };
        if base.starts_with("xformOp") {
            return self.xform_property(prim, base, suffix, line);
        }
        let has_value = self.skip_if(b'=')?;
        let mut curves = curves;
        match (curves.as_deref_mut(), suffix, has_value) {
            (Some(curves), None, true) => self.curves_attribute(curves, base, type_name, line)?,
            (Some(curves), Some("timeSamples"), true) if base == "points" => {
                self.point_samples(curves)?;
            }
            (_, _, true) => {
                if suffix == Some("timeSamples") && base != "points" && curves.is_some() {
                    self.layer.warnings.push(|| {
                        let base = short(base);
                        format!(
                            "line {line}: time samples of {base} are not read (only points move)"
                        )
                    });
                }
                self.skip_value()?;
            }
            _ => {}
        }
        if self.skip_if(b'(')? {
            let said = self.metadata(Owner::Property)?;
            if let (Some(curves), Some(interpolation)) = (curves, said.interpolation) {
                match base {
                    "widths" | "primvars:widths" => {
                        if let Some(widths) = curves.widths.as_mut() {
                            widths.interpolation = Some(interpolation);
                        }
                    }
                    "primvars:displayColor" => {
                        if let Some(colours) = curves.colours.as_mut() {
                            colours.interpolation = Some(interpolation);
                        }
                    }
                    _ => {}
                }
            }
        }
        Ok(())
    }

    /// A `BasisCurves` attribute's default value (after `=`).
    fn curves_attribute(
        &mut self,
        curves: &mut CurvesPrim,
        name: &str,
        type_name: &str,
        line: usize,
    ) -> Result<(), ReadError> {
        if self.peek()? == Token::Ident("None") {
            self.next()?;
            return Ok(());
        }
        fn array<T>(line: usize, values: Vec<T>) -> ArrayValue<T> {
            ArrayValue {
                line,
                values,
                interpolation: None,
            }
        }
        match name {
            "type" => curves.curve_type = Some(self.string("a token in quotes")?.to_string()),
            "basis" => curves.basis = Some(self.string("a token in quotes")?.to_string()),
            "wrap" => curves.wrap = Some(self.string("a token in quotes")?.to_string()),
            "curveVertexCounts" => curves.counts = Some(array(line, self.number_array()?)),
            "points" => curves.points = Some(array(line, self.vec3_array()?)),
            "widths" | "primvars:widths" if type_name == "float" => {
                curves.widths = Some(array(line, self.number_array()?));
            }
            "primvars:displayColor" if type_name == "color3f" => {
                curves.colours = Some(array(line, self.vec3_array()?));
            }
            _ => self.skip_value()?,
        }
        Ok(())
    }

    /// `points.timeSamples = { time: [points] | None, … }`.
    fn point_samples(&mut self, curves: &mut CurvesPrim) -> Result<(), ReadError> {
        self.expect(b'{')?;
        loop {
            let (time, line) = match self.next()? {
                (Token::Punct(b'}'), _) => return Ok(()),
                (Token::Number(time), line) => (time, line),
                (token, line) => return Err(self.unexpected(token, line, "a time code or '}'")),
            };
            self.expect(b':')?;
            let values = if self.peek()? == Token::Ident("None") {
                self.next()?;
                None
            } else {
                Some(self.vec3_array()?)
            };
            curves.point_samples.push((time, line, values));
            if !self.skip_if(b',')? {
                self.expect(b'}')?;
                return Ok(());
            }
        }
    }

    /// A transform op (`xformOp:translate`, `xformOpOrder`…) on any prim.
    fn xform_property(
        &mut self,
        prim: usize,
        name: &str,
        suffix: Option<&str>,
        line: usize,
    ) -> Result<(), ReadError> {
        if self.skip_if(b'=')? {
            if suffix == Some("timeSamples") {
                self.layer.prims[prim].animated_xform = true;
                self.skip_value()?;
            } else if name == "xformOpOrder" {
                let order = self.string_array()?;
                self.layer.prims[prim].xform_op_order = Some(order);
            } else if suffix.is_none() && self.peek()? != Token::Ident("None") {
                let values = self.flat_numbers()?;
                self.layer.prims[prim]
                    .xform_ops
                    .push((name.to_string(), line, values));
            } else {
                self.skip_value()?;
            }
        }
        if self.skip_if(b'(')? {
            self.metadata(Owner::Property)?;
        }
        Ok(())
    }

    /// A metadata block after its `(`, through its `)`.
    fn metadata(&mut self, owner: Owner) -> Result<Said, ReadError> {
        let mut said = Said::default();
        loop {
            let (key, line) = match self.next()? {
                (Token::Punct(b')'), _) => return Ok(said),
                (Token::Punct(b';'), _) | (Token::Str(_), _) => continue,
                (Token::Ident(key), line) => (key, line),
                (token, line) => {
                    return Err(self.unexpected(token, line, "a metadata entry or ')'"));
                }
            };
            let key = match key {
                "prepend" | "append" | "add" | "delete" | "reorder" => {
                    self.ident("a metadata key")?.0
                }
                key => key,
            };
            self.expect(b'=')?;
            match (owner, key) {
                (Owner::Layer, "metersPerUnit") => {
                    self.layer.metadata.meters_per_unit = Some((line, self.number()?));
                }
                (Owner::Layer, "upAxis") => {
                    let axis = self.string("an axis in quotes")?.to_string();
                    self.layer.metadata.up_axis = Some((line, axis));
                }
                (Owner::Layer, "timeCodesPerSecond") => {
                    self.layer.metadata.time_codes_per_second = Some(self.number()?);
                }
                (Owner::Layer, "framesPerSecond") => {
                    self.layer.metadata.frames_per_second = Some(self.number()?);
                }
                (Owner::Property, "interpolation") => {
                    said.interpolation =
                        Some(self.string("an interpolation in quotes")?.to_string());
                }
                (Owner::Prim, "active") => {
                    let (value, _) = self.next()?;
                    said.inactive = matches!(value, Token::Ident("false" | "False"))
                        || value == Token::Number(0.0);
                }
                (
                    Owner::Prim,
                    "references" | "payload" | "inherits" | "specializes" | "variants",
                ) => {
                    self.layer
                        .warnings
                        .push(|| format!("line {line}: {key} (composition) are not followed"));
                    self.skip_value()?;
                }
                _ => self.skip_value()?,
            }
        }
    }

    /// One number: digits, `inf`, `-inf` or `nan`.
    fn number(&mut self) -> Result<f64, ReadError> {
        match self.next()? {
            (Token::Number(value), _) => Ok(value),
            (Token::Ident("inf" | "+inf"), _) => Ok(f64::INFINITY),
            (Token::Ident("-inf"), _) => Ok(f64::NEG_INFINITY),
            (Token::Ident("nan" | "-nan"), _) => Ok(f64::NAN),
            (token, line) => Err(self.unexpected(token, line, "a number")),
        }
    }

    /// `[a, b, …]` of numbers (a trailing comma allowed).
    fn number_array(&mut self) -> Result<Vec<f64>, ReadError> {
        let mut values = Vec::new();
        self.list(|parser| {
            values.push(parser.number()?);
            Ok(())
        })?;
        Ok(values)
    }

    /// `[(x, y, z), …]`.
    fn vec3_array(&mut self) -> Result<Vec<[f64; 3]>, ReadError> {
        let mut values = Vec::new();
        self.list(|parser| {
            parser.expect(b'(')?;
            let x = parser.number()?;
            parser.expect(b',')?;
            let y = parser.number()?;
            parser.expect(b',')?;
            let z = parser.number()?;
            parser.expect(b')')?;
            values.push([x, y, z]);
            Ok(())
        })?;
        Ok(values)
    }

    /// `["a", "b"]` of strings or tokens.
    fn string_array(&mut self) -> Result<Vec<String>, ReadError> {
        let mut values = Vec::new();
        self.list(|parser| {
            values.push(parser.string("a token in quotes")?.to_string());
            Ok(())
        })?;
        Ok(values)
    }

    /// `[ item, item, … ]` with a trailing comma allowed.
    fn list(
        &mut self,
        mut item: impl FnMut(&mut Parser<'a>) -> Result<(), ReadError>,
    ) -> Result<(), ReadError> {
        self.expect(b'[')?;
        loop {
            if self.skip_if(b']')? {
                return Ok(());
            }
            item(self)?;
            if !self.skip_if(b',')? {
                self.expect(b']')?;
                return Ok(());
            }
        }
    }

    /// Every number in a value of nested tuples (`(1, 2, 3)`, a matrix's
    /// `( (…), (…) )`), flattened.
    fn flat_numbers(&mut self) -> Result<Vec<f64>, ReadError> {
        let mut values = Vec::new();
        let mut depth = 0usize;
        loop {
            match self.peek()? {
                Token::Punct(b'(') => {
                    self.next()?;
                    depth += 1;
                    if depth > MAX_DEPTH {
                        let line = self.lexer.line() + self.line_offset;
                        return Err(self.error(
                            line,
                            ReadErrorKind::TooLarge,
                            format!("tuples nest deeper than {MAX_DEPTH} levels"),
                        ));
                    }
                }
                Token::Punct(b')') if depth > 0 => {
                    self.next()?;
                    depth -= 1;
                }
                Token::Punct(b',') if depth > 0 => {
                    self.next()?;
                }
                _ => values.push(self.number()?),
            }
            if depth == 0 {
                return Ok(values);
            }
        }
    }

    /// Skips one value of any shape without storing it: a single token, or
    /// a bracketed group (balanced, at most [`MAX_DEPTH`] deep).
    fn skip_value(&mut self) -> Result<(), ReadError> {
        let mut open: Vec<u8> = Vec::new();
        loop {
            let (token, line) = self.next()?;
            match token {
                Token::Punct(byte @ (b'(' | b'[' | b'{')) => {
                    if open.len() >= MAX_DEPTH {
                        return Err(self.error(
                            line,
                            ReadErrorKind::TooLarge,
                            format!("brackets nest deeper than {MAX_DEPTH} levels"),
                        ));
                    }
                    open.push(match byte {
                        b'(' => b')',
                        b'[' => b']',
                        _ => b'}',
                    });
                }
                Token::Punct(byte @ (b')' | b']' | b'}')) => {
                    let expected = open.pop();
                    if expected != Some(byte) {
                        return Err(self.unexpected(token, line, "a value"));
                    }
                }
                Token::End => return Err(self.unexpected(token, line, "the rest of a value")),
                Token::Asset(_) if open.is_empty() => {
                    if matches!(self.peek()?, Token::Path(_)) {
                        self.next()?;
                    }
                }
                _ => {}
            }
            if open.is_empty() {
                return Ok(());
            }
        }
    }
}

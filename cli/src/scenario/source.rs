//! A scenario file's text and its tree of spanned keys, and the error
//! that names a place in it: the file, line and column, the key and the
//! value written there.

use std::ops::Range;
use std::path::Path;

use toml::de::{DeTable, DeValue};
use toml::Spanned;

/// One step of a key path: a table's key or an array's index.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Segment {
    /// A key of a table.
    Key(String),
    /// An element of an array.
    Index(usize),
}

/// A key path in a scenario, written as in the file's own terms:
/// `law.youngs_modulus`, `bodies[2].radius`.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct KeyPath(pub Vec<Segment>);

impl KeyPath {
    /// The path of a top-level key.
    pub fn root(key: &str) -> Self {
        Self(vec![Segment::Key(key.to_string())])
    }

    /// This path followed by `key`.
    pub fn key(&self, key: &str) -> Self {
        let mut next = self.clone();
        next.0.push(Segment::Key(key.to_string()));
        next
    }

    /// This path followed by element `index`.
    pub fn index(&self, index: usize) -> Self {
        let mut next = self.clone();
        next.0.push(Segment::Index(index));
        next
    }
}

impl std::fmt::Display for KeyPath {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.0.is_empty() {
            return write!(f, "(the file)");
        }
        for (k, segment) in self.0.iter().enumerate() {
            match segment {
                Segment::Key(key) if k == 0 => write!(f, "{key}")?,
                Segment::Key(key) => write!(f, ".{key}")?,
                Segment::Index(i) => write!(f, "[{i}]")?,
            }
        }
        Ok(())
    }
}

/// A refusal of a scenario file, placed in it: the file, the line and
/// column (from 1), the key and the value as written, and what is wrong.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Located {
    /// The file as given on the command line.
    pub file: String,
    /// Line, from 1.
    pub line: usize,
    /// Column (characters), from 1.
    pub column: usize,
    /// The key the refusal is about (`law.friction`), or several joined by
    /// ` and ` for a combination the library cannot compose.
    pub key: String,
    /// The value as written in the file, where there is one (shortened).
    pub value: Option<String>,
    /// What is wrong and what to change.
    pub message: String,
}

impl Located {
    /// The refusal as a [`super::ScenarioError`].
    pub fn into_error(self) -> super::ScenarioError {
        super::ScenarioError::Invalid(Box::new(self))
    }
}

impl std::fmt::Display for Located {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{}:{}:{}: `{}`",
            self.file, self.line, self.column, self.key
        )?;
        if let Some(value) = &self.value {
            write!(f, " = {value}")?;
        }
        write!(f, ": {}", self.message)
    }
}

/// The text of a scenario file and its parsed tree (every key and value
/// with its span in the text).
pub struct Source<'i> {
    file: String,
    text: &'i str,
    tree: Spanned<DeTable<'i>>,
}

/// The longest value quoted in a message, in characters.
const QUOTED_VALUE: usize = 60;

impl<'i> Source<'i> {
    /// Parse `text`, read from `file`.
    ///
    /// # Errors
    /// A [`Located`] error at the first TOML syntax error (its line and
    /// column, and the key it is in where there is one).
    pub fn parse(file: &Path, text: &'i str) -> Result<Self, Box<Located>> {
        let file = file.display().to_string();
        match DeTable::parse(text) {
            Ok(tree) => Ok(Self { file, text, tree }),
            Err(e) => {
                let span = e.span().unwrap_or(0..0);
                let message = format!("not valid TOML: {}", e.message().trim_end());
                Err(Box::new(Located {
                    key: "(syntax)".into(),
                    value: None,
                    ..locate_text(&file, text, span, message)
                }))
            }
        }
    }

    /// The tree, to be deserialized (it is taken; the source keeps a copy
    /// to place errors).
    pub fn tree(&self) -> Spanned<DeTable<'i>> {
        self.tree.clone()
    }

    /// The file name.
    pub fn file(&self) -> &str {
        &self.file
    }

    /// The error `message` about the place `span` of the text: its line
    /// and column, and the innermost key whose key or value holds it.
    pub fn at_span(&self, span: Range<usize>, message: impl Into<String>) -> Located {
        let path = innermost(&self.tree, &span).unwrap_or_default();
        let value = lookup(&self.tree, &path).map(|(_, v)| self.quote(v));
        let key = path.to_string();
        Located {
            key,
            value,
            ..locate_text(&self.file, self.text, span, message.into())
        }
    }

    /// The error `message` about the value at `path` (placed at the
    /// value, or at the nearest table on the path that the file has).
    pub fn at_key(&self, path: &KeyPath, message: impl Into<String>) -> Located {
        let (span, value) = match lookup(&self.tree, path) {
            Some((_, v)) => (v.clone(), Some(self.quote(v))),
            None => (self.nearest(path), None),
        };
        Located {
            key: path.to_string(),
            value,
            ..locate_text(&self.file, self.text, span, message.into())
        }
    }

    /// The error `message` about a combination of values at `paths`
    /// (placed at the first that the file has; every key named).
    pub fn at_keys(&self, paths: &[&KeyPath], message: impl Into<String>) -> Located {
        let mut unique: Vec<&KeyPath> = Vec::with_capacity(paths.len());
        for p in paths {
            if !unique.contains(p) {
                unique.push(p);
            }
        }
        let paths = unique.as_slice();
        let present = paths
            .iter()
            .find_map(|p| lookup(&self.tree, p).map(|(_, v)| v));
        let span = present.unwrap_or_else(|| self.nearest(paths[0]));
        let named: Vec<String> = paths
            .iter()
            .map(|p| match lookup(&self.tree, p) {
                Some((_, v)) => format!("{p} = {}", self.quote(v)),
                None => format!("{p} (not given)"),
            })
            .collect();
        Located {
            key: paths
                .iter()
                .map(|p| p.to_string())
                .collect::<Vec<_>>()
                .join("` and `"),
            value: None,
            ..locate_text(
                &self.file,
                self.text,
                span,
                format!("{} ({})", message.into(), named.join(", ")),
            )
        }
    }

    /// The span of the longest prefix of `path` the file has (the whole
    /// file for none).
    fn nearest(&self, path: &KeyPath) -> Range<usize> {
        let mut prefix = path.clone();
        while !prefix.0.is_empty() {
            if let Some((_, v)) = lookup(&self.tree, &prefix) {
                return v;
            }
            prefix.0.pop();
        }
        0..0
    }

    /// The text at `span`, on one line and shortened.
    fn quote(&self, span: Range<usize>) -> String {
        let raw = self.text.get(span).unwrap_or("");
        let one_line: String = raw.split_whitespace().collect::<Vec<_>>().join(" ");
        if one_line.chars().count() > QUOTED_VALUE {
            let cut: String = one_line.chars().take(QUOTED_VALUE).collect();
            format!("{cut}…")
        } else {
            one_line
        }
    }
}

/// The innermost key of `source` whose key or value holds `span`, if any
/// (none for the span of the whole file).
pub fn innermost_key(source: &Source<'_>, span: Range<usize>) -> Option<KeyPath> {
    if span == source.tree.span() {
        return None;
    }
    innermost(&source.tree, &span)
}

/// A [`Located`] at byte `span.start` of `text`, without key or value.
fn locate_text(file: &str, text: &str, span: Range<usize>, message: String) -> Located {
    let start = floor_char_boundary(text, span.start.min(text.len()));
    let before = &text[..start];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |k| k + 1);
    let column = before[line_start..].chars().count() + 1;
    Located {
        file: file.to_string(),
        line,
        column,
        key: String::new(),
        value: None,
        message,
    }
}

/// The largest char boundary of `text` at or below `index`.
fn floor_char_boundary(text: &str, mut index: usize) -> usize {
    while index > 0 && !text.is_char_boundary(index) {
        index -= 1;
    }
    index
}

/// The key and the value at `path`.
fn lookup<'a, 'i>(
    tree: &'a Spanned<DeTable<'i>>,
    path: &KeyPath,
) -> Option<(Range<usize>, Range<usize>)> {
    let mut value: Option<&'a Spanned<DeValue<'i>>> = None;
    let mut key_span = tree.span();
    for segment in &path.0 {
        match (segment, value.map(|v| v.get_ref())) {
            (Segment::Key(key), None) => {
                let (k, v) = tree.get_ref().get_key_value(key.as_str())?;
                key_span = k.span();
                value = Some(v);
            }
            (Segment::Key(key), Some(DeValue::Table(table))) => {
                let (k, v) = table.get_key_value(key.as_str())?;
                key_span = k.span();
                value = Some(v);
            }
            (Segment::Index(i), Some(DeValue::Array(array))) => {
                let v = array.get(*i)?;
                key_span = v.span();
                value = Some(v);
            }
            _ => return None,
        }
    }
    Some((key_span, value.map_or(tree.span(), |v| v.span())))
}

/// The path of the innermost key whose key or value holds `span`. A
/// table's span may be its header alone, so every branch is searched.
fn innermost(tree: &Spanned<DeTable<'_>>, span: &Range<usize>) -> Option<KeyPath> {
    fn holds(outer: &Range<usize>, inner: &Range<usize>) -> bool {
        outer.start <= inner.start && inner.end <= outer.end.max(outer.start + 1)
    }
    fn in_table(table: &DeTable<'_>, path: &KeyPath, span: &Range<usize>) -> Option<KeyPath> {
        for (k, v) in table.iter() {
            let here = path.key(k.get_ref());
            if holds(&k.span(), span) {
                return Some(here);
            }
            if let Some(deeper) = in_value(v, &here, span) {
                return Some(deeper);
            }
        }
        None
    }
    fn in_value(v: &Spanned<DeValue<'_>>, path: &KeyPath, span: &Range<usize>) -> Option<KeyPath> {
        let deeper = match v.get_ref() {
            DeValue::Table(table) => in_table(table, path, span),
            DeValue::Array(array) => array
                .iter()
                .enumerate()
                .find_map(|(i, item)| in_value(item, &path.index(i), span)),
            _ => None,
        };
        deeper.or_else(|| holds(&v.span(), span).then(|| path.clone()))
    }
    in_table(tree.get_ref(), &KeyPath::default(), span)
}

//! XML plumbing shared by the COLLADA readers: locating nodes in the text,
//! making located errors and warnings, finding children and resolving `#url`s.

use crate::desc::SourceLoc;
use crate::error::{ErrorKind, LoadError};
use crate::report::Collector;
use crate::text_file::LineIndex;
use roxmltree::{Document, Node};
use std::cell::RefCell;
use std::collections::HashMap;
use std::path::Path;

/// An element of the parsed document.
pub(crate) type XNode<'a, 'i> = Node<'a, 'i>;

/// Everything a reader needs to look things up and to complain precisely.
pub(crate) struct Ctx<'a, 'i> {
    /// The whole source text (to turn byte offsets into line:col).
    pub text: &'i str,
    /// The file name used in messages and to resolve relative paths.
    pub file: &'a Path,
    ids: HashMap<&'a str, XNode<'a, 'i>>,
    warnings: RefCell<Collector>,
    lines: LineIndex,
}

impl<'a, 'i> Ctx<'a, 'i> {
    /// Indexes every `id` attribute of `doc` (first definition wins).
    pub fn new(doc: &'a Document<'i>, text: &'i str, file: &'a Path, strict: bool) -> Self {
        let mut ids = HashMap::new();
        for n in doc.descendants().filter(|n| n.is_element()) {
            if let Some(id) = n.attribute("id") {
                ids.entry(id).or_insert(n);
            }
        }
        Self {
            text,
            file,
            ids,
            warnings: RefCell::new(Collector::new(file.to_path_buf(), strict)),
            lines: LineIndex::default(),
        }
    }

    /// Hands back the collected warnings.
    pub fn into_report(self) -> crate::Report {
        self.warnings.into_inner().finish()
    }

    /// Line and column of a byte offset in the source text.
    pub fn loc_at(&self, byte: usize) -> SourceLoc {
        self.lines.loc(self.text, byte)
    }

    /// Where an element starts.
    pub fn loc(&self, node: XNode) -> SourceLoc {
        self.loc_at(node.range().start)
    }

    /// Byte offset of `s` if it is a slice of the source text (element text
    /// without entities is), so a bad number can be pointed at exactly.
    pub fn offset_of(&self, s: &str) -> Option<usize> {
        let base = self.text.as_ptr() as usize;
        let p = s.as_ptr() as usize;
        (p >= base && p + s.len() <= base + self.text.len()).then(|| p - base)
    }

    /// An error located at the start of `node`.
    pub fn err(&self, node: XNode, kind: ErrorKind, message: impl Into<String>) -> LoadError {
        self.err_at(node.range().start, node, kind, message)
    }

    /// An error located at a byte offset inside `node`.
    pub fn err_at(
        &self,
        byte: usize,
        node: XNode,
        kind: ErrorKind,
        message: impl Into<String>,
    ) -> LoadError {
        LoadError {
            file: self.file.to_path_buf(),
            loc: Some(self.loc_at(byte)),
            element: describe(node),
            kind,
            message: message.into(),
        }
    }

    /// An error pointing at the token `token` (a slice of `node`'s text), or at
    /// `node` when the token is not part of the source text.
    pub fn err_token(
        &self,
        node: XNode,
        token: &str,
        kind: ErrorKind,
        message: impl Into<String>,
    ) -> LoadError {
        let byte = self.offset_of(token).unwrap_or(node.range().start);
        self.err_at(byte, node, kind, message)
    }

    /// Records that something in `node` was ignored (an error in strict mode).
    pub fn warn(&self, node: XNode, message: impl Into<String>) -> Result<(), LoadError> {
        let element = format!("<{}>", node.tag_name().name());
        self.warnings
            .borrow_mut()
            .warn(element, message.into(), || self.loc(node))
    }

    /// Whether this is a strict load (no warnings, no repairs, no aliases).
    pub fn strict(&self) -> bool {
        self.warnings.borrow().strict()
    }

    /// Repairs a defect: `err` in strict mode, otherwise a warning saying
    /// what was wrong and the `fix` applied (see [`super::lenient`]).
    pub fn repair(&self, err: LoadError, fix: &str) -> Result<(), LoadError> {
        self.warnings.borrow_mut().repair(err, fix)
    }

    /// The element with this `id`, if any.
    pub fn by_id(&self, id: &str) -> Option<XNode<'a, 'i>> {
        self.ids.get(id).copied()
    }

    /// Resolves `node`'s URL attribute `attr` (`#id`) to an element whose tag is
    /// one of `expected`. A missing attribute, a dangling id or an element of the
    /// wrong kind is an error; an external URL (no `#`) is unsupported and gives
    /// `None` after a warning.
    pub fn resolve(
        &self,
        node: XNode<'a, 'i>,
        attr: &str,
        expected: &[&str],
    ) -> Result<Option<XNode<'a, 'i>>, LoadError> {
        let url = node.attribute(attr).ok_or_else(|| {
            self.err(
                node,
                ErrorKind::MissingElement,
                format!("missing attribute {attr}"),
            )
        })?;
        let Some(id) = url.strip_prefix('#') else {
            self.warn(node, format!("external reference {attr}=\"{url}\" ignored"))?;
            return Ok(None);
        };
        let target = self.by_id(id).ok_or_else(|| {
            self.err(
                node,
                ErrorKind::MissingReference,
                format!("{attr}=\"{url}\" names no element"),
            )
        })?;
        if !expected.contains(&target.tag_name().name()) {
            return Err(self.err(
                node,
                ErrorKind::MissingReference,
                format!(
                    "{attr}=\"{url}\" names a <{}>, expected <{}>",
                    target.tag_name().name(),
                    expected.join("> or <")
                ),
            ));
        }
        Ok(Some(target))
    }
}

pub(crate) use crate::text_file::loc_in;

/// How an element is named in messages: `<tag id="...">` (or `name`/`sid`).
pub(crate) fn describe(node: XNode) -> String {
    let tag = node.tag_name().name();
    for key in ["id", "name", "sid", "semantic"] {
        if let Some(v) = node.attribute(key) {
            return format!("<{tag} {key}=\"{v}\">");
        }
    }
    format!("<{tag}>")
}

/// The first child element called `name`.
pub(crate) fn child<'a, 'i>(node: XNode<'a, 'i>, name: &str) -> Option<XNode<'a, 'i>> {
    node.children()
        .find(|c| c.is_element() && c.tag_name().name() == name)
}

/// All child elements called `name`.
pub(crate) fn children<'a, 'i: 'a>(
    node: XNode<'a, 'i>,
    name: &'a str,
) -> impl Iterator<Item = XNode<'a, 'i>> + 'a {
    node.children()
        .filter(move |c| c.is_element() && c.tag_name().name() == name)
}

/// All child elements.
pub(crate) fn elements<'a, 'i: 'a>(node: XNode<'a, 'i>) -> impl Iterator<Item = XNode<'a, 'i>> {
    node.children().filter(|c| c.is_element())
}

/// The first child element called `name`, or a `MissingElement` error.
pub(crate) fn require<'a, 'i>(
    ctx: &Ctx,
    node: XNode<'a, 'i>,
    name: &str,
) -> Result<XNode<'a, 'i>, LoadError> {
    child(node, name)
        .ok_or_else(|| ctx.err(node, ErrorKind::MissingElement, format!("missing <{name}>")))
}

/// The element's text content (empty when it has none).
pub(crate) fn text<'a>(node: XNode<'a, '_>) -> &'a str {
    node.text().unwrap_or("")
}

/// The `<technique profile="...">` under `node` (directly or inside `<extra>`).
pub(crate) fn technique<'a, 'i>(node: XNode<'a, 'i>, profile: &str) -> Option<XNode<'a, 'i>> {
    let direct = children(node, "technique").find(|t| t.attribute("profile") == Some(profile));
    direct.or_else(|| {
        children(node, "extra")
            .flat_map(|e| children(e, "technique"))
            .find(|t| t.attribute("profile") == Some(profile))
    })
}

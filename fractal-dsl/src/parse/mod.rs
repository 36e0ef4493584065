//! The parser: scene source (Rust-expression syntax, read by syn) to IR. Shared by `scene!` (tokens with spans) and
//! by `.fractal` files loaded at run time (text; errors carry line:column).
//!
//! A scene is one Rust expression over a fixed vocabulary ([`vocabulary`] lists it): free functions such as
//! `sphere(1.0)` and `union(a, b)`, chained methods such as `.translate(vec3(..))`, numbers with `+ - * /`, `t`
//! and `param("name", default, min..max)`. `//` comments are allowed in files. Three stages:
//! - `scan`: a pass over the raw tokens that refuses what the language never uses and bounds nesting, so hostile
//!   input cannot make syn recurse without limit;
//! - syn parses the tokens as a `syn::Expr`;
//! - `build`: looks every call up in the `names` table, checks arity and argument types, builds the value with the
//!   builder API (one place defines what a word means) and checks it with the rules of [`crate::validate`], so each
//!   broken rule is reported at the offending argument.
//!
//! Smooth CSG takes its blend radius last: `smooth_union(a, b, k)`, `smooth_union(a, b, c, k)`,
//! `smooth_intersect(a, b, k)`, `smooth_subtract(a, b, k)`. `box` is a Rust keyword, so the box is `box3(half)`.

mod build;
mod formula;
mod names;
mod scan;

use std::str::FromStr;

use crate::ir::Scene;

pub use build::MAX_EVAL_DEPTH;
pub use scan::{MAX_NESTING_COST, MAX_PAREN_NESTING, MAX_TOKENS};

/// An error in scene text, located at `line:column` (both 1-based).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{line}:{column}: {message}")]
pub struct SourceError {
    pub line: usize,
    pub column: usize,
    pub message: String,
}

/// Stack for parsing scene text: syn recurses once per nesting level with large frames in unoptimised builds, and
/// the scan bounds nesting, not frame sizes; a thread of its own makes the bound safe whatever thread calls in.
const PARSE_STACK: usize = 64 << 20;

/// Largest scene (or camera path) file read, in bytes: well above what the token cap ([`MAX_TOKENS`]) admits, and
/// small enough that `/dev/zero` or a mistyped video path is refused after 8 MiB rather than when memory runs out.
pub const MAX_SOURCE_BYTES: u64 = 8 << 20;

/// Reads a scene file as text, refusing one over [`MAX_SOURCE_BYTES`] before reading the rest of it.
pub fn read_source(path: &std::path::Path) -> std::io::Result<String> {
    use std::io::{Error, ErrorKind, Read};
    let mut bytes = Vec::new();
    std::fs::File::open(path)?.take(MAX_SOURCE_BYTES + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > MAX_SOURCE_BYTES {
        let limit = MAX_SOURCE_BYTES >> 20;
        return Err(Error::new(ErrorKind::InvalidData, format!("larger than {limit} MiB: not a scene file")));
    }
    String::from_utf8(bytes).map_err(|_| Error::new(ErrorKind::InvalidData, "not UTF-8 text: not a scene file"))
}

/// Parses scene text (the contents of a `.fractal` file).
pub fn parse_str(src: &str) -> Result<Scene, SourceError> {
    parse_str_on_own_thread(src).map_err(|e| SourceError { message: crate::sanitise::tidy(&e.message), ..e })
}

fn parse_str_on_own_thread(src: &str) -> Result<Scene, SourceError> {
    // The lexer's span table is per thread and only grows; parsing on a thread of our own also frees it afterwards.
    std::thread::scope(|scope| {
        let spawned = std::thread::Builder::new()
            .name("fractal-parse".into())
            .stack_size(PARSE_STACK)
            .spawn_scoped(scope, || parse_str_here(src));
        match spawned {
            Ok(handle) => handle.join().unwrap_or_else(|_| {
                Err(SourceError { line: 1, column: 1, message: "internal error: the parser panicked".into() })
            }),
            // No thread to be had: parse here (the nesting caps still hold on an ordinary stack).
            Err(_) => parse_str_here(src),
        }
    })
}

fn parse_str_here(src: &str) -> Result<Scene, SourceError> {
    let tokens = proc_macro2::TokenStream::from_str(src).map_err(|e| lex_error(src, &e))?;
    let end = tokens.clone().into_iter().last().map(|t| t.span().end());
    parse_tokens(tokens).map_err(|e| {
        let message = e.to_string();
        let start = e.span().start();
        // syn reports a missing expression at the end of the input at the call site (1:0): put it after the last token.
        let at = match end {
            Some(end) if message.starts_with("unexpected end of input") && start.line == 1 && start.column == 0 => end,
            None if message.starts_with("unexpected end of input") => {
                return SourceError { line: 1, column: 1, message: "the scene is empty: write a shape".into() }
            }
            _ => start,
        };
        SourceError { line: at.line, column: at.column + 1, message }
    })
}

/// The lexer's error names no cause; the character it stopped at tells it.
fn lex_error(src: &str, e: &proc_macro2::LexError) -> SourceError {
    let at = e.span().start();
    let c = src.lines().nth(at.line.saturating_sub(1)).and_then(|l| l.chars().nth(at.column));
    let message = match c {
        Some(c @ ('(' | '[' | '{')) => format!("this `{c}` is never closed"),
        Some(c @ (')' | ']' | '}')) => format!("this `{c}` closes nothing"),
        Some('"') => "this string is never closed".to_string(),
        Some('/') => "this comment is never closed".to_string(),
        Some(c) => format!("`{c}` is not part of the scene language"),
        None => "the text cannot be read as tokens".to_string(),
    };
    SourceError { line: at.line.max(1), column: at.column + 1, message }
}

/// The formula of canonical fractal text such as `escape_time(|z, c| z + c)` (as the printer writes it): how the
/// `scene!` expansion rebuilds a formula's IR. Text that is not one gives a formula with no maps, whose orbit stays at
/// the point.
pub fn formula_from_source(text: &str) -> crate::ir::formula::Formula {
    let fractal = parse_str(text).ok().and_then(|scene| match &scene.root {
        crate::ir::Node::Fractal(f) => f.formula().cloned(),
        _ => None,
    });
    fractal.unwrap_or(crate::ir::formula::Formula { kind: crate::ir::formula::FormulaKind::EscapeTime, maps: vec![] })
}

/// Parses the tokens of a `scene!` invocation; errors carry the span of the offending token.
pub fn parse_tokens(tokens: proc_macro2::TokenStream) -> Result<Scene, syn::Error> {
    scan::check(&tokens)?;
    let expr: syn::Expr = syn::parse2(tokens)?;
    build::scene(&expr)
}

/// Every function and method of the language with its signature, e.g. `sphere(radius: number) -> shape` and
/// `shape.translate(offset: vec3) -> shape`, followed by the names `t` and `PI`.
pub fn vocabulary() -> Vec<String> {
    let calls = names::functions().chain(names::methods()).map(|e| e.signature());
    calls.chain(["t -> number".to_string(), "PI -> number".to_string()]).collect()
}

//! The parser: scene source (Rust-expression syntax, read by syn) to IR. Shared by `scene!` (tokens with spans) and
//! by `.fractal` files loaded at run time (text; errors carry line:column).

use crate::ir::Scene;

/// An error in scene text, located at `line:column` (both 1-based).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{line}:{column}: {message}")]
pub struct SourceError {
    pub line: usize,
    pub column: usize,
    pub message: String,
}

/// Parses scene text (the contents of a `.fractal` file).
pub fn parse_str(src: &str) -> Result<Scene, SourceError> {
    let _ = src;
    todo!("parser")
}

/// Parses the tokens of a `scene!` invocation; errors carry the span of the offending token.
pub fn parse_tokens(tokens: proc_macro2::TokenStream) -> Result<Scene, syn::Error> {
    let _ = tokens;
    todo!("parser")
}

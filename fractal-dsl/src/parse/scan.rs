//! A pass over the raw tokens before syn sees them: refuses what the scene language never uses (blocks, brackets,
//! statements, keywords, attributes) with a message that says so, and bounds how deeply the input can make syn and
//! the lowering recurse. Inside the parentheses of a formula (`escape_time(..)`, `fold(..)`, `hybrid(..)`) closures,
//! blocks, `let`, `if`/`else`, comparisons and `&&`, `||`, `!` are allowed too; an `if` counts as a parenthesis. Both syn's parser and the drop of its tree recurse once per nesting level, so hostile input
//! (thousands of parentheses or signs) must be refused here, without recursion, before it reaches them.

use proc_macro2::{Delimiter, Spacing, Span, TokenStream, TokenTree};

/// Most tokens a scene may have.
pub const MAX_TOKENS: usize = 500_000;
/// Deepest parentheses may nest.
pub const MAX_PAREN_NESTING: usize = 160;
/// Bound on the nesting a scene can make syn build: a parenthesis counts `PAREN_COST`, an operator 1.
pub const MAX_NESTING_COST: usize = 2048;
const PAREN_COST: usize = 8;
/// Most operators in a row (`a * -b` has two): longer runs of signs only serve to nest.
const MAX_OPERATOR_RUN: usize = 2;

const KEYWORDS: &[&str] = &[
    "as", "async", "await", "break", "const", "continue", "crate", "dyn", "else", "enum", "extern", "false", "fn",
    "for", "if", "impl", "in", "let", "loop", "match", "mod", "move", "mut", "pub", "ref", "return", "self", "Self",
    "static", "struct", "super", "trait", "true", "type", "unsafe", "use", "where", "while", "abstract", "become",
    "do", "final", "macro", "override", "priv", "typeof", "unsized", "virtual", "yield", "try",
];

struct Frame {
    tokens: proc_macro2::token_stream::IntoIter,
    /// Span of the group this frame reads (for errors about the group as a whole).
    span: Span,
    /// Operators in the current comma-separated segment.
    operators: usize,
    /// Largest nesting cost of a group met in the current segment.
    deepest_child: usize,
    /// Largest cost of a finished segment.
    cost: usize,
    /// Operators since the last operand.
    run: usize,
    /// Whether the previous token was a `.` joined to the next one (the first half of `..`), or in a formula any
    /// punctuation joined to the next (`<=`, `&&`, `||`).
    joint_dot: bool,
    /// Inside a formula's parentheses.
    formula: bool,
    /// The previous token names a formula (`escape_time`, `fold`, `hybrid`): its parentheses hold one.
    before_formula: bool,
}

/// The calls whose parentheses hold formulas.
const FORMULA_CALLS: &[&str] = &["escape_time", "fold", "hybrid"];
/// The keywords a formula may use.
const FORMULA_KEYWORDS: &[&str] = &["let", "if", "else"];

impl Frame {
    fn new(stream: TokenStream, span: Span, formula: bool) -> Frame {
        Frame {
            tokens: stream.into_iter(),
            span,
            operators: 0,
            deepest_child: 0,
            cost: 0,
            run: 0,
            joint_dot: false,
            formula,
            before_formula: false,
        }
    }
    fn end_segment(&mut self) {
        self.cost = self.cost.max(self.operators + self.deepest_child);
        self.operators = 0;
        self.deepest_child = 0;
    }
}

fn err(span: Span, message: impl std::fmt::Display) -> syn::Error {
    syn::Error::new(span, message)
}

fn punct_message(c: char) -> String {
    match c {
        '#' => "attributes and doc comments (`///`, `//!`, `/** */`) are not part of the scene language; \
                use `//` comments"
            .into(),
        ';' => "a scene is a single expression: remove the `;`".into(),
        ':' => "paths (`::`) and type annotations are not part of the scene language".into(),
        '=' => "`=` is not part of the scene language: a scene is a single expression, without assignments or \
                comparisons"
            .into(),
        c => format!("`{c}` is not part of the scene language (its operators are + - * / and `..` in param ranges)"),
    }
}

/// Checks the tokens of a scene; see the module doc for what is refused.
pub(crate) fn check(tokens: &TokenStream) -> syn::Result<()> {
    let mut count = 0usize;
    let mut stack = vec![Frame::new(tokens.clone(), Span::call_site(), false)];
    while let Some(frame) = stack.last_mut() {
        let Some(tree) = frame.tokens.next() else {
            let Some(mut done) = stack.pop() else { break };
            done.end_segment();
            if done.cost > MAX_NESTING_COST {
                return Err(err(
                    done.span,
                    "this nests too deeply: too many nested parentheses and operators for the parser to follow",
                ));
            }
            if let Some(parent) = stack.last_mut() {
                parent.deepest_child = parent.deepest_child.max(PAREN_COST + done.cost);
            }
            continue;
        };
        count += 1;
        if count > MAX_TOKENS {
            return Err(err(tree.span(), format!("the scene is too long (more than {MAX_TOKENS} tokens)")));
        }
        let joint_dot = std::mem::take(&mut frame.joint_dot);
        let before_formula = std::mem::take(&mut frame.before_formula);
        match tree {
            TokenTree::Group(g) => {
                frame.run = 0;
                let formula = frame.formula || (before_formula && g.delimiter() == Delimiter::Parenthesis);
                match g.delimiter() {
                    Delimiter::Parenthesis | Delimiter::None => {}
                    Delimiter::Brace if formula => {}
                    Delimiter::Bracket => {
                        return Err(err(
                            g.span_open(),
                            "`[` is not part of the scene language: write vectors as vec3(x, y, z)",
                        ))
                    }
                    Delimiter::Brace => {
                        return Err(err(
                            g.span_open(),
                            "`{` is not part of the scene language: a scene is a single expression",
                        ))
                    }
                }
                if stack.len() > MAX_PAREN_NESTING {
                    return Err(err(
                        g.span_open(),
                        format!("parentheses nest more than {MAX_PAREN_NESTING} levels deep"),
                    ));
                }
                stack.push(Frame::new(g.stream(), g.span(), formula));
            }
            TokenTree::Ident(i) => {
                frame.run = 0;
                let name = i.to_string();
                if name == "box" {
                    return Err(err(
                        i.span(),
                        "`box` is a Rust keyword: the box primitive is `box3(half_extents)`, \
                         e.g. box3(vec3(1.0, 1.0, 1.0))",
                    ));
                }
                frame.before_formula = FORMULA_CALLS.contains(&name.as_str());
                if frame.formula && FORMULA_KEYWORDS.contains(&name.as_str()) {
                    // An `if` nests its branches as a parenthesis does (an `else if` chain nests deeper each time).
                    if name == "if" {
                        frame.operators += PAREN_COST;
                    }
                    continue;
                }
                if KEYWORDS.contains(&name.as_str()) {
                    return Err(err(
                        i.span(),
                        format!("`{name}` is a Rust keyword and not part of the scene language"),
                    ));
                }
            }
            TokenTree::Literal(_) => frame.run = 0,
            TokenTree::Punct(p) => {
                let c = p.as_char();
                let formula_punct = frame.formula && matches!(c, '|' | ';' | '=' | '<' | '>' | '!' | '&');
                if !matches!(c, '+' | '-' | '*' | '/' | '.' | ',') && !formula_punct {
                    return Err(err(p.span(), punct_message(c)));
                }
                if c == ',' || (c == ';' && frame.formula) {
                    frame.end_segment();
                    frame.run = 0;
                    continue;
                }
                // The second dot of `..` continues the operator the first one began (in a formula, the second half of
                // any joined pair: `<=`, `&&`).
                if !((c == '.' || frame.formula) && joint_dot) {
                    frame.operators += 1;
                    frame.run += 1;
                    if frame.run > MAX_OPERATOR_RUN {
                        return Err(err(
                            p.span(),
                            "too many operators in a row: use parentheses, e.g. `a * -b` or `-(-a)`",
                        ));
                    }
                }
                frame.joint_dot = (c == '.' || frame.formula) && p.spacing() == Spacing::Joint && !joint_dot;
            }
        }
    }
    Ok(())
}

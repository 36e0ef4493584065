//! User text quoted back in a message: control characters escaped, so a NUL byte or an escape sequence never
//! reaches the terminal raw, and each quotation (text between backticks) cut at [`MAX_QUOTED`] characters, so a
//! 1 MB identifier costs one line. Every message that can hold user text passes through [`tidy`] before it is shown.

/// Longest quotation kept whole, in characters.
pub const MAX_QUOTED: usize = 64;

/// `message` with control characters (other than line breaks) escaped and long quotations cut with `…`.
pub fn tidy(message: &str) -> String {
    let mut out = String::with_capacity(message.len().min(1 << 12));
    let mut quoted = false;
    let mut run = 0usize;
    for c in message.chars() {
        if c == '`' {
            quoted = !quoted;
            run = 0;
            out.push(c);
            continue;
        }
        if quoted {
            run += 1;
            if run == MAX_QUOTED + 1 {
                out.push('…');
            }
            if run > MAX_QUOTED {
                continue;
            }
        }
        if c.is_control() && c != '\n' {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn control_characters_are_escaped_and_quotations_cut() {
        assert_eq!(tidy("unknown name `a\0b`"), "unknown name `a\\u{0}b`");
        assert_eq!(tidy("line one\nline two\t!"), "line one\nline two\\t!");
        let long = format!("unknown function `{}`; did you mean `sphere`?", "x".repeat(1 << 20));
        assert_eq!(tidy(&long), format!("unknown function `{}…`; did you mean `sphere`?", "x".repeat(MAX_QUOTED)));
    }
}

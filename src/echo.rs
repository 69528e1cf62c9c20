//! Echoing user input in messages: every error is **one printable line**.
//!
//! Input reaches messages in many places (a cost's text, a path, a format tag, a learning
//! rate). This module is the one place that makes such text safe to print: control characters
//! (newlines, tabs, `ESC` of ANSI escape sequences, `DEL`, the C1 controls) and the Unicode
//! direction overrides become visible escapes (`\n`, `\x1b`, `\u{202e}`), and long text is
//! shortened with "…". [`echo`] is for a piece of input inside a message (at most
//! [`MAX_ECHO`] characters); [`one_line`] is applied by the command line to every error
//! message as a whole (at most [`MAX_LINE`] characters).

/// The most characters of one echoed piece of input.
pub const MAX_ECHO: usize = 80;

/// The most characters of a whole error line (without the `error: ` prefix).
pub const MAX_LINE: usize = 300;

/// Whether `c` must not reach a terminal raw: a control character or a bidirectional
/// formatting character (which reorders what the terminal shows).
fn hidden(c: char) -> bool {
    c.is_control()
        || matches!(c, '\u{200b}'..='\u{200f}' | '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}' | '\u{feff}')
}

/// The visible escape of one character.
fn escaped(c: char) -> String {
    match c {
        '\n' => "\\n".into(),
        '\r' => "\\r".into(),
        '\t' => "\\t".into(),
        c if (c as u32) < 0x100 && hidden(c) => format!("\\x{:02x}", c as u32),
        c if hidden(c) => format!("\\u{{{:x}}}", c as u32),
        c => c.to_string(),
    }
}

/// `text` with every control and direction-formatting character escaped, shortened to at most
/// `max` characters (counted after escaping, the "…" included). An escape is never cut.
///
/// ```
/// use truecost::echo::escape;
/// assert_eq!(escape("a\nb\x1b[31m", 100), "a\\nb\\x1b[31m");
/// assert_eq!(escape("abcdef", 4), "abc…");
/// assert_eq!(escape("abc", 3), "abc");
/// ```
pub fn escape(text: &str, max: usize) -> String {
    let max = max.max(1);
    let total: usize = text.chars().map(|c| escaped(c).chars().count()).sum();
    if total <= max {
        return text.chars().map(escaped).collect();
    }
    let mut out = String::new();
    let mut len = 0;
    for piece in text.chars().map(escaped) {
        let n = piece.chars().count();
        if len + n > max - 1 {
            break;
        }
        out.push_str(&piece);
        len += n;
    }
    out.push('…');
    out
}

/// A piece of input as it may appear inside a message: escaped, at most [`MAX_ECHO`]
/// characters.
///
/// ```
/// let long = "7".repeat(5000);
/// let e = truecost::echo::echo(&long);
/// assert_eq!(e.chars().count(), truecost::echo::MAX_ECHO);
/// assert!(e.ends_with('…'));
/// ```
pub fn echo(text: &str) -> String {
    escape(text, MAX_ECHO)
}

/// Input as it may appear in a report on stdout (a file path, an `--env` text naming a map
/// file): every control and direction character escaped, nothing shortened. One line, so it
/// cannot break out of a LaTeX comment or a Markdown heading, nor move the terminal's cursor.
///
/// ```
/// assert_eq!(truecost::echo::printable("m\n\\input{x}\u{1b}[2J"), "m\\n\\input{x}\\x1b[2J");
/// ```
pub fn printable(text: &str) -> String {
    text.chars().map(escaped).collect()
}

/// A whole message as one printable line of at most [`MAX_LINE`] characters.
///
/// ```
/// let line = truecost::echo::one_line("bad\ninput \u{1b}[2J");
/// assert_eq!(line, "bad\\ninput \\x1b[2J");
/// assert!(truecost::echo::one_line(&"x".repeat(10_000)).chars().count() <= 300);
/// ```
pub fn one_line(message: &str) -> String {
    escape(message, MAX_LINE)
}

/// The LaTeX text-mode form of one of LaTeX's ten special characters (`None` for any other
/// character): the one escape the LaTeX renderings of `verify` and `reproduce` share, applied a
/// character at a time so that no escape is escaped again.
///
/// ```
/// use truecost::echo::tex_special;
/// assert_eq!(tex_special('\\'), Some(r"\textbackslash{}"));
/// assert_eq!(tex_special('{'), Some(r"\{"));
/// assert_eq!(tex_special('^'), Some(r"\^{}"));
/// assert_eq!(tex_special('a'), None);
/// ```
pub fn tex_special(c: char) -> Option<&'static str> {
    Some(match c {
        '\\' => r"\textbackslash{}",
        '&' => r"\&",
        '%' => r"\%",
        '_' => r"\_",
        '#' => r"\#",
        '{' => r"\{",
        '}' => r"\}",
        '$' => r"\$",
        '^' => r"\^{}",
        '~' => r"\~{}",
        _ => return None,
    })
}

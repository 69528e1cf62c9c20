//! Source scanning shared by the tests that read Rust sources as text
//! (`array_comparisons.rs`, `feasibility.rs`): comments and literals blanked, unit-test modules
//! dropped, functions split out. A text scan, not a parser.
#![allow(dead_code)]

/// `text` with comments, string and char literals replaced by spaces (same length, same lines).
pub fn blank(text: &str) -> String {
    let b: Vec<char> = text.chars().collect();
    let mut out = b.clone();
    let mut i = 0;
    let wipe = |out: &mut Vec<char>, from: usize, to: usize| {
        for c in out.iter_mut().take(to).skip(from) {
            if *c != '\n' {
                *c = ' ';
            }
        }
    };
    while i < b.len() {
        if b[i] == '/' && b.get(i + 1) == Some(&'/') {
            let end = (i..b.len()).find(|&j| b[j] == '\n').unwrap_or(b.len());
            wipe(&mut out, i, end);
            i = end;
        } else if b[i] == '/' && b.get(i + 1) == Some(&'*') {
            let (mut depth, mut j) = (1, i + 2);
            while j < b.len() && depth > 0 {
                if b[j] == '/' && b.get(j + 1) == Some(&'*') {
                    depth += 1;
                    j += 1;
                } else if b[j] == '*' && b.get(j + 1) == Some(&'/') {
                    depth -= 1;
                    j += 1;
                }
                j += 1;
            }
            wipe(&mut out, i, j);
            i = j;
        } else if b[i] == 'r' && (b.get(i + 1) == Some(&'"') || b.get(i + 1) == Some(&'#')) {
            let hashes = (i + 1..b.len()).take_while(|&j| b[j] == '#').count();
            if b.get(i + 1 + hashes) != Some(&'"') {
                i += 1;
                continue;
            }
            let mut j = i + 2 + hashes;
            while j < b.len() {
                if b[j] == '"' && (j + 1..j + 1 + hashes).all(|k| b.get(k) == Some(&'#')) {
                    break;
                }
                j += 1;
            }
            wipe(&mut out, i + 1, j + 1 + hashes);
            i = j + 1 + hashes;
        } else if b[i] == '"' {
            let mut j = i + 1;
            while j < b.len() && b[j] != '"' {
                j += if b[j] == '\\' { 2 } else { 1 };
            }
            wipe(&mut out, i + 1, j);
            i = j + 1;
        } else if b[i] == '\'' {
            // A char literal ('x', '\n', '\u{..}'), or a lifetime ('a, 'static): left alone.
            if b.get(i + 1) == Some(&'\\') {
                let end = (i + 2..b.len()).find(|&j| b[j] == '\'').unwrap_or(b.len());
                wipe(&mut out, i + 1, end);
                i = end + 1;
            } else if b.get(i + 2) == Some(&'\'') {
                wipe(&mut out, i + 1, i + 2);
                i += 3;
            } else {
                i += 1;
            }
        } else {
            i += 1;
        }
    }
    out.into_iter().collect()
}

/// The position just after the bracket group that opens at `open` (`(`, `[` or `{`).
pub fn close_of(b: &[char], open: usize) -> usize {
    let mut depth = 0i32;
    for (j, &c) in b.iter().enumerate().skip(open) {
        match c {
            '(' | '[' | '{' => depth += 1,
            ')' | ']' | '}' => {
                depth -= 1;
                if depth == 0 {
                    return j + 1;
                }
            }
            _ => {}
        }
    }
    b.len()
}

/// The `{` that opens the body of the item whose signature starts at `from`: the first `{` at
/// bracket depth 0 after its parameter list (`None` when a `;` comes first: a declaration).
pub fn body_open(b: &[char], from: usize) -> Option<usize> {
    let mut depth = 0i32;
    for j in from..b.len() {
        match b[j] {
            '(' | '[' | '<' => depth += 1,
            ')' | ']' => depth -= 1,
            '>' if b[j - 1] != '-' => depth -= 1,
            '{' if depth <= 0 => return Some(j),
            ';' if depth <= 0 => return None,
            _ => {}
        }
    }
    None
}

pub fn is_ident(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

/// Removes the code under `#[cfg(test)]`-like attributes that gate a `mod` (unit tests are not
/// reached by harnesses).
pub fn drop_test_modules(text: &str) -> String {
    let b: Vec<char> = text.chars().collect();
    let mut out = b.clone();
    let s: String = b.iter().collect();
    let mut from = 0;
    while let Some(k) = s[from..].find("#[cfg(").map(|k| k + from) {
        let attr_end = close_of(&b, k + 1);
        let attr: String = b[k..attr_end].iter().collect();
        from = attr_end;
        let rest: String = b[attr_end..].iter().collect();
        let trimmed = rest.trim_start();
        let item = trimmed
            .trim_start_matches("pub(crate) ")
            .trim_start_matches("pub ");
        if attr.contains("test") && item.starts_with("mod ") {
            let offset = attr_end + (rest.len() - trimmed.len());
            if let Some(brace) = (offset..b.len()).find(|&j| b[j] == '{' || b[j] == ';') {
                let end = if b[brace] == '{' {
                    close_of(&b, brace)
                } else {
                    brace + 1
                };
                for c in out.iter_mut().take(end).skip(k) {
                    if *c != '\n' {
                        *c = ' ';
                    }
                }
                from = end;
            }
        }
    }
    out.into_iter().collect()
}

/// Every function with a body: `(name, signature, body)` (the body includes its braces).
pub fn functions(code: &str) -> Vec<(String, String, String)> {
    let b: Vec<char> = code.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i + 3 < b.len() {
        let starts =
            b[i] == 'f' && b[i + 1] == 'n' && b[i + 2] == ' ' && (i == 0 || !is_ident(b[i - 1]));
        if !starts {
            i += 1;
            continue;
        }
        let name: String = b[i + 3..].iter().take_while(|&&c| is_ident(c)).collect();
        // A declaration without a body is passed over.
        match body_open(&b, i + 3) {
            Some(open) => {
                let end = close_of(&b, open);
                out.push((
                    name,
                    b[i..open].iter().collect(),
                    b[open..end].iter().collect(),
                ));
                // Nested functions are scanned as part of this body.
                i = end;
            }
            None => i += 3,
        }
    }
    out
}

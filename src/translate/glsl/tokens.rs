//! Tokens of preprocessed GLSL: identifiers, numbers, punctuation, and the whitespace between
//! them (kept, so a rewrite keeps the program's line structure).

/// What a token is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A name: keyword, type, function, variable.
    Ident,
    /// A number literal.
    Number,
    /// Operators and punctuation (`+=`, `(`, `;`, ...), one or more characters.
    Punct,
    /// Spaces, tabs and newlines.
    Space,
    /// A preprocessor line left in preprocessed source (`#version`, `#extension`, `#line`,
    /// `#pragma`), up to its end of line.
    Directive,
}

/// One token and its text.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Token {
    /// What it is.
    pub kind: Kind,
    /// Its text.
    pub text: String,
}

impl Token {
    /// Whether this is the punctuation `p`.
    pub fn is(&self, p: &str) -> bool {
        self.kind != Kind::Space && self.text == p
    }
}

/// Operators of more than one character, longest first.
const LONG_PUNCT: &[&str] = &[
    "<<=", ">>=", "++", "--", "<<", ">>", "<=", ">=", "==", "!=", "&&", "||", "^^", "+=", "-=", "*=", "/=", "%=",
    "&=", "|=", "^=",
];

/// Splits preprocessed source into tokens (comments are already gone).
pub fn tokenize(source: &str) -> Vec<Token> {
    let chars: Vec<char> = source.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    let mut line_start = true;
    while i < chars.len() {
        let c = chars[i];
        let start = i;
        let kind = if c.is_whitespace() {
            while i < chars.len() && chars[i].is_whitespace() {
                if chars[i] == '\n' {
                    line_start = true;
                }
                i += 1;
            }
            out.push(Token { kind: Kind::Space, text: chars[start..i].iter().collect() });
            continue;
        } else if c == '#' && line_start {
            while i < chars.len() && chars[i] != '\n' {
                i += 1;
            }
            Kind::Directive
        } else if c.is_ascii_alphabetic() || c == '_' {
            while i < chars.len() && (chars[i].is_ascii_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            Kind::Ident
        } else if c.is_ascii_digit() || (c == '.' && chars.get(i + 1).is_some_and(|d| d.is_ascii_digit())) {
            i = number_end(&chars, i);
            Kind::Number
        } else {
            let rest: String = chars[i..(i + 3).min(chars.len())].iter().collect();
            let len = LONG_PUNCT.iter().find(|p| rest.starts_with(*p)).map_or(1, |p| p.len());
            i += len;
            Kind::Punct
        };
        line_start = false;
        out.push(Token { kind, text: chars[start..i].iter().collect() });
    }
    out
}

/// The end of the number literal starting at `i`: digits, a fraction, an exponent, hex digits
/// and the suffixes `u`, `f`, `F`.
fn number_end(chars: &[char], mut i: usize) -> usize {
    if chars[i] == '0' && matches!(chars.get(i + 1), Some('x' | 'X')) {
        i += 2;
        while i < chars.len() && chars[i].is_ascii_hexdigit() {
            i += 1;
        }
    } else {
        while i < chars.len() && (chars[i].is_ascii_digit() || chars[i] == '.') {
            i += 1;
        }
        if matches!(chars.get(i), Some('e' | 'E')) {
            i += 1;
            if matches!(chars.get(i), Some('+' | '-')) {
                i += 1;
            }
            while i < chars.len() && chars[i].is_ascii_digit() {
                i += 1;
            }
        }
    }
    while matches!(chars.get(i), Some('u' | 'U' | 'f' | 'F')) {
        i += 1;
    }
    i
}

/// The tokens' text joined back together.
pub fn join(tokens: &[Token]) -> String {
    tokens.iter().map(|t| t.text.as_str()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn splits_and_joins_back() {
        let src = "#version 110\nuniform vec4 a[2];\nvoid main(){ x+=1.5e-3*a[1].xy; b <<= 2; }\n";
        let tokens = tokenize(src);
        assert_eq!(join(&tokens), src);
        let texts: Vec<_> = tokens.iter().filter(|t| t.kind != Kind::Space).map(|t| t.text.as_str()).collect();
        assert_eq!(texts[0], "#version 110");
        assert!(texts.contains(&"+="));
        assert!(texts.contains(&"1.5e-3"));
        assert!(texts.contains(&"<<="));
        assert_eq!(tokens.iter().filter(|t| t.kind == Kind::Directive).count(), 1);
    }
}

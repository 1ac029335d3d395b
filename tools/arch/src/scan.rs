//! Paths inside macro invocations: token sequences `a :: b :: c` that syn does not parse.

use proc_macro2::{Spacing, TokenStream, TokenTree};

/// Every path of two or more segments written in `tokens` (recursing into groups).
///
/// `$crate` counts as a first segment; other `$name` metavariables and paths starting with
/// `::` (other crates) are skipped.
pub(crate) fn token_paths(tokens: TokenStream) -> Vec<Vec<String>> {
    let mut paths = Vec::new();
    collect(tokens, &mut paths);
    paths
}

/// Whether `tokens[i..]` starts with `::`.
fn is_path_sep(tokens: &[TokenTree], i: usize) -> bool {
    matches!(
        (tokens.get(i), tokens.get(i + 1)),
        (Some(TokenTree::Punct(a)), Some(TokenTree::Punct(b)))
            if a.as_char() == ':' && a.spacing() == Spacing::Joint && b.as_char() == ':'
    )
}

/// Adds the paths of one token stream to `paths`.
fn collect(tokens: TokenStream, paths: &mut Vec<Vec<String>>) {
    let tokens: Vec<TokenTree> = tokens.into_iter().collect();
    let mut i = 0;
    while i < tokens.len() {
        let (first, global) = match &tokens[i] {
            TokenTree::Group(g) => {
                collect(g.stream(), paths);
                i += 1;
                continue;
            }
            TokenTree::Punct(p) if p.as_char() == '$' => match tokens.get(i + 1) {
                Some(TokenTree::Ident(id)) if id == "crate" => {
                    i += 1;
                    ("$crate".to_string(), false)
                }
                Some(TokenTree::Ident(_)) => {
                    i += 2;
                    continue;
                }
                _ => {
                    i += 1;
                    continue;
                }
            },
            TokenTree::Punct(_) if is_path_sep(&tokens, i) => match tokens.get(i + 2) {
                Some(TokenTree::Ident(id)) => {
                    i += 2;
                    (id.to_string(), true)
                }
                _ => {
                    i += 2;
                    continue;
                }
            },
            TokenTree::Ident(id) => (id.to_string(), false),
            _ => {
                i += 1;
                continue;
            }
        };
        let mut segs = vec![first];
        let mut j = i + 1;
        while is_path_sep(&tokens, j) {
            match tokens.get(j + 2) {
                Some(TokenTree::Ident(id)) => {
                    segs.push(id.to_string());
                    j += 3;
                }
                _ => break,
            }
        }
        if !global && segs.len() >= 2 {
            paths.push(segs);
        }
        i = j;
    }
}

#[cfg(test)]
mod tests {
    use super::token_paths;

    /// The paths found in `src`, each joined with `::`.
    fn paths(src: &str) -> Vec<String> {
        let tokens: proc_macro2::TokenStream = src.parse().expect("valid tokens");
        token_paths(tokens).iter().map(|p| p.join("::")).collect()
    }

    #[test]
    fn finds_paths_in_groups_and_skips_other_crates_and_metavariables() {
        assert_eq!(paths(r#""{}", crate::a::X, (super::b(y))"#), ["crate::a::X", "super::b"]);
        assert_eq!(paths("::std::mem::take(x), $crate::guard(), $name::f, single"), ["$crate::guard"]);
        assert_eq!(paths("Vec::<u8>::new(), a :: b"), ["a::b"]);
    }
}

//! Every `stratad` command line the README shows parses as written, in every variant it
//! describes (each `[optional part]` left out and put in, each `a|b` alternative), with sample
//! values for its placeholders.

use clap::Parser;

use super::Cli;

/// A sample value for a placeholder the README writes in capitals.
fn fill(word: &str) -> &str {
    match word {
        "SURFACE" | "ID" => "7",
        "X" | "Y" | "W" | "H" => "10",
        "NAME" => "ic",
        "FILE.json" => "/tmp/strata-test.json",
        "Z" | "A" => "0.5",
        "S" => "16",
        "PATH" => "/tmp/strata-test.sock",
        "FILE.png" => "/tmp/strata-test.png",
        "OUTPUT" => "headless",
        "X,Y,Z" => "0,0,1",
        "R,G,B" => "1,1,1",
        other => other,
    }
}

/// Every variant of the words `words`, as argument lists.
fn variants(words: &[&str]) -> Vec<Vec<String>> {
    let Some((&first, rest)) = words.split_first() else { return vec![Vec::new()] };
    let (heads, rest): (Vec<Vec<String>>, &[&str]) = if let Some(open) = first.strip_prefix('[') {
        // An optional group, up to the word that closes it.
        let end = words.iter().position(|w| w.ends_with(']')).unwrap_or(words.len() - 1);
        let mut inner: Vec<&str> = words[..=end].to_vec();
        inner[0] = open;
        let last = inner.len() - 1;
        inner[last] = inner[last].strip_suffix(']').unwrap_or(inner[last]);
        let mut heads = vec![Vec::new()];
        heads.extend(variants(&inner));
        (heads, &words[end + 1..])
    } else {
        (first.split('|').map(|w| vec![fill(w).to_string()]).collect(), rest)
    };
    let tails = variants(rest);
    heads.iter().flat_map(|h| tails.iter().map(move |t| [h.clone(), t.clone()].concat())).collect()
}

#[test]
fn every_command_line_the_readme_shows_parses() {
    let readme = include_str!("../../README.md");
    let mut tried = 0;
    for line in readme.lines().filter(|l| l.starts_with("stratad ")) {
        let command = line.split(" #").next().unwrap_or(line).trim().trim_end_matches('&').trim();
        let words: Vec<&str> = command.split_whitespace().collect();
        for args in variants(&words) {
            if let Err(e) = Cli::try_parse_from(&args) {
                panic!("README line {line:?} as {args:?} does not parse:\n{e}");
            }
            tried += 1;
        }
    }
    assert!(tried >= 20, "only {tried} command lines found in the README");
}

#[test]
fn ctl_options_go_before_or_after_the_command() {
    for args in [
        &["stratad", "ctl", "list", "--json"][..],
        &["stratad", "ctl", "--json", "list"],
        &["stratad", "ctl", "list", "--socket", "/tmp/s"],
    ] {
        assert!(Cli::try_parse_from(args).is_ok(), "{args:?}");
    }
}

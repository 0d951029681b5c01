//! Arguments clap would misread, named as typed with what was probably meant, before clap sees
//! them: a long flag spelled with one dash (`-ids`, which clap reads as `-i ds`), a misspelt
//! one-dash flag (`-szie`, which clap reports as `-s`), a scene path without `-i`
//! (`lanecast good.sc`, which clap takes for a subcommand), and a render flag given to
//! `compare` or compare's flag to the render command (which clap calls unexpected, without
//! saying why), and `--method`, which went to the accuracy lab.
//!
//! The arguments are walked as clap walks them, from clap's own `Command` (which flags exist,
//! which take a value), so that a value is never read as a flag: `--eye -1,2,3`, `-o -`.

use super::SINGLE_DASH;
use crate::error::{Error, Result};
use clap::{Arg, Command};
use std::ffi::OsString;
use std::path::Path;

/// Refuses the first argument of `args` (translated: [`super::translate`], program name first)
/// that clap would misread, with a message naming it as typed and what it probably meant.
/// Arguments clap reads as meant are left to clap.
pub(super) fn check(args: &[OsString], top: &Command) -> Result<()> {
    let mut cmd = top;
    let mut in_compare = false;
    let mut input_given = false;
    let mut tokens = args.iter().skip(1);
    while let Some(tok) = tokens.next() {
        let Some(tok) = tok.to_str() else { continue };
        if tok == "--" {
            break;
        }
        if let Some(long) = tok.strip_prefix("--") {
            let (name, inline) = split_value(long);
            match find_long(cmd, name) {
                Some(arg) => {
                    input_given |= arg.get_id() == "input";
                    if takes_value(arg) && !inline {
                        tokens.next();
                    }
                }
                None if in_compare && find_long(top, name).is_some() => {
                    return Err(render_only(tok, name));
                }
                None if !in_compare
                    && top
                        .find_subcommand("compare")
                        .is_some_and(|c| find_long(c, name).is_some()) =>
                {
                    return Err(Error::usage(format!(
                        "{tok}: applies to compare only (lanecast compare -i SCENE {tok} ...)"
                    )));
                }
                None if name == "method" => return Err(lab_only(tok)),
                None => {}
            }
            continue;
        }
        if let Some(body) = tok.strip_prefix('-')
            && !body.is_empty()
        {
            if tok.parse::<f64>().is_ok() {
                continue; // a stray negative number: clap says where it does not belong
            }
            let (name, inline) = split_value(body);
            let mut chars = name.chars();
            let first = chars.next().expect("not empty");
            let short = cmd.get_arguments().find(|a| a.get_short() == Some(first));
            if chars.next().is_none() {
                if let Some(arg) = short {
                    input_given |= arg.get_id() == "input";
                    if takes_value(arg) && !inline {
                        tokens.next();
                    }
                }
                continue;
            }
            if let Some(arg) = find_long(cmd, name).or_else(|| find_long(top, name)) {
                return Err(one_dash(tok, arg));
            }
            if let Some(arg) = short
                && takes_value(arg)
            {
                input_given |= arg.get_id() == "input";
                continue; // `-iscene.sc`: the value attached to its short flag
            }
            return Err(match closest(cmd, name) {
                Some(meant) => Error::usage(format!(
                    "{tok}: no such flag; did you mean {meant}? (lanecast --help lists them)"
                )),
                None => Error::usage(format!("{tok}: no such flag (lanecast --help lists them)")),
            });
        }
        // a word: the subcommand, or a stray argument
        if !in_compare && !input_given && tok == "compare" {
            if let Some(sub) = top.find_subcommand("compare") {
                cmd = sub;
                in_compare = true;
            }
            continue;
        }
        if !input_given && looks_like_scene(tok) {
            let command = if in_compare {
                "lanecast compare"
            } else {
                "lanecast"
            };
            return Err(Error::usage(format!(
                "{tok}: the scene is given with -i: {command} -i {tok}"
            )));
        }
    }
    Ok(())
}

/// `name=value` as `(name, true)`, `name` as `(name, false)`.
fn split_value(s: &str) -> (&str, bool) {
    match s.split_once('=') {
        Some((name, _)) => (name, true),
        None => (s, false),
    }
}

fn find_long<'a>(cmd: &'a Command, name: &str) -> Option<&'a Arg> {
    cmd.get_arguments().find(|a| a.get_long() == Some(name))
}

fn takes_value(arg: &Arg) -> bool {
    arg.get_action().takes_values()
}

/// A long flag typed with one dash (`-ids`): its two-dash form.
fn one_dash(typed: &str, arg: &Arg) -> Error {
    let long = arg.get_long().expect("found by its long name");
    let originals: Vec<&str> = SINGLE_DASH.iter().map(|(short, _)| *short).collect();
    Error::usage(format!(
        "{typed}: long flags take two dashes: --{long} (one dash works only for the original's \
         {})",
        originals.join(", ")
    ))
}

/// `--method`, which moved to the accuracy lab: where it went.
fn lab_only(typed: &str) -> Error {
    Error::usage(format!(
        "{typed}: intersection methods are the accuracy lab's, not lanecast's: cargo run -p \
         lanecast-lab --release --bin lab-render -- -i SCENE --method M"
    ))
}

/// A render flag given to `compare`, with the reason it does not apply.
fn render_only(typed: &str, name: &str) -> Error {
    let why = match name {
        "kernel" => {
            "compare always renders with both kernels, the simd packet kernel against the \
             scalar f64 oracle, so it takes no --kernel"
        }
        "views" | "orbit" | "skip-existing" => {
            "compare checks one view, the scene's camera (with --eye, --look, --up)"
        }
        "repeat" | "time" | "stats" => "compare reports its own counts, not timings",
        _ => {
            "compare writes only a diff image (-o DIFF.png) and its report; images, colours, \
             ids and depths are the render command's"
        }
    };
    Error::usage(format!(
        "{typed}: applies to the render command (lanecast -i SCENE ...), not to compare: {why}"
    ))
}

/// The flag nearest to a misspelt one-dash `name` (`szie`), as it would be typed: the
/// original's one-dash form where there is one (`-size`), else the long form (`--seed`).
/// `None` when nothing is near.
fn closest(cmd: &Command, name: &str) -> Option<String> {
    let longs = cmd
        .get_arguments()
        .filter_map(|a| a.get_long())
        .map(|l| (l.to_string(), format!("--{l}")));
    let originals = SINGLE_DASH
        .iter()
        .map(|(short, _)| (short[1..].to_string(), short.to_string()));
    let limit = if name.chars().count() <= 4 { 1 } else { 2 };
    originals
        .chain(longs)
        .map(|(bare, typed)| (distance(name, &bare), typed))
        .filter(|(d, _)| *d <= limit)
        .min_by_key(|(d, _)| *d)
        .map(|(_, typed)| typed)
}

/// Edit distance with adjacent transpositions (optimal string alignment), in characters.
fn distance(a: &str, b: &str) -> usize {
    let (a, b): (Vec<char>, Vec<char>) = (a.chars().collect(), b.chars().collect());
    let mut d = vec![vec![0; b.len() + 1]; a.len() + 1];
    for (i, row) in d.iter_mut().enumerate() {
        row[0] = i;
    }
    for (j, cell) in d[0].iter_mut().enumerate() {
        *cell = j;
    }
    for i in 1..=a.len() {
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            d[i][j] = (d[i - 1][j] + 1)
                .min(d[i][j - 1] + 1)
                .min(d[i - 1][j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                d[i][j] = d[i][j].min(d[i - 2][j - 2] + 1);
            }
        }
    }
    d[a.len()][b.len()]
}

/// Whether a stray word is a scene given without `-i`: a scene or mesh extension, or a file
/// that exists.
fn looks_like_scene(word: &str) -> bool {
    let path = Path::new(word);
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    matches!(ext.as_deref(), Some("sc" | "obj" | "ply")) || path.is_file()
}

#[cfg(test)]
mod tests {
    use super::distance;

    #[test]
    fn distance_counts_a_swap_as_one() {
        assert_eq!(distance("szie", "size"), 1);
        assert_eq!(distance("seed", "seed"), 0);
        assert_eq!(distance("thread", "threads"), 1);
        assert_eq!(distance("", "fov"), 3);
    }
}

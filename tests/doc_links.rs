//! The documents hold together: every relative link in README.md,
//! ARCHITECTURE.md, CHANGELOG.md and docs/*.md names a file that exists
//! (and, for a `#fragment` into a markdown file, a heading it has); every
//! picture in docs/images/ is shown by some document; README.md is a
//! guide of at most 200 lines whose test command is the last line of
//! `.ci/run`; and no document but CHANGELOG.md and the generated benchmark
//! report carries a date or a load average (history lives in git).
//!
//! # How it works
//!
//! Links are read as markdown writes them, `[text](target)`, outside
//! fenced code blocks; targets with a scheme (`https:`) are skipped. A
//! heading's anchor is GitHub's: lower case, punctuation other than `-`
//! and `_` dropped, spaces turned into `-`.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// README.md, ARCHITECTURE.md, CHANGELOG.md and every docs/*.md.
fn documents() -> Vec<PathBuf> {
    let root = root();
    let mut docs: Vec<PathBuf> = ["README.md", "ARCHITECTURE.md", "CHANGELOG.md"]
        .iter()
        .map(|name| root.join(name))
        .collect();
    let mut pages: Vec<PathBuf> = std::fs::read_dir(root.join("docs"))
        .expect("docs/ is readable")
        .map(|entry| entry.expect("a docs/ entry").path())
        .filter(|path| path.extension().is_some_and(|ext| ext == "md"))
        .collect();
    pages.sort();
    docs.extend(pages);
    docs
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// `text` without its fenced code blocks.
fn prose(text: &str) -> String {
    let mut out = String::new();
    let mut fenced = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if !fenced {
            out.push_str(line);
            out.push('\n');
        }
    }
    out
}

/// Every `[text](target)` target in `text`.
fn link_targets(text: &str) -> Vec<String> {
    let mut targets = Vec::new();
    let mut rest = text;
    while let Some(at) = rest.find("](") {
        let after = &rest[at + 2..];
        match after.find(')') {
            Some(end) => {
                let target = &after[..end];
                if !target.is_empty() && !target.contains(char::is_whitespace) {
                    targets.push(target.to_owned());
                }
                rest = &after[end..];
            }
            None => break,
        }
    }
    targets
}

/// GitHub's anchors of `text`'s headings.
fn anchors(text: &str) -> BTreeSet<String> {
    prose(text)
        .lines()
        .filter_map(|line| {
            let title = line.trim_start_matches('#');
            (title.len() < line.len() && title.starts_with(' ')).then(|| {
                title
                    .trim()
                    .to_lowercase()
                    .chars()
                    .filter(|c| c.is_alphanumeric() || matches!(c, '-' | '_' | ' '))
                    .map(|c| if c == ' ' { '-' } else { c })
                    .collect()
            })
        })
        .collect()
}

#[test]
fn every_relative_link_names_a_file_and_a_heading_that_exist() {
    let mut broken = Vec::new();
    for doc in documents() {
        let text = read(&doc);
        let folder = doc.parent().expect("a document's folder");
        for target in link_targets(&prose(&text)) {
            if target.contains(':') {
                continue;
            }
            let (path, fragment) = target.split_once('#').unwrap_or((&target, ""));
            let file = if path.is_empty() {
                doc.clone()
            } else {
                folder.join(path)
            };
            if !file.exists() {
                broken.push(format!("{}: {target} (no such file)", doc.display()));
            } else if !fragment.is_empty()
                && file.extension().is_some_and(|ext| ext == "md")
                && !anchors(&read(&file)).contains(fragment)
            {
                broken.push(format!("{}: {target} (no such heading)", doc.display()));
            }
        }
    }
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
}

#[test]
fn every_picture_in_docs_images_is_shown_by_a_document() {
    let all: String = documents().iter().map(|doc| read(doc)).collect();
    let mut unused = Vec::new();
    for entry in std::fs::read_dir(root().join("docs/images")).expect("docs/images") {
        let path = entry.expect("an entry").path();
        if path.is_file() {
            let name = path
                .file_name()
                .expect("a name")
                .to_string_lossy()
                .into_owned();
            if !all.contains(&format!("images/{name}")) {
                unused.push(name);
            }
        }
    }
    assert!(unused.is_empty(), "pictures no document shows: {unused:?}");
}

#[test]
fn the_readme_is_a_short_guide_whose_test_command_is_cis() {
    let readme = read(&root().join("README.md"));
    let lines = readme.lines().count();
    assert!(lines <= 200, "README.md has {lines} lines");
    let ci = read(&root().join(".ci/run"));
    let last = ci
        .lines()
        .rev()
        .find(|l| !l.trim().is_empty())
        .expect("a last line");
    assert!(
        readme
            .lines()
            .any(|l| l.split('#').next().unwrap_or("").trim() == last.trim()),
        "README.md does not give `.ci/run`'s test command `{last}`"
    );
}

#[test]
fn no_document_but_the_changelog_and_the_report_carries_a_date_or_a_load() {
    let mut found = Vec::new();
    for doc in documents() {
        let name = doc
            .file_name()
            .expect("a name")
            .to_string_lossy()
            .into_owned();
        if name == "CHANGELOG.md" || name == "benchmarks.md" {
            continue;
        }
        for (i, line) in read(&doc).lines().enumerate() {
            let lower = line.to_lowercase();
            let dated = lower.as_bytes().windows(10).any(|w| {
                w[..4].iter().all(u8::is_ascii_digit)
                    && w[4] == b'-'
                    && w[5..7].iter().all(u8::is_ascii_digit)
                    && w[7] == b'-'
                    && w[8..].iter().all(u8::is_ascii_digit)
            });
            if dated || lower.contains("load average") || lower.contains("earlier machine") {
                found.push(format!("{name}:{}: {line}", i + 1));
            }
        }
    }
    assert!(
        found.is_empty(),
        "history outside CHANGELOG.md:\n{}",
        found.join("\n")
    );
}

#[test]
fn anchors_follow_githubs_rule() {
    let got = anchors("# Engines: throughput\n## f32 on long straight strands\n```\n# not\n```\n");
    let want: BTreeSet<String> = ["engines-throughput", "f32-on-long-straight-strands"]
        .into_iter()
        .map(str::to_owned)
        .collect();
    assert_eq!(got, want);
    assert_eq!(
        link_targets("a [b](c.md#d) e [f](https://g) [h](i j)"),
        ["c.md#d", "https://g"]
    );
}

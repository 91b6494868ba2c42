//! Every relative link in the repository's Markdown resolves: the file it names exists, and a
//! `#fragment` names a heading of that file (GitHub's anchors: lower case, punctuation
//! dropped, spaces as hyphens). External links (`http:`, `https:`, `mailto:`) are not
//! followed: no network in tests.

use std::collections::BTreeSet;
use std::fs;
use std::path::{Path, PathBuf};

/// The repository's root (the tests crate sits one folder below it).
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .canonicalize()
        .unwrap()
}

/// The Markdown files of the repository that people read: tracked folders only, never build
/// output, installed packages or fetched tools.
fn markdown_files(dir: &Path, out: &mut Vec<PathBuf>) {
    const SKIP: [&str; 6] = ["target", "node_modules", ".git", "pkg", ".venv", "corpus"];
    for entry in fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if path.is_dir() {
            if !SKIP.contains(&name.as_str()) && !name.starts_with('.') {
                markdown_files(&path, out);
            }
        } else if name.ends_with(".md") {
            out.push(path);
        }
    }
}

/// The anchor GitHub gives a heading.
fn anchor(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter_map(|c| match c {
            ' ' => Some('-'),
            c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
            _ => None,
        })
        .collect()
}

/// The anchors of a Markdown text's headings (outside code blocks).
fn anchors(text: &str) -> BTreeSet<String> {
    let mut fenced = false;
    let mut out = BTreeSet::new();
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
        } else if !fenced && line.starts_with('#') {
            out.insert(anchor(line.trim_start_matches('#')));
        }
    }
    out
}

/// The targets of the inline links `[text](target)` of a Markdown text, outside code.
fn link_targets(text: &str) -> Vec<String> {
    let mut fenced = false;
    let mut out = Vec::new();
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if fenced {
            continue;
        }
        // Inline code spans hold examples, not links.
        let prose: String = line
            .split('`')
            .enumerate()
            .filter(|(i, _)| i % 2 == 0)
            .map(|(_, s)| s)
            .collect::<Vec<_>>()
            .join(" ");
        let mut rest = prose.as_str();
        while let Some(at) = rest.find("](") {
            let after = &rest[at + 2..];
            let Some(end) = after.find(')') else { break };
            out.push(after[..end].trim().to_owned());
            rest = &after[end..];
        }
    }
    out
}

/// The broken links of the Markdown file `file`: `(target, why)`.
fn broken_links(file: &Path) -> Vec<(String, String)> {
    let text = fs::read_to_string(file).unwrap();
    let mut broken = Vec::new();
    for target in link_targets(&text) {
        if target.is_empty()
            || ["http://", "https://", "mailto:"]
                .iter()
                .any(|scheme| target.starts_with(scheme))
        {
            continue;
        }
        let (path, fragment) = match target.split_once('#') {
            Some((path, fragment)) => (path, Some(fragment)),
            None => (target.as_str(), None),
        };
        let linked = if path.is_empty() {
            file.to_path_buf()
        } else {
            file.parent().unwrap().join(path)
        };
        if !linked.exists() {
            broken.push((target.clone(), "no such file".to_owned()));
            continue;
        }
        if let Some(fragment) = fragment
            && linked.extension().is_some_and(|e| e == "md")
            && !anchors(&fs::read_to_string(&linked).unwrap()).contains(fragment)
        {
            broken.push((target.clone(), "no such heading".to_owned()));
        }
    }
    broken
}

#[test]
fn every_relative_link_in_the_docs_resolves() {
    let root = root();
    let mut files = Vec::new();
    markdown_files(&root, &mut files);
    let names: Vec<String> = files
        .iter()
        .map(|f| f.strip_prefix(&root).unwrap().display().to_string())
        .collect();
    for expected in [
        "README.md",
        "CHANGELOG.md",
        "docs/rust.md",
        "docs/benchmarks.md",
    ] {
        assert!(names.iter().any(|n| n == expected), "{expected} not found");
    }
    let mut broken = Vec::new();
    for file in &files {
        for (target, why) in broken_links(file) {
            broken.push(format!(
                "{}: ({target}) {why}",
                file.strip_prefix(&root).unwrap().display()
            ));
        }
    }
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
}

/// The check itself on a document made here: a missing file, a missing heading and a good
/// link of each kind, so that a check passing on the repository is not one that finds nothing.
#[test]
fn the_link_check_finds_a_missing_file_and_a_missing_heading() {
    let dir = std::env::temp_dir().join(format!("meshq-links-{}", std::process::id()));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(dir.join("docs")).unwrap();
    fs::write(dir.join("docs/guide.md"), "# A guide\n\n## Two commands\n").unwrap();
    let readme = dir.join("README.md");
    fs::write(
        &readme,
        "[guide](docs/guide.md), [commands](docs/guide.md#two-commands), [self](#top-heading)\n\
         [gone](DESIGN.md), [nowhere](docs/guide.md#no-such-part), [web](https://example.org)\n\
         `[code](not-a-link.md)`\n\n# Top heading\n```\n[fenced](nor-this.md)\n```\n",
    )
    .unwrap();
    let broken = broken_links(&readme);
    fs::remove_dir_all(&dir).unwrap();
    assert_eq!(
        broken,
        [
            ("DESIGN.md".to_owned(), "no such file".to_owned()),
            (
                "docs/guide.md#no-such-part".to_owned(),
                "no such heading".to_owned()
            ),
        ]
    );
}

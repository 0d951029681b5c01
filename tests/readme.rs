//! README's Library section shows `examples/library.rs` line for line (CI runs the example, so
//! the README's code is code that compiles and runs).

use std::path::Path;

/// The body of the first ```rust block after `## Library` in README.md.
fn readme_library_block(readme: &str) -> Vec<&str> {
    let section = &readme[readme
        .find("## Library")
        .expect("README has a Library section")..];
    let start = section.find("```rust\n").expect("a rust block in Library") + "```rust\n".len();
    let len = section[start..].find("```").expect("the block ends");
    section[start..start + len].lines().collect()
}

#[test]
fn readme_library_example_is_examples_library_rs() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(root.join("README.md")).expect("README.md");
    let example = std::fs::read_to_string(root.join("examples/library.rs")).expect("example");
    // The example's file starts with its `//!` comment, which README's prose replaces.
    let code: Vec<&str> = example
        .lines()
        .skip_while(|l| l.starts_with("//!"))
        .collect();
    assert!(code.len() > 5, "examples/library.rs has code");
    assert_eq!(readme_library_block(&readme), code);
}

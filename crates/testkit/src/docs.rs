//! Reading the examples out of the Markdown documents, for the tests that keep them true.
//!
//! Invariant: a block is the text between a fence line (`` ```lang ``, surrounding white space
//! ignored) and the next line that is only `` ``` ``, each of its lines ending in `\n`.

/// The `` ```lang `` blocks of `doc`, in order; panics on a block that is never closed.
pub fn fenced_blocks(doc: &str, lang: &str) -> Vec<String> {
    let fence = format!("```{lang}");
    let mut blocks = Vec::new();
    let mut current: Option<String> = None;
    for line in doc.lines() {
        match current.as_mut() {
            None if line.trim() == fence => current = Some(String::new()),
            None => {}
            Some(_) if line.trim() == "```" => blocks.extend(current.take()),
            Some(block) => {
                block.push_str(line);
                block.push('\n');
            }
        }
    }
    assert!(current.is_none(), "unterminated {fence} block");
    blocks
}

//! `fractal list`: the built-in scenes, each with the first sentence of the comment its `.fractal` file opens with.

use std::io::Write;

use crate::cli::error::CliError;
use crate::cli::scene::SceneLibrary;

/// The first sentence of the `//` comment block at the top of `source` (the whole block when it has no full stop).
pub fn description(source: &str) -> String {
    let block: Vec<&str> = source
        .lines()
        .map(str::trim)
        .take_while(|l| l.starts_with("//"))
        .map(|l| l.trim_start_matches('/').trim())
        .collect();
    let text = block.join(" ");
    match text.find(". ") {
        Some(end) => text[..=end].to_string(),
        None => text,
    }
}

pub fn list(library: &SceneLibrary) -> Result<(), CliError> {
    let width = library.scenes.iter().map(|(n, _)| n.len()).max().unwrap_or(0);
    let mut out = std::io::stdout().lock();
    for (name, _) in library.scenes {
        let about = (library.source_file)(name).map(description).unwrap_or_default();
        writeln!(out, "{name:<width$}  {about}").map_err(|e| CliError::failure(format!("writing the list: {e}")))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn descriptions_are_the_first_sentence_of_the_leading_comment() {
        let src = "// One lit sphere: the smallest scene.\n// More detail.\nscene(sphere(1.0)) // not this\n";
        assert_eq!(description(src), "One lit sphere: the smallest scene.");
        let wrapped =
            "// The power-8 Mandelbulb as the baseline draws it: same camera and\n// epsilon, so it compares.\nx";
        assert_eq!(
            description(wrapped),
            "The power-8 Mandelbulb as the baseline draws it: same camera and epsilon, so it compares."
        );
        assert_eq!(description("sphere(1.0)"), "");
    }
}

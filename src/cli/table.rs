//! The one aligned text table of the command line (`check`'s ledger, `bench`'s tables): column
//! widths from the cells' display width (comfy-table, which counts what a terminal shows, so
//! "θ" and "≻" take one column), no borders, numbers right-aligned where asked.

use comfy_table::{presets, CellAlignment, ContentArrangement, Table};

/// `header` and `rows` as aligned text, columns `right` right-aligned; every line without
/// trailing spaces, ending in a newline.
pub fn text_table(header: &[&str], rows: &[Vec<String>], right: &[usize]) -> String {
    let mut t = Table::new();
    t.load_preset(presets::NOTHING).set_content_arrangement(ContentArrangement::Disabled).set_header(header.to_vec());
    for r in rows {
        t.add_row(r.clone());
    }
    for col in t.column_iter_mut() {
        col.set_padding((0, 2));
    }
    for &c in right {
        if let Some(col) = t.column_mut(c) {
            col.set_cell_alignment(CellAlignment::Right);
        }
    }
    t.lines().map(|l| l.trim_end().to_string() + "\n").collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_line_up_by_display_width() {
        let text = text_table(
            &["id", "equation", "time"],
            &[
                vec!["w-bounds".into(), "W ≻ 0 (θ, q)".into(), "0.12s".into()],
                vec!["x".into(), "ab".into(), "10.00s".into()],
            ],
            &[2],
        );
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 3, "{text}");
        // every column starts at the same display column on every line
        let col = |l: &str, word: &str| l.find(word).map(|b| l[..b].chars().count());
        assert_eq!(col(lines[0], "equation"), col(lines[1], "W ≻"));
        assert_eq!(col(lines[1], "W ≻"), col(lines[2], "ab"));
        // right-aligned: the times end in the same column
        assert_eq!(lines[1].chars().count(), lines[2].chars().count(), "{text}");
        assert!(text.lines().all(|l| !l.ends_with(' ')));
    }
}

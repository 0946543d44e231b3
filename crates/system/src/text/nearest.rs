//! "Did you mean": the known name a misspelt one is nearest to, for the messages that refuse a
//! name (a results file's column, a solver).

/// The name of `known` nearest to `given` by edits (a letter changed, added, removed, or two
/// swapped), if it is near enough to be a misspelling of it: at most a third of the known name's
/// letters (at least one) edited ([`edits`]); the first of equally near names.
pub fn nearest<'a>(given: &str, known: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    known
        .into_iter()
        .map(|name| (edits(given, name), name))
        .filter(|&(d, name)| d > 0 && d <= (name.chars().count() / 3).max(1))
        .min_by_key(|&(d, _)| d)
        .map(|(_, name)| name)
}

/// The edits that turn `a` into `b`: letters changed, added, removed, or two neighbours swapped
/// (the optimal string alignment distance, in characters).
fn edits(a: &str, b: &str) -> usize {
    let (a, b): (Vec<char>, Vec<char>) = (a.chars().collect(), b.chars().collect());
    // d[i][j]: the edits from a's first i letters to b's first j.
    let mut d = vec![vec![0; b.len() + 1]; a.len() + 1];
    for (i, row) in d.iter_mut().enumerate() {
        row[0] = i;
    }
    for (j, cell) in d[0].iter_mut().enumerate() {
        *cell = j;
    }
    for i in 1..=a.len() {
        for j in 1..=b.len() {
            let changed = usize::from(a[i - 1] != b[j - 1]);
            d[i][j] = (d[i - 1][j - 1] + changed)
                .min(d[i - 1][j] + 1)
                .min(d[i][j - 1] + 1);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                d[i][j] = d[i][j].min(d[i - 2][j - 2] + 1);
            }
        }
    }
    d[a.len()][b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    const COLUMNS: [&str; 3] = ["normal_force", "tangential_force", "contact_radius"];

    /// Requirement: a misspelling (a letter dropped, swapped, added) finds its name; a name far
    /// from all, or the name itself, finds none. Reference: the edits counted by hand.
    #[test]
    fn a_misspelling_finds_its_name_and_nothing_else_does() {
        assert_eq!(edits("tangental_force", "tangential_force"), 1);
        assert_eq!(edits("kitten", "sitting"), 3);
        assert_eq!(edits("hretz", "hertz"), 1);
        assert_eq!(nearest("tangental_force", COLUMNS), Some("tangential_force"));
        assert_eq!(nearest("normal_froce", COLUMNS), Some("normal_force"));
        assert_eq!(nearest("contact_radiuss", COLUMNS), Some("contact_radius"));
        assert_eq!(nearest("force", COLUMNS), None);
        assert_eq!(nearest("SECRET-5f1e9c", COLUMNS), None);
        assert_eq!(nearest("normal_force", COLUMNS), None);
        assert_eq!(
            nearest("mdr-domian", ["mdr", "mdr-domain", "hertz"]),
            Some("mdr-domain")
        );
        assert_eq!(nearest("hrtz", ["mdr", "hertz"]), Some("hertz"));
    }
}

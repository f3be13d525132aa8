//! Naming helpers: the generated type's name and "did you mean" suggestions.

/// `pendulum` -> `Pendulum`, `example_1_1` -> `Example11`.
pub fn upper_camel_case(snake: &str) -> String {
    snake
        .split('_')
        .filter(|p| !p.is_empty())
        .map(|p| {
            let mut c = p.chars();
            match c.next() {
                Some(f) => f.to_uppercase().chain(c).collect::<String>(),
                None => String::new(),
            }
        })
        .collect()
}

/// The Damerau–Levenshtein distance (optimal string alignment): insertions,
/// deletions, substitutions and transpositions of neighbours count one
/// each, so `omgea` is one edit from `omega`, as a typist's slip is.
fn edit_distance(a: &str, b: &str) -> usize {
    let (a, b): (Vec<char>, Vec<char>) = (a.chars().collect(), b.chars().collect());
    // Three rows of the table: two back (for transpositions), one back, this.
    let mut before: Vec<usize> = vec![0; b.len() + 1];
    let mut previous: Vec<usize> = (0..=b.len()).collect();
    let mut current = vec![0; b.len() + 1];
    for i in 1..=a.len() {
        current[0] = i;
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            let mut d = (previous[j - 1] + cost).min(previous[j] + 1).min(current[j - 1] + 1);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                d = d.min(before[j - 2] + 1);
            }
            current[j] = d;
        }
        std::mem::swap(&mut before, &mut previous);
        std::mem::swap(&mut previous, &mut current);
    }
    previous[b.len()]
}

/// The known name closest to `name`, if it is close enough to be a typo.
pub fn did_you_mean<'a>(name: &str, known: impl Iterator<Item = &'a str>) -> Option<&'a str> {
    // One edit turns any one-letter name into any other: suggest only for
    // names long enough that a typo is the likely story.
    let limit = name.chars().count() / 3;
    if limit == 0 {
        return None;
    }
    known.map(|k| (edit_distance(name, k), k)).filter(|&(d, _)| d <= limit).min().map(|(_, k)| k)
}

/// The user's tokens as compact source text for messages and docs:
/// `der (x) == u` becomes `der(x) == u`, `a * (b + c)` stays as it is.
pub fn source_text(tokens: &proc_macro2::TokenStream) -> String {
    let text = tokens.to_string();
    let chars: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    for (i, &c) in chars.iter().enumerate() {
        if c == ' ' {
            let before = out.chars().last();
            let after = chars.get(i + 1).copied();
            let call_or_index = matches!(after, Some('(' | '['))
                && before.is_some_and(|b| b.is_alphanumeric() || b == '_' || b == ')' || b == ']');
            // A unary minus: `-` after an operator, an opening bracket or
            // nothing, as in `== - k` (written `== -k`).
            let unary_minus = before == Some('-')
                && out
                    .trim_end_matches('-')
                    .trim_end()
                    .chars()
                    .last()
                    .is_none_or(|p| "([,=*/+-!<>".contains(p));
            let drop = call_or_index
                || unary_minus
                || matches!(before, Some('(' | '[' | '.'))
                || matches!(after, Some(')' | ']' | ',' | '.' | ';'));
            if drop {
                continue;
            }
        }
        out.push(c);
    }
    out.trim_end_matches(';').trim().to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn camel_case_and_suggestions() {
        assert_eq!(upper_camel_case("pendulum"), "Pendulum");
        assert_eq!(upper_camel_case("three_body_2d"), "ThreeBody2d");
        assert_eq!(did_you_mean("lamda", ["lambda", "l", "m"].into_iter()), Some("lambda"));
        assert_eq!(did_you_mean("zeta", ["lambda", "l", "m"].into_iter()), None);
        // A transposition is one slip, not two substitutions.
        assert_eq!(edit_distance("omgea", "omega"), 1);
        assert_eq!(edit_distance("omega", "omega"), 0);
        assert_eq!(edit_distance("lamda", "lambda"), 1);
        assert_eq!(edit_distance("abc", "ca"), 3);
        assert_eq!(did_you_mean("omgea", ["omega", "theta"].into_iter()), Some("omega"));
    }

    #[test]
    fn source_text_reads_as_written() {
        let text = |s: &str| source_text(&s.parse().unwrap());
        assert_eq!(text("der (x) == - k * x"), "der(x) == -k * x");
        assert_eq!(text("a - b * (- c)"), "a - b * (-c)");
        assert_eq!(text("- x . powi (2)"), "-x.powi(2)");
        assert_eq!(text("f (a , - b)"), "f(a, -b)");
        assert_eq!(did_you_mean("y", ["k", "x"].into_iter()), None);
    }
}

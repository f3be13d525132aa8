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

fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut prev = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let cur = row[j + 1];
            row[j + 1] = (prev + usize::from(ca != cb)).min(row[j] + 1).min(cur + 1);
            prev = cur;
        }
    }
    row[b.len()]
}

/// The known name closest to `name`, if it is close enough to be a typo.
pub fn did_you_mean<'a>(name: &str, known: impl Iterator<Item = &'a str>) -> Option<&'a str> {
    // One edit turns any one-letter name into any other: suggest only for
    // names long enough that a typo is the likely story.
    let limit = name.chars().count() / 3;
    if limit == 0 {
        return None;
    }
    known
        .map(|k| (edit_distance(name, k), k))
        .filter(|&(d, _)| d <= limit)
        .min()
        .map(|(_, k)| k)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn camel_case_and_suggestions() {
        assert_eq!(upper_camel_case("pendulum"), "Pendulum");
        assert_eq!(upper_camel_case("three_body_2d"), "ThreeBody2d");
        assert_eq!(
            did_you_mean("lamda", ["lambda", "l", "m"].into_iter()),
            Some("lambda")
        );
        assert_eq!(did_you_mean("zeta", ["lambda", "l", "m"].into_iter()), None);
        assert_eq!(did_you_mean("y", ["k", "x"].into_iter()), None);
    }
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
            let drop = call_or_index
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

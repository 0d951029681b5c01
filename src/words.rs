//! Counts in messages, in the singular for one ("1 thread", "2 threads").

/// `n` and the noun that agrees with it: `one` for 1, `many` otherwise.
pub(crate) fn count(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

#[cfg(test)]
mod tests {
    #[test]
    fn singular_for_one_only() {
        assert_eq!(super::count(1, "vertex", "vertices"), "1 vertex");
        assert_eq!(super::count(0, "vertex", "vertices"), "0 vertices");
        assert_eq!(super::count(2, "quad", "quads"), "2 quads");
    }
}

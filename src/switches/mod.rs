//! Command-line switch parsers shared by the `idmesh` command line and the C ABI (and through
//! it the source-compatibility shims in `compat/`): one parser per reference program, so that a
//! switch string means the same thing wherever it is given (`idmesh tetgen -pq1.4`, the TetGen
//! compatibility layer's `tetrahedralize("pq1.4", ...)`, Triangle's `triangulate("pq30", ...)`).

pub mod tetgen;
pub mod tetgen_extra;
pub mod triangle;

/// `box` -> `box.1`, `box.1` -> `box.2`, `dir.v2/box` -> `dir.v2/box.1`. Only the last path
/// component is examined, so dots in directory names do not count.
pub fn next_iteration(stem: &str) -> String {
    let name_start = stem.rfind(['/', '\\']).map_or(0, |i| i + 1);
    let name = &stem[name_start..];
    // A leading dot starts a hidden file name, not an iteration number.
    if let Some(dot) = name.rfind('.').filter(|&d| d > 0) {
        let digits = &name[dot + 1..];
        if !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()) {
            if let Ok(n) = digits.parse::<u64>() {
                if let Some(next) = n.checked_add(1) {
                    return format!("{}{next}", &stem[..name_start + dot + 1]);
                }
            }
        }
    }
    format!("{stem}.1")
}

#[cfg(test)]
mod tests {
    use super::next_iteration;

    #[test]
    fn iteration_numbers_advance() {
        assert_eq!(next_iteration("box"), "box.1");
        assert_eq!(next_iteration("box.1"), "box.2");
        assert_eq!(next_iteration("dir.7/box"), "dir.7/box.1");
        assert_eq!(next_iteration(".5"), ".5.1");
    }
}

//! Input and output file names, as Triangle forms them.
//!
//! * `FILE`, `FILE.node` and `FILE.poly` all name the input `FILE`; a `.poly` extension implies
//!   `-p` (Triangle does the same). With `-p` the input is `FILE.poly`, else `FILE.node`.
//! * Outputs are `FILE.1.node`, `FILE.1.ele`, ...; when `FILE` already ends in an iteration
//!   number (`box.1`), the next one is used (`box.2.*`).

use idmesh::switches::next_iteration;

/// Where to read and where to write.
#[derive(Debug, Clone, PartialEq)]
pub struct Files {
    /// The file to read.
    pub input: String,
    /// Whether `input` is a `.poly` file.
    pub poly: bool,
    /// The output name without extension, e.g. `box.1`.
    pub out_stem: String,
}

impl Files {
    /// The output file with extension `ext` (without dot).
    pub fn output(&self, ext: &str) -> String {
        format!("{}.{ext}", self.out_stem)
    }
}

/// Resolves the file argument and the `-p` switch.
pub fn resolve(file: &str, poly_switch: bool) -> Files {
    let (stem, poly) = if let Some(s) = file.strip_suffix(".poly") {
        (s, true)
    } else if let Some(s) = file.strip_suffix(".node") {
        (s, poly_switch)
    } else {
        (file, poly_switch)
    };
    let input = format!("{stem}.{}", if poly { "poly" } else { "node" });
    Files {
        input,
        poly,
        out_stem: next_iteration(stem),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extension_is_optional_and_poly_implies_p() {
        let f = resolve("data/box", true);
        assert_eq!((f.input.as_str(), f.poly), ("data/box.poly", true));
        let f = resolve("data/box", false);
        assert_eq!((f.input.as_str(), f.poly), ("data/box.node", false));
        let f = resolve("data/box.poly", false);
        assert_eq!((f.input.as_str(), f.poly), ("data/box.poly", true));
        let f = resolve("data/box.node", true);
        assert_eq!((f.input.as_str(), f.poly), ("data/box.poly", true));
        let f = resolve("data/box.node", false);
        assert_eq!((f.input.as_str(), f.poly), ("data/box.node", false));
        assert_eq!(f.output("ele"), "data/box.1.ele");
    }

    #[test]
    fn iteration_numbers_advance() {
        assert_eq!(resolve("box.poly", true).out_stem, "box.1");
        assert_eq!(resolve("box.1.poly", true).out_stem, "box.2");
        assert_eq!(resolve("a/box.19", false).out_stem, "a/box.20");
        assert_eq!(resolve("box.v1", false).out_stem, "box.v1.1");
        assert_eq!(resolve("dir.7/box", false).out_stem, "dir.7/box.1");
        assert_eq!(resolve(".5", false).out_stem, ".5.1");
        assert_eq!(
            resolve("x.99999999999999999999999", false).out_stem,
            "x.99999999999999999999999.1"
        );
    }
}

//! Texture wrap modes (`-smode/-tmode`, OpenEXR `wrapmodes` attribute: `"periodic,clamp"`).

/// How a texture extends outside `[0,1]`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum WrapMode {
    /// Outside is black (zero, including alpha).
    Black,
    /// Coordinates clamp to the edge texel.
    Clamp,
    /// The texture repeats.
    Periodic,
}

impl WrapMode {
    /// Parses `black`, `clamp`, `periodic` (and `repeat`, the OIIO spelling).
    pub fn parse(word: &str) -> Option<WrapMode> {
        match word.trim().to_ascii_lowercase().as_str() {
            "black" => Some(WrapMode::Black),
            "clamp" => Some(WrapMode::Clamp),
            "periodic" | "repeat" => Some(WrapMode::Periodic),
            _ => None,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            WrapMode::Black => "black",
            WrapMode::Clamp => "clamp",
            WrapMode::Periodic => "periodic",
        }
    }

    /// Maps texel index `i` of an axis of `n` texels: `None` means "black".
    #[inline]
    pub fn texel(self, i: i64, n: usize) -> Option<usize> {
        let n = n as i64;
        if (0..n).contains(&i) {
            return Some(i as usize);
        }
        match self {
            WrapMode::Black => None,
            WrapMode::Clamp => Some(i.clamp(0, n - 1) as usize),
            WrapMode::Periodic => Some(i.rem_euclid(n) as usize),
        }
    }
}

/// Parses an OpenEXR `wrapmodes` value: one keyword for both axes or `"s,t"`.
pub fn parse_wrapmodes(text: &str) -> Option<[WrapMode; 2]> {
    let mut parts = text.split(',');
    let s = WrapMode::parse(parts.next()?)?;
    let t = match parts.next() {
        Some(word) => WrapMode::parse(word)?,
        None => s,
    };
    Some([s, t])
}

/// Formats the `wrapmodes` attribute value.
pub fn format_wrapmodes(modes: [WrapMode; 2]) -> String {
    format!("{},{}", modes[0].name(), modes[1].name())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrapmodes_round_trip_and_single_keyword_applies_to_both_axes() {
        let m = [WrapMode::Periodic, WrapMode::Clamp];
        assert_eq!(parse_wrapmodes(&format_wrapmodes(m)), Some(m));
        assert_eq!(parse_wrapmodes(" black "), Some([WrapMode::Black; 2]));
        assert_eq!(
            parse_wrapmodes("clamp, black "),
            Some([WrapMode::Clamp, WrapMode::Black])
        );
        assert_eq!(parse_wrapmodes("mirrorish"), None);
    }

    #[test]
    fn periodic_wraps_negative_indices_and_black_rejects_them() {
        assert_eq!(WrapMode::Periodic.texel(-1, 8), Some(7));
        assert_eq!(WrapMode::Clamp.texel(9, 8), Some(7));
        assert_eq!(WrapMode::Black.texel(8, 8), None);
    }
}

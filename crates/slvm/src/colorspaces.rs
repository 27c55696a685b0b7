//! `ctransform` and colour literals in a named space (RI 3.2 §15.3): `rgb`, `hsv`, `hsl`,
//! `xyz` (CIE XYZ of linear Rec. 709 RGB, D65), `xyY`, `YIQ` (NTSC). Names are matched
//! case-insensitively as PRMan does; `None` for an unknown space (the caller warns once).
use glam::{DMat3, DVec3, Vec3};

fn rgb_to_xyz() -> DMat3 {
    // Rec. 709 primaries, D65 white (IEC 61966-2-1), columns = R, G, B.
    DMat3::from_cols(
        DVec3::new(0.412_456_4, 0.212_672_9, 0.019_333_9),
        DVec3::new(0.357_576_1, 0.715_152_2, 0.119_192),
        DVec3::new(0.180_437_5, 0.072_175, 0.950_304_1),
    )
}

fn rgb_to_yiq() -> DMat3 {
    // FCC NTSC YIQ (rows Y, I, Q), as columns.
    DMat3::from_cols(
        DVec3::new(0.299, 0.596, 0.211),
        DVec3::new(0.587, -0.274, -0.523),
        DVec3::new(0.114, -0.322, 0.312),
    )
}

fn rgb_to_hsv(c: DVec3) -> DVec3 {
    let max = c.max_element();
    let min = c.min_element();
    let d = max - min;
    let v = max;
    let s = if max > 0.0 { d / max } else { 0.0 };
    (hue(c, max, d), s, v).into()
}

/// Hue in [0,1) (a sixth per sector), 0 for greys.
fn hue(c: DVec3, max: f64, d: f64) -> f64 {
    if d <= 0.0 {
        return 0.0;
    }
    let h = if c.x == max {
        (c.y - c.z) / d
    } else if c.y == max {
        2.0 + (c.z - c.x) / d
    } else {
        4.0 + (c.x - c.y) / d
    };
    (h / 6.0).rem_euclid(1.0)
}

fn hsv_to_rgb(c: DVec3) -> DVec3 {
    let (h, s, v) = (c.x.rem_euclid(1.0) * 6.0, c.y, c.z);
    let sector = h.floor();
    let f = h - sector;
    let (p, q, t) = (v * (1.0 - s), v * (1.0 - s * f), v * (1.0 - s * (1.0 - f)));
    match sector as i32 {
        0 => DVec3::new(v, t, p),
        1 => DVec3::new(q, v, p),
        2 => DVec3::new(p, v, t),
        3 => DVec3::new(p, q, v),
        4 => DVec3::new(t, p, v),
        _ => DVec3::new(v, p, q),
    }
}

fn rgb_to_hsl(c: DVec3) -> DVec3 {
    let max = c.max_element();
    let min = c.min_element();
    let d = max - min;
    let l = 0.5 * (max + min);
    let s = if d <= 0.0 {
        0.0
    } else if l <= 0.5 {
        d / (max + min)
    } else {
        d / (2.0 - max - min)
    };
    DVec3::new(hue(c, max, d), s, l)
}

fn hsl_to_rgb(c: DVec3) -> DVec3 {
    let (h, s, l) = (c.x, c.y, c.z);
    if s <= 0.0 {
        return DVec3::splat(l);
    }
    // HSL is HSV with v = l + s·min(l, 1-l) and s_v = 2(1 - l/v).
    let v = l + s * l.min(1.0 - l);
    let sv = if v > 0.0 { 2.0 * (1.0 - l / v) } else { 0.0 };
    hsv_to_rgb(DVec3::new(h, sv, v))
}

fn xyz_to_xyy(c: DVec3) -> DVec3 {
    let sum = c.x + c.y + c.z;
    if sum <= 0.0 {
        return DVec3::new(0.0, 0.0, c.y);
    }
    DVec3::new(c.x / sum, c.y / sum, c.y)
}

fn xyy_to_xyz(c: DVec3) -> DVec3 {
    if c.y <= 0.0 {
        return DVec3::ZERO;
    }
    DVec3::new(c.x * c.z / c.y, c.z, (1.0 - c.x - c.y) * c.z / c.y)
}

/// RGB into colour space `space`.
pub fn from_rgb(space: &str, c: Vec3) -> Option<Vec3> {
    let c = c.as_dvec3();
    let r = match space.to_ascii_lowercase().as_str() {
        "rgb" => c,
        "hsv" => rgb_to_hsv(c),
        "hsl" => rgb_to_hsl(c),
        "xyz" => rgb_to_xyz() * c,
        "xyy" => xyz_to_xyy(rgb_to_xyz() * c),
        "yiq" => rgb_to_yiq() * c,
        _ => return None,
    };
    Some(r.as_vec3())
}

/// Colour space `space` into RGB (how `color "hsv" (h, s, v)` is read).
pub fn to_rgb(space: &str, c: Vec3) -> Option<Vec3> {
    let c = c.as_dvec3();
    let r = match space.to_ascii_lowercase().as_str() {
        "rgb" => c,
        "hsv" => hsv_to_rgb(c),
        "hsl" => hsl_to_rgb(c),
        "xyz" => rgb_to_xyz().inverse() * c,
        "xyy" => rgb_to_xyz().inverse() * xyy_to_xyz(c),
        "yiq" => rgb_to_yiq().inverse() * c,
        _ => return None,
    };
    Some(r.as_vec3())
}

/// SL `ctransform(from, to, c)`.
pub fn ctransform(from: &str, to: &str, c: Vec3) -> Option<Vec3> {
    from_rgb(to, to_rgb(from, c)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3, b: Vec3, tol: f32) -> bool {
        (a - b).abs().max_element() < tol
    }

    #[test]
    fn hsv_of_primaries() {
        // Red is hue 0, green 1/3, blue 2/3; full saturation and value.
        assert!(close(
            from_rgb("hsv", Vec3::X).unwrap(),
            Vec3::new(0.0, 1.0, 1.0),
            1e-6
        ));
        assert!(close(
            from_rgb("hsv", Vec3::Y).unwrap(),
            Vec3::new(1.0 / 3.0, 1.0, 1.0),
            1e-6
        ));
        assert!(close(
            from_rgb("hsv", Vec3::Z).unwrap(),
            Vec3::new(2.0 / 3.0, 1.0, 1.0),
            1e-6
        ));
        // Grey: hue and saturation 0, value = the grey.
        assert!(close(
            from_rgb("hsv", Vec3::splat(0.4)).unwrap(),
            Vec3::new(0.0, 0.0, 0.4),
            1e-6
        ));
    }

    #[test]
    fn hsl_of_a_pastel() {
        // (1, .5, .5): max 1, min .5, l = .75, s = .5/(2 - 1.5) = 1, hue 0.
        assert!(close(
            from_rgb("hsl", Vec3::new(1.0, 0.5, 0.5)).unwrap(),
            Vec3::new(0.0, 1.0, 0.75),
            1e-6
        ));
    }

    #[test]
    fn every_space_round_trips() {
        let c = Vec3::new(0.8, 0.3, 0.55);
        for space in ["rgb", "hsv", "hsl", "xyz", "xyY", "YIQ"] {
            let back = to_rgb(space, from_rgb(space, c).unwrap()).unwrap();
            assert!(close(back, c, 1e-5), "{space}: {back:?}");
        }
        assert_eq!(from_rgb("cmyk", c), None);
    }

    #[test]
    fn white_is_d65_in_xyy() {
        // D65 chromaticity (0.3127, 0.3290), luminance 1.
        let w = from_rgb("xyY", Vec3::ONE).unwrap();
        assert!(close(w, Vec3::new(0.3127, 0.3290, 1.0), 2e-4), "{w:?}");
        // Y of YIQ is the NTSC luma.
        let y = from_rgb("yiq", Vec3::new(0.2, 0.4, 0.6)).unwrap().x;
        assert!((y - (0.299 * 0.2 + 0.587 * 0.4 + 0.114 * 0.6)).abs() < 1e-6);
    }
}

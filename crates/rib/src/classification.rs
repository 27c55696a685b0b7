//! Which family of RI Spec 3.2 chapter 4/5 a request belongs to. The shape of a request is
//! this crate's business, so the families live here, where a new request variant has to be
//! placed in one of them; `illume-ri` dispatches on them.
use crate::Request;

impl Request {
    /// The frame options of RI Spec 3.2 §4.1 (camera, display, additional and
    /// implementation-specific `Option`): fixed once `WorldBegin` is reached.
    pub fn is_option(&self) -> bool {
        use Request::*;
        matches!(
            self,
            Format { .. }
                | FrameAspectRatio(_)
                | ScreenWindow { .. }
                | CropWindow { .. }
                | Projection { .. }
                | Clipping { .. }
                | ClippingPlane { .. }
                | DepthOfField { .. }
                | Shutter { .. }
                | PixelVariance(_)
                | PixelSamples { .. }
                | PixelFilter { .. }
                | Exposure { .. }
                | Imager { .. }
                | Quantize { .. }
                | Display { .. }
                | Hider { .. }
                | DisplayChannel { .. }
                | ColorSamples { .. }
                | RelativeDetail(_)
                | Option { .. }
        )
    }

    /// The transformation requests of RI Spec 3.2 §4.3 that a motion block may hold (the
    /// ones that change the current transformation; `CoordinateSystem` only names it).
    pub fn is_transform(&self) -> bool {
        use Request::*;
        matches!(
            self,
            Identity
                | Transform(_)
                | ConcatTransform(_)
                | Perspective(_)
                | Translate(_)
                | Rotate { .. }
                | Scale(_)
                | Skew(_)
                | CoordSysTransform(_)
        )
    }

    /// The geometric primitives of RI Spec 3.2 chapter 5 (everything that adds surfaces to
    /// the world; `Procedural` is not one: it adds requests).
    pub fn is_geometry(&self) -> bool {
        use Request::*;
        matches!(
            self,
            Polygon { .. }
                | GeneralPolygon { .. }
                | PointsPolygons { .. }
                | PointsGeneralPolygons { .. }
                | Patch { .. }
                | PatchMesh { .. }
                | NuPatch { .. }
                | Sphere { .. }
                | Cone { .. }
                | Cylinder { .. }
                | Hyperboloid { .. }
                | Paraboloid { .. }
                | Disk { .. }
                | Torus { .. }
                | Points { .. }
                | Curves { .. }
                | SubdivisionMesh { .. }
                | Blobby { .. }
                | Geometry { .. }
        )
    }
}

#[cfg(test)]
mod tests {
    use crate::Parser;

    /// One request of each kind the families must tell apart, with its family by the chapter
    /// of RI Spec 3.2 it is defined in: (option §4.1, transform §4.3 minus
    /// `CoordinateSystem`, geometry chapter 5 minus `Procedural`).
    #[test]
    fn families_follow_the_spec_chapters_and_do_not_overlap() {
        let cases: &[(&str, [bool; 3])] = &[
            ("Format 64 48 1", [true, false, false]),
            (
                "Projection \"perspective\" \"fov\" [40]",
                [true, false, false],
            ),
            ("PixelFilter \"box\" 1 1", [true, false, false]),
            ("Hider \"hidden\"", [true, false, false]),
            (
                "Option \"limits\" \"bucketsize\" [16 16]",
                [true, false, false],
            ),
            ("Translate 1 0 0", [false, true, false]),
            (
                "ConcatTransform [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1]",
                [false, true, false],
            ),
            ("CoordSysTransform \"world\"", [false, true, false]),
            ("CoordinateSystem \"a\"", [false, false, false]),
            ("Sphere 1 -1 1 360", [false, false, true]),
            ("Polygon \"P\" [0 0 0 1 0 0 1 1 0]", [false, false, true]),
            ("Geometry \"teapot\"", [false, false, true]),
            (
                "Procedural \"DelayedReadArchive\" [\"a.rib\"] [-1 1 -1 1 -1 1]",
                [false, false, false],
            ),
            ("Color [1 0 0]", [false, false, false]),
            ("Surface \"plastic\"", [false, false, false]),
            ("WorldBegin", [false, false, false]),
        ];
        for (rib, expected) in cases {
            let req = Parser::new(rib.as_bytes(), "t.rib")
                .next()
                .expect("one request")
                .expect("parses")
                .value;
            let got = [req.is_option(), req.is_transform(), req.is_geometry()];
            assert_eq!(&got, expected, "{rib}");
        }
    }
}

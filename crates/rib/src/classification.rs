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

//! The attribute state of RI Spec 3.2 §4.2, shared (`Arc`) by every primitive made under it.
use crate::state::Ri;
use glam::DMat4;
use illume_rib::{Handle, ParamList, Request, Span};
use std::sync::Arc;

mod geometry;
mod shading;
mod user;

/// A shader instance: name, parameter list as written, and the coordinate system it was
/// declared in ("shader" space).
#[derive(Clone, Debug, PartialEq)]
pub struct Shader {
    pub name: String,
    pub params: ParamList,
    pub camera_from_shader: DMat4,
    pub span: Span,
}

/// A light source or area light in the frame's light list.
#[derive(Clone, Debug, PartialEq)]
pub struct Light {
    pub handle: Handle,
    pub shader: Shader,
    pub area: bool,
    /// `Attribute "light" "shadows" ["on"]` when the light was declared (BMRT): its visibility
    /// is decided by ray-traced shadow rays.
    pub shadows: bool,
    /// `Attribute "light" "nsamples"` when the light was declared: samples per shading point
    /// on an area light's geometry (and shadow rays per point of a ray-traced shadow).
    pub samples: u32,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Attributes {
    pub color: [f32; 3],
    pub opacity: [f32; 3],
    pub shading_rate: f32,
    /// `ShadingInterpolation "smooth"` (else "constant").
    pub smooth_shading: bool,
    pub matte: bool,
    pub sides: i32,
    /// The current orientation relative to the handedness of the current coordinate system
    /// (RI Spec 3.2 `RiOrientation`: "outside" is `false`, "inside" `true`; "lh"/"rh" are
    /// turned into one of them against the handedness when they are called). It is resolved
    /// per primitive against the sign of its object-to-camera determinant (see
    /// [`crate::FramePrimitive::normal_sign`]), so a mirroring transform or camera given
    /// after it keeps an "outside" surface's normals pointing out, as PRMan and Aqsis do.
    pub orientation_inside: bool,
    pub texture_coordinates: [f32; 8],
    /// (u basis, u step, v basis, v step), matrices in RIB row order.
    pub basis: ([f32; 16], i32, [f32; 16], i32),
    pub surface: Option<Arc<Shader>>,
    pub displacement: Option<Arc<Shader>>,
    pub atmosphere: Option<Arc<Shader>>,
    pub interior: Option<Arc<Shader>>,
    pub exterior: Option<Arc<Shader>>,
    /// Indices into [`crate::Frame::lights`] of the lights that illuminate this primitive.
    pub lights: Vec<usize>,
    /// The area light this geometry defines, if inside an `AreaLightSource` block.
    pub area_light: Option<usize>,
    pub identifier: Option<String>,
    /// `Attribute "displacementbound" "sphere"`, already scaled into camera space.
    pub displacement_bound: f32,
    /// `Attribute "dice" "binary"`: dice rates are powers of two.
    pub dice_binary: bool,
    /// `Detail` bound in camera space corners and `DetailRange`.
    pub detail: Option<([f32; 6], DMat4)>,
    pub detail_range: Option<[f32; 4]>,
    /// `GeometricApproximation "flatness"`.
    pub flatness: Option<f32>,
    /// `Attribute "light" "shadows"` ("on"/"off"), given to lights declared under it.
    pub light_shadows: bool,
    /// `Attribute "light" "nsamples"`, given to lights declared under it.
    pub light_samples: u32,
    /// Whether this geometry blocks shadow rays: `Attribute "visibility" "transmission"` and
    /// `Attribute "render" "casts_shadows"`. BMRT's values: "opaque", "Os" and "shader" cast
    /// (all as fully opaque here), "transparent" and "none" do not; PRMan's integer form
    /// (`"int transmission" [0]`) too.
    pub casts_shadows: bool,
    /// Shadow rays (`transmission()`, `visibility()`, `occlusion()` from SL) see this
    /// geometry as partly transparent, `1 − Os`: the `"Os"` and `"shader"` values of the
    /// transmission attribute (shaders do not run for shadow rays: `"shader"` reads `Os`).
    pub transmission_os: bool,
    /// Whether `trace()` rays see this geometry: `Attribute "visibility" "trace"` /
    /// `"reflection"` (0/1) and bit 2 of BMRT's `Attribute "render" "visibility"`. By default
    /// rays see everything, as in BMRT.
    pub visible_to_rays: bool,
    /// `TrimCurve` loops for the NuPatches that follow (RI Spec 3.2 §5.5: an attribute).
    pub trim_curves: Option<Arc<illume_geom::TrimCurves>>,
}

impl Default for Attributes {
    fn default() -> Self {
        // Bezier is the spec's default `Basis` (RI Spec 3.2 §5.2.1).
        let (bezier, _) = illume_geom::basis::basis_matrix("bezier").expect("a predefined basis");
        Attributes {
            color: [1.0; 3],
            opacity: [1.0; 3],
            shading_rate: 1.0,
            smooth_shading: false,
            matte: false,
            sides: 2,
            orientation_inside: false,
            texture_coordinates: [0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            basis: (bezier, 3, bezier, 3),
            surface: None,
            displacement: None,
            atmosphere: None,
            interior: None,
            exterior: None,
            lights: Vec::new(),
            area_light: None,
            identifier: None,
            displacement_bound: 0.0,
            dice_binary: false,
            detail: None,
            detail_range: None,
            flatness: None,
            light_shadows: false,
            light_samples: 16,
            casts_shadows: true,
            transmission_os: false,
            visible_to_rays: true,
            trim_curves: None,
        }
    }
}

impl Ri {
    /// The current attributes, copied first if a saved block still shares them.
    pub(crate) fn attrs(&mut self) -> &mut Attributes {
        Arc::make_mut(&mut self.attributes)
    }

    /// The attribute requests of RI Spec 3.2 §4.2, by family.
    pub(crate) fn attribute(&mut self, req: Request, span: &Span) {
        use Request::*;
        match req {
            Color(_)
            | Opacity(_)
            | TextureCoordinates(_)
            | ShadingRate(_)
            | ShadingInterpolation(_)
            | Matte(_)
            | Surface { .. }
            | Displacement { .. }
            | Atmosphere { .. }
            | Interior { .. }
            | Exterior { .. }
            | Deformation { .. } => self.shading_attribute(req, span),
            Sides(_)
            | Orientation(_)
            | ReverseOrientation
            | TrimCurve { .. }
            | Basis { .. }
            | Bound(_)
            | Detail(_)
            | DetailRange(_)
            | GeometricApproximation { .. }
            | GeometricRepresentation(_) => self.geometry_attribute(req, span),
            LightSource { .. } | AreaLightSource { .. } | Illuminate { .. } => {
                self.light_request(req, span)
            }
            Attribute { name: n, params } => self.user_attribute(&n, &params, span),
            other => self.diagnostics.error_kind(
                crate::ErrorKind::Bug,
                span,
                other.name(),
                "request not handled here (internal)",
            ),
        }
    }
}

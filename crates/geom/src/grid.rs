//! A diced grid: the unit of shading and sampling in REYES.
use glam::Vec3;

/// A user primitive variable interpolated over a grid (one value per vertex).
#[derive(Clone, Debug, PartialEq)]
pub struct GridVar {
    pub name: String,
    pub ty: illume_rib::Type,
    /// Scalars per vertex (`ty.components() × array_len`).
    pub components: usize,
    /// `nu·nv·components` values, vertex-major.
    pub data: Vec<f32>,
}

/// The surface variable name under which a primitive hands the dicer a smooth default normal
/// (a subdivision surface's limit normal, a blobby's field gradient): taken as `N` but, unlike
/// a user's `N`, flipped with `Ng` by the orientation. Not a valid RIB identifier, so it can
/// not collide with a declared variable.
pub const SMOOTH_N: &str = "N(smooth)";

/// Surface variable names under which a primitive hands the dicer the `u`, `v` the shaders
/// see when they are not the surface's own parameters: a polygon's are its object-space
/// (x, y) (RI Spec 3.2 §5.1, as PRMan and Aqsis give). `du`, `dv` and `dPdu`, `dPdv` stay
/// those of the surface parameters. Not valid RIB identifiers.
pub const PARAM_U: &str = "u(object)";
pub const PARAM_V: &str = "v(object)";

/// `nu × nv` vertices, row-major with u fastest: vertex `(i, j)` is at `j * nu + i`.
/// All positions and vectors are in camera space.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Grid {
    pub nu: usize,
    pub nv: usize,
    pub p: Vec<Vec3>,
    /// Shading normal: the user's `N` if given, else a default (`ng`, or the smooth normal a
    /// subdivision surface or blobby provides, oriented like `ng`). Unit length.
    pub n: Vec<Vec3>,
    /// Whether `n` is the user's `N` primitive variable: the orientation flip (RI Spec 3.2
    /// `Orientation`, mirroring transforms) applies to `ng` and a default `n`, never to a
    /// normal the user supplied.
    pub user_normals: bool,
    /// Geometric normal `normalize(dPdu × dPdv)`, unflipped. Unit length (a degenerate point
    /// takes its neighbour's normal).
    pub ng: Vec<Vec3>,
    pub dpdu: Vec<Vec3>,
    pub dpdv: Vec<Vec3>,
    /// Surface parameters in the primitive's own (u, v) range.
    pub u: Vec<f32>,
    pub v: Vec<f32>,
    /// Parametric step between neighbouring vertices.
    pub du: f32,
    pub dv: f32,
    /// Texture coordinates: the user's s/t/st if given, else from `TextureCoordinates`.
    pub s: Vec<f32>,
    pub t: Vec<f32>,
    /// `Cs`/`Os` primitive variables when given (else the hider uses the attribute colours).
    pub cs: Option<Vec<Vec3>>,
    pub os: Option<Vec<Vec3>>,
    /// Any other primitive variables, for shader parameters of the same name.
    pub vars: Vec<GridVar>,
    /// Per micropolygon (`(nu-1)·(nv-1)`, u fastest): `true` where the surface is cut away
    /// (trim curves). Empty when nothing is hidden.
    pub hidden: Vec<bool>,
}

impl Grid {
    pub fn len(&self) -> usize {
        self.nu * self.nv
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

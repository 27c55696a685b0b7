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

/// `nu × nv` vertices, row-major with u fastest: vertex `(i, j)` is at `j * nu + i`.
/// All positions and vectors are in camera space.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Grid {
    pub nu: usize,
    pub nv: usize,
    pub p: Vec<Vec3>,
    /// Shading normal: the user's `N` if given, else equal to `ng`. Unit length.
    pub n: Vec<Vec3>,
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

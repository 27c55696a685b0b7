//! Polygon, GeneralPolygon, PointsPolygons and PointsGeneralPolygons (RI Spec 3.2 §5.1).
//!
//! Each face is projected onto the plane of its Newell normal and cut into pieces: a convex
//! quadrilateral without holes becomes one bilinear patch (corners 0, 1, 3, 2), anything else
//! is triangulated by ear clipping and each triangle becomes a bilinear patch whose last two
//! corners coincide. Primitive variables are interpolated with the same bilinear weights, so
//! over a triangle they are exactly linear. Without user `s`/`t`/`st`, texture coordinates are
//! the object-space (x, y) of the surface, as the spec defines a polygon's parameters.
use crate::ear_clipping::triangulate;
use crate::parametric::{with_default_st, Interp, Parametric, Surface, SurfaceVar};
use crate::patch::BilinearSurface;
use crate::primvar::{element64, resolve, surface_vars, ClassCounts, PrimVar};
use crate::{BuildContext, GeomError, Primitive};
use glam::{DVec2, DVec3};
use illume_rib::{Class, ParamList, Type};
use std::sync::Arc;

/// One corner of a face: its vertex (index into vertex/varying values) and its face corner
/// (index into facevarying values).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Corner {
    vertex: usize,
    face_corner: usize,
}

/// The faces of a polygon request: per face, its loops of corners (outer first).
struct Topology {
    faces: Vec<Vec<Vec<Corner>>>,
    vertices: usize,
}

fn invalid(request: &str, message: String) -> GeomError {
    GeomError::Invalid {
        request: request.to_string(),
        message,
    }
}

fn counts_of(request: &str, what: &str, v: &[i32]) -> Result<Vec<usize>, GeomError> {
    v.iter()
        .map(|&n| {
            usize::try_from(n)
                .map_err(|_| invalid(request, format!("{what} must not be negative, found {n}")))
        })
        .collect()
}

/// Builds the topology of `PointsGeneralPolygons` (the most general form; the other three
/// requests are special cases of it).
fn topology(
    request: &str,
    nloops: &[usize],
    nverts: &[usize],
    verts: Option<&[i32]>,
) -> Result<Topology, GeomError> {
    let total_loops: usize = nloops.iter().sum();
    if total_loops != nverts.len() {
        return Err(invalid(
            request,
            format!(
                "nloops adds up to {total_loops} loops but nverts has {} entries",
                nverts.len()
            ),
        ));
    }
    let total: usize = nverts.iter().sum();
    let vertex_of: Vec<usize> = match verts {
        Some(vs) => {
            if vs.len() != total {
                return Err(invalid(
                    request,
                    format!(
                        "nverts adds up to {total} corners but vertices has {} entries",
                        vs.len()
                    ),
                ));
            }
            counts_of(request, "vertex indices", vs)?
        }
        None => (0..total).collect(),
    };
    let vertices = vertex_of.iter().max().map_or(0, |m| m + 1);
    let mut faces = Vec::with_capacity(nloops.len());
    let (mut next_loop, mut next_corner) = (0, 0);
    for &nl in nloops {
        let mut face = Vec::with_capacity(nl);
        for &nv in &nverts[next_loop..next_loop + nl] {
            face.push(
                (next_corner..next_corner + nv)
                    .map(|fc| Corner {
                        vertex: vertex_of[fc],
                        face_corner: fc,
                    })
                    .collect::<Vec<_>>(),
            );
            next_corner += nv;
        }
        next_loop += nl;
        faces.push(face);
    }
    Ok(Topology { faces, vertices })
}

/// Builds any of the four polygon requests.
pub fn build_polygons(
    request: &illume_rib::Request,
    ctx: &BuildContext,
) -> Result<Vec<Box<dyn Primitive>>, GeomError> {
    use illume_rib::Request as R;
    let name = request.name();
    let (topo, params): (Topology, &ParamList) = match request {
        R::Polygon { params } => {
            let n = point_count(name, params)?;
            (topology(name, &[1], &[n], None)?, params)
        }
        R::GeneralPolygon { nverts, params } => {
            let nv = counts_of(name, "nverts", nverts)?;
            // Check against the points given before allocating per-corner tables.
            let (total, n) = (nv.iter().sum::<usize>(), point_count(name, params)?);
            if total != n {
                return Err(invalid(
                    name,
                    format!("nverts adds up to {total} vertices but {n} points were given"),
                ));
            }
            (topology(name, &[nv.len()], &nv, None)?, params)
        }
        R::PointsPolygons {
            nverts,
            verts,
            params,
        } => {
            let nv = counts_of(name, "nverts", nverts)?;
            (
                topology(name, &vec![1; nv.len()], &nv, Some(verts))?,
                params,
            )
        }
        R::PointsGeneralPolygons {
            nloops,
            nverts,
            verts,
            params,
        } => {
            let nl = counts_of(name, "nloops", nloops)?;
            let nv = counts_of(name, "nverts", nverts)?;
            (topology(name, &nl, &nv, Some(verts))?, params)
        }
        _ => return Err(GeomError::Unsupported(name.to_string())),
    };
    let corners: usize = topo.faces.iter().flatten().map(Vec::len).sum();
    let counts = ClassCounts {
        uniform: topo.faces.len(),
        varying: topo.vertices,
        vertex: topo.vertices,
        facevarying: corners,
    };
    let vars = resolve(name, params, ctx.declarations, &counts, ctx.warnings)?;
    let pts = positions(name, &vars)?;
    let mut out: Vec<Box<dyn Primitive>> = Vec::new();
    for (f, face) in topo.faces.iter().enumerate() {
        for piece in face_pieces(&pts, face) {
            let surface = BilinearSurface {
                p: piece.map(|c| ctx.camera_from_object.transform_point3(pts[c.vertex])),
            };
            let svars = surface_vars(&vars, &ctx.camera_from_object, |v| {
                piece_interp(v, f, &piece)
            });
            let mut svars = with_default_st(svars, default_st(&pts, &piece));
            svars.extend(object_uv(&pts, &piece));
            out.push(Box::new(Parametric::new(
                Arc::new(surface) as Arc<dyn Surface>,
                Arc::new(svars),
            )));
        }
    }
    Ok(out)
}

/// RI Spec 3.2 §5.1: "the surface parameters of a polygon are its (x, y) coordinates" and its
/// texture coordinates default to them (not to `TextureCoordinates`): object-space x, y.
fn default_st(pts: &[DVec3], piece: &[Corner; 4]) -> [SurfaceVar; 2] {
    let var = |name: &str, axis: fn(DVec3) -> f64| SurfaceVar {
        name: name.to_string(),
        ty: Type::Float,
        components: 1,
        interp: Interp::Bilinear(piece.map(|c| vec![axis(pts[c.vertex])])),
    };
    [var("s", |p| p.x), var("t", |p| p.y)]
}

/// A polygon's u, v: object-space x, y (RI Spec 3.2 §5.1), as PRMan and Aqsis give them,
/// rather than the parameters of the bilinear piece it is diced as.
fn object_uv(pts: &[DVec3], piece: &[Corner; 4]) -> [SurfaceVar; 2] {
    let [u, v] = default_st(pts, piece);
    [
        SurfaceVar {
            name: crate::grid::PARAM_U.to_string(),
            ..u
        },
        SurfaceVar {
            name: crate::grid::PARAM_V.to_string(),
            ..v
        },
    ]
}

fn piece_interp(var: &PrimVar, face: usize, piece: &[Corner; 4]) -> Interp {
    match var.class {
        Class::Constant => Interp::Constant(element64(var, 0)),
        Class::Uniform => Interp::Constant(element64(var, face)),
        Class::Varying | Class::Vertex => Interp::Bilinear(piece.map(|c| element64(var, c.vertex))),
        Class::FaceVarying | Class::FaceVertex => {
            Interp::Bilinear(piece.map(|c| element64(var, c.face_corner)))
        }
    }
}

/// Object-space vertex positions from `P` or `Pw` (divided by w).
fn positions(request: &str, vars: &[PrimVar]) -> Result<Vec<DVec3>, GeomError> {
    let pts: Vec<DVec3> = if let Some(p) = vars.iter().find(|v| v.name == "P") {
        p.floats()
            .chunks_exact(3)
            .map(|c| DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64))
            .collect()
    } else if let Some(p) = vars.iter().find(|v| v.name == "Pw") {
        p.floats()
            .chunks_exact(4)
            .map(|c| DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64) / c[3] as f64)
            .collect()
    } else {
        return Err(invalid(request, "needs \"P\" or \"Pw\"".to_string()));
    };
    if let Some(k) = pts.iter().position(|p| !p.is_finite()) {
        return Err(invalid(
            request,
            format!("vertex {k} is not finite: {}", pts[k]),
        ));
    }
    Ok(pts)
}

/// The bilinear pieces of one face, corners in patch order `(0,0), (1,0), (0,1), (1,1)`.
fn face_pieces(pts: &[DVec3], face: &[Vec<Corner>]) -> Vec<[Corner; 4]> {
    let loops: Vec<&Vec<Corner>> = face.iter().filter(|l| l.len() >= 3).collect();
    let Some(outer) = loops.first() else {
        return Vec::new();
    };
    // Newell's normal of the outer loop picks the projection plane (drop its largest axis).
    let normal = (0..outer.len()).fold(DVec3::ZERO, |n, i| {
        let (a, b) = (
            pts[outer[i].vertex],
            pts[outer[(i + 1) % outer.len()].vertex],
        );
        n + DVec3::new(
            (a.y - b.y) * (a.z + b.z),
            (a.z - b.z) * (a.x + b.x),
            (a.x - b.x) * (a.y + b.y),
        )
    });
    let na = normal.abs();
    if na.max_element().is_nan() || na.max_element() <= 0.0 {
        return Vec::new();
    }
    let project = |p: DVec3| {
        if na.z >= na.x && na.z >= na.y {
            DVec2::new(p.x, p.y)
        } else if na.y >= na.x {
            DVec2::new(p.z, p.x)
        } else {
            DVec2::new(p.y, p.z)
        }
    };
    let flat: Vec<Vec<DVec2>> = loops
        .iter()
        .map(|l| l.iter().map(|c| project(pts[c.vertex])).collect())
        .collect();
    if loops.len() == 1 && outer.len() == 4 && is_convex(&flat[0]) {
        return vec![[outer[0], outer[1], outer[3], outer[2]]];
    }
    let all: Vec<Corner> = loops.iter().flat_map(|l| l.iter().copied()).collect();
    // Triangles come out counter-clockwise in the projection; keep the file's winding (it
    // decides the geometric normal, hence Orientation and backface culling).
    let clockwise = signed_area(&flat[0]) < 0.0;
    triangulate(&flat)
        .into_iter()
        .map(|[a, b, c]| {
            let (b, c) = if clockwise { (c, b) } else { (b, c) };
            [all[a], all[b], all[c], all[c]]
        })
        .collect()
}

/// Strictly convex (every turn the same way, none straight).
fn is_convex(p: &[DVec2]) -> bool {
    let n = p.len();
    let turns: Vec<f64> = (0..n)
        .map(|i| (p[(i + 1) % n] - p[i]).perp_dot(p[(i + 2) % n] - p[(i + 1) % n]))
        .collect();
    turns.iter().all(|&t| t > 0.0) || turns.iter().all(|&t| t < 0.0)
}

fn signed_area(p: &[DVec2]) -> f64 {
    (0..p.len())
        .map(|i| p[i].perp_dot(p[(i + 1) % p.len()]))
        .sum::<f64>()
        * 0.5
}

/// How many points `P` (or `Pw`) holds, for the requests whose topology is implicit.
fn point_count(request: &str, params: &ParamList) -> Result<usize, GeomError> {
    params
        .iter()
        .find(|p| matches!(bare_name(&p.name), "P" | "Pw"))
        .map(|p| p.value.len() / if bare_name(&p.name) == "Pw" { 4 } else { 3 })
        .ok_or_else(|| invalid(request, "needs \"P\" or \"Pw\"".to_string()))
}

/// The variable name of a parameter token, without any inline declaration.
fn bare_name(token: &str) -> &str {
    illume_rib::Declaration::split_inline(token).map_or(token, |(_, n)| n)
}

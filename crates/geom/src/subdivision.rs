//! `SubdivisionMesh "catmull-clark"` (RI Spec 3.2 §5.6) with the `crease`, `corner`, `hole`
//! and `interpolateboundary` tags and every primitive-variable class.
//!
//! **Method**: a few uniform Catmull–Clark steps (Catmull & Clark 1978) with the semi-sharp
//! crease rules of DeRose, Kass & Truong 1998 (a sharpness-`s` edge uses the sharp rule for
//! `⌊s⌋` steps, blends for the fractional step, children get `s − 1`), then every vertex is
//! pushed to its **limit position** with the limit stencils (Halstead, Kass & DeRose 1993):
//! smooth `(n²·v + 4Σeⱼ + Σfⱼ) / (n(n+5))`, crease `(e₀ + 4v + e₁)/6`, corner `v`. Each
//! resulting quad is diced as a bilinear patch of limit points, with the area-weighted limit-
//! mesh vertex normals as `N` so shading is smooth.
//!
//! *Why not Stam's exact evaluation*: it only covers regular-or-one-extraordinary smooth
//! faces; creases, corners, holes and boundaries would need a second path anyway. Pushing
//! to the limit is one path for all tags, its points lie exactly on the limit surface, and
//! the remaining error (the bilinear facets between limit points) shrinks 4× per level.
//!
//! Everything is done in camera space: the rules are affine combinations, so they commute
//! with the affine camera transform.
//!
//! Boundaries: boundary edges always use the sharp rule. With `interpolateboundary` the
//! boundary is a cubic B-spline of the boundary polygon and valence-2 boundary vertices are
//! corners; without it, faces touching the boundary are not rendered (they only shape their
//! neighbours), as in PRMan.
use crate::parametric::{default_st, with_default_st, Interp, Parametric, Surface, SurfaceVar};
use crate::patch::BilinearSurface;
use crate::primvar::{camera_values, is_position, resolve, ClassCounts, PrimVar, PrimVarData};
use crate::{BuildContext, GeomError, Primitive};
use glam::{DMat4, DVec3};
use illume_rib::{Class, ParamList, Type};
use std::collections::HashMap;
use std::sync::Arc;

/// Refinement stops before the final quad count passes this (memory bound for huge meshes).
const MAX_QUADS: usize = 1 << 16;
/// Catmull–Clark steps for a small mesh (8×8 quads per original quad).
const MAX_LEVELS: usize = 3;

/// The arrays of one `SubdivisionMesh` request, as the RIB gives them.
#[derive(Clone, Copy, Debug)]
pub struct SubdivisionArgs<'a> {
    pub scheme: &'a str,
    pub nvertices: &'a [i32],
    pub vertices: &'a [i32],
    pub tags: &'a [String],
    pub nargs: &'a [i32],
    pub intargs: &'a [i32],
    pub floatargs: &'a [f32],
}

/// A polygon mesh with per-vertex rows (position first, then vertex variables), per-vertex
/// varying rows, per-face-corner facevarying rows, and the tags.
#[derive(Clone, Debug, Default)]
pub struct Mesh {
    /// Vertex indices of each face, in order.
    pub faces: Vec<Vec<usize>>,
    /// Per vertex: `x y z` then the vertex variables' components.
    pub rows: Vec<Vec<f64>>,
    /// Per vertex: varying variables (interpolated linearly).
    pub varying: Vec<Vec<f64>>,
    /// Per face, per corner: facevarying variables (interpolated linearly).
    pub facevarying: Vec<Vec<Vec<f64>>>,
    /// The original face each face descends from (its uniform values).
    pub origin: Vec<usize>,
    pub hole: Vec<bool>,
    /// Sharpness of creased edges, keyed by (smaller, larger) vertex index.
    pub crease: HashMap<(usize, usize), f64>,
    /// Corner sharpness per vertex (0 for none).
    pub corner: Vec<f64>,
    pub interpolate_boundary: bool,
}

/// Adjacency of a mesh: the faces around each edge and each vertex.
struct Topology {
    /// Edge index by sorted endpoint pair; `edges[e]` = (a, b, adjacent faces).
    edge_index: HashMap<(usize, usize), usize>,
    edges: Vec<(usize, usize, Vec<usize>)>,
    vertex_edges: Vec<Vec<usize>>,
    vertex_faces: Vec<Vec<usize>>,
}

fn key(a: usize, b: usize) -> (usize, usize) {
    (a.min(b), a.max(b))
}

impl Topology {
    fn new(m: &Mesh) -> Topology {
        let nv = m.rows.len();
        let mut t = Topology {
            edge_index: HashMap::new(),
            edges: Vec::new(),
            vertex_edges: vec![Vec::new(); nv],
            vertex_faces: vec![Vec::new(); nv],
        };
        for (f, face) in m.faces.iter().enumerate() {
            for (k, &a) in face.iter().enumerate() {
                let b = face[(k + 1) % face.len()];
                t.vertex_faces[a].push(f);
                let n = t.edges.len();
                let e = *t.edge_index.entry(key(a, b)).or_insert(n);
                if e == n {
                    t.edges.push((a, b, Vec::new()));
                    t.vertex_edges[a].push(e);
                    t.vertex_edges[b].push(e);
                }
                t.edges[e].2.push(f);
            }
        }
        t
    }

    fn is_boundary(&self, e: usize) -> bool {
        self.edges[e].2.len() != 2
    }

    fn other(&self, e: usize, v: usize) -> usize {
        let (a, b, _) = self.edges[e];
        if a == v {
            b
        } else {
            a
        }
    }
}

fn lerp_rows(a: &[f64], b: &[f64], t: f64) -> Vec<f64> {
    a.iter().zip(b).map(|(x, y)| x + (y - x) * t).collect()
}

fn average<'a>(rows: impl Iterator<Item = &'a Vec<f64>>, len: usize) -> Vec<f64> {
    let mut out = vec![0.0; len];
    let mut n = 0usize;
    for r in rows {
        out.iter_mut().zip(r).for_each(|(o, x)| *o += x);
        n += 1;
    }
    let inv = 1.0 / n.max(1) as f64;
    out.iter_mut().for_each(|o| *o *= inv);
    out
}

/// How a vertex moves: the sharp edges through it decide (DeRose et al. §3).
enum VertexRule {
    Smooth,
    /// Two sharp edges: the B-spline rule along them, blended with smooth by the sharpness.
    Crease([usize; 2], f64),
    /// A corner, or three or more sharp edges: the vertex stays (blended when semi-sharp).
    Corner(f64),
}

impl Mesh {
    fn edge_sharpness(&self, t: &Topology, e: usize) -> f64 {
        if t.is_boundary(e) {
            return f64::INFINITY;
        }
        let (a, b, _) = t.edges[e];
        self.crease.get(&key(a, b)).copied().unwrap_or(0.0)
    }

    fn vertex_rule(&self, t: &Topology, v: usize) -> VertexRule {
        let sharp: Vec<(usize, f64)> = t.vertex_edges[v]
            .iter()
            .map(|&e| (e, self.edge_sharpness(t, e)))
            .filter(|&(_, s)| s > 0.0)
            .collect();
        let on_boundary = t.vertex_edges[v].iter().any(|&e| t.is_boundary(e));
        let boundary_corner =
            self.interpolate_boundary && on_boundary && t.vertex_faces[v].len() == 1;
        if self.corner[v] > 0.0 || boundary_corner || sharp.len() > 2 {
            let s = if boundary_corner || sharp.len() > 2 {
                f64::INFINITY
            } else {
                self.corner[v]
            };
            return VertexRule::Corner(s);
        }
        match sharp.as_slice() {
            [(e0, s0), (e1, s1)] => {
                VertexRule::Crease([t.other(*e0, v), t.other(*e1, v)], 0.5 * (s0 + s1))
            }
            // A boundary vertex with fewer than two boundary edges (non-manifold): keep it.
            _ if on_boundary => VertexRule::Corner(f64::INFINITY),
            _ => VertexRule::Smooth,
        }
    }

    /// One Catmull–Clark step: face points, edge points, moved vertices, quads.
    fn subdivide(&self) -> Mesh {
        let t = Topology::new(self);
        let (nv, nf) = (self.rows.len(), self.faces.len());
        let d = self.rows.first().map_or(3, Vec::len);
        let dvar = self.varying.first().map_or(0, Vec::len);
        let face_pts: Vec<Vec<f64>> = self
            .faces
            .iter()
            .map(|f| average(f.iter().map(|&v| &self.rows[v]), d))
            .collect();
        let face_var: Vec<Vec<f64>> = self
            .faces
            .iter()
            .map(|f| average(f.iter().map(|&v| &self.varying[v]), dvar))
            .collect();
        let mut rows = self.rows.clone();
        let mut varying = self.varying.clone();
        // Moved original vertices.
        for (v, moved) in rows.iter_mut().enumerate().take(nv) {
            let n = t.vertex_edges[v].len();
            if n == 0 {
                continue;
            }
            let smooth = || {
                let q = average(t.vertex_faces[v].iter().map(|&f| &face_pts[f]), d);
                let mids: Vec<Vec<f64>> = t.vertex_edges[v]
                    .iter()
                    .map(|&e| lerp_rows(&self.rows[v], &self.rows[t.other(e, v)], 0.5))
                    .collect();
                let r = average(mids.iter(), d);
                let nf = n as f64;
                (0..d)
                    .map(|k| (q[k] + 2.0 * r[k] + (nf - 3.0) * self.rows[v][k]) / nf)
                    .collect::<Vec<f64>>()
            };
            *moved = match self.vertex_rule(&t, v) {
                VertexRule::Smooth => smooth(),
                VertexRule::Crease([a, b], s) => {
                    let sharp: Vec<f64> = (0..d)
                        .map(|k| (self.rows[a][k] + 6.0 * self.rows[v][k] + self.rows[b][k]) / 8.0)
                        .collect();
                    if s >= 1.0 {
                        sharp
                    } else {
                        lerp_rows(&smooth(), &sharp, s)
                    }
                }
                VertexRule::Corner(s) if s >= 1.0 => self.rows[v].clone(),
                VertexRule::Corner(s) => lerp_rows(&smooth(), &self.rows[v], s),
            };
        }
        rows.extend(face_pts);
        varying.extend(face_var);
        // Edge points.
        for (e, (a, b, faces)) in t.edges.iter().enumerate() {
            let mid = lerp_rows(&self.rows[*a], &self.rows[*b], 0.5);
            let s = self.edge_sharpness(&t, e);
            let p = if s >= 1.0 {
                mid
            } else {
                let f = average(faces.iter().map(|&f| &rows[nv + f]), d);
                let smooth = lerp_rows(&mid, &f, 0.5);
                lerp_rows(&smooth, &mid, s)
            };
            rows.push(p);
            varying.push(lerp_rows(&self.varying[*a], &self.varying[*b], 0.5));
        }
        let edge_point = |a: usize, b: usize| nv + nf + t.edge_index[&key(a, b)];
        let mut out = Mesh {
            rows,
            varying,
            interpolate_boundary: self.interpolate_boundary,
            ..Mesh::default()
        };
        for (f, face) in self.faces.iter().enumerate() {
            let n = face.len();
            let fv = &self.facevarying[f];
            let fv_centre = average(fv.iter(), fv.first().map_or(0, Vec::len));
            for k in 0..n {
                let (prev, cur, next) = (face[(k + n - 1) % n], face[k], face[(k + 1) % n]);
                out.faces.push(vec![
                    cur,
                    edge_point(cur, next),
                    nv + f,
                    edge_point(prev, cur),
                ]);
                out.facevarying.push(vec![
                    fv[k].clone(),
                    lerp_rows(&fv[k], &fv[(k + 1) % n], 0.5),
                    fv_centre.clone(),
                    lerp_rows(&fv[(k + n - 1) % n], &fv[k], 0.5),
                ]);
                out.origin.push(self.origin[f]);
                out.hole.push(self.hole[f]);
            }
        }
        for (&(a, b), &s) in &self.crease {
            if s > 1.0 && t.edge_index.contains_key(&(a, b)) {
                let m = edge_point(a, b);
                out.crease.insert(key(a, m), s - 1.0);
                out.crease.insert(key(m, b), s - 1.0);
            }
        }
        out.corner = vec![0.0; out.rows.len()];
        for (v, &s) in self.corner.iter().enumerate() {
            out.corner[v] = (s - 1.0).max(0.0);
        }
        out
    }

    /// Every vertex moved to its limit position (all faces must be quads: call after one
    /// subdivision step). Only the position and vertex rows move; varying values stay.
    pub fn push_to_limit(&mut self) {
        let t = Topology::new(self);
        let d = self.rows.first().map_or(3, Vec::len);
        let rows = &self.rows;
        let limit: Vec<Vec<f64>> = (0..rows.len())
            .map(|v| {
                let n = t.vertex_edges[v].len();
                if n == 0 {
                    return rows[v].clone();
                }
                match self.vertex_rule(&t, v) {
                    VertexRule::Corner(_) => rows[v].clone(),
                    VertexRule::Crease([a, b], _) => (0..d)
                        .map(|k| (rows[a][k] + 4.0 * rows[v][k] + rows[b][k]) / 6.0)
                        .collect(),
                    VertexRule::Smooth => {
                        let nf = n as f64;
                        let mut acc: Vec<f64> = rows[v].iter().map(|x| nf * nf * x).collect();
                        for &e in &t.vertex_edges[v] {
                            let o = &rows[t.other(e, v)];
                            acc.iter_mut().zip(o).for_each(|(a, x)| *a += 4.0 * x);
                        }
                        for &f in &t.vertex_faces[v] {
                            let face = &self.faces[f];
                            let k = face.iter().position(|&x| x == v).unwrap_or(0);
                            let o = &rows[face[(k + 2) % face.len()]];
                            acc.iter_mut().zip(o).for_each(|(a, x)| *a += x);
                        }
                        acc.iter().map(|a| a / (nf * (nf + 5.0))).collect()
                    }
                }
            })
            .collect();
        self.rows = limit;
    }

    /// Subdivides `levels ≥ 1` times and pushes to the limit.
    pub fn limit_mesh(&self, levels: usize) -> Mesh {
        let mut m = self.subdivide();
        for _ in 1..levels {
            m = m.subdivide();
        }
        m.push_to_limit();
        m
    }

    /// `levels ≥ 1` plain subdivision steps (no limit push).
    pub fn subdivided(&self, levels: usize) -> Mesh {
        let mut m = self.clone();
        for _ in 0..levels {
            m = m.subdivide();
        }
        m
    }

    /// Position of vertex `v`.
    pub fn position(&self, v: usize) -> DVec3 {
        DVec3::new(self.rows[v][0], self.rows[v][1], self.rows[v][2])
    }

    /// Whether face `f` has a vertex on the boundary of the mesh.
    fn touches_boundary(&self, t: &Topology, f: usize) -> bool {
        self.faces[f]
            .iter()
            .any(|&v| t.vertex_edges[v].iter().any(|&e| t.is_boundary(e)))
    }
}

/// Builds a `SubdivisionMesh`.
pub fn build_subdivision(
    a: SubdivisionArgs,
    params: &ParamList,
    ctx: &BuildContext,
) -> Result<Vec<Box<dyn Primitive>>, GeomError> {
    let (mesh, vars) = control_mesh_of(a, params, ctx)?;
    let corners: usize = mesh.faces.iter().map(Vec::len).sum();
    let mut levels = 1;
    while levels < MAX_LEVELS && corners << (2 * levels) <= MAX_QUADS {
        levels += 1;
    }
    let limit = mesh.limit_mesh(levels);
    Ok(quads(&limit, &mesh, &vars, ctx))
}

/// The control mesh of a request in camera space, with its tags, and the resolved variables.
pub fn control_mesh_of(
    a: SubdivisionArgs,
    params: &ParamList,
    ctx: &BuildContext,
) -> Result<(Mesh, Vec<PrimVar>), GeomError> {
    let invalid = |message: String| GeomError::Invalid {
        request: "SubdivisionMesh".to_string(),
        message,
    };
    if a.scheme != "catmull-clark" {
        return Err(GeomError::Unsupported(format!(
            "SubdivisionMesh \"{}\"",
            a.scheme
        )));
    }
    let (faces, nverts) = faces(a.nvertices, a.vertices).map_err(invalid)?;
    let corners: usize = faces.iter().map(Vec::len).sum();
    let counts = ClassCounts {
        uniform: faces.len(),
        varying: nverts,
        vertex: nverts,
        facevarying: corners,
    };
    let vars = resolve(
        "SubdivisionMesh",
        params,
        ctx.declarations,
        &counts,
        ctx.warnings,
    )?;
    let mut mesh = control_mesh(faces, nverts, &vars, &ctx.camera_from_object).map_err(invalid)?;
    apply_tags(&mut mesh, &a).map_err(invalid)?;
    Ok((mesh, vars))
}

/// Splits `vertices` by `nvertices`; the vertex count is the largest index + 1.
fn faces(nvertices: &[i32], vertices: &[i32]) -> Result<(Vec<Vec<usize>>, usize), String> {
    let mut out = Vec::with_capacity(nvertices.len());
    let mut at = 0usize;
    for (f, &n) in nvertices.iter().enumerate() {
        if n < 3 {
            return Err(format!("face {f} has {n} vertices, needs at least 3"));
        }
        let idx = vertices.get(at..at + n as usize).ok_or_else(|| {
            format!(
                "vertices has {} indices, nvertices needs more",
                vertices.len()
            )
        })?;
        if let Some(bad) = idx.iter().find(|&&i| i < 0) {
            return Err(format!("face {f}: negative vertex index {bad}"));
        }
        out.push(idx.iter().map(|&i| i as usize).collect());
        at += n as usize;
    }
    if at != vertices.len() {
        return Err(format!(
            "vertices has {} indices, nvertices adds up to {at}",
            vertices.len()
        ));
    }
    let nverts = out.iter().flatten().max().map_or(0, |&m| m + 1);
    Ok((out, nverts))
}

/// The control mesh in camera space with its vertex, varying and facevarying rows.
fn control_mesh(
    faces: Vec<Vec<usize>>,
    nverts: usize,
    vars: &[PrimVar],
    m: &DMat4,
) -> Result<Mesh, String> {
    let p = vars.iter().find(|v| v.name == "P").ok_or("needs \"P\"")?;
    let camera = |var: &PrimVar| camera_values(var, m);
    let numeric = |class: Class| {
        vars.iter()
            .filter(move |v| v.class == class && !is_position(v))
            .filter(|v| matches!(v.data, PrimVarData::Floats(_)))
    };
    let pos = camera(p);
    if let Some(k) = pos.iter().position(|x| !x.is_finite()) {
        return Err(format!("P value {k} is not finite"));
    }
    let gather = |class: Class, n: usize| -> Vec<Vec<f64>> {
        let cols: Vec<(usize, Vec<f64>)> = numeric(class)
            .map(|v| (v.element_size(), camera(v)))
            .collect();
        (0..n)
            .map(|i| {
                cols.iter()
                    .flat_map(|(c, vals)| vals[i * c..(i + 1) * c].iter().copied())
                    .collect()
            })
            .collect()
    };
    let vertex_vars = gather(Class::Vertex, nverts);
    let rows = (0..nverts)
        .map(|i| {
            let mut r = pos[3 * i..3 * i + 3].to_vec();
            r.extend_from_slice(&vertex_vars[i]);
            r
        })
        .collect();
    let corners: usize = faces.iter().map(Vec::len).sum();
    let fv_flat = gather(Class::FaceVarying, corners);
    let mut at = 0;
    let facevarying = faces
        .iter()
        .map(|f| {
            let c = fv_flat[at..at + f.len()].to_vec();
            at += f.len();
            c
        })
        .collect();
    let nf = faces.len();
    Ok(Mesh {
        faces,
        rows,
        varying: gather(Class::Varying, nverts),
        facevarying,
        origin: (0..nf).collect(),
        hole: vec![false; nf],
        crease: HashMap::new(),
        corner: vec![0.0; nverts],
        interpolate_boundary: false,
    })
}

/// Reads `crease`, `corner`, `hole`, `interpolateboundary` (RI Spec 3.2 §5.6); other tags are
/// ignored.
fn apply_tags(mesh: &mut Mesh, a: &SubdivisionArgs) -> Result<(), String> {
    if a.nargs.len() != 2 * a.tags.len() {
        return Err(format!(
            "nargs has {} values, expected 2 per tag ({})",
            a.nargs.len(),
            2 * a.tags.len()
        ));
    }
    let (mut ia, mut fa) = (0usize, 0usize);
    let nverts = mesh.rows.len();
    for (k, tag) in a.tags.iter().enumerate() {
        let (ni, nf) = (
            a.nargs[2 * k].max(0) as usize,
            a.nargs[2 * k + 1].max(0) as usize,
        );
        let ints = a
            .intargs
            .get(ia..ia + ni)
            .ok_or_else(|| format!("tag \"{tag}\": intargs too short"))?;
        let floats = a
            .floatargs
            .get(fa..fa + nf)
            .ok_or_else(|| format!("tag \"{tag}\": floatargs too short"))?;
        (ia, fa) = (ia + ni, fa + nf);
        let vertex = |i: i32| -> Result<usize, String> {
            (i >= 0 && (i as usize) < nverts)
                .then_some(i as usize)
                .ok_or_else(|| format!("tag \"{tag}\": vertex {i} out of range"))
        };
        match tag.as_str() {
            "crease" => {
                let s = f64::from(floats.first().copied().unwrap_or(0.0));
                for w in ints.windows(2) {
                    let (a, b) = (vertex(w[0])?, vertex(w[1])?);
                    mesh.crease.insert(key(a, b), s);
                }
            }
            "corner" => {
                for (j, &i) in ints.iter().enumerate() {
                    let s = floats.get(j).or(floats.first()).copied().unwrap_or(0.0);
                    mesh.corner[vertex(i)?] = f64::from(s);
                }
            }
            "hole" => {
                for &f in ints {
                    let f = usize::try_from(f)
                        .ok()
                        .filter(|&f| f < mesh.faces.len())
                        .ok_or_else(|| format!("tag \"hole\": face {f} out of range"))?;
                    mesh.hole[f] = true;
                }
            }
            "interpolateboundary" => {
                mesh.interpolate_boundary = ints.first().is_none_or(|&i| i != 0)
            }
            _ => {}
        }
    }
    Ok(())
}

/// One bilinear [`Parametric`] per rendered quad of the limit mesh.
fn quads(
    limit: &Mesh,
    control: &Mesh,
    vars: &[PrimVar],
    ctx: &BuildContext,
) -> Vec<Box<dyn Primitive>> {
    let coarse = Topology::new(control);
    let normals = vertex_normals(limit);
    let st = default_st(
        &ctx.texture_coordinates,
        [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]],
    );
    let numeric = |class: Class| -> Vec<&PrimVar> {
        vars.iter()
            .filter(|v| v.class == class && !is_position(v))
            .filter(|v| matches!(v.data, PrimVarData::Floats(_)))
            .collect()
    };
    let (vertex, varying, facevarying) = (
        numeric(Class::Vertex),
        numeric(Class::Varying),
        numeric(Class::FaceVarying),
    );
    let uniform: Vec<(&PrimVar, Vec<f64>)> = numeric(Class::Uniform)
        .into_iter()
        .chain(numeric(Class::Constant))
        .map(|v| (v, camera_values(v, &ctx.camera_from_object)))
        .collect();
    let skip_boundary = !control.interpolate_boundary;
    let mut out: Vec<Box<dyn Primitive>> = Vec::with_capacity(limit.faces.len());
    for (f, face) in limit.faces.iter().enumerate() {
        if limit.hole[f] || (skip_boundary && control.touches_boundary(&coarse, limit.origin[f])) {
            continue;
        }
        // Cyclic a b c d → bilinear corners (0,0)=a (1,0)=b (0,1)=d (1,1)=c.
        let order = [face[0], face[1], face[3], face[2]];
        let fv_order = [0, 1, 3, 2];
        let surface: Arc<dyn Surface> = Arc::new(BilinearSurface {
            p: order.map(|v| limit.position(v)),
        });
        let mut svars = Vec::new();
        let mut push = |name: &str, ty: Type, components: usize, interp: Interp| {
            svars.push(SurfaceVar {
                name: name.to_string(),
                ty,
                components,
                interp,
            })
        };
        let mut columns = |list: &[&PrimVar], row: &dyn Fn(usize) -> Vec<f64>, start: usize| {
            let mut at = start;
            for v in list {
                let c = v.element_size();
                let corners = std::array::from_fn(|k| row(k)[at..at + c].to_vec());
                push(&v.name, v.ty, c, Interp::Bilinear(corners));
                at += c;
            }
        };
        columns(&vertex, &|k| limit.rows[order[k]].clone(), 3);
        columns(&varying, &|k| limit.varying[order[k]].clone(), 0);
        columns(
            &facevarying,
            &|k| limit.facevarying[f][fv_order[k]].clone(),
            0,
        );
        for (v, values) in &uniform {
            let c = v.element_size();
            let i = if v.class == Class::Uniform {
                limit.origin[f]
            } else {
                0
            };
            svars.push(SurfaceVar {
                name: v.name.clone(),
                ty: v.ty,
                components: c,
                interp: Interp::Constant(values[i * c..(i + 1) * c].to_vec()),
            });
        }
        if !svars.iter().any(|v| v.name == "N") {
            svars.push(SurfaceVar {
                name: crate::grid::SMOOTH_N.to_string(),
                ty: Type::Normal,
                components: 3,
                interp: Interp::Bilinear(order.map(|v| normals[v].to_array().to_vec())),
            });
        }
        out.push(Box::new(Parametric::new(
            surface,
            Arc::new(with_default_st(svars, st.clone())),
        )));
    }
    out
}

/// Area-weighted normals of the limit mesh (its quads' `(c−a)×(d−b)`), oriented like
/// `dPdu × dPdv` of the bilinear pieces.
fn vertex_normals(m: &Mesh) -> Vec<DVec3> {
    let mut n = vec![DVec3::ZERO; m.rows.len()];
    for face in &m.faces {
        let [a, b, c, d] = [face[0], face[1], face[2], face[3]].map(|v| m.position(v));
        let fnrm = (c - a).cross(d - b);
        for &v in face {
            n[v] += fnrm;
        }
    }
    n.into_iter().map(|x| x.normalize_or_zero()).collect()
}

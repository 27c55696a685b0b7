//! `Option "limits" "memory"`: the frame's memory, estimated as the world is read, against a
//! budget, so that a scene too big for the machine ends in an error at the request that went
//! over rather than in the kernel's out-of-memory killer.
//!
//! The estimate is what the frame's primitives take once built: a fixed cost per built
//! primitive (its `FramePrimitive`, the boxed surface and its variables, measured with
//! heaptrack on 10⁵ spheres) plus its data (every number of its parameter lists and index arrays, counted
//! twice: geometry converts positions to f64 or splits them into faces), plus the texture
//! cache's own budget (`texturememory`). A shared object instance counts as one primitive, or
//! as one placement when it joins a run of instances (`instance_batch.rs`), and a mesh kept as
//! its request as one primitive and its numbers: their primitives exist only while the hider
//! works on the buckets they cover. Past the budget the primitive is culled with one
//! error naming its `file:line:col`, and so is every later one of the same world (PRMan culls
//! too); the frame still renders what fitted.
use crate::state::Ri;
use illume_rib::{ParamList, Request, Span};

/// Bytes one built primitive costs besides its data (see the module documentation): heaptrack
/// counts 98.6 MB at the peak of 10⁵ spheres outside the crop window (986 bytes each).
pub const PER_PRIMITIVE: u64 = 1024;

/// Bytes an `ObjectInstance` costs when it joins a run of instances (`instance_batch.rs`):
/// its placement's affine matrix (96 bytes), with room for the run's growth.
pub const PER_PLACEMENT: u64 = 128;

/// The parameter list of a geometry request.
fn params(req: &Request) -> Option<&ParamList> {
    use Request::*;
    match req {
        Polygon { params }
        | GeneralPolygon { params, .. }
        | PointsPolygons { params, .. }
        | PointsGeneralPolygons { params, .. }
        | Patch { params, .. }
        | PatchMesh { params, .. }
        | NuPatch { params, .. }
        | Sphere { params, .. }
        | Cone { params, .. }
        | Cylinder { params, .. }
        | Hyperboloid { params, .. }
        | Paraboloid { params, .. }
        | Disk { params, .. }
        | Torus { params, .. }
        | Points { params }
        | Curves { params, .. }
        | SubdivisionMesh { params, .. }
        | Blobby { params, .. }
        | Geometry { params, .. } => Some(params),
        _ => None,
    }
}

/// The numbers of a request's index arrays (vertex counts and indices).
fn indices(req: &Request) -> usize {
    use Request::*;
    match req {
        GeneralPolygon { nverts, .. } => nverts.len(),
        PointsPolygons { nverts, verts, .. } => nverts.len() + verts.len(),
        PointsGeneralPolygons {
            nloops,
            nverts,
            verts,
            ..
        } => nloops.len() + nverts.len() + verts.len(),
        NuPatch { uknot, vknot, .. } => uknot.len() + vknot.len(),
        Curves { nvertices, .. } => nvertices.len(),
        SubdivisionMesh {
            nvertices,
            vertices,
            intargs,
            floatargs,
            ..
        } => nvertices.len() + vertices.len() + intargs.len() + floatargs.len(),
        Blobby { code, floats, .. } => code.len() + floats.len(),
        _ => 0,
    }
}

/// The estimated bytes of the `primitives` a geometry request built.
pub fn request_bytes(req: &Request, primitives: usize) -> u64 {
    let values: usize = params(req).map_or(0, |ps| ps.iter().map(|p| p.value.len()).sum());
    PER_PRIMITIVE * primitives as u64 + 8 * (values + indices(req)) as u64
}

impl Ri {
    /// Adds `bytes` to the frame's estimate; false (and, the first time in this world, an
    /// error at `span`) when that goes over `Option "limits" "memory"`: the caller culls.
    pub(crate) fn charge_memory(&mut self, bytes: u64, span: &Span, request: &str) -> bool {
        if self.memory_exceeded {
            return false;
        }
        let limits = &self.options.limits;
        let texture = u64::from(self.options.texture_memory) * 1024;
        let total = self
            .frame_bytes
            .saturating_add(bytes)
            .saturating_add(texture);
        if total <= limits.memory {
            self.frame_bytes += bytes;
            return true;
        }
        let mb = |b: u64| b.div_ceil(1 << 20);
        let message = format!(
            "the frame's geometry ({} MB estimated, with this primitive) and texture cache ({} MB) \
             exceed Option \"limits\" \"memory\" {} MB: this primitive and the rest of the world \
             are culled",
            mb(self.frame_bytes + bytes),
            mb(texture),
            mb(limits.memory)
        );
        self.diagnostics
            .error_kind(crate::ErrorKind::Limit, span, request, message);
        self.memory_exceeded = true;
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn data_counts_every_number_and_index() {
        let rib = "PointsPolygons [3 3] [0 1 2 0 2 3] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0]\n";
        let req = illume_rib::Parser::new(rib.as_bytes(), "t.rib")
            .next()
            .unwrap()
            .unwrap()
            .value;
        // 2 counts + 6 indices + 12 coordinates, 8 bytes each, and one primitive.
        assert_eq!(request_bytes(&req, 1), PER_PRIMITIVE + 8 * 20);
    }
}

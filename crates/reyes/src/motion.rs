//! Motion blur and depth of field in the hider: a grid whose vertices move over the shutter
//! (motion keys diced at one `nu × nv`, linearly interpolated) or shift with the lens position.
//!
//! Shading happened once, at the first key (PRMan's default: shading at shutter open); only
//! positions move. Each micropolygon is bounded over every key (a vertex moving linearly in
//! camera space moves along a straight line in raster space, so the keys' raster box holds its
//! whole path) and grown by the circle of confusion over its depth range; every sample in that
//! box is then tested against the micropolygon moved to the sample's own time and lens
//! position, with the same edge rules as a still micropolygon.
use crate::dice::ShadedGrid;
use crate::lens::Lens;
use crate::sample_buffer::{split_quad, Hit, RasterTriangle, SampleBuffer};
use glam::{DVec3, Vec3};
use illume_ri::motion::segment;
use illume_ri::Camera;

/// The camera-space positions of a grid at each motion key (one key: depth of field only).
pub(crate) struct GridMotion {
    pub times: Vec<f64>,
    pub keys: Vec<Vec<Vec3>>,
}

impl GridMotion {
    fn at(&self, v: usize, (k, w): (usize, f64)) -> DVec3 {
        let a = self.keys[k][v].as_dvec3();
        if w == 0.0 || self.keys.len() == 1 {
            return a;
        }
        let b = self.keys[k + 1][v].as_dvec3();
        a + (b - a) * w
    }
}

/// Most shutter sub-intervals a micropolygon's path is cut into.
const MAX_SUBFRAMES: usize = 16;

/// Raster boxes `[x0, x1, y0, y1]` of a micropolygon over each of `n` equal sub-intervals of
/// the shutter, so a sample is tested in full only if it lies in the box of its own time: a
/// micropolygon sweeping 40 pixels has most of its candidate samples at times when it is
/// elsewhere. A vertex moves linearly in camera space between keys, hence along a straight
/// raster line (a projective map keeps lines), so the box of its positions at the ends of a
/// sub-interval and at any key inside it holds its whole path there.
fn subframe_boxes(
    m: &GridMotion,
    quad: &[usize; 4],
    [open, close]: [f64; 2],
    n: usize,
    project: &dyn Fn(DVec3) -> Option<DVec3>,
) -> Option<Vec<[f64; 4]>> {
    let mut boxes = Vec::with_capacity(n);
    let at = |t: f64| -> Option<[DVec3; 4]> {
        let seg = segment(&m.times, t);
        let mut v = [DVec3::ZERO; 4];
        for (q, &k) in v.iter_mut().zip(quad) {
            *q = project(m.at(k, seg)).filter(|q| q.is_finite())?;
        }
        Some(v)
    };
    let mut start = at(open)?;
    for s in 0..n {
        let (ta, tb) = (
            open + (close - open) * s as f64 / n as f64,
            open + (close - open) * (s + 1) as f64 / n as f64,
        );
        let end = at(tb)?;
        let mut b = [f64::MAX, f64::MIN, f64::MAX, f64::MIN];
        let mut add = |v: &[DVec3; 4]| {
            for q in v {
                b = [b[0].min(q.x), b[1].max(q.x), b[2].min(q.y), b[3].max(q.y)];
            }
        };
        add(&start);
        add(&end);
        for (k, &t) in m.times.iter().enumerate() {
            if t > ta && t < tb {
                let mut v = [DVec3::ZERO; 4];
                for (q, &i) in v.iter_mut().zip(quad) {
                    *q = project(m.keys[k][i].as_dvec3()).filter(|q| q.is_finite())?;
                }
                add(&v);
            }
        }
        boxes.push(b);
        start = end;
    }
    Some(boxes)
}

/// Cuts the shutter so each sub-interval moves micropolygon `quad` about 2 pixels (given its
/// raster box `[x0, x1, y0, y1]` over every key): the number of sub-intervals and, when more
/// than one, the micropolygon's box in each (see [`subframe_boxes`]).
fn shutter_cut(
    m: &GridMotion,
    quad: &[usize; 4],
    [x0, x1, y0, y1]: [f64; 4],
    [open, close]: [f64; 2],
    project: &impl Fn(DVec3) -> Option<DVec3>,
) -> (usize, Option<Vec<[f64; 4]>>) {
    let (w0, h0) = {
        let v: Vec<DVec3> = quad
            .iter()
            .filter_map(|&k| project(m.keys[0][k].as_dvec3()))
            .collect();
        let f = |g: fn(&DVec3) -> f64| {
            let xs = v.iter().map(g);
            xs.clone().fold(f64::MIN, f64::max) - xs.fold(f64::MAX, f64::min)
        };
        (f(|q| q.x), f(|q| q.y))
    };
    let sweep = ((x1 - x0) - w0).max((y1 - y0) - h0).max(0.0);
    let n_sub = if m.keys.len() > 1 && close > open {
        ((sweep / 2.0).ceil() as usize).clamp(1, MAX_SUBFRAMES)
    } else {
        1
    };
    let sub = if n_sub > 1 {
        subframe_boxes(m, quad, [open, close], n_sub, project)
    } else {
        None
    };
    (n_sub, sub)
}

/// Samples every micropolygon of a moving or lens-blurred grid; returns the samples hit.
pub(crate) fn sample_moving_grid(
    g: &ShadedGrid,
    m: &GridMotion,
    id: usize,
    cam: &Camera,
    lens: Option<&Lens>,
    out: &mut SampleBuffer,
) -> u64 {
    let persp = cam.is_perspective();
    let project = |p: DVec3| -> Option<DVec3> {
        if persp && p.z <= 0.0 {
            return None;
        }
        cam.raster_from_camera(p)
    };
    let mut hits = 0;
    for j in 0..g.nv - 1 {
        for i in 0..g.nu - 1 {
            hits += sample_moving_micropolygon(g, m, id, [i, j], &project, persp, lens, out);
        }
    }
    hits
}

/// Samples micropolygon `(i, j)` of a moving grid over every sample its path (and circle of
/// confusion) may reach; returns the samples hit.
#[allow(clippy::too_many_arguments)]
fn sample_moving_micropolygon(
    g: &ShadedGrid,
    m: &GridMotion,
    id: usize,
    [i, j]: [usize; 2],
    project: &impl Fn(DVec3) -> Option<DVec3>,
    persp: bool,
    lens: Option<&Lens>,
    out: &mut SampleBuffer,
) -> u64 {
    let nu = g.nu;
    let mut hits = 0;
    let mp = j * (nu - 1) + i;
    if g.backface[mp] {
        return 0;
    }
    let a = j * nu + i;
    let quad = [a, a + 1, a + nu + 1, a + nu];
    // Raster box over every key, depth range for the circle of confusion.
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    let (mut z0, mut z1) = (f64::MAX, f64::MIN);
    for key in &m.keys {
        for &v in &quad {
            let Some(q) = project(key[v].as_dvec3()) else {
                return hits;
            };
            if !q.is_finite() {
                return hits;
            }
            (x0, x1, y0, y1) = (x0.min(q.x), x1.max(q.x), y0.min(q.y), y1.max(q.y));
            (z0, z1) = (z0.min(q.z), z1.max(q.z));
        }
    }
    let reach = g.border_reach(i, j);
    let [bottom, right, top, left] = reach;
    let grow = bottom.max(top).max(left).max(right);
    let (gx, gy) = match lens {
        Some(l) => l.blur_radius(z0, z1),
        None => (0.0, 0.0),
    };
    let [ox, oy] = out.origin;
    let [sw, sh] = out.size;
    let qx0 = ((x0 - grow - gx).floor() as i32 - ox).max(0);
    let qx1 = ((x1 + grow + gx).floor() as i32 - ox).min(sw as i32 - 1);
    let qy0 = ((y0 - grow - gy).floor() as i32 - oy).max(0);
    let qy1 = ((y1 + grow + gy).floor() as i32 - oy).min(sh as i32 - 1);
    if qx0 > qx1 || qy0 > qy1 {
        return 0;
    }
    let order = ((id as u64) << 32) | mp as u64;
    let [open, close] = out.shutter.map(f64::from);
    let (n_sub, sub) = shutter_cut(m, &quad, [x0, x1, y0, y1], [open, close], project);
    let key_box = [x0, x1, y0, y1];
    let pad = grow + 1e-6;
    for qy in qy0..=qy1 {
        for qx in qx0..=qx1 {
            let base = (qy as usize * sw + qx as usize) * out.n_per;
            for s in base..base + out.n_per {
                let (t, l) = out.time_lens[s];
                let (x, y) = (f64::from(out.pos[s].0), f64::from(out.pos[s].1));
                // The pinhole box at this sample's time, shifted by this sample's lens
                // offset over the micropolygon's depth range: most candidates end here.
                let b = match &sub {
                    Some(boxes) => {
                        let k = (((f64::from(t) - open) / (close - open)) * n_sub as f64)
                            .floor()
                            .clamp(0.0, (n_sub - 1) as f64);
                        boxes[k as usize]
                    }
                    None => key_box,
                };
                let (ex, ey) = match lens {
                    Some(lens) => lens.offset_range(z0, z1, l),
                    None => ([0.0; 2], [0.0; 2]),
                };
                if x < b[0] + ex[0] - pad
                    || x > b[1] + ex[1] + pad
                    || y < b[2] + ey[0] - pad
                    || y > b[3] + ey[1] + pad
                {
                    continue;
                }
                let seg = segment(&m.times, f64::from(t));
                let mut v = [DVec3::ZERO; 4];
                for (vk, &k) in v.iter_mut().zip(&quad) {
                    let Some(mut q) = project(m.at(k, seg)) else {
                        return hits;
                    };
                    if let Some(lens) = lens {
                        let (dx, dy) = lens.offset(q.z, l);
                        q.x += dx;
                        q.y += dy;
                    }
                    *vk = q;
                }
                for (tri, reach) in split_quad([0, 1, 2, 3], reach) {
                    let Some(t) = RasterTriangle::new(tri.map(|k| v[k]), tri, reach) else {
                        continue;
                    };
                    let Some(w) = t.covers(x, y) else {
                        continue;
                    };
                    // Divided per sample (this triangle exists for one sample only);
                    // a still triangle multiplies by reciprocals it computes once.
                    let vd = t.v;
                    let z = if persp {
                        (1.0 / (w[0] / vd[0].z + w[1] / vd[1].z + w[2] / vd[2].z)) as f32
                    } else {
                        (w[0] * vd[0].z + w[1] * vd[1].z + w[2] * vd[2].z) as f32
                    };
                    let [near, far] = out.near_far;
                    if z < near || z > far || z >= out.opaque_z[s] {
                        continue;
                    }
                    let (idx, ccw) = (t.idx.map(|k| quad[k]), t.ccw);
                    out.deposit(
                        g,
                        s,
                        Hit {
                            idx,
                            w,
                            first: a,
                            z,
                            order,
                            ccw,
                        },
                    );
                    hits += 1;
                }
            }
        }
    }
    hits
}

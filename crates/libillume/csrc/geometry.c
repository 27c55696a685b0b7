/*
 * The C half of libillume, part 2: geometric primitives, procedurals and texture making.
 * Each primitive sizes its parameter arrays by the class counts of RI Spec 3.2 §5.
 */
#include "internal.h"
#include <stdlib.h>
#include <string.h>

static int sum(int n, const RtInt *v) {
  int s = 0;
  for (int i = 0; v && i < n; i++) s += v[i];
  return s;
}

static int max_plus_one(int n, const RtInt *v) {
  int m = -1;
  for (int i = 0; v && i < n; i++)
    if (v[i] > m) m = v[i];
  return m + 1;
}

static int is(RtToken a, const char *b) { return a && strcmp(a, b) == 0; }

/* ---- polygons ---------------------------------------------------------------------------- */

RtVoid RiPolygonV(RtInt nverts, RtInt n, RtToken tokens[], RtPointer parms[]) {
  illume_call("Polygon");
  illume_paramsc(n, tokens, parms, 1, nverts, nverts, nverts);
  illume_send();
}
RtVoid RiPolygon(RtInt nverts, ...) { ILLUME_VARARGS(nverts, RiPolygonV(nverts, n_, t_, v_)); }

RtVoid RiGeneralPolygonV(RtInt nloops, RtInt nverts[], RtInt n, RtToken tokens[],
                         RtPointer parms[]) {
  int total = sum(nloops, nverts);
  illume_call("GeneralPolygon");
  illume_ints(nloops, nverts);
  illume_paramsc(n, tokens, parms, 1, total, total, total);
  illume_send();
}
RtVoid RiGeneralPolygon(RtInt nloops, RtInt nverts[], ...) {
  ILLUME_VARARGS(nverts, RiGeneralPolygonV(nloops, nverts, n_, t_, v_));
}

RtVoid RiPointsPolygonsV(RtInt npolys, RtInt nverts[], RtInt verts[], RtInt n, RtToken tokens[],
                         RtPointer parms[]) {
  int total = sum(npolys, nverts), points = max_plus_one(total, verts);
  illume_call("PointsPolygons");
  illume_ints(npolys, nverts);
  illume_ints(total, verts);
  illume_paramsc(n, tokens, parms, npolys, points, points, total);
  illume_send();
}
RtVoid RiPointsPolygons(RtInt npolys, RtInt nverts[], RtInt verts[], ...) {
  ILLUME_VARARGS(verts, RiPointsPolygonsV(npolys, nverts, verts, n_, t_, v_));
}

RtVoid RiPointsGeneralPolygonsV(RtInt npolys, RtInt nloops[], RtInt nverts[], RtInt verts[],
                                RtInt n, RtToken tokens[], RtPointer parms[]) {
  int loops = sum(npolys, nloops), total = sum(loops, nverts);
  int points = max_plus_one(total, verts);
  illume_call("PointsGeneralPolygons");
  illume_ints(npolys, nloops);
  illume_ints(loops, nverts);
  illume_ints(total, verts);
  illume_paramsc(n, tokens, parms, npolys, points, points, total);
  illume_send();
}
RtVoid RiPointsGeneralPolygons(RtInt npolys, RtInt nloops[], RtInt nverts[], RtInt verts[], ...) {
  ILLUME_VARARGS(verts, RiPointsGeneralPolygonsV(npolys, nloops, nverts, verts, n_, t_, v_));
}

/* ---- patches ----------------------------------------------------------------------------- */

RtVoid RiPatchV(RtToken type, RtInt n, RtToken tokens[], RtPointer parms[]) {
  int vertex = is(type, RI_BICUBIC) ? 16 : 4;
  illume_call("Patch");
  illume_string(type);
  illume_paramsc(n, tokens, parms, 1, 4, vertex, 4);
  illume_send();
}
RtVoid RiPatch(RtToken type, ...) { ILLUME_VARARGS(type, RiPatchV(type, n_, t_, v_)); }

/* Segments along one direction of a patch mesh or curve with `nv` vertices. */
static int segments(int bicubic, int periodic, int nv, int step) {
  if (!bicubic) return periodic ? nv : nv - 1;
  if (step <= 0) return 0;
  return periodic ? nv / step : (nv - 4) / step + 1;
}

RtVoid RiPatchMeshV(RtToken type, RtInt nu, RtToken uwrap, RtInt nv, RtToken vwrap, RtInt n,
                    RtToken tokens[], RtPointer parms[]) {
  int cubic = is(type, RI_BICUBIC), up = is(uwrap, RI_PERIODIC), vp = is(vwrap, RI_PERIODIC);
  int us = segments(cubic, up, nu, illume_ustep()), vs = segments(cubic, vp, nv, illume_vstep());
  int varying = (us + !up) * (vs + !vp);
  illume_call("PatchMesh");
  illume_string(type);
  illume_int(nu);
  illume_string(uwrap);
  illume_int(nv);
  illume_string(vwrap);
  illume_paramsc(n, tokens, parms, us * vs, varying, nu * nv, 4 * us * vs);
  illume_send();
}
RtVoid RiPatchMesh(RtToken type, RtInt nu, RtToken uwrap, RtInt nv, RtToken vwrap, ...) {
  ILLUME_VARARGS(vwrap, RiPatchMeshV(type, nu, uwrap, nv, vwrap, n_, t_, v_));
}

RtVoid RiNuPatchV(RtInt nu, RtInt uorder, RtFloat uknot[], RtFloat umin, RtFloat umax, RtInt nv,
                  RtInt vorder, RtFloat vknot[], RtFloat vmin, RtFloat vmax, RtInt n,
                  RtToken tokens[], RtPointer parms[]) {
  int us = nu - uorder + 1, vs = nv - vorder + 1;
  illume_call("NuPatch");
  illume_int(nu);
  illume_int(uorder);
  illume_floats(nu + uorder, uknot);
  illume_float(umin);
  illume_float(umax);
  illume_int(nv);
  illume_int(vorder);
  illume_floats(nv + vorder, vknot);
  illume_float(vmin);
  illume_float(vmax);
  illume_paramsc(n, tokens, parms, us * vs, (us + 1) * (vs + 1), nu * nv, 4 * us * vs);
  illume_send();
}
RtVoid RiNuPatch(RtInt nu, RtInt uorder, RtFloat uknot[], RtFloat umin, RtFloat umax, RtInt nv,
                 RtInt vorder, RtFloat vknot[], RtFloat vmin, RtFloat vmax, ...) {
  ILLUME_VARARGS(vmax, RiNuPatchV(nu, uorder, uknot, umin, umax, nv, vorder, vknot, vmin, vmax,
                                  n_, t_, v_));
}

RtVoid RiTrimCurve(RtInt nloops, RtInt ncurves[], RtInt order[], RtFloat knot[], RtFloat min[],
                   RtFloat max[], RtInt n[], RtFloat u[], RtFloat v[], RtFloat w[]) {
  int curves = sum(nloops, ncurves), points = sum(curves, n);
  int knots = sum(curves, order) + points;
  illume_call("TrimCurve");
  illume_ints(nloops, ncurves);
  illume_ints(curves, order);
  illume_floats(knots, knot);
  illume_floats(curves, min);
  illume_floats(curves, max);
  illume_ints(curves, n);
  illume_floats(points, u);
  illume_floats(points, v);
  illume_floats(points, w);
  illume_send();
}

/* ---- quadrics: uniform 1, varying and vertex 4 (the parametric corners) ---------------------- */

static void quadric(const char *name, int nargs, const RtFloat *args, RtInt n, RtToken t[],
                    RtPointer p[]) {
  illume_call(name);
  for (int i = 0; i < nargs; i++) illume_float(args[i]);
  illume_paramsc(n, t, p, 1, 4, 4, 4);
  illume_send();
}

#define QUADRIC4(Fn, Req, a, b, c, d)                                                          \
  RtVoid Fn##V(RtFloat a, RtFloat b, RtFloat c, RtFloat d, RtInt n, RtToken t[], RtPointer p[]) { \
    RtFloat v[4] = {a, b, c, d};                                                               \
    quadric(Req, 4, v, n, t, p);                                                               \
  }                                                                                            \
  RtVoid Fn(RtFloat a, RtFloat b, RtFloat c, RtFloat d, ...) {                                 \
    ILLUME_VARARGS(d, Fn##V(a, b, c, d, n_, t_, v_));                                          \
  }
#define QUADRIC3(Fn, Req, a, b, c)                                                             \
  RtVoid Fn##V(RtFloat a, RtFloat b, RtFloat c, RtInt n, RtToken t[], RtPointer p[]) {         \
    RtFloat v[3] = {a, b, c};                                                                  \
    quadric(Req, 3, v, n, t, p);                                                               \
  }                                                                                            \
  RtVoid Fn(RtFloat a, RtFloat b, RtFloat c, ...) { ILLUME_VARARGS(c, Fn##V(a, b, c, n_, t_, v_)); }

QUADRIC4(RiSphere, "Sphere", radius, zmin, zmax, thetamax)
QUADRIC4(RiCylinder, "Cylinder", radius, zmin, zmax, thetamax)
QUADRIC4(RiParaboloid, "Paraboloid", rmax, zmin, zmax, thetamax)
QUADRIC3(RiCone, "Cone", height, radius, thetamax)
QUADRIC3(RiDisk, "Disk", height, radius, thetamax)

RtVoid RiHyperboloidV(RtPoint point1, RtPoint point2, RtFloat thetamax, RtInt n,
                      RtToken tokens[], RtPointer parms[]) {
  RtFloat v[7] = {0, 0, 0, 0, 0, 0, thetamax};
  if (point1) memcpy(v, point1, sizeof(RtPoint));
  if (point2) memcpy(v + 3, point2, sizeof(RtPoint));
  quadric("Hyperboloid", 7, v, n, tokens, parms);
}
RtVoid RiHyperboloid(RtPoint point1, RtPoint point2, RtFloat thetamax, ...) {
  ILLUME_VARARGS(thetamax, RiHyperboloidV(point1, point2, thetamax, n_, t_, v_));
}
RtVoid RiTorusV(RtFloat majorradius, RtFloat minorradius, RtFloat phimin, RtFloat phimax,
                RtFloat thetamax, RtInt n, RtToken tokens[], RtPointer parms[]) {
  RtFloat v[5] = {majorradius, minorradius, phimin, phimax, thetamax};
  quadric("Torus", 5, v, n, tokens, parms);
}
RtVoid RiTorus(RtFloat majorradius, RtFloat minorradius, RtFloat phimin, RtFloat phimax,
               RtFloat thetamax, ...) {
  ILLUME_VARARGS(thetamax,
                 RiTorusV(majorradius, minorradius, phimin, phimax, thetamax, n_, t_, v_));
}

/* ---- points, curves, subdivision meshes, blobbies ------------------------------------------ */

RtVoid RiPointsV(RtInt npoints, RtInt n, RtToken tokens[], RtPointer parms[]) {
  illume_call("Points");
  illume_paramsc(n, tokens, parms, 1, npoints, npoints, npoints);
  illume_send();
}
RtVoid RiPoints(RtInt npoints, ...) { ILLUME_VARARGS(npoints, RiPointsV(npoints, n_, t_, v_)); }

RtVoid RiCurvesV(RtToken type, RtInt ncurves, RtInt nvertices[], RtToken wrap, RtInt n,
                 RtToken tokens[], RtPointer parms[]) {
  int cubic = is(type, RI_CUBIC), periodic = is(wrap, RI_PERIODIC), varying = 0;
  for (int i = 0; nvertices && i < ncurves; i++)
    varying += segments(cubic, periodic, nvertices[i], illume_vstep()) + !periodic;
  int vertex = sum(ncurves, nvertices);
  illume_call("Curves");
  illume_string(type);
  illume_ints(ncurves, nvertices);
  illume_string(wrap);
  illume_paramsc(n, tokens, parms, ncurves, varying, vertex, varying);
  illume_send();
}
RtVoid RiCurves(RtToken type, RtInt ncurves, RtInt nvertices[], RtToken wrap, ...) {
  ILLUME_VARARGS(wrap, RiCurvesV(type, ncurves, nvertices, wrap, n_, t_, v_));
}

RtVoid RiSubdivisionMeshV(RtToken scheme, RtInt nfaces, RtInt nvertices[], RtInt vertices[],
                          RtInt ntags, RtToken tags[], RtInt nargs[], RtInt intargs[],
                          RtFloat floatargs[], RtInt n, RtToken tokens[], RtPointer parms[]) {
  int total = sum(nfaces, nvertices), points = max_plus_one(total, vertices);
  int nint = 0, nfloat = 0;
  for (int i = 0; nargs && i < ntags; i++) {
    nint += nargs[2 * i];
    nfloat += nargs[2 * i + 1];
  }
  illume_call("SubdivisionMesh");
  illume_string(scheme);
  illume_ints(nfaces, nvertices);
  illume_ints(total, vertices);
  illume_strings(ntags, (const char *const *)tags);
  illume_ints(2 * ntags, nargs);
  illume_ints(nint, intargs);
  illume_floats(nfloat, floatargs);
  illume_paramsc(n, tokens, parms, nfaces, points, points, total);
  illume_send();
}
RtVoid RiSubdivisionMesh(RtToken scheme, RtInt nfaces, RtInt nvertices[], RtInt vertices[],
                         RtInt ntags, RtToken tags[], RtInt nargs[], RtInt intargs[],
                         RtFloat floatargs[], ...) {
  ILLUME_VARARGS(floatargs, RiSubdivisionMeshV(scheme, nfaces, nvertices, vertices, ntags, tags,
                                               nargs, intargs, floatargs, n_, t_, v_));
}

RtVoid RiBlobbyV(RtInt nleaf, RtInt ncode, RtInt code[], RtInt nflt, RtFloat flt[], RtInt nstr,
                 RtToken str[], RtInt n, RtToken tokens[], RtPointer parms[]) {
  illume_call("Blobby");
  illume_int(nleaf);
  illume_ints(ncode, code);
  illume_floats(nflt, flt);
  illume_strings(nstr, (const char *const *)str);
  illume_paramsc(n, tokens, parms, 1, nleaf, nleaf, nleaf);
  illume_send();
}
RtVoid RiBlobby(RtInt nleaf, RtInt ncode, RtInt code[], RtInt nflt, RtFloat flt[], RtInt nstr,
                RtToken str[], ...) {
  ILLUME_VARARGS(str, RiBlobbyV(nleaf, ncode, code, nflt, flt, nstr, str, n_, t_, v_));
}

/* ---- procedurals ------------------------------------------------------------------------- */

static void procedural_request(const char *name, int nargs, RtPointer data, const RtFloat *bound) {
  static const RtFloat everywhere[6] = {-RI_INFINITY, RI_INFINITY, -RI_INFINITY,
                                        RI_INFINITY,  -RI_INFINITY, RI_INFINITY};
  illume_call("Procedural");
  illume_string(name);
  illume_strings(nargs, (const char *const *)data);
  illume_floats(6, bound ? bound : everywhere);
  illume_send();
}

/*
 * The built-in procedurals become RIB `Procedural` requests (the renderer runs them). A
 * program's own subdivide function is called at once with RI_INFINITY detail, inside an
 * attribute block, and its free function after it: both back ends see the same expanded
 * requests, so a program and its captured RIB render alike.
 */
RtVoid RiProcedural(RtPointer data, RtBound bound, RtProcSubdivFunc subdivfunc,
                    RtProcFreeFunc freefunc) {
  if (!subdivfunc) {
    illume_report(RIE_MISSINGDATA, RIE_ERROR, "RiProcedural: NULL subdivide function (ignored)");
    return;
  }
  if (subdivfunc == RiProcDelayedReadArchive) {
    procedural_request("DelayedReadArchive", 1, data, bound);
  } else if (subdivfunc == RiProcRunProgram) {
    procedural_request("RunProgram", 2, data, bound);
  } else if (subdivfunc == RiProcDynamicLoad) {
    procedural_request("DynamicLoad", 2, data, bound);
  } else {
    RiAttributeBegin();
    subdivfunc(data, RI_INFINITY);
    RiAttributeEnd();
  }
  if (freefunc) freefunc(data);
}

/* Called by a program's own subdivide function to hand on to a built-in one. */
RtVoid RiProcDelayedReadArchive(RtPointer data, RtFloat detail) {
  (void)detail;
  RiReadArchive(data ? ((RtString *)data)[0] : NULL, NULL, RI_NULL);
}
RtVoid RiProcRunProgram(RtPointer data, RtFloat detail) {
  (void)detail;
  procedural_request("RunProgram", 2, data, NULL);
}
RtVoid RiProcDynamicLoad(RtPointer data, RtFloat detail) {
  (void)detail;
  procedural_request("DynamicLoad", 2, data, NULL);
}
RtVoid RiProcFree(RtPointer data) { free(data); }

/* ---- texture making ---------------------------------------------------------------------- */

static void texture_head(const char *req, char *pic, char *tex) {
  illume_call(req);
  illume_string(pic);
  illume_string(tex);
}

/* MakeTexture and MakeBump take the same arguments in the same order. */
static void make_wrapped(const char *req, char *pic, char *tex, RtToken swrap, RtToken twrap,
                         RtFilterFunc filterfunc, RtFloat swidth, RtFloat twidth, RtInt n,
                         RtToken tokens[], RtPointer parms[]) {
  texture_head(req, pic, tex);
  illume_string(swrap);
  illume_string(twrap);
  illume_string(illume_filter_name(filterfunc));
  illume_float(swidth);
  illume_float(twidth);
  illume_params1(n, tokens, parms);
  illume_send();
}

RtVoid RiMakeTextureV(char *pic, char *tex, RtToken swrap, RtToken twrap, RtFilterFunc filterfunc,
                      RtFloat swidth, RtFloat twidth, RtInt n, RtToken tokens[],
                      RtPointer parms[]) {
  make_wrapped("MakeTexture", pic, tex, swrap, twrap, filterfunc, swidth, twidth, n, tokens,
               parms);
}
RtVoid RiMakeTexture(char *pic, char *tex, RtToken swrap, RtToken twrap, RtFilterFunc filterfunc,
                     RtFloat swidth, RtFloat twidth, ...) {
  ILLUME_VARARGS(twidth,
                 RiMakeTextureV(pic, tex, swrap, twrap, filterfunc, swidth, twidth, n_, t_, v_));
}
RtVoid RiMakeBumpV(char *pic, char *tex, RtToken swrap, RtToken twrap, RtFilterFunc filterfunc,
                   RtFloat swidth, RtFloat twidth, RtInt n, RtToken tokens[], RtPointer parms[]) {
  make_wrapped("MakeBump", pic, tex, swrap, twrap, filterfunc, swidth, twidth, n, tokens, parms);
}
RtVoid RiMakeBump(char *pic, char *tex, RtToken swrap, RtToken twrap, RtFilterFunc filterfunc,
                  RtFloat swidth, RtFloat twidth, ...) {
  ILLUME_VARARGS(twidth,
                 RiMakeBumpV(pic, tex, swrap, twrap, filterfunc, swidth, twidth, n_, t_, v_));
}
RtVoid RiMakeLatLongEnvironmentV(char *pic, char *tex, RtFilterFunc filterfunc, RtFloat swidth,
                                 RtFloat twidth, RtInt n, RtToken tokens[], RtPointer parms[]) {
  texture_head("MakeLatLongEnvironment", pic, tex);
  illume_string(illume_filter_name(filterfunc));
  illume_float(swidth);
  illume_float(twidth);
  illume_params1(n, tokens, parms);
  illume_send();
}
RtVoid RiMakeLatLongEnvironment(char *pic, char *tex, RtFilterFunc filterfunc, RtFloat swidth,
                                RtFloat twidth, ...) {
  ILLUME_VARARGS(twidth, RiMakeLatLongEnvironmentV(pic, tex, filterfunc, swidth, twidth, n_, t_, v_));
}
RtVoid RiMakeCubeFaceEnvironmentV(char *px, char *nx, char *py, char *ny, char *pz, char *nz,
                                  char *tex, RtFloat fov, RtFilterFunc filterfunc, RtFloat swidth,
                                  RtFloat twidth, RtInt n, RtToken tokens[], RtPointer parms[]) {
  illume_call("MakeCubeFaceEnvironment");
  illume_string(px);
  illume_string(nx);
  illume_string(py);
  illume_string(ny);
  illume_string(pz);
  illume_string(nz);
  illume_string(tex);
  illume_float(fov);
  illume_string(illume_filter_name(filterfunc));
  illume_float(swidth);
  illume_float(twidth);
  illume_params1(n, tokens, parms);
  illume_send();
}
RtVoid RiMakeCubeFaceEnvironment(char *px, char *nx, char *py, char *ny, char *pz, char *nz,
                                 char *tex, RtFloat fov, RtFilterFunc filterfunc, RtFloat swidth,
                                 RtFloat twidth, ...) {
  ILLUME_VARARGS(twidth, RiMakeCubeFaceEnvironmentV(px, nx, py, ny, pz, nz, tex, fov, filterfunc,
                                                    swidth, twidth, n_, t_, v_));
}
RtVoid RiMakeShadowV(char *pic, char *tex, RtInt n, RtToken tokens[], RtPointer parms[]) {
  texture_head("MakeShadow", pic, tex);
  illume_params1(n, tokens, parms);
  illume_send();
}
RtVoid RiMakeShadow(char *pic, char *tex, ...) {
  ILLUME_VARARGS(tex, RiMakeShadowV(pic, tex, n_, t_, v_));
}

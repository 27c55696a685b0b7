/*
 * The C half of libillume, part 1: errors, filters, blocks, options, attributes, transforms.
 * Each procedure turns its arguments into illume_* calls (src/ffi); the V form does the work
 * and the varargs form collects its token/value pairs (ILLUME_VARARGS) and calls it.
 */
#include "internal.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- error handling --------------------------------------------------------------------- */

static RtErrorHandler handler = RiErrorPrint;

RtVoid RiErrorHandler(RtErrorHandler h) { handler = h ? h : RiErrorPrint; }

void illume_dispatch_error(int code, int severity, const char *message) {
  RiLastError = code;
  handler(code, severity, (char *)message);
}

RtVoid RiErrorIgnore(RtInt code, RtInt severity, char *message) {
  (void)code;
  (void)severity;
  (void)message;
}

static const char *severity_name(RtInt severity) {
  switch (severity) {
  case RIE_INFO: return "info";
  case RIE_WARNING: return "warning";
  case RIE_ERROR: return "error";
  default: return "severe error";
  }
}

RtVoid RiErrorPrint(RtInt code, RtInt severity, char *message) {
  fprintf(stderr, "illume: %s (%d): %s\n", severity_name(severity), (int)code, message);
}

RtVoid RiErrorAbort(RtInt code, RtInt severity, char *message) {
  RiErrorPrint(code, severity, message);
  if (severity >= RIE_ERROR) exit(1);
}

RtInt illume_collect(va_list ap, RtToken tokens[], RtPointer parms[]) {
  RtInt n = 0;
  RtToken t;
  while ((t = va_arg(ap, RtToken)) != RI_NULL) {
    if (n == ILLUME_MAXPARAMS) {
      illume_report(RIE_LIMIT, RIE_ERROR, "more than 1024 parameters in one call (rest ignored)");
      break;
    }
    tokens[n] = t;
    parms[n] = va_arg(ap, RtPointer);
    n++;
  }
  return n;
}

void illume_paramsc(RtInt n, RtToken tokens[], RtPointer parms[], int uniform, int varying,
                    int vertex, int facevarying) {
  illume_params(n, (const char *const *)tokens, (const void *const *)parms, uniform, varying,
                vertex, facevarying);
}

void illume_params1(RtInt n, RtToken tokens[], RtPointer parms[]) {
  illume_paramsc(n, tokens, parms, 1, 1, 1, 1);
}

/* ---- filters (RI Spec 3.2 Appendix E) ------------------------------------------------------ */

RtFloat RiBoxFilter(RtFloat x, RtFloat y, RtFloat xwidth, RtFloat ywidth) {
  (void)x;
  (void)y;
  (void)xwidth;
  (void)ywidth;
  return 1.0f;
}

RtFloat RiTriangleFilter(RtFloat x, RtFloat y, RtFloat xwidth, RtFloat ywidth) {
  RtFloat hx = xwidth * 0.5f, hy = ywidth * 0.5f, ax = fabsf(x), ay = fabsf(y);
  if (ax > hx || ay > hy) return 0.0f;
  return (hx - ax) / hx * (hy - ay) / hy;
}

RtFloat RiGaussianFilter(RtFloat x, RtFloat y, RtFloat xwidth, RtFloat ywidth) {
  x *= 2.0f / xwidth;
  y *= 2.0f / ywidth;
  return expf(-2.0f * (x * x + y * y));
}

RtFloat RiCatmullRomFilter(RtFloat x, RtFloat y, RtFloat xwidth, RtFloat ywidth) {
  (void)xwidth;
  (void)ywidth;
  RtFloat r2 = x * x + y * y, r = sqrtf(r2);
  if (r >= 2.0f) return 0.0f;
  if (r < 1.0f) return 3.0f * r * r2 - 5.0f * r2 + 2.0f;
  return -r * r2 + 5.0f * r2 - 8.0f * r + 4.0f;
}

static RtFloat windowed_sinc(RtFloat x, RtFloat width) {
  if (x == 0.0f) return 1.0f;
  x *= 3.14159265358979f;
  return cosf(0.5f * x / width) * sinf(x) / x;
}

RtFloat RiSincFilter(RtFloat x, RtFloat y, RtFloat xwidth, RtFloat ywidth) {
  return windowed_sinc(x, xwidth) * windowed_sinc(y, ywidth);
}

const char *illume_standard_filter(RtFilterFunc f) {
  if (f == RiBoxFilter) return "box";
  if (f == RiTriangleFilter) return "triangle";
  if (f == RiGaussianFilter) return "gaussian";
  if (f == RiCatmullRomFilter) return "catmull-rom";
  if (f == RiSincFilter) return "sinc";
  return NULL;
}

const char *illume_filter_name(RtFilterFunc f) {
  const char *name = illume_standard_filter(f);
  if (name) return name;
  illume_report(RIE_UNIMPLEMENT, RIE_WARNING,
                "a program-defined filter function can not be used; gaussian is used instead");
  return "gaussian";
}

/* ---- blocks ------------------------------------------------------------------------------- */

/* Basis steps follow the attribute stack (PatchMesh and Curves counts depend on them). */
#define STEP_DEPTH 256
static RtInt steps[STEP_DEPTH][2] = {{3, 3}};
static int step_top = 0;

RtInt illume_ustep(void) { return steps[step_top][0]; }
RtInt illume_vstep(void) { return steps[step_top][1]; }

static void push_steps(void) {
  if (step_top + 1 < STEP_DEPTH) {
    steps[step_top + 1][0] = steps[step_top][0];
    steps[step_top + 1][1] = steps[step_top][1];
  }
  step_top = step_top + 1 < STEP_DEPTH ? step_top + 1 : step_top;
}

static void pop_steps(void) {
  if (step_top > 0) step_top--;
}

static void request0(const char *name) {
  illume_call(name);
  illume_send();
}

RtVoid RiBegin(RtToken name) {
  step_top = 0;
  steps[0][0] = steps[0][1] = 3;
  illume_begin(name);
}
RtVoid RiEnd(void) { illume_end(); }
RtVoid RiFrameBegin(RtInt frame) {
  push_steps();
  illume_call("FrameBegin");
  illume_int(frame);
  illume_send();
}
RtVoid RiFrameEnd(void) {
  pop_steps();
  request0("FrameEnd");
}
RtVoid RiWorldBegin(void) {
  push_steps();
  request0("WorldBegin");
}
RtVoid RiWorldEnd(void) {
  pop_steps();
  request0("WorldEnd");
}
RtVoid RiAttributeBegin(void) {
  push_steps();
  request0("AttributeBegin");
}
RtVoid RiAttributeEnd(void) {
  pop_steps();
  request0("AttributeEnd");
}
RtVoid RiTransformBegin(void) { request0("TransformBegin"); }
RtVoid RiTransformEnd(void) { request0("TransformEnd"); }
RtVoid RiSolidBegin(RtToken operation) {
  illume_call("SolidBegin");
  illume_string(operation);
  illume_send();
}
RtVoid RiSolidEnd(void) { request0("SolidEnd"); }

RtObjectHandle RiObjectBegin(void) {
  int h = illume_handle();
  illume_call("ObjectBegin");
  illume_int(h);
  illume_send();
  return (RtObjectHandle)(intptr_t)h;
}
RtVoid RiObjectEnd(void) { request0("ObjectEnd"); }
RtVoid RiObjectInstance(RtObjectHandle handle) {
  illume_call("ObjectInstance");
  illume_int((int)(intptr_t)handle);
  illume_send();
}

RtVoid RiMotionBeginV(RtInt n, RtFloat times[]) {
  illume_call("MotionBegin");
  illume_floats(n, times);
  illume_send();
}
RtVoid RiMotionBegin(RtInt n, ...) {
  RtFloat times[64];
  if (n < 0 || n > 64) {
    illume_report(RIE_LIMIT, RIE_ERROR, "RiMotionBegin: between 0 and 64 times (ignored)");
    return;
  }
  va_list ap;
  va_start(ap, n);
  for (RtInt i = 0; i < n; i++) times[i] = (RtFloat)va_arg(ap, double);
  va_end(ap);
  RiMotionBeginV(n, times);
}
RtVoid RiMotionEnd(void) { request0("MotionEnd"); }

/* ---- requests of the form Name "string" params ---------------------------------------------- */

#define NAMED_PARAMS(Fn, Req)                                                                  \
  RtVoid Fn##V(RtToken name, RtInt n, RtToken tokens[], RtPointer parms[]) {                   \
    illume_call(Req);                                                                          \
    illume_string(name);                                                                       \
    illume_params1(n, tokens, parms);                                                          \
    illume_send();                                                                             \
  }                                                                                            \
  RtVoid Fn(RtToken name, ...) { ILLUME_VARARGS(name, Fn##V(name, n_, t_, v_)); }

NAMED_PARAMS(RiProjection, "Projection")
NAMED_PARAMS(RiImager, "Imager")
NAMED_PARAMS(RiHider, "Hider")
NAMED_PARAMS(RiOption, "Option")
NAMED_PARAMS(RiSurface, "Surface")
NAMED_PARAMS(RiDisplacement, "Displacement")
NAMED_PARAMS(RiAtmosphere, "Atmosphere")
NAMED_PARAMS(RiInterior, "Interior")
NAMED_PARAMS(RiExterior, "Exterior")
NAMED_PARAMS(RiDeformation, "Deformation")
NAMED_PARAMS(RiAttribute, "Attribute")
NAMED_PARAMS(RiGeometry, "Geometry")

static RtLightHandle light(const char *req, RtToken name, RtInt n, RtToken t[], RtPointer p[]) {
  int h = illume_handle();
  illume_call(req);
  illume_string(name);
  illume_int(h);
  illume_params1(n, t, p);
  illume_send();
  return (RtLightHandle)(intptr_t)h;
}
RtLightHandle RiLightSourceV(RtToken name, RtInt n, RtToken tokens[], RtPointer parms[]) {
  return light("LightSource", name, n, tokens, parms);
}
RtLightHandle RiLightSource(RtToken name, ...) {
  RtLightHandle h;
  ILLUME_VARARGS(name, h = RiLightSourceV(name, n_, t_, v_));
  return h;
}
RtLightHandle RiAreaLightSourceV(RtToken name, RtInt n, RtToken tokens[], RtPointer parms[]) {
  return light("AreaLightSource", name, n, tokens, parms);
}
RtLightHandle RiAreaLightSource(RtToken name, ...) {
  RtLightHandle h;
  ILLUME_VARARGS(name, h = RiAreaLightSourceV(name, n_, t_, v_));
  return h;
}
RtVoid RiIlluminate(RtLightHandle light, RtBoolean onoff) {
  illume_call("Illuminate");
  illume_int((int)(intptr_t)light);
  illume_int(onoff ? 1 : 0);
  illume_send();
}

/* ---- options ---------------------------------------------------------------------------- */

static void floats_request(const char *name, int n, const RtFloat *v) {
  illume_call(name);
  for (int i = 0; i < n; i++) illume_float(v[i]);
  illume_send();
}

RtVoid RiFormat(RtInt xres, RtInt yres, RtFloat aspect) {
  illume_call("Format");
  illume_int(xres);
  illume_int(yres);
  illume_float(aspect);
  illume_send();
}
RtVoid RiFrameAspectRatio(RtFloat aspect) { floats_request("FrameAspectRatio", 1, &aspect); }
RtVoid RiScreenWindow(RtFloat left, RtFloat right, RtFloat bottom, RtFloat top) {
  RtFloat v[4] = {left, right, bottom, top};
  floats_request("ScreenWindow", 4, v);
}
RtVoid RiCropWindow(RtFloat xmin, RtFloat xmax, RtFloat ymin, RtFloat ymax) {
  RtFloat v[4] = {xmin, xmax, ymin, ymax};
  floats_request("CropWindow", 4, v);
}
RtVoid RiClipping(RtFloat hither, RtFloat yon) {
  RtFloat v[2] = {hither, yon};
  floats_request("Clipping", 2, v);
}
RtVoid RiClippingPlane(RtFloat x, RtFloat y, RtFloat z, RtFloat nx, RtFloat ny, RtFloat nz) {
  RtFloat v[6] = {x, y, z, nx, ny, nz};
  floats_request("ClippingPlane", 6, v);
}
RtVoid RiDepthOfField(RtFloat fstop, RtFloat focallength, RtFloat focaldistance) {
  RtFloat v[3] = {fstop, focallength, focaldistance};
  floats_request("DepthOfField", 3, v);
}
RtVoid RiShutter(RtFloat min, RtFloat max) {
  RtFloat v[2] = {min, max};
  floats_request("Shutter", 2, v);
}
RtVoid RiPixelVariance(RtFloat variation) { floats_request("PixelVariance", 1, &variation); }
RtVoid RiPixelSamples(RtFloat xsamples, RtFloat ysamples) {
  RtFloat v[2] = {xsamples, ysamples};
  floats_request("PixelSamples", 2, v);
}
RtVoid RiPixelFilter(RtFilterFunc function, RtFloat xwidth, RtFloat ywidth) {
  if (function && !illume_standard_filter(function)) {
    /* A program's own function: tabulated and used as the filter (src/ffi). */
    illume_user_pixel_filter(function, xwidth, ywidth);
    return;
  }
  illume_call("PixelFilter");
  illume_string(illume_filter_name(function));
  illume_float(xwidth);
  illume_float(ywidth);
  illume_send();
}
RtVoid RiExposure(RtFloat gain, RtFloat gamma) {
  RtFloat v[2] = {gain, gamma};
  floats_request("Exposure", 2, v);
}
RtVoid RiQuantize(RtToken type, RtInt one, RtInt min, RtInt max, RtFloat ampl) {
  illume_call("Quantize");
  illume_string(type);
  illume_int(one);
  illume_int(min);
  illume_int(max);
  illume_float(ampl);
  illume_send();
}
RtVoid RiDisplayV(char *name, RtToken type, RtToken mode, RtInt n, RtToken tokens[],
                  RtPointer parms[]) {
  illume_call("Display");
  illume_string(name);
  illume_string(type);
  illume_string(mode);
  illume_params1(n, tokens, parms);
  illume_send();
}
RtVoid RiDisplay(char *name, RtToken type, RtToken mode, ...) {
  ILLUME_VARARGS(mode, RiDisplayV(name, type, mode, n_, t_, v_));
}
RtVoid RiColorSamples(RtInt n, RtFloat nRGB[], RtFloat RGBn[]) {
  illume_call("ColorSamples");
  illume_floats(3 * n, nRGB);
  illume_floats(3 * n, RGBn);
  illume_send();
}
RtVoid RiRelativeDetail(RtFloat relativedetail) {
  floats_request("RelativeDetail", 1, &relativedetail);
}

/* ---- attributes ------------------------------------------------------------------------- */

static void array_request(const char *name, int n, const RtFloat *v) {
  illume_call(name);
  illume_floats(n, v);
  illume_send();
}
static void string_request(const char *name, RtToken s) {
  illume_call(name);
  illume_string(s);
  illume_send();
}
static void int_request(const char *name, RtInt i) {
  illume_call(name);
  illume_int(i);
  illume_send();
}

RtVoid RiColor(RtColor color) { array_request("Color", 3, color); }
RtVoid RiOpacity(RtColor color) { array_request("Opacity", 3, color); }
RtVoid RiTextureCoordinates(RtFloat s1, RtFloat t1, RtFloat s2, RtFloat t2, RtFloat s3,
                            RtFloat t3, RtFloat s4, RtFloat t4) {
  RtFloat v[8] = {s1, t1, s2, t2, s3, t3, s4, t4};
  floats_request("TextureCoordinates", 8, v);
}
RtVoid RiShadingRate(RtFloat size) { floats_request("ShadingRate", 1, &size); }
RtVoid RiShadingInterpolation(RtToken type) { string_request("ShadingInterpolation", type); }
RtVoid RiMatte(RtBoolean onoff) { int_request("Matte", onoff ? 1 : 0); }
RtVoid RiBound(RtBound bound) { array_request("Bound", 6, bound); }
RtVoid RiDetail(RtBound bound) { array_request("Detail", 6, bound); }
RtVoid RiDetailRange(RtFloat minvis, RtFloat lowtran, RtFloat uptran, RtFloat maxvis) {
  RtFloat v[4] = {minvis, lowtran, uptran, maxvis};
  floats_request("DetailRange", 4, v);
}
RtVoid RiGeometricApproximation(RtToken type, RtFloat value) {
  illume_call("GeometricApproximation");
  illume_string(type);
  illume_float(value);
  illume_send();
}
RtVoid RiGeometricRepresentation(RtToken type) {
  string_request("GeometricRepresentation", type);
}
RtVoid RiOrientation(RtToken orientation) { string_request("Orientation", orientation); }
RtVoid RiReverseOrientation(void) { request0("ReverseOrientation"); }
RtVoid RiSides(RtInt sides) { int_request("Sides", sides); }

/* Named bases print by name (RIB readers know them); others as 16 numbers. */
static void basis_arg(RtBasis b) {
  static const struct {
    const char *name;
    RtFloat (*m)[4];
  } named[] = {{"bezier", RiBezierBasis},
               {"b-spline", RiBSplineBasis},
               {"catmull-rom", RiCatmullRomBasis},
               {"hermite", RiHermiteBasis},
               {"power", RiPowerBasis}};
  for (size_t i = 0; i < sizeof named / sizeof named[0]; i++)
    if (b && memcmp(b, named[i].m, sizeof(RtBasis)) == 0) {
      illume_string(named[i].name);
      return;
    }
  illume_floats(16, b ? &b[0][0] : NULL);
}

RtVoid RiBasis(RtBasis ubasis, RtInt ustep, RtBasis vbasis, RtInt vstep) {
  steps[step_top][0] = ustep;
  steps[step_top][1] = vstep;
  illume_call("Basis");
  basis_arg(ubasis);
  illume_int(ustep);
  basis_arg(vbasis);
  illume_int(vstep);
  illume_send();
}

/* ---- transformations --------------------------------------------------------------------- */

RtVoid RiIdentity(void) { request0("Identity"); }
RtVoid RiTransform(RtMatrix transform) { array_request("Transform", 16, &transform[0][0]); }
RtVoid RiConcatTransform(RtMatrix transform) {
  array_request("ConcatTransform", 16, &transform[0][0]);
}
RtVoid RiPerspective(RtFloat fov) { floats_request("Perspective", 1, &fov); }
RtVoid RiTranslate(RtFloat dx, RtFloat dy, RtFloat dz) {
  RtFloat v[3] = {dx, dy, dz};
  floats_request("Translate", 3, v);
}
RtVoid RiRotate(RtFloat angle, RtFloat dx, RtFloat dy, RtFloat dz) {
  RtFloat v[4] = {angle, dx, dy, dz};
  floats_request("Rotate", 4, v);
}
RtVoid RiScale(RtFloat sx, RtFloat sy, RtFloat sz) {
  RtFloat v[3] = {sx, sy, sz};
  floats_request("Scale", 3, v);
}
RtVoid RiSkew(RtFloat angle, RtFloat dx1, RtFloat dy1, RtFloat dz1, RtFloat dx2, RtFloat dy2,
              RtFloat dz2) {
  RtFloat v[7] = {angle, dx1, dy1, dz1, dx2, dy2, dz2};
  floats_request("Skew", 7, v);
}
RtVoid RiCoordinateSystem(RtToken space) { string_request("CoordinateSystem", space); }
RtVoid RiCoordSysTransform(RtToken space) { string_request("CoordSysTransform", space); }
RtPoint *RiTransformPoints(RtToken fromspace, RtToken tospace, RtInt n, RtPoint points[]) {
  return illume_transform_points(fromspace, tospace, n, (float *)points) ? points : NULL;
}

/* ---- declarations and archives ------------------------------------------------------------ */

RtToken RiDeclare(char *name, char *declaration) {
  illume_call("Declare");
  illume_string(name);
  illume_string(declaration);
  illume_send();
  return name;
}

RtVoid RiArchiveRecord(RtToken type, char *format, ...) {
  va_list ap;
  va_start(ap, format);
  int len = format ? vsnprintf(NULL, 0, format, ap) : -1;
  va_end(ap);
  if (len < 0 || !type) {
    illume_report(RIE_MISSINGDATA, RIE_ERROR, "RiArchiveRecord: NULL type or format (ignored)");
    return;
  }
  char *text = malloc((size_t)len + 4);
  if (!text) {
    illume_report(RIE_NOMEM, RIE_ERROR, "RiArchiveRecord: out of memory");
    return;
  }
  int structure = strcmp(type, RI_STRUCTURE) == 0;
  va_start(ap, format);
  vsnprintf(text + (structure ? 2 : 0), (size_t)len + 1, format, ap);
  va_end(ap);
  if (structure) {
    text[0] = text[1] = '#';
    strcpy(text + 2 + len, "\n");
    illume_verbatim(text);
  } else if (strcmp(type, RI_VERBATIM) == 0) {
    illume_verbatim(text);
  } else {
    illume_comment(text);
  }
  free(text);
}

/* Hands one comment record of an archive to the program's RtArchiveCallback. */
static void archive_record(void *context, int structural, const char *text) {
  RtArchiveCallback callback = *(RtArchiveCallback *)context;
  callback(structural ? RI_STRUCTURE : RI_COMMENT, "%s", (char *)text);
}

/* The callback sees the archive's comment records (RI_COMMENT for `#`, RI_STRUCTURE for `##`,
   text after the `#`s) in file order, before the archive's requests are read. */
RtVoid RiReadArchiveV(RtToken name, RtArchiveCallback callback, RtInt n, RtToken tokens[],
                      RtPointer parms[]) {
  if (callback) illume_archive_records(name, archive_record, &callback);
  illume_call("ReadArchive");
  illume_string(name);
  illume_params1(n, tokens, parms);
  illume_send();
}
RtVoid RiReadArchive(RtToken name, RtArchiveCallback callback, ...) {
  ILLUME_VARARGS(callback, RiReadArchiveV(name, callback, n_, t_, v_));
}

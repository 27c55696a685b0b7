/* A polygon mesh given with RI_P and RI_N (PointsPolygons, V form) and a general polygon.
 * Writes mesh.tif. */
#include <math.h>
#include <ri.h>

#define RINGS 8
#define SEGS 16

int main(void) {
  /* A faceted hemisphere-like dome: RINGS x SEGS quads sharing vertices, smooth normals. */
  static RtPoint P[(RINGS + 1) * SEGS], N[(RINGS + 1) * SEGS];
  static RtInt nverts[RINGS * SEGS], verts[4 * RINGS * SEGS];
  for (int r = 0; r <= RINGS; r++)
    for (int s = 0; s < SEGS; s++) {
      float phi = 1.4f * r / RINGS, theta = 6.2831853f * s / SEGS;
      float *p = P[r * SEGS + s], *n = N[r * SEGS + s];
      n[0] = sinf(phi) * cosf(theta);
      n[1] = cosf(phi);
      n[2] = sinf(phi) * sinf(theta);
      for (int k = 0; k < 3; k++) p[k] = n[k];
    }
  int f = 0;
  for (int r = 0; r < RINGS; r++)
    for (int s = 0; s < SEGS; s++, f++) {
      nverts[f] = 4;
      verts[4 * f + 0] = r * SEGS + s;
      verts[4 * f + 1] = r * SEGS + (s + 1) % SEGS;
      verts[4 * f + 2] = (r + 1) * SEGS + (s + 1) % SEGS;
      verts[4 * f + 3] = (r + 1) * SEGS + s;
    }

  RtFloat fov = 35, kd = 0.8f;
  RtColor teal = {0.2f, 0.7f, 0.65f}, sand = {0.8f, 0.7f, 0.5f};
  RtToken tokens[2] = {RI_P, RI_N};
  RtPointer parms[2] = {P, N};

  RiBegin(RI_NULL);
  RiFormat(200, 150, 1);
  RiDisplay("mesh.tif", RI_FILE, RI_RGB, RI_NULL);
  RiProjection(RI_PERSPECTIVE, RI_FOV, &fov, RI_NULL);
  RiTranslate(0, -0.2f, 4.5f);
  RiRotate(-25, 1, 0, 0);
  RiWorldBegin();
  RtFloat amb = 0.2f;
  RiLightSource(RI_AMBIENTLIGHT, RI_INTENSITY, &amb, RI_NULL);
  RiLightSource(RI_DISTANTLIGHT, RI_NULL);
  RiSurface(RI_MATTE, RI_KD, &kd, RI_NULL);
  RiAttributeBegin();
  RiColor(teal);
  RiPointsPolygonsV(RINGS * SEGS, nverts, verts, 2, tokens, parms);
  RiAttributeEnd();
  /* The floor: a square with a square hole (two loops). */
  RtInt loops[2] = {4, 4};
  RtPoint floor[8] = {{-3, 0, -3}, {3, 0, -3}, {3, 0, 3}, {-3, 0, 3},
                      {-1, 0, -1}, {-1, 0, 1}, {1, 0, 1},  {1, 0, -1}};
  RiColor(sand);
  RiTranslate(0, -0.4f, 0);
  RiGeneralPolygon(2, loops, RI_P, floor, RI_NULL);
  RiWorldEnd();
  RiEnd();
  return 0;
}

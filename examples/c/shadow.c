/* Two-pass shadow map: frame 1 renders depth from the light, RiMakeShadow turns it into a
 * shadow map, frame 2 lights the scene with a shadowed spotlight. Writes shadow.tif. */
#include <ri.h>

static void scene(void) {
  RtColor red = {0.9f, 0.35f, 0.2f}, ground = {0.8f, 0.8f, 0.75f};
  RtPoint quad[4] = {{-3, 0, -3}, {3, 0, -3}, {3, 0, 3}, {-3, 0, 3}};
  RiAttributeBegin();
  RiColor(red);
  RiTranslate(0, 1.5f, 0);
  RiSphere(0.5f, -0.5f, 0.5f, 360, RI_NULL);
  RiAttributeEnd();
  RiAttributeBegin();
  RiColor(ground);
  RiPolygon(4, RI_P, quad, RI_NULL);
  RiAttributeEnd();
}

int main(void) {
  RtFloat fov = 50, zero = 0, one = 1;
  RiBegin(RI_NULL);
  /* Pass 1: depth from the light at (1 5 0) looking at the origin. */
  RiFrameBegin(1);
  RiFormat(128, 128, 1);
  RiPixelSamples(1, 1);
  RiPixelFilter(RiBoxFilter, 1, 1);
  RiHider(RI_HIDDEN, "uniform integer jitter", &zero, RI_NULL);
  RiDisplay("shadow_depth.z", "zfile", "z", RI_NULL);
  RiProjection(RI_PERSPECTIVE, RI_FOV, &fov, RI_NULL);
  RiRotate(-90, 1, 0, 0);
  RiRotate(11.309932f, 0, 0, 1);
  RiTranslate(-1, -5, 0);
  RiWorldBegin();
  RiSurface("null", RI_NULL);
  scene();
  RiWorldEnd();
  RiFrameEnd();
  RiMakeShadow("shadow_depth.z", "shadow.sm", RI_NULL);

  /* Pass 2: the viewer at (0 5 -6). */
  RtFloat fov2 = 40, amb = 0.08f, intensity = 26, cone = 0.4f, delta = 0.05f, samples = 16;
  RtFloat blur = 0.01f, bias = 0.01f, ks = 0.5f;
  RtPoint from = {1, 5, 0}, to = {0, 0, 0};
  RtString map = "shadow.sm";
  RiFrameBegin(2);
  RiFormat(200, 150, 1);
  RiPixelSamples(2, 2);
  RiHider(RI_HIDDEN, "uniform integer jitter", &one, RI_NULL);
  RiDisplay("shadow.tif", RI_FILE, RI_RGBA, RI_NULL);
  RiProjection(RI_PERSPECTIVE, RI_FOV, &fov2, RI_NULL);
  RiRotate(-39.805571f, 1, 0, 0);
  RiTranslate(0, -5, 6);
  RiWorldBegin();
  RiLightSource(RI_AMBIENTLIGHT, RI_INTENSITY, &amb, RI_NULL);
  RiLightSource("shadowspot", RI_INTENSITY, &intensity, RI_FROM, from, RI_TO, to,
                RI_CONEANGLE, &cone, RI_CONEDELTAANGLE, &delta, "uniform string shadowname",
                &map, "uniform float samples", &samples, "uniform float blur", &blur,
                "uniform float bias", &bias, RI_NULL);
  RiSurface(RI_PLASTIC, RI_KS, &ks, RI_NULL);
  scene();
  RiWorldEnd();
  RiFrameEnd();
  RiEnd();
  return 0;
}

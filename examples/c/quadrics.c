/* Quadrics and lights, in the style of The RenderMan Companion chapter 4/9 examples.
 * cc quadrics.c -I../../include -L../../target/release -lillume -lm && ./a.out
 * writes quadrics.tif (RiBegin(RI_NULL) renders; ILLUME_RIBOUT=f.rib writes RIB instead). */
#include <ri.h>

int main(void) {
  RtFloat fov = 40, intensity = 0.6f, ambient = 0.15f, ks = 0.6f, rough = 0.15f;
  RtPoint from = {-2, 3, -4}, to = {0, 0, 0};
  RtColor red = {0.85f, 0.2f, 0.15f}, blue = {0.2f, 0.35f, 0.85f}, gold = {0.9f, 0.7f, 0.2f};
  RtColor grey = {0.7f, 0.7f, 0.7f};

  RiBegin(RI_NULL);
  RiFormat(240, 160, 1);
  RiPixelSamples(2, 2);
  RiDisplay("quadrics.tif", RI_FILE, RI_RGBA, RI_NULL);
  RiProjection(RI_PERSPECTIVE, RI_FOV, &fov, RI_NULL);
  RiTranslate(0, -0.3f, 6);
  RiRotate(-20, 1, 0, 0);
  RiWorldBegin();
  RiLightSource(RI_AMBIENTLIGHT, RI_INTENSITY, &ambient, RI_NULL);
  RiLightSource(RI_DISTANTLIGHT, RI_INTENSITY, &intensity, RI_FROM, from, RI_TO, to, RI_NULL);
  RtPoint lamp = {2, 2, -2};
  RtFloat bright = 6;
  RiLightSource(RI_POINTLIGHT, RI_INTENSITY, &bright, RI_FROM, lamp, RI_NULL);
  RiSurface(RI_PLASTIC, RI_KS, &ks, RI_ROUGHNESS, &rough, RI_NULL);

  RiAttributeBegin();
  RiTranslate(-1.6f, 0, 0);
  RiColor(red);
  RiSphere(0.7f, -0.7f, 0.7f, 360, RI_NULL);
  RiAttributeEnd();

  RiAttributeBegin();
  RiColor(blue);
  RiRotate(-90, 1, 0, 0);
  RiTranslate(0, 0, -0.7f);
  RiCylinder(0.5f, 0, 1.0f, 300, RI_NULL);
  RiDisk(1.0f, 0.5f, 300, RI_NULL);
  RiAttributeEnd();

  RiAttributeBegin();
  RiTranslate(1.6f, -0.3f, 0);
  RiRotate(-70, 1, 0, 0);
  RiColor(gold);
  RiTorus(0.5f, 0.2f, 0, 360, 360, RI_NULL);
  RiTranslate(0, 0, 0.2f);
  RiCone(0.9f, 0.3f, 360, RI_NULL);
  RiAttributeEnd();

  RiAttributeBegin();
  RiColor(grey);
  RiRotate(-90, 1, 0, 0);
  RiTranslate(0, 0, -0.7f);
  RiDisk(0, 4, 360, RI_NULL);
  RiAttributeEnd();
  RiWorldEnd();
  RiEnd();
  return 0;
}

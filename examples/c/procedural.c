/* A program-defined procedural (RiProcedural with subdivide and free functions): a recursive
 * cluster of spheres, each level a procedural of its own. Writes procedural.tif. */
#include <ri.h>
#include <stdlib.h>

typedef struct {
  int depth;
  float radius;
} Cluster;

static RtVoid free_cluster(RtPointer data) { free(data); }

static RtVoid subdivide(RtPointer data, RtFloat detail) {
  (void)detail;
  Cluster *c = data;
  RtColor color = {0.3f + 0.2f * c->depth, 0.5f, 0.9f - 0.2f * c->depth};
  RiColor(color);
  RiSphere(c->radius, -c->radius, c->radius, 360, RI_NULL);
  if (c->depth == 0) return;
  for (int i = 0; i < 4; i++) {
    Cluster *child = malloc(sizeof *child);
    child->depth = c->depth - 1;
    child->radius = c->radius * 0.45f;
    float d = c->radius * 1.4f;
    RtBound bound = {-d * 2, d * 2, -d * 2, d * 2, -d * 2, d * 2};
    RiTransformBegin();
    RiRotate(90.0f * i + 45, 0, 0, 1);
    RiRotate(60, 0, 1, 0);
    RiTranslate(0, 0, d);
    RiProcedural(child, bound, subdivide, free_cluster);
    RiTransformEnd();
  }
}

int main(void) {
  RtFloat fov = 30;
  RiBegin(RI_NULL);
  RiFormat(160, 160, 1);
  RiDisplay("procedural.tif", RI_FILE, RI_RGBA, RI_NULL);
  RiProjection(RI_PERSPECTIVE, RI_FOV, &fov, RI_NULL);
  RiTranslate(0, 0, 6);
  RiWorldBegin();
  RiLightSource(RI_DISTANTLIGHT, RI_NULL);
  RtFloat amb = 0.2f;
  RiLightSource(RI_AMBIENTLIGHT, RI_INTENSITY, &amb, RI_NULL);
  RiSurface(RI_PLASTIC, RI_NULL);
  Cluster *root = malloc(sizeof *root);
  root->depth = 2;
  root->radius = 0.8f;
  RtBound bound = {-3, 3, -3, 3, -3, 3};
  RiProcedural(root, bound, subdivide, free_cluster);
  RiWorldEnd();
  RiEnd();
  return 0;
}

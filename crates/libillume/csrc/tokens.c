/* The standard tokens and bases of ri.h (RI Specification 3.2, Appendix C). */
#include "ri.h"

RtToken RI_FRAMEBUFFER = "framebuffer", RI_FILE = "file";
RtToken RI_RGB = "rgb", RI_RGBA = "rgba", RI_RGBZ = "rgbz", RI_RGBAZ = "rgbaz", RI_A = "a",
        RI_Z = "z", RI_AZ = "az";
RtToken RI_PERSPECTIVE = "perspective", RI_ORTHOGRAPHIC = "orthographic";
RtToken RI_HIDDEN = "hidden", RI_PAINT = "paint";
RtToken RI_CONSTANT = "constant", RI_SMOOTH = "smooth";
RtToken RI_FLATNESS = "flatness", RI_FOV = "fov";
RtToken RI_AMBIENTLIGHT = "ambientlight", RI_POINTLIGHT = "pointlight",
        RI_DISTANTLIGHT = "distantlight", RI_SPOTLIGHT = "spotlight";
RtToken RI_INTENSITY = "intensity", RI_LIGHTCOLOR = "lightcolor", RI_FROM = "from", RI_TO = "to",
        RI_CONEANGLE = "coneangle", RI_CONEDELTAANGLE = "conedeltaangle",
        RI_BEAMDISTRIBUTION = "beamdistribution";
RtToken RI_MATTE = "matte", RI_METAL = "metal", RI_SHINYMETAL = "shinymetal",
        RI_PLASTIC = "plastic", RI_PAINTEDPLASTIC = "paintedplastic";
RtToken RI_KA = "Ka", RI_KD = "Kd", RI_KS = "Ks", RI_ROUGHNESS = "roughness", RI_KR = "Kr",
        RI_TEXTURENAME = "texturename", RI_SPECULARCOLOR = "specularcolor";
RtToken RI_DEPTHCUE = "depthcue", RI_FOG = "fog", RI_BUMPY = "bumpy";
RtToken RI_MINDISTANCE = "mindistance", RI_MAXDISTANCE = "maxdistance",
        RI_BACKGROUND = "background", RI_DISTANCE = "distance", RI_AMPLITUDE = "amplitude";
RtToken RI_INSIDE = "inside", RI_OUTSIDE = "outside", RI_LH = "lh", RI_RH = "rh";
RtToken RI_P = "P", RI_PZ = "Pz", RI_PW = "Pw", RI_N = "N", RI_NP = "Np", RI_CS = "Cs",
        RI_OS = "Os", RI_S = "s", RI_T = "t", RI_ST = "st";
RtToken RI_BILINEAR = "bilinear", RI_BICUBIC = "bicubic", RI_LINEAR = "linear",
        RI_CUBIC = "cubic";
RtToken RI_PRIMITIVE = "primitive", RI_INTERSECTION = "intersection", RI_UNION = "union",
        RI_DIFFERENCE = "difference";
RtToken RI_PERIODIC = "periodic", RI_NONPERIODIC = "nonperiodic", RI_CLAMP = "clamp",
        RI_BLACK = "black";
RtToken RI_IGNORE = "ignore", RI_PRINT = "print", RI_ABORT = "abort", RI_HANDLER = "handler";
RtToken RI_ORIGIN = "origin", RI_IDENTIFIER = "identifier", RI_NAME = "name";
RtToken RI_COMMENT = "comment", RI_STRUCTURE = "structure", RI_VERBATIM = "verbatim";
RtToken RI_WIDTH = "width", RI_CONSTANTWIDTH = "constantwidth";
RtToken RI_CURRENT = "current", RI_WORLD = "world", RI_OBJECT = "object", RI_SHADER = "shader",
        RI_CAMERA = "camera", RI_SCREEN = "screen", RI_RASTER = "raster", RI_NDC = "NDC";

RtBasis RiBezierBasis = {{-1, 3, -3, 1}, {3, -6, 3, 0}, {-3, 3, 0, 0}, {1, 0, 0, 0}};
RtBasis RiBSplineBasis = {{-1.0f / 6, 3.0f / 6, -3.0f / 6, 1.0f / 6},
                          {3.0f / 6, -6.0f / 6, 3.0f / 6, 0},
                          {-3.0f / 6, 0, 3.0f / 6, 0},
                          {1.0f / 6, 4.0f / 6, 1.0f / 6, 0}};
RtBasis RiCatmullRomBasis = {{-0.5f, 1.5f, -1.5f, 0.5f},
                             {1, -2.5f, 2, -0.5f},
                             {-0.5f, 0, 0.5f, 0},
                             {0, 1, 0, 0}};
RtBasis RiHermiteBasis = {{2, 1, -2, 1}, {-3, -2, 3, -1}, {0, 1, 0, 0}, {1, 0, 0, 0}};
RtBasis RiPowerBasis = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};

RtInt RiLastError = RIE_NOERROR;

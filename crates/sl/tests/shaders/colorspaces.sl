/* Colour spaces, matrices, strings, arrays, splines and derivatives in one surface. */
surface colorspaces (float hue = 0.3; string space = "current"; float knots[4] = {0, 0.2, 0.8, 1};)
{
    color c = color "hsv" (hue, 1, 1);
    color d = ctransform ("hsl", c);
    matrix m = matrix "shader" (1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1);
    matrix w = 1;
    uniform float det = determinant (m * w);
    point q = transform (space, "world", P);
    vector dq = Du (q) + Dv (q);
    float a = area (P);
    float sp = spline ("catmull-rom", s, knots);
    string msg = format ("%f %s", det, space);
    if (match ("cur", msg) != 0)
        printf ("%s %p\n", msg, q);
    float r = comp (c, 0);
    setcomp (d, 1, r);
    Oi = Os;
    Ci = Os * (c * sp + d * (length (dq) + a)) * (det != 0 ? 1 : 0);
}

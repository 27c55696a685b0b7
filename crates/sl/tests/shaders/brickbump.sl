/* A brick displacement in the style of the RenderMan Companion, with #define'd constants,
   a user function with an output parameter and uniform loop bookkeeping. */
#define BRICKWIDTH  0.25
#define BRICKHEIGHT 0.08
#define MORTARTHICKNESS 0.01
#define BMWIDTH  (BRICKWIDTH + MORTARTHICKNESS)
#define BMHEIGHT (BRICKHEIGHT + MORTARTHICKNESS)
#define MWF (MORTARTHICKNESS * 0.5 / BMWIDTH)
#define MHF (MORTARTHICKNESS * 0.5 / BMHEIGHT)
#define boxstep(a,b,x) clamp(((x)-(a))/((b)-(a)), 0, 1)

float brickcoords (float ss, tt; output float sbrick, tbrick;)
{
    float x = ss / BMWIDTH, y = tt / BMHEIGHT;
    if (mod (y * 0.5, 1) > 0.5)
        x += 0.5;
    sbrick = floor (x);
    tbrick = floor (y);
    return x - sbrick;
}

displacement brickbump (float Km = 0.5;)
{
    float sbrick, tbrick;
    float ss = brickcoords (s, t, sbrick, tbrick);
    float tt = t / BMHEIGHT - tbrick;
    float w = step (MWF, ss) - step (1 - MWF, ss);
    float h = step (MHF, tt) - step (1 - MHF, tt);
    uniform float i, total = 0;
    for (i = 0; i < 3; i += 1)
        total += i;
    float soft = boxstep (0, MWF, ss) * boxstep (0, MHF, tt);
    P += Km * w * h * soft * normalize (N) * total / 3;
    N = calculatenormal (P);
}

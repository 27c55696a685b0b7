surface components() { point p = point (s, t, 3); setycomp (p, xcomp (p) + zcomp (p)); color c = color (1, 2, 3); setcomp (c, 2, comp (c, 0) + s); Ci = color (ycomp (p), comp (c, 2), 0); }

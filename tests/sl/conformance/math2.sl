surface math2() { Ci = color (mod (-3.5 * s, 1.25) + abs (s - t), floor (4 * s) + ceil (3 * t) + sign (t - 0.5), atan (t, s + 0.1) + atan (s)); }

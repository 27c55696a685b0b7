surface ternary() { Ci = (s > t) ? color (1, 0, 0) : color (0, s, t); }

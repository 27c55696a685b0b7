surface varying_for() { float i, n = 0; for (i = 0; i < 10 * s; i += 1) n += 1; Ci = n; }

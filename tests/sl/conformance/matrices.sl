surface matrices() { matrix m = translate (matrix 1, vector (1, 2, 3)); m = scale (m, point (2, 2, 2)); point q = transform (m, point (s, t, 0)); Ci = color (q) + determinant (m); }

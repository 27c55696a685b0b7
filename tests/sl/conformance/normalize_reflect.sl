surface normalize_reflect() { vector d = normalize (vector (s, 1, t + 1)); Ci = color (reflect (d, normal (0, 1, 0))); }

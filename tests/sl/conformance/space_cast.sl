surface space_cast() { point o = point "world" (0, 0, 0); Ci = color (o) + color (transform ("world", "camera", point (s, 0, 0))); }

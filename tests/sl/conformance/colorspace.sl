surface colorspace() { color c = color "hsv" (s, 1, 1); Ci = c + ctransform ("hsv", color (t, 0.5, 0.25)); }

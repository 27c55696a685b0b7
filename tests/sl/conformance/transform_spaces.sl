surface transform_spaces() { point pw = transform ("world", P); vector vw = vtransform ("world", vector (1, 0, 0)); Ci = color (pw) + color (vw); }

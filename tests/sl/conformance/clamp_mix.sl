surface clamp_mix() { Ci = color (clamp (3 * s - 1, 0, 1), mix (2, 5, t), min (s, t, 0.4) + max (s, t)); }

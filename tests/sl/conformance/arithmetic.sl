surface arithmetic() { Ci = color (s + t * 2, s * t - 1, (s + 1) / (t + 1)); }

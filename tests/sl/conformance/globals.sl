surface globals() { Ci = color (u + 10 * v, du, dv) + Cs; Oi = Os * 0.5; }

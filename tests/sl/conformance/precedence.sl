surface precedence() { float a = 2 + 3 * s - t / 2; Ci = a; }

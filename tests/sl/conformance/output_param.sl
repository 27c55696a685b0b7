void split (float x; output float lo, hi) { lo = floor (x); hi = x - lo; }
surface output_param() { float a, b; split (s * 3.5 + t, a, b); Ci = color (a, b, 0); }

float tri (float x) { if (x < 0.5) return 2 * x; return 2 - 2 * x; }
surface function_return() { Ci = tri (s); }

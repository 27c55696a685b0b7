surface nested_if() { Ci = 0; if (s > 0.2) { if (t > 0.4) Ci = 1; else Ci = 0.5; } }

surface if_else() { if (s < 0.5) Ci = s; else Ci = 1 - s; }

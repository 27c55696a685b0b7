surface logic() { Ci = color ((s > 0.2 && t < 0.6) ? 1 : 0, (s < 0.1 || t > 0.9) ? 1 : 0, !(s > 0.5) ? 1 : 0); }

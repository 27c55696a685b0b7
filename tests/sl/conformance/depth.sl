surface depth() {
    Ci = color (depth (P), depth (P + vector (0, 0, s)), depth (point (0, 0, 1)));
}

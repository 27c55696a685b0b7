surface geometric() { vector a = vector (s, t, 1), b = vector (1, -t, s); Ci = color (length (a), distance (point a, point b), a . b) + color (a ^ b); }

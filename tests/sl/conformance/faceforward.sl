surface faceforward() { Ci = color (faceforward (normal (0, 0, 1), I)) + color (faceforward (normal (s, 0, 1), vector (0, 0, -1), normal (0, 0, 1))); }

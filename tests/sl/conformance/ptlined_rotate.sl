surface ptlined_rotate() { point q = point (s, t, 0); Ci = color (ptlined (point (0, 0, 0), point (0.5, 0, 0), q), 0, 0) + color (rotate (q, PI / 2, point (0, 0, 0), point (0, 0, 1))); }

surface spline() { Ci = color (spline (s, 0, 1, 4, 2, 3, 7), spline ("linear", t, 9, 0, 10, 20, 9), spline ("bezier", 0.5, 0, 2, 5, 1)); }

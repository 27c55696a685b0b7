surface arrays() { float a[3] = { 1, 2, 3 }; a[1] = s; float k = floor (t * 2.99); Ci = color (a[0], a[1], a[k]); }

surface math() { Ci = color (sin (s) + cos (t), sqrt (s + 1) * exp (-t), pow (2, s) + log (t + 1)); }

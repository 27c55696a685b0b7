surface calculatenormal() { Ci = color (normalize (calculatenormal (P))); }

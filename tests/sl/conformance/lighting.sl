surface lighting() { normal Nf = normalize (N); Ci = diffuse (Nf) + 0.5 * ambient () + specular (Nf, -normalize (I), 0.2); }

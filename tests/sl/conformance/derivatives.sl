surface derivatives() { Ci = color (Du (s * s), Dv (3 * t), area (P)); }

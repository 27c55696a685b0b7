surface steps() { Ci = color (step (0.5, s), smoothstep (0.2, 0.8, t), filterstep (0.5, s)); }

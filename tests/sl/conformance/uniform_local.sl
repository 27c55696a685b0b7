surface uniform_local() { uniform float k = 2; k = k * 3; Ci = k * s; }

surface for_loop() { float sum = 0, i; for (i = 0; i < 5; i += 1) sum += pow (s, i); Ci = sum; }

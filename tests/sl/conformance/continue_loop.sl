surface continue_loop() { float sum = 0, i; for (i = 0; i < 6; i += 1) { if (mod (i, 2) == 0) continue; sum += s * i; } Ci = sum; }

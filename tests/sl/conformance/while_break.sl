surface while_break() { float x = 1, n = 0; while (1) { if (x > 4 * t + 1) break; x *= 1.5; n += 1; } Ci = n; }

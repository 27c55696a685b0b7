surface illuminance_loop() { color c = 0; illuminance (P, N, PI / 2) { c += Cl * (normalize (L) . normalize (N)); } Ci = c; }

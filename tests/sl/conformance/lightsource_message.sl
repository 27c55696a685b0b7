surface lightsource_message() { float total = 0; illuminance (P) { float x = 0; if (lightsource ("__nonspecular", x) > 0) total += x + 1; } Ci = total; }

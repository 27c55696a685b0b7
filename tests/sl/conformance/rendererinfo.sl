surface rendererinfo() {
    string r = "", vs = "";
    float v[4] = { -1, -1, -1, -1 };
    float ok = rendererinfo ("renderer", r) + rendererinfo ("version", v)
             + rendererinfo ("versionstring", vs) + 10 * rendererinfo ("nosuch", r);
    Ci = color (ok, match ("Illume", r) + 2 * match (vs, "0.1.0"),
                v[0] * 100 + v[1] * 10 + v[2] + v[3]);
}

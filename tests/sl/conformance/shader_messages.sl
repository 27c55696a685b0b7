surface shader_messages() {
    float kd = 0, km = 0, bad = 0;
    color fog = 0;
    float ok = surface ("Kd", kd) + displacement ("Km", km) + atmosphere ("fogcolor", fog);
    float miss = displacement ("nosuch", bad) + displacement ("Km", fog) + surface ("Km", bad);
    Ci = color (ok + 10 * miss, kd + km, comp (fog, 0) + comp (fog, 2)) + bad;
}

surface attribute_query() {
    float sr = -1, sides = -1, missing = 7;
    string nm = "";
    float bound = 0;
    float ok = attribute ("ShadingRate", sr) + attribute ("Sides", sides)
             + attribute ("identifier:name", nm) + attribute ("displacementbound:sphere", bound);
    float bad = attribute ("nosuch", missing) + attribute ("Sides", nm);
    Ci = color (ok + 10 * bad, sr + sides + bound, match ("ball", nm) + missing);
}

surface option_query() {
    float fmt[3] = { 0, 0, 0 }, res[3] = { 0, 0, 0 }, cw[4] = { 0, 0, 0, 0 };
    float ar = 0, fr = 0;
    float ok = option ("Format", fmt) + option ("FrameAspectRatio", ar) + option ("Frame", fr)
             + option ("CropWindow", cw) + option ("DeviceResolution", res);
    float bad = option ("Format", ar) + option ("nosuch", fr);
    Ci = color (ok + 10 * bad, fmt[0] + fmt[1] / 100 + fmt[2] + ar,
                fr + cw[1] + cw[2] + res[0] / 1000);
}

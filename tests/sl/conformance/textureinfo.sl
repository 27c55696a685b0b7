surface textureinfo() {
    float res[2] = { 0, 0 }, ch = 0;
    string ty = "";
    matrix vm = 0;
    float ok = textureinfo ("grid.tx", "resolution", res) + textureinfo ("grid.tx", "channels", ch)
             + textureinfo ("grid.tx", "type", ty) + textureinfo ("spot.shd", "viewingmatrix", vm);
    float bad = textureinfo ("nosuch.tx", "resolution", res) + textureinfo ("grid.tx", "type", ch);
    Ci = color (ok + 10 * bad, res[0] + res[1] / 1000 + ch, match ("texture", ty) + comp (vm, 3, 0));
}

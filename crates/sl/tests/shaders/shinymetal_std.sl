/* The RI spec's shinymetal (a texture-map reflection), not the chapter's. */
surface shinymetal (float Ka = 1, Ks = 1, Kr = 1, roughness = .1;
                    string texturename = "";)
{
    normal Nf = faceforward (normalize(N), I);
    vector V = -normalize(I);
    vector D = reflect (I, Nf);
    D = vtransform ("world", D);
    Oi = Os;
    Ci = Os * Cs * (Ka*ambient() + Ks*specular(Nf, V, roughness));
    if (texturename != "")
        Ci += Os * Cs * Kr * color environment (texturename, D);
}

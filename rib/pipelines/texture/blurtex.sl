/* A texture-mapped matte surface whose lookup is blurred and widened on request: the SL form
 * of paintedplastic's texture() call, with texture()'s optional "blur" (an extra filter width,
 * as a fraction of the texture) and "width" (a multiplier of the filter width the grid's
 * st-footprint gives) parameters. */
surface blurtex (string texturename = "";
                 float blur = 0;
                 float width = 1;
                 float Ka = 1;
                 float Kd = 1;)
{
    normal Nf = faceforward (normalize (N), I);
    color Ct = Cs;
    if (texturename != "")
        Ct = Cs * color texture (texturename, s, t, "blur", blur, "width", width);
    Oi = Os;
    Ci = Os * Ct * (Ka * ambient () + Kd * diffuse (Nf));
}

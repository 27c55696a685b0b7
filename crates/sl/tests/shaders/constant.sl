/* RI 3.2 standard shader: constant colour, no lighting. */
surface constant ()
{
    Oi = Os;
    Ci = Os * Cs;
}

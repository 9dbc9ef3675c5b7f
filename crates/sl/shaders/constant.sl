/* constant: the surface colour, unlit (RenderMan Interface 3.2, Appendix A). */
surface constant()
{
    Oi = Os;
    Ci = Os * Cs;
}

/* tiles: a procedural surface written for reyes-render (issue #30). Square tiles of two
 * colours in (s, t), separated by grout lines antialiased with filterstep, each tile's colour
 * varied by cellnoise; lit as plastic: ambient, diffuse and a specular highlight. */
surface tiles(float Ka = 1, Kd = 0.7, Ks = 0.4, roughness = 0.15;
              float frequency = 6, grout = 0.06;
              color tilecolor = color (0.8, 0.35, 0.2), altcolor = color (0.9, 0.8, 0.55);
              color groutcolor = color (0.15, 0.15, 0.15))
{
    float ss = s * frequency, tt = t * frequency;
    float cs = floor(ss), ct = floor(tt);
    float fs = ss - cs, ft = tt - ct;
    /* 1 inside a tile, 0 on the grout, with filtered edges. */
    float ins = filterstep(grout, fs) * (1 - filterstep(1 - grout, fs));
    float int = filterstep(grout, ft) * (1 - filterstep(1 - grout, ft));
    float which = mod(cs + ct, 2);
    float vary = 0.8 + 0.4 * cellnoise(cs, ct);
    color tile = mix(tilecolor, altcolor, which) * vary;
    color base = mix(groutcolor, tile, ins * int);
    normal Nf = faceforward(normalize(N), I);
    vector V = -normalize(I);
    Oi = Os;
    Ci = Os * (Cs * base * (Ka * ambient() + Kd * diffuse(Nf))
               + Ks * ins * int * specular(Nf, V, roughness));
}

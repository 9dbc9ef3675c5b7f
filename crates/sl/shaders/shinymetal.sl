/* shinymetal: metal plus a reflection looked up in an environment map (in world space). */
surface shinymetal(float Ka = 1; float Ks = 1; float Kr = 1; float roughness = 0.1;
                   string texturename = "";)
{
    normal Nf = faceforward(normalize(N), I);
    vector V = -normalize(I);
    vector D = vtransform("world", reflect(I, Nf));
    color reflection = 0;
    if (texturename != "")
        reflection = Kr * color environment(texturename, D);
    Oi = Os;
    Ci = Os * Cs * (Ka * ambient() + Ks * specular(Nf, V, roughness) + reflection);
}

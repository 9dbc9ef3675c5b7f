/* paintedplastic: plastic whose colour is multiplied by a texture map over (s, t). */
surface paintedplastic(float Ks = 0.5; float Kd = 0.5; float Ka = 1; float roughness = 0.1;
                       color specularcolor = 1; string texturename = "";)
{
    normal Nf = faceforward(normalize(N), I);
    vector V = -normalize(I);
    color Ct = Cs;
    if (texturename != "")
        Ct *= color texture(texturename);
    Oi = Os;
    Ci = Os * (Ct * (Ka * ambient() + Kd * diffuse(Nf))
               + specularcolor * Ks * specular(Nf, V, roughness));
}

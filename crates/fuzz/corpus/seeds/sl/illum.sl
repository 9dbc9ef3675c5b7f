/* Seed for the sl target: illuminance with a category, message passing, matrices, strings. */
surface illum(float Ks = 0.5, roughness = 0.1; uniform string cat = "spot") {
    normal Nf = faceforward(normalize(N), I);
    vector V = -normalize(I);
    color diff = 0, spec = 0;
    illuminance(cat, P, Nf, PI / 2) {
        float nd = 0;
        lightsource("__nondiffuse", nd);
        vector Ln = normalize(L);
        diff += (1 - nd) * Cl * (Ln . Nf);
        spec += Cl * specularbrdf(Ln, Nf, V, roughness);
    }
    matrix m = matrix "world" 1;
    matrix r = rotate(m, radians(45), vector(0, 1, 0));
    point q = transform(r, P);
    vector d = vtransform("world", "camera", vector(1, 0, 0));
    normal n2 = ntransform("object", N);
    color hsv = ctransform("hsv", Cs);
    string msg = format("%f %p %c", s, q, hsv);
    float found = match("^[0-9]", msg);
    float a = area(P);
    vector dp = Du(P) * du + Dv(P) * dv;
    normal nn = calculatenormal(P + 0.01 * N);
    uniform float solid = 0;
    attribute("identifier:name", msg);
    option("Format", solid);
    Oi = Os;
    Ci = Os * (Cs * diff + Ks * spec) + 0 * (found + a + length(dp) + (nn . n2) + (d . d));
}

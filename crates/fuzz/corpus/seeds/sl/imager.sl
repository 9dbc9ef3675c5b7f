imager vignette(float strength = 0.5; color tint = 1) {
    float r = 0;
    uniform float res[3];
    option("Format", res);
    r = length(vector(xcomp(P) / res[0] - 0.5, ycomp(P) / res[1] - 0.5, 0));
    Ci *= tint * (1 - strength * r * r);
    alpha = clamp(alpha, 0, 1);
}
